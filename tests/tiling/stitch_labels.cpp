// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/kernels/label/connected_components.hpp>
#include <lidarfx/tiling/stitch_labels.hpp>

#include "reference/morphology.hpp"

#include <array>
#include <cstdint>
#include <random>
#include <vector>

using namespace lidarfx;

namespace {

constexpr std::array<connectivity, 2> both_connectivities{connectivity::four, connectivity::eight};

// stitch_labels against connected_components, component_bounds and a plain per-label sum.
void check_against_whole(raster_view<const std::uint8_t> m, const raster<std::int32_t>& values, connectivity conn,
                         std::ptrdiff_t tile_cells, int threads = 1)
{
    CAPTURE(tile_cells);
    CAPTURE(conn == connectivity::eight);
    const components whole = connected_components(m, conn);
    const stitched_components got =
        stitch_labels(m, values, {.conn = conn, .tile_cells = tile_cells, .run = {.threads = threads}});
    CHECK(got.labels == whole.labels);
    CHECK(got.sizes == whole.sizes);
    CHECK(got.boxes == component_bounds(whole));
    std::vector<std::int64_t> sums(whole.sizes.size(), 0);
    for (std::ptrdiff_t r = 0; r < m.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < m.cols(); ++c) sums[std::size_t(whole.labels(r, c))] += values(r, c);
    CHECK(got.sums == sums);
    CHECK(got.count() == whole.count());
}

reference::mask from_rows(const std::vector<const char*>& rows)
{
    reference::mask m(std::ptrdiff_t(rows.size()), std::ptrdiff_t(std::char_traits<char>::length(rows[0])));
    for (std::ptrdiff_t r = 0; r < m.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < m.cols(); ++c) m(r, c) = rows[std::size_t(r)][c] == '#';
    return m;
}

raster<std::int32_t> ramp(std::ptrdiff_t rows, std::ptrdiff_t cols)
{
    raster<std::int32_t> v(rows, cols);
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c) v(r, c) = std::int32_t(1000 * r + c - 50000);
    return v;
}

}  // namespace

TEST_CASE("tiling/stitch_labels: equals connected_components on random masks for any tile size")
{
    std::mt19937 rng(1510);
    std::uniform_int_distribution<std::int32_t> value(-1000000, 1000000);
    for (int trial = 0; trial < 24; ++trial) {
        CAPTURE(trial);
        const double density = 0.2 + 0.1 * (trial % 6);  // below, near and above the percolation threshold
        const reference::mask big = reference::random_mask(rng, 66, 75, density);
        const raster_view<const std::uint8_t> m = raster_view<const std::uint8_t>(big.view()).window(3, 5, 61, 67);
        raster<std::int32_t> values(61, 67);
        for (auto& v : values) v = value(rng);
        for (const connectivity conn : both_connectivities) {
            for (const std::ptrdiff_t t : {1, 2, 7, 60, 100000}) check_against_whole(m, values, conn, t);
        }
        check_against_whole(m, values, connectivity::eight, 5, 2);  // threads change nothing
    }
}

TEST_CASE("tiling/stitch_labels: one label across many tiles, a U joined only in a later tile, corners")
{
    // A snake crossing many 2 x 2 tiles, a U whose arms meet only at the bottom (tiles further
    // down), cells touching only at tile corners (8-connected, not 4-connected), a single cell.
    const reference::mask m = from_rows({
        "##########..#...#",
        ".........#..#...#",
        "##########..#...#",
        "#...........#...#",
        "##########..#####",
        "..........#......",
        "...........#...#.",
        "#...........###..",
    });
    const raster<std::int32_t> v = ramp(m.rows(), m.cols());
    for (const connectivity conn : both_connectivities) {
        for (const std::ptrdiff_t t : {1, 2, 3, 5, 7, 10, 11, 60}) check_against_whole(m, v, conn, t);
    }
    // By hand: the snake (32 cells), then the chain of diagonal cells (5, 10), (6, 11), (7, 12..14), (6, 15);
    // the U (13 cells), whose arms are separate pieces in the tiles above row 4; the lone cell (7, 0).
    const stitched_components eight = stitch_labels(m, {.conn = connectivity::eight, .tile_cells = 2});
    CHECK(eight.count() == 3);
    CHECK(eight.sizes == std::vector<std::size_t>{136 - 38 - 13 - 1, 38, 13, 1});
    CHECK(eight.labels(7, 0) == 3);
    CHECK(eight.labels(6, 15) == 1);
    CHECK(eight.boxes[1] == cell_box{0, 0, 7, 15});
    CHECK(eight.boxes[2] == cell_box{0, 12, 4, 16});
    const stitched_components four = stitch_labels(m, {.conn = connectivity::four, .tile_cells = 2});
    CHECK(four.count() == 7);
    CHECK(four.sizes == std::vector<std::size_t>{136 - 38 - 13 - 1, 32, 13, 1, 1, 1, 1, 3});
}

TEST_CASE("tiling/stitch_labels: diagonal contacts exactly at tile corners")
{
    // Checkerboard: under 8-connectivity one component, every contact a diagonal, many at tile corners.
    const reference::mask board = reference::checkerboard(9, 10);
    const raster<std::int32_t> v = ramp(9, 10);
    for (const std::ptrdiff_t t : {1, 2, 3, 4}) {
        check_against_whole(board, v, connectivity::eight, t);
        check_against_whole(board, v, connectivity::four, t);
    }
    CHECK(stitch_labels(board, {.conn = connectivity::eight, .tile_cells = 2}).count() == 1);
    CHECK(stitch_labels(board, {.conn = connectivity::four, .tile_cells = 2}).count() == 45);
}

TEST_CASE("tiling/stitch_labels: empty, full, 1 x 1 and refusals")
{
    const raster<std::int32_t> v0(0, 0);
    const reference::mask empty(0, 0);
    CHECK(stitch_labels(empty).count() == connected_components(empty).count());
    const reference::mask full(13, 9, 1), none(13, 9, 0), one(1, 1, 7);
    const raster<std::int32_t> v = ramp(13, 9);
    for (const std::ptrdiff_t t : {1, 4, 100}) {
        check_against_whole(full, v, connectivity::four, t);
        check_against_whole(none, v, connectivity::eight, t);
        check_against_whole(one, ramp(1, 1), connectivity::eight, t);
    }
    CHECK_THROWS_AS(stitch_labels(full, {.tile_cells = 0}), invalid_input);
    CHECK_THROWS_AS(stitch_labels(full, {.run = {.threads = -1}}), invalid_input);
    CHECK_THROWS_AS(stitch_labels(full, ramp(13, 8)), invalid_input);
}
