// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/tiling/tile_plan.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

using namespace lidarfx;

namespace {

// The tile whose core holds cell (r, c).
const survey_tile& tile_of(const tile_plan& p, std::ptrdiff_t r, std::ptrdiff_t c)
{
    return p.tiles[static_cast<std::size_t>((r / p.tile_cells) * p.tile_cols + c / p.tile_cells)];
}

bool inside(const cell_box& b, std::ptrdiff_t r, std::ptrdiff_t c)
{
    return r >= b.row_min && r <= b.row_max && c >= b.col_min && c <= b.col_max;
}

std::string message_of(const grid& g, const std::vector<survey_file_extent>& files, const tile_plan_options& opt)
{
    try {
        (void)make_tile_plan(g, files, opt);
    } catch (const invalid_input& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("tiling/make_tile_plan: cores partition the grid, row-major, the last row and column smaller")
{
    const grid g{1000, 5000, 2, 23, 17};
    for (const double edge_m : {1.0, 2.0, 14.0, 20.0, 34.0, 46.0, 1000.0}) {
        const tile_plan p = make_tile_plan(g, {}, {.tile_edge_m = edge_m, .halo_cells = 3});
        CAPTURE(edge_m);
        CHECK(p.tile_cells == std::clamp<std::ptrdiff_t>(std::ptrdiff_t(std::lround(edge_m / 2)), 1, 23));
        CHECK(p.tile_rows == (23 + p.tile_cells - 1) / p.tile_cells);
        CHECK(p.tile_cols == (17 + p.tile_cells - 1) / p.tile_cells);
        REQUIRE(p.tiles.size() == std::size_t(p.tile_rows * p.tile_cols));
        std::vector<int> owners(std::size_t(g.size()), 0);
        for (std::size_t i = 0; i < p.tiles.size(); ++i) {
            const survey_tile& t = p.tiles[i];
            CHECK(t.index == i);
            CHECK(t.core.row_min == std::ptrdiff_t(i) / p.tile_cols * p.tile_cells);
            CHECK(t.core.col_min == std::ptrdiff_t(i) % p.tile_cols * p.tile_cells);
            CHECK(t.with_halo.row_min == std::max<std::ptrdiff_t>(0, t.core.row_min - 3));
            CHECK(t.with_halo.col_max == std::min<std::ptrdiff_t>(16, t.core.col_max + 3));
            CHECK(t.files.empty());  // no files: every tile is kept, empty
            for (std::ptrdiff_t r = t.core.row_min; r <= t.core.row_max; ++r)
                for (std::ptrdiff_t c = t.core.col_min; c <= t.core.col_max; ++c) ++owners[std::size_t(r * 17 + c)];
        }
        CHECK(std::all_of(owners.begin(), owners.end(), [](int n) { return n == 1; }));
    }
}

TEST_CASE("tiling/make_tile_plan: a tile lists every file that has a point in its halo")
{
    std::mt19937 rng(15015);
    std::uniform_real_distribution<double> u(0, 1);
    for (int trial = 0; trial < 40; ++trial) {
        CAPTURE(trial);
        const double cell = trial % 2 ? 0.5 : 2.0;
        // Files on a jittered grid of extents, some reaching outside the survey grid, some on lattice lines.
        std::vector<survey_file_extent> files;
        std::vector<std::vector<std::array<double, 2>>> points;
        for (int i = 0; i < 9; ++i) {
            double x0 = 500000 + 30 * (i % 3) + (trial % 3 == 0 ? 0 : 10 * u(rng)) - 5;
            double y0 = 4000000 + 30 * (i / 3) + (trial % 3 == 0 ? 0 : 10 * u(rng)) - 5;
            if (trial % 3 == 0) {
                x0 = std::round(x0 / cell) * cell;
                y0 = std::round(y0 / cell) * cell;
            }
            const double w = trial % 3 == 0 ? 30 : 5 + 40 * u(rng), h = trial % 3 == 0 ? 30 : 5 + 40 * u(rng);
            std::vector<std::array<double, 2>> pts{{x0, y0}, {x0 + w, y0 + h}, {x0, y0 + h}, {x0 + w, y0}};
            for (int k = 0; k < 200; ++k) pts.push_back({x0 + w * u(rng), y0 + h * u(rng)});
            files.push_back({{x0, y0, x0 + w, y0 + h}, std::uint64_t(pts.size())});
            points.push_back(pts);
        }
        const grid g = snapped_grid({500000, 4000000, 500080, 4000080}, cell);  // cuts some files
        const tile_plan p =
            make_tile_plan(g, files, {.tile_edge_m = cell * double(1 + trial % 13), .halo_cells = trial % 4});
        for (std::size_t f = 0; f < files.size(); ++f) {
            for (const auto& pt : points[f]) {
                const auto at = g.cell_of(pt[0], pt[1]);
                if (!at) continue;
                for (const survey_tile& t : p.tiles) {
                    if (!inside(t.with_halo, at->row, at->col)) continue;
                    CHECK(std::binary_search(t.files.begin(), t.files.end(), f));
                }
                CHECK(inside(tile_of(p, at->row, at->col).core, at->row, at->col));
            }
        }
        for (const survey_tile& t : p.tiles) CHECK(std::is_sorted(t.files.begin(), t.files.end()));
    }
}

TEST_CASE("tiling/make_tile_plan: a file is listed only where its box can land, halo included")
{
    const grid g{0, 100, 1, 100, 100};
    // One file in cells rows 10..19 and cols 30..39 (x 30..39.5, y 80.5..90).
    const std::vector<survey_file_extent> files{{{30, 80.5, 39.5, 90}, 1000}};
    const tile_plan p = make_tile_plan(g, files, {.tile_edge_m = 10, .halo_cells = 1});
    for (const survey_tile& t : p.tiles) {
        const bool touches = t.with_halo.row_max >= 10 && t.with_halo.row_min <= 19 && t.with_halo.col_max >= 30 &&
                             t.with_halo.col_min <= 39;
        CAPTURE(t.index);
        CHECK(t.files.size() == (touches ? 1u : 0u));
    }
    // Only the core holding the whole box expects its points: uniform density.
    CHECK(tile_of(p, 10, 30).points_estimate == 1000);
    CHECK(tile_of(p, 9, 30).points_estimate == 0);
    CHECK(tile_of(p, 9, 30).files == std::vector<std::size_t>{0});   // halo reaches row 10
    CHECK(tile_of(p, 25, 30).files == std::vector<std::size_t>{0});  // halo reaches row 19
    CHECK(tile_of(p, 35, 30).files.empty());
    CHECK(tile_of(p, 10, 55).files.empty());
}

TEST_CASE("tiling/make_tile_plan: points_estimate splits a file by area and sums to its points")
{
    const grid g{0, 40, 1, 40, 40};
    const std::vector<survey_file_extent> files{{{5, 5, 35, 35}, 9000}, {{-10, 0, 10, 40}, 400}, {{20, 20, 20, 20}, 7}};
    const tile_plan p = make_tile_plan(g, files, {.tile_edge_m = 20});
    REQUIRE(p.tiles.size() == 4);
    // File 0: a quarter in each tile; file 1: half of it outside the grid, split between tiles 0 and 2;
    // file 2 is one point on the lattice corner (20, 20): cell (20, 20), the south-east tile.
    CHECK(p.tiles[0].points_estimate == 2250 + 100);
    CHECK(p.tiles[1].points_estimate == 2250);
    CHECK(p.tiles[2].points_estimate == 2250 + 100);
    CHECK(p.tiles[3].points_estimate == 2250 + 7);
}

TEST_CASE("tiling/make_tile_plan: 1-cell grid, zero-point files, files outside the grid, tiny edges")
{
    const grid one{10, 20, 1, 1, 1};
    const std::vector<survey_file_extent> files{{{10, 19, 11, 20}, 0}, {{50, 50, 60, 60}, 99}, {{-5, -5, -1, -1}, 5}};
    const tile_plan p = make_tile_plan(one, files);
    REQUIRE(p.tiles.size() == 1);
    CHECK(p.tile_cells == 1);
    CHECK(p.tiles[0].files == std::vector<std::size_t>{0});
    CHECK(p.tiles[0].points_estimate == 0);
    CHECK(p.tiles[0].core == cell_box{0, 0, 0, 0});
    CHECK(p.tiles[0].with_halo == cell_box{0, 0, 0, 0});

    const grid g{0, 10, 2, 5, 5};
    CHECK(make_tile_plan(g, {}, {.tile_edge_m = 0.3}).tile_cells == 1);  // below a cell: 1 cell
    CHECK(make_tile_plan(g, {}, {.tile_edge_m = 3.1}).tile_cells == 2);  // rounded to whole cells
    CHECK(make_tile_plan(g, {}, {}).tile_cells == 5);                    // no budget, no edge: one tile
    CHECK(make_tile_plan(g, {}, {.halo_cells = 1000000}).tiles[0].with_halo == cell_box{0, 0, 4, 4});
}

TEST_CASE("tiling/make_tile_plan: peak_bytes_estimate follows the memory model")
{
    const grid g{0, 0, 1, 100, 80};
    const tile_plan_options opt{.tile_edge_m = 30,
                                .halo_cells = 2,
                                .bytes_per_cell = 10,
                                .bytes_per_tile_cell = 3,
                                .bytes_per_point = 5,
                                .chunk_points = 1000,
                                .tiles_in_flight = 2};
    const tile_plan p = make_tile_plan(g, {}, opt);
    // The largest with_halo is an interior tile: 34 x 34 cells.
    CHECK(p.peak_bytes_estimate == doctest::Approx(8000.0 * 10 + 2 * (34.0 * 34 * 3 + 1000 * 5)));
}

TEST_CASE("tiling/make_tile_plan: the budget picks the largest edge that fits and refuses what does not")
{
    const grid g{0, 0, 1, 1000, 1000};
    tile_plan_options opt{.halo_cells = 10,
                          .memory_budget_bytes = 0,
                          .bytes_per_cell = 64,
                          .bytes_per_tile_cell = 48,
                          .bytes_per_point = 40,
                          .chunk_points = 1 << 16};
    const double fixed = 1e6 * 64 + 65536.0 * 40;
    opt.memory_budget_bytes = std::uint64_t(fixed + 48.0 * 220 * 220);  // with_halo of 200 + 2 x 10 fits
    const tile_plan p = make_tile_plan(g, {}, opt);
    CHECK(p.tile_cells == 200);
    CHECK(p.peak_bytes_estimate <= double(opt.memory_budget_bytes));
    opt.memory_budget_bytes -= 1;
    CHECK(make_tile_plan(g, {}, opt).tile_cells == 199);

    opt.tile_edge_m = 300;  // explicit edge over the budget: the message names the edge that fits
    const std::string big = message_of(g, {}, opt);
    CHECK(big.find("make_tile_plan: tile_edge_m 300") != std::string::npos);
    CHECK(big.find("largest tile edge that fits is 199 m (199 cells)") != std::string::npos);

    opt.tile_edge_m = 0;
    opt.memory_budget_bytes = 32'000'000;  // the grid alone needs 64 MB: a coarser cell is proposed
    const std::string coarse = message_of(g, {}, opt);
    CHECK(coarse.find("the survey grid alone (1000 x 1000 cells") != std::string::npos);
    CHECK(coarse.find("m instead of 1 m would fit") != std::string::npos);
    opt.memory_budget_bytes = 1000;  // not even the chunk buffers fit
    CHECK(message_of(g, {}, opt).find("chunk buffers alone") != std::string::npos);
}

TEST_CASE("tiling/make_tile_plan: the proposed cell size does fit")
{
    const grid g{0, 0, 0.5, 3000, 2000};
    tile_plan_options opt{.memory_budget_bytes = 100'000'000};
    const std::string m = message_of(g, {}, opt);
    const auto at = m.find("a cell of ");
    REQUIRE(at != std::string::npos);
    const double cell = std::stod(m.substr(at + 10));
    CHECK(cell > 0.5);
    const grid coarse = snapped_grid(g.extent(), cell);
    CHECK_NOTHROW(make_tile_plan(coarse, {}, opt));
}

TEST_CASE("tiling/make_tile_plan: refuses bad options and extents")
{
    const grid g{0, 0, 1, 10, 10};
    const double nan = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_AS(make_tile_plan(g, {}, {.tile_edge_m = nan}), invalid_input);
    CHECK_THROWS_AS(make_tile_plan(g, {}, {.tile_edge_m = -1}), invalid_input);
    CHECK_THROWS_AS(make_tile_plan(g, {}, {.halo_cells = -1}), invalid_input);
    CHECK_THROWS_AS(make_tile_plan(g, {}, {.bytes_per_cell = nan}), invalid_input);
    CHECK_THROWS_AS(make_tile_plan(g, {}, {.bytes_per_tile_cell = -1}), invalid_input);
    CHECK_THROWS_AS(make_tile_plan(g, {}, {.bytes_per_point = std::numeric_limits<double>::infinity()}), invalid_input);
    CHECK_THROWS_AS(make_tile_plan(g, {}, {.tiles_in_flight = 0}), invalid_input);
    CHECK_THROWS_AS(make_tile_plan(grid{0, 0, 1, 0, 5}, {}), invalid_input);
    const std::vector<survey_file_extent> flipped{{{5, 5, 4, 6}, 1}};
    CHECK(message_of(g, flipped, {}).find("file 0: extent must be finite with min <= max") != std::string::npos);
    const std::vector<survey_file_extent> nan_box{{{nan, 5, 4, 6}, 1}};
    CHECK_THROWS_AS(make_tile_plan(g, nan_box), invalid_input);
}

TEST_CASE("tiling/assign_file_readers: files cut along the tile lines are read once, their slivers handed on")
{
    // 4 x 4 tiles of 100 cells; 4 x 4 files of 100 m whose boxes end on the tile lines, so that each also
    // reaches one column into the tile east of it and one row into the tile south of it.
    const grid g{0, 400, 1, 400, 400};
    std::vector<survey_file_extent> files;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) files.push_back({{c * 100.0, r * 100.0, c * 100.0 + 100, r * 100.0 + 100}, 10000});
    const tile_plan p = make_tile_plan(g, files, {.tile_edge_m = 100});
    REQUIRE(p.tiles.size() == 16);
    std::vector<double> per_tile;
    const auto readers = assign_file_readers(p, files, 1000, &per_tile);
    REQUIRE(per_tile.size() == p.tiles.size());
    double handed = 0;
    for (const double h : per_tile) handed += h;
    CHECK(per_tile[0] == 0);  // the north-west tile is nobody's east or south neighbour
    REQUIRE(readers.size() == files.size());
    double expected = 0;
    for (std::size_t f = 0; f < files.size(); ++f) {
        CAPTURE(f);
        const int r = int(f) / 4, c = int(f) % 4;
        const std::size_t home = std::size_t((3 - r) * 4 + c);  // the tile of its 100 x 100 cells (rows run south)
        CHECK(readers[f].home == home);
        std::vector<std::size_t> slivers;  // east, south, south-east when inside the grid
        for (const auto& t : p.tiles)
            if (t.index != home && std::find(t.files.begin(), t.files.end(), f) != t.files.end())
                slivers.push_back(t.index);
        CHECK(readers[f].handed_to == slivers);
        CHECK(slivers.size() == std::size_t((c < 3) + (r > 0) + (c < 3 && r > 0)));
        // The range has one more column and row where a sliver is (the grid's far borders fold into the last
        // cell); the slivers hold 100, 100 and 1 of its cells; uniform density.
        const double cells = (c < 3 ? 101.0 : 100.0) * (r > 0 ? 101.0 : 100.0);
        for (const std::size_t t : slivers) expected += 10000.0 * (t == home + 5 ? 1 : 100) / cells;
    }
    CHECK(handed == doctest::Approx(expected));
    // Larger shares than allowed, or nothing allowed: every listing tile reads the file itself.
    for (const std::uint64_t max : {std::uint64_t{50}, std::uint64_t{0}}) {
        const auto strict = assign_file_readers(p, files, max);
        for (std::size_t f = 0; f < files.size(); ++f) {
            CHECK(strict[f].home == readers[f].home);
            for (const std::size_t t : strict[f].handed_to) CHECK(t == strict[f].home + 5);  // 1 cell: ~1 point
            if (max == 0) CHECK(strict[f].handed_to.empty());
        }
    }
}

TEST_CASE("tiling/assign_file_readers: a file over many tiles is handed only to its home's neighbours")
{
    const grid g{0, 400, 1, 400, 400};
    const std::vector<survey_file_extent> files{{{0.5, 0.5, 399.5, 399.5}, 1000}, {{-50, -50, -10, -10}, 5}};
    const tile_plan p = make_tile_plan(g, files, {.tile_edge_m = 100});
    const auto readers = assign_file_readers(p, files, 100);
    CHECK(readers[0].home == 0);  // every tile holds 100 x 100 of its cells: the lowest index wins
    CHECK(readers[0].handed_to == std::vector<std::size_t>{1, 4, 5});
    CHECK(readers[1].home == p.tiles.size());  // outside the grid: no tile lists it
    CHECK(readers[1].handed_to.empty());
    CHECK_THROWS_AS(assign_file_readers(p, std::vector<survey_file_extent>{}, 100),
                    invalid_input);  // plan lists file 0
}
