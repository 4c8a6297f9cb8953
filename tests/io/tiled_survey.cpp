// SPDX-License-Identifier: Apache-2.0
// Reading a survey tile by tile (examples/cli/tiled_survey, tile_store): the same survey as read_survey.
#include <doctest/doctest.h>

#include "cli/tile_store.hpp"
#include "cli/tiled_survey.hpp"
#include "io/las_writer.hpp"

#include <csignal>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <lidarfx/synth/scenes.hpp>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/stat.h>

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
    const auto in = [&](double v, int k) {
        return (k == 0 || v >= k * 100 - overlap_m) && (k == 2 || v < k * 100 + 100 + overlap_m);
    };
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
    REQUIRE(std::count(sc.data(), sc.data() + sc.size(), 1) > 100);  // lakes lose pulses: scan lines cross
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
        CHECK(handed >= 12);  // each inner border is crossed by the files on both sides
        const auto want = cli::read_survey(overlapping, o);
        for (const int threads : {1, 2})
            check_same_survey(want, cli::read_survey_tiled(overlapping, quiet(2.0, threads), 100.0, {}));
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
    far.x = {600150.0, 630000.0};  // the second point 30 km east of a 300 m survey
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
    for (const int threads : {1, 2})
        CHECK(io_test::error_of([&] { cli::read_survey_tiled(paths, quiet(2.0, threads), 200.0, {}); }) == want);
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
    REQUIRE(plan.tiles.size() == 25);  // 150 x 150 cells in tiles of 30 x 30
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
    CHECK(std::filesystem::is_regular_file(folder / ".lidarfx-tile-store"));
    io_test::write_bytes((folder / "tile_4.bin.tmp99").string(), {9});  // a temporary of a killed run
    {
        cli::tile_store store(folder, "inputs A\n");
        CHECK(store.done(3));
        CHECK(store.done(7));
        CHECK(!store.done(4));
        CHECK(store.done_count() == 2);
        CHECK(!std::filesystem::exists(folder / "tile_4.bin.tmp99"));
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

TEST_CASE("io/tile_store: a link, a file or a folder lidarfx did not make is refused and nothing in it is touched")
{
    io_test::temp_dir dir;
    const std::filesystem::path theirs = dir.file("theirs");
    std::filesystem::create_directories(theirs);
    const std::vector<std::uint8_t> precious{'k', 'e', 'e', 'p'};
    for (const char* name : {"tile_0.bin", "manifest.txt", "notes"})
        io_test::write_bytes((theirs / name).string(), precious);
    const auto untouched = [&] {
        for (const char* name : {"tile_0.bin", "manifest.txt", "notes"})
            CHECK(io_test::read_bytes((theirs / name).string()) == precious);
    };
    // A symlink at the store's name, to a folder of someone's files.
    const std::filesystem::path link = dir.file("link");
    std::filesystem::create_directory_symlink(theirs, link);
    CHECK(io_test::contains(io_test::error_of([&] { cli::tile_store s(link, "A\n"); }), "is a symbolic link"));
    CHECK_THROWS_AS(cli::tile_store(link, "A\n"), cli::usage_error);
    cli::remove_tile_folder(link);
    untouched();
    // The folder itself, without the marker.
    CHECK(io_test::contains(io_test::error_of([&] { cli::tile_store s(theirs, "A\n"); }), "not a lidarfx tile folder"));
    cli::remove_tile_folder(theirs);
    untouched();
    // A file at the store's name.
    const std::filesystem::path file = dir.file("file");
    io_test::write_bytes(file.string(), precious);
    CHECK(io_test::contains(io_test::error_of([&] { cli::tile_store s(file, "A\n"); }), "is not a folder"));
    CHECK(io_test::read_bytes(file.string()) == precious);
    // A store of ours holding a file it did not write: refused, under either fingerprint; the file stays.
    const std::filesystem::path ours = dir.file("ours");
    {
        cli::tile_store s(ours, "A\n");
        s.save(1, {1});
    }
    io_test::write_bytes((ours / "notes").string(), precious);
    for (const char* fingerprint : {"A\n", "B\n"})
        CHECK(io_test::contains(io_test::error_of([&] { cli::tile_store s(ours, fingerprint); }),
                                "notes, which lidarfx did not write"));
    CHECK(std::filesystem::exists(ours / "tile_1.bin"));
    cli::remove_tile_folder(ours);  // removes its own files only, and keeps the folder for the foreign one
    CHECK(io_test::read_bytes((ours / "notes").string()) == precious);
    CHECK(!std::filesystem::exists(ours / "tile_1.bin"));
}

TEST_CASE(
    "io/tiled_survey: tiles altered between runs are recomputed; the resumed survey is a clean run's, bit for bit")
{
    io_test::temp_dir dir;
    const auto paths = write_lake_survey(dir);
    const auto o = quiet(2.0, 2);
    const auto want = cli::read_survey(paths, o);
    const std::filesystem::path kept = dir.file("kept");
    check_same_survey(want, cli::read_survey_tiled(paths, o, 60.0, kept));  // 25 tiles, all kept
    const auto tile = [&](int t) { return (kept / ("tile_" + std::to_string(t) + ".bin")).string(); };
    REQUIRE(std::filesystem::is_regular_file(tile(24)));
    auto flipped = io_test::read_bytes(tile(3));
    flipped[flipped.size() / 2] ^= 0x10;  // one bit of a raster cell
    io_test::write_bytes(tile(3), flipped);
    std::filesystem::copy_file(tile(5), tile(4),
                               std::filesystem::copy_options::overwrite_existing);  // a neighbour's copy
    std::filesystem::remove(tile(6));
    std::filesystem::create_symlink(tile(7), tile(6));  // a link to a neighbour
    std::filesystem::remove(tile(8));
    REQUIRE(::mkfifo(tile(8).c_str(), 0644) == 0);  // would block a plain open
    for (const int threads : {1, 2}) {
        CAPTURE(threads);
        check_same_survey(want, cli::read_survey_tiled(paths, quiet(2.0, threads), 60.0, kept));
    }
    CHECK(std::filesystem::is_symlink(tile(6)));  // not ours: left as it was
    CHECK(std::filesystem::is_fifo(tile(8)));
    cli::tile_store store(kept, cli::tiled_fingerprint(paths, o, 60.0));
    CHECK(store.done_count() == 23);  // 3 and 4 recomputed and saved again; 6 and 8 not saved
}

TEST_CASE("io/tiled_fingerprint: an input edited in place, its size and modification time kept, is another input")
{
    io_test::temp_dir dir;
    const auto paths = write_lake_survey(dir);
    const auto o = quiet(2.0, 1);
    const auto before = cli::tiled_fingerprint(paths, o, 60.0);
    struct stat st {};
    REQUIRE(::stat(paths[4].c_str(), &st) == 0);
    auto bytes = io_test::read_bytes(paths[4]);
    REQUIRE(bytes.size() > 20000);
    bytes[bytes.size() - 3000] ^= 0x01;  // a point's coordinate, in the last 64 KiB
    io_test::write_bytes(paths[4], bytes);
    const struct timespec times[2] = {st.st_atim, st.st_mtim};
    REQUIRE(::utimensat(AT_FDCWD, paths[4].c_str(), times, 0) == 0);
    CHECK(cli::tiled_fingerprint(paths, o, 60.0) != before);
}

TEST_CASE("io/write_file_atomically: a failed write names the system's reason and leaves no temporary")
{
    io_test::temp_dir dir;
    const std::string path = dir.file("tile_1.bin");
    io_test::write_bytes(path, {7, 7});
    // A file size limit makes write() fail (EFBIG) as a full disk makes it fail (ENOSPC); the signal is ignored.
    const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
    struct rlimit old_limit {};
    REQUIRE(::getrlimit(RLIMIT_FSIZE, &old_limit) == 0);
    struct rlimit small = old_limit;
    small.rlim_cur = 4096;
    REQUIRE(::setrlimit(RLIMIT_FSIZE, &small) == 0);
    const auto error =
        io_test::error_of([&] { cli::write_file_atomically(path, std::vector<std::uint8_t>(100000, 1)); });
    ::setrlimit(RLIMIT_FSIZE, &old_limit);
    std::signal(SIGXFSZ, old_handler);
    CHECK(io_test::contains(error, "write failed (File too large)"));
    CHECK(io_test::read_bytes(path) == std::vector<std::uint8_t>{7, 7});  // the earlier file as it was
    std::size_t entries = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.file(""))) ++entries;
    CHECK(entries == 1);  // no temporary left
}

TEST_CASE("io/survey_files: a folder stands for its LAS and LAZ files sorted by name; files pass as they are")
{
    io_test::temp_dir dir;
    const std::filesystem::path folder = dir.file("survey");
    std::filesystem::create_directories(folder);
    for (const char* name : {"b.las", "a.LAZ", "c.las", "notes.txt"})
        io_test::write_bytes((folder / name).string(), {0});
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
