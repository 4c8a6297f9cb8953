// SPDX-License-Identifier: Apache-2.0
// Reading a survey tile by tile (examples/cli/tiled_survey, tile_store): the same survey as read_survey.
#include <doctest/doctest.h>

#include "cli/tile_store.hpp"
#include "cli/tiled_survey.hpp"
#include "io/las_writer.hpp"

#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <lidarfx/synth/scenes.hpp>

#include "io_test_util.hpp"

using namespace lidarfx;
using namespace lidarfx::io;

namespace {

/// A lake scene of 300 m (GPS times, so scan lines count) cut into 3 x 3 LAS files of 100 m, each also holding
/// the points up to `overlap_m` beyond its edges (as flight strips overlap); returns the paths.
std::vector<std::string> write_lake_survey(const io_test::temp_dir& dir, double overlap_m = 0)
{
    const auto scene = synth::lake_scene({.seed = 7, .size_m = 300, .density_per_m2 = 1.5});
    std::vector<las_points> parts(9);
    const auto all = las_points_from(scene.points);
    const auto in = [&](double v, int k) { return (k == 0 || v >= k * 100 - overlap_m) && (k == 2 || v < k * 100 + 100 + overlap_m); };
    for (std::size_t i = 0; i < all.size(); ++i)
    for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
        if (!in(all.x[i], c) || !in(all.y[i], r)) continue;
        auto& p = parts[static_cast<std::size_t>(r * 3 + c)];
        p.x.push_back(all.x[i] + 600000.0);
        p.y.push_back(all.y[i] + 5000000.0);
        p.z.push_back(all.z[i]);
        p.intensity.push_back(all.intensity[i]);
        p.return_number.push_back(all.return_number[i]);
        p.number_of_returns.push_back(all.number_of_returns[i]);
        p.classification.push_back(all.classification[i]);
        p.gps_time.push_back(all.gps_time[i]);
    }
    std::vector<std::string> paths;
    for (std::size_t k = 0; k < parts.size(); ++k) {
        paths.push_back(dir.file("part_" + std::to_string(k) + ".las"));
        write_las(paths.back(), parts[k], {.point_format = 1, .epsg_projected = 32633});
    }
    return paths;
}

template <class T>
bool same_bits(const raster<T>& a, const raster<T>& b)
{
    return a.rows() == b.rows() && a.cols() == b.cols() &&
           std::memcmp(a.data(), b.data(), static_cast<std::size_t>(a.size()) * sizeof(T)) == 0;
}

void check_same_survey(const cli::survey& want, const cli::survey& got)
{
    const auto& a = want.rasters;
    const auto& b = got.rasters;
    CHECK(a.g == b.g);
    CHECK(same_bits(a.min_z, b.min_z));
    CHECK(same_bits(a.max_z, b.max_z));
    CHECK(same_bits(a.mean_intensity, b.mean_intensity));
    CHECK(same_bits(a.count, b.count));
    CHECK(same_bits(a.dropout, b.dropout));
    CHECK(same_bits(a.multiple_returns, b.multiple_returns));
    CHECK(same_bits(want.scan_covered, got.scan_covered));
    CHECK(a.points_used == b.points_used);
    CHECK(a.points_outside == b.points_outside);
    CHECK(a.points_nan == b.points_nan);
    CHECK(want.points == got.points);
    CHECK(want.files == got.files);
    CHECK(want.epsg == got.epsg);
}

cli::survey_options quiet(double cell_m, int threads)
{
    cli::survey_options o;
    o.cell_m = cell_m;
    o.threads = threads;
    o.show_progress = false;
    return o;
}

}  // namespace

TEST_CASE("io/tiled_survey: tile by tile, the survey read_survey reads, bit for bit (scan lines included)")
{
    io_test::temp_dir dir;
    const auto paths = write_lake_survey(dir);
    // 1.5 m cells: the files' 100 m borders fall inside cells, and the tiles' borders elsewhere.
    const auto untiled = cli::read_survey(paths, quiet(1.5, 1));
    const auto& sc = untiled.scan_covered;
    REQUIRE(!sc.empty());
    REQUIRE(std::count(sc.data(), sc.data() + sc.size(), 1) > 100);   // lakes lose pulses: scan lines cross
    for (const double edge : {10.5, 45.0, 1000.0}) {
        for (const int threads : {1, 2}) {
            CAPTURE(edge);
            CAPTURE(threads);
            check_same_survey(untiled, cli::read_survey_tiled(paths, quiet(1.5, threads), edge, {}));
        }
    }
    SUBCASE("files that reach a metre into their neighbours' tiles: their homes hand those points on")
    {
        io_test::temp_dir other;
        const auto overlapping = write_lake_survey(other, 1.0);
        const auto o = quiet(2.0, 2);
        const auto layout = cli::survey_layout_of(overlapping, o);
        const auto plan = cli::plan_survey_tiles(layout, 100.0, o, 2);
        const auto readers = cli::survey_file_readers(layout, plan, true);
        std::size_t handed = 0;
        for (const auto& r : readers) handed += r.handed_to.size();
        CHECK(handed >= 12);   // each inner border is crossed by the files on both sides
        const auto want = cli::read_survey(overlapping, o);
        for (const int threads : {1, 2}) check_same_survey(want, cli::read_survey_tiled(overlapping, quiet(2.0, threads), 100.0, {}));
    }
    SUBCASE("with --crop (files outside it are read by no tile)")
    {
        auto o = quiet(1.5, 2);
        o.crop = bounds{600020.0, 5000030.0, 600150.0, 5000140.0};
        check_same_survey(cli::read_survey(paths, o), cli::read_survey_tiled(paths, o, 30.0, {}));
    }
}

