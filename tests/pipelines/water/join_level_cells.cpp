// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/pipelines/water/join_level_cells.hpp>

#include <cmath>
#include <deque>
#include <random>
#include <vector>

#include "water_test_rasters.hpp"

using namespace lidarfx;
using water_test::grid_of;

namespace {

struct strip {
    raster<float> min_z, max_z;
    raster<std::uint8_t> eligible;
    explicit strip(std::initializer_list<float> z)
        : min_z(1, static_cast<std::ptrdiff_t>(z.size())),
          max_z(1, static_cast<std::ptrdiff_t>(z.size())),
          eligible(1, static_cast<std::ptrdiff_t>(z.size()), 1)
    {
        std::ptrdiff_t c = 0;
        for (const float v : z) min_z(0, c) = max_z(0, c) = v, ++c;
    }
    std::vector<std::ptrdiff_t> join(std::vector<std::ptrdiff_t> region, const join_level_cells_options& o)
    {
        join_level_cells(region, min_z, max_z, eligible, o);
        return region;
    }
};

using cells = std::vector<std::ptrdiff_t>;
constexpr join_level_cells_options eighth{.tolerance_m = 0.125, .max_rise_m = 0.5, .depth_cells = 2};

/// The refinement by definition: a FIFO walk started from EVERY region cell with a return (the step under
/// test starts only from edge cells), each carrying the level of the cell it started from.
cells reference_join(cells region, const raster<float>& lo, const raster<float>& hi,
                     const raster<std::uint8_t>& eligible, const join_level_cells_options& o)
{
    if (o.tolerance_m <= 0 || o.depth_cells <= 0) return region;
    const std::ptrdiff_t rows = lo.rows(), cols = lo.cols();
    std::vector<std::uint8_t> in(static_cast<std::size_t>(rows * cols), 0);
    struct entry {
        std::ptrdiff_t cell;
        double level;
        int depth;
    };
    std::deque<entry> queue;
    for (const auto i : region) in[static_cast<std::size_t>(i)] = 1;
    for (const auto i : region)
        if (std::isfinite(lo.data()[i])) queue.push_back({i, lo.data()[i], 0});
    while (!queue.empty()) {
        const entry e = queue.front();
        queue.pop_front();
        if (e.depth >= o.depth_cells) continue;
        for (std::ptrdiff_t dr = -1; dr <= 1; ++dr)
            for (std::ptrdiff_t dc = -1; dc <= 1; ++dc) {
                const std::ptrdiff_t r = e.cell / cols + dr, c = e.cell % cols + dc;
                if (r < 0 || c < 0 || r >= rows || c >= cols) continue;
                const auto j = r * cols + c;
                if (in[static_cast<std::size_t>(j)] || !eligible(r, c) || !std::isfinite(lo(r, c))) continue;
                if (std::abs(lo(r, c) - e.level) > o.tolerance_m || !(hi(r, c) - e.level <= o.max_rise_m)) continue;
                in[static_cast<std::size_t>(j)] = 1;
                region.push_back(j);
                queue.push_back({j, e.level, e.depth + 1});
            }
    }
    return region;
}

}  // namespace

TEST_CASE("water/join_level_cells: cells at the water level join, up to depth_cells steps away")
{
    strip s{10.0f, 10.0f, 10.125f, 10.125f, 10.125f, 10.0f};
    // Cell 2 is within 0.125 m (inclusive) of the level 10 of cell 1, cell 3 too and two steps away; cell 4
    // would be the third step.
    CHECK(s.join({0, 1}, eighth) == cells{0, 1, 2, 3});
    strip deeper{10.0f, 10.0f, 10.125f, 10.125f, 10.125f, 10.0f};
    CHECK(deeper.join({0, 1}, {.tolerance_m = 0.125, .depth_cells = 3}) == cells{0, 1, 2, 3, 4});
}

TEST_CASE("water/join_level_cells: the level is the region's, not the last joined cell's")
{
    // Cell 3 is within tolerance of cell 2 but not of the water level 10 the walk carries.
    strip s{10.0f, 10.0f, 10.125f, 10.25f};
    CHECK(s.join({0, 1}, eighth) == cells{0, 1, 2});
}

TEST_CASE("water/join_level_cells: the highest return may rise max_rise_m above the level, inclusive")
{
    strip s{10.0f, 10.0f, 10.0f, 10.0f};
    s.max_z(0, 2) = 10.5f;
    CHECK(s.join({0, 1}, eighth) == cells{0, 1, 2, 3});
    strip bank{10.0f, 10.0f, 10.0f, 10.0f};
    bank.max_z(0, 2) = 10.625f;  // a shore cell: water below, bank above
    CHECK(bank.join({0, 1}, eighth) == cells{0, 1});
}