TEST_CASE("io/tiled_survey: a point far from the rest is refused as read_survey refuses it, as the tiles read it")
{
    io_test::temp_dir dir;
    auto paths = write_lake_survey(dir);
    las_points far;
    far.x = {600150.0, 630000.0};   // the second point 30 km east of a 300 m survey
    far.y = {5000150.0, 5000150.0};
    far.z = {10.0, 10.0};
    far.intensity = {100, 100};
    far.return_number = far.number_of_returns = {1, 1};
    far.classification = {1, 1};
    far.gps_time = {1.0e6, 1.0e6 + 1};
    paths.push_back(dir.file("far.las"));
    write_las(paths.back(), far, {.point_format = 1, .epsg_projected = 32633});
    const auto want = io_test::error_of([&] { cli::read_survey(paths, quiet(2.0, 1)); });
    REQUIRE(io_test::contains(want, "1 of "));
    REQUIRE(io_test::contains(want, "lie far from the rest"));
    for (const int threads : {1, 2}) CHECK(io_test::error_of([&] { cli::read_survey_tiled(paths, quiet(2.0, threads), 200.0, {}); }) == want);
    // A resumed run (some tiles already kept) checks before reading, with the same message.
    const std::filesystem::path kept = dir.file("kept");
    {
        cli::tile_store store(kept, cli::tiled_fingerprint(paths, quiet(2.0, 1), 200.0));
        store.save(0, {1, 2, 3});
    }
    CHECK(io_test::error_of([&] { cli::read_survey_tiled(paths, quiet(2.0, 1), 200.0, kept); }) == want);
}

TEST_CASE("io/tiled_survey: a tile packed and unpacked is the same tile; damaged bytes are refused by name")
{
    io_test::temp_dir dir;
    const auto paths = write_lake_survey(dir);
    const auto o = quiet(2.0, 1);
    const auto layout = cli::survey_layout_of(paths, o);
    const auto plan = cli::plan_survey_tiles(layout, 60.0, o, 1);
    REQUIRE(plan.tiles.size() == 25);   // 150 x 150 cells in tiles of 30 x 30
    const auto tile = cli::read_tile(layout, paths, plan, cli::survey_file_readers(layout, plan, false), 12, false);
    CHECK(tile.rasters.points_used > 0);
    const auto bytes = cli::pack_tile(tile);
    const auto back = cli::unpack_tile(bytes, plan, "tile 12");
    CHECK(cli::pack_tile(back) == bytes);
    auto cut = bytes;
    cut.resize(bytes.size() - 1);
    CHECK(io_test::contains(io_test::error_of([&] { cli::unpack_tile(cut, plan, "saved tile 12"); }), "saved tile 12"));
    auto wrong = bytes;
    wrong[0] = 'X';
    CHECK(io_test::contains(io_test::error_of([&] { cli::unpack_tile(wrong, plan, "saved tile 12"); }), "not a saved"));
}

TEST_CASE("io/tile_store: finished tiles survive a reopen with the same fingerprint, not with another")
{
    io_test::temp_dir dir;
    const std::filesystem::path folder = dir.file("tiles");
    {
        cli::tile_store store(folder, "inputs A\n");
        store.save(3, {1, 2, 3});
        store.save(7, {4});
        CHECK(store.done_count() == 2);
    }
    // What a killed run may leave besides finished tiles: a temporary file, and names that are no tile.
    for (const char* stray : {"tile_4.bin.tmp99", "tile_x.bin", "tile_5.binx", "notes"})
        io_test::write_bytes((folder / stray).string(), {9});
    {
        cli::tile_store store(folder, "inputs A\n");
        CHECK(store.done(3));
        CHECK(store.done(7));
        CHECK(!store.done(4));
        CHECK(store.done_count() == 2);
        CHECK(!std::filesystem::exists(folder / "tile_4.bin.tmp99"));
        CHECK(!std::filesystem::exists(folder / "notes"));
        CHECK(store.load(3) == std::vector<std::uint8_t>{1, 2, 3});
    }
    {
        cli::tile_store store(folder, "inputs B\n");
        CHECK(store.done_count() == 0);
        CHECK(!std::filesystem::exists(folder / "tile_3.bin"));
        store.remove();
    }
    CHECK(!std::filesystem::exists(folder));
}

TEST_CASE("io/survey_files: a folder stands for its LAS and LAZ files sorted by name; files pass as they are")
{
    io_test::temp_dir dir;
    const std::filesystem::path folder = dir.file("survey");
    std::filesystem::create_directories(folder);
    for (const char* name : {"b.las", "a.LAZ", "c.las", "notes.txt"}) io_test::write_bytes((folder / name).string(), {0});
    const auto files = cli::survey_files({folder.string(), dir.file("other.las")});
    REQUIRE(files.size() == 4);
    CHECK(files[0] == (folder / "a.LAZ").string());
    CHECK(files[1] == (folder / "b.las").string());
    CHECK(files[2] == (folder / "c.las").string());
    CHECK(files[3] == dir.file("other.las"));
    const std::filesystem::path empty = dir.file("empty");
    std::filesystem::create_directories(empty);
    CHECK_THROWS_AS(cli::survey_files({empty.string()}), cli::usage_error);
}