TEST_CASE("water/join_level_cells: no returns, vegetation and disabled options join nothing")
{
    strip nan_cell{10.0f, 10.0f, NAN, 10.0f};
    CHECK(nan_cell.join({0, 1}, eighth) == cells{0, 1});
    strip veg{10.0f, 10.0f, 10.0f};
    veg.eligible(0, 2) = 0;
    CHECK(veg.join({0, 1}, eighth) == cells{0, 1});
    // A region whose cells have no return has no level to offer.
    strip dry{NAN, NAN, 10.0f};
    CHECK(dry.join({0, 1}, eighth) == cells{0, 1});
    strip off{10.0f, 10.0f, 10.0f};
    CHECK(off.join({0, 1}, {.tolerance_m = 0}) == cells{0, 1});
    CHECK(off.join({0, 1}, {.depth_cells = 0}) == cells{0, 1});
}

TEST_CASE("water/join_level_cells: the walk reaches diagonal neighbours")
{
    const auto z = grid_of<float>({{10.0f, 12.0f, 12.0f},  //
                                   {12.0f, 10.0f, 12.0f},
                                   {12.0f, 12.0f, 10.0f}});
    raster<std::uint8_t> eligible(3, 3, 1);
    cells region{0};
    join_level_cells(region, z, z, eligible, eighth);
    CHECK(region == cells{0, 4, 8});
}

TEST_CASE("water/join_level_cells: starting from edge cells equals starting from every cell, on random scenes")
{
    std::mt19937 rng(3131);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    int grew = 0;
    for (int trial = 0; trial < 180; ++trial) {
        CAPTURE(trial);
        // One row or one column now and then; the region a blob (it fills its box: the edge is flagged by a
        // pass over the box), scattered cells or two blobs far apart (cell by cell).
        const std::ptrdiff_t rows = 1 + rng() % 25, cols = 1 + rng() % 25;
        raster<float> lo(rows, cols), hi(rows, cols);
        raster<std::uint8_t> eligible(rows, cols);
        for (std::ptrdiff_t i = 0; i < lo.size(); ++i) {
            const float pick = u(rng);
            lo.data()[i] = pick < 0.1f ? NAN : 10.0f + (pick < 0.6f ? 0.2f * u(rng) : 2.0f * u(rng));
            hi.data()[i] = lo.data()[i] + (u(rng) < 0.8f ? 0.3f * u(rng) : 3.0f);
            eligible.data()[i] = u(rng) < 0.9f;
        }
        cells region;
        const int shape = trial % 3;
        const auto r0 = static_cast<std::ptrdiff_t>(rng() % static_cast<unsigned>(rows));
        const auto c0 = static_cast<std::ptrdiff_t>(rng() % static_cast<unsigned>(cols));
        const double radius = 1.0 + 4.0 * u(rng);
        for (std::ptrdiff_t r = 0; r < rows; ++r) {
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                const double near = std::hypot(static_cast<double>(r - r0), static_cast<double>(c - c0));
                const double far =
                    std::hypot(static_cast<double>(r - (rows - 1 - r0)), static_cast<double>(c - (cols - 1 - c0)));
                const bool in = shape == 0 ? near <= radius : shape == 1 ? u(rng) < 0.08f : near <= 1.0 || far <= 1.0;
                if (in) region.push_back(r * cols + c);
            }
        }
        std::shuffle(region.begin(), region.end(), rng);
        const join_level_cells_options o{
            .tolerance_m = 0.05 + 0.2 * u(rng), .max_rise_m = 0.5 * u(rng), .depth_cells = static_cast<int>(rng() % 4)};
        cells got = region;
        join_level_cells(got, lo, hi, eligible, o);
        CHECK(got == reference_join(region, lo, hi, eligible, o));
        grew += got.size() > region.size();
    }
    CHECK(grew > 45);
}

TEST_CASE("water/join_level_cells: bad arguments are refused")
{
    strip s{10.0f, 10.0f};
    CHECK_THROWS_WITH_AS(s.join({0, 2}, {}), "join_level_cells: region cell index must be inside the rasters (got 2)",
                         invalid_input);
    CHECK_THROWS_WITH_AS(s.join({0}, {.max_rise_m = -1}), "join_level_cells: max_rise_m must be >= 0 (got -1)",
                         invalid_input);
    raster<std::uint8_t> wrong(2, 2, 1);
    cells region{0};
    CHECK_THROWS_AS(join_level_cells(region, s.min_z, s.max_z, wrong), invalid_input);
}
