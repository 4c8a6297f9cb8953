// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/core/error.hpp>
#include <lidarfx/kernels/filter/geodesic_distance.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

#include "reference/geodesic.hpp"
#include "reference/morphology.hpp"

using namespace lidarfx;

namespace geodesic_test {

constexpr float unreached = std::numeric_limits<float>::infinity();

/// Cells where the kernel and the Bellman-Ford reference differ. Both take the minimum over paths of the same
/// double sums (rounding is monotone), so after the conversion to float they agree exactly.
std::ptrdiff_t differences(raster_view<const std::uint8_t> inside, std::ptrdiff_t r, std::ptrdiff_t c, double cell_m)
{
    const auto fast = geodesic_distance(inside, r, c, cell_m);
    const auto slow = reference::geodesic_bellman_ford(inside, r, c, cell_m);
    REQUIRE(fast.rows() == inside.rows());
    REQUIRE(fast.cols() == inside.cols());
    std::ptrdiff_t wrong = 0;
    for (std::ptrdiff_t y = 0; y < inside.rows(); ++y)
        for (std::ptrdiff_t x = 0; x < inside.cols(); ++x) wrong += fast(y, x) != slow(y, x);
    return wrong;
}

/// A uniformly drawn cell of the mask (its row-major rank), or (-1, -1) when the mask is empty.
std::pair<std::ptrdiff_t, std::ptrdiff_t> random_inside(std::mt19937& rng, raster_view<const std::uint8_t> inside)
{
    std::vector<std::pair<std::ptrdiff_t, std::ptrdiff_t>> cells;
    for (std::ptrdiff_t r = 0; r < inside.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < inside.cols(); ++c)
            if (inside(r, c) != 0) cells.emplace_back(r, c);
    if (cells.empty()) return {-1, -1};
    return cells[std::uniform_int_distribution<std::size_t>(0, cells.size() - 1)(rng)];
}

}  // namespace geodesic_test

TEST_CASE("filter/geodesic_distance: equals Bellman-Ford relaxation on random masks of every density")
{
    const unsigned seed = 20260313;
    std::mt19937 rng(seed);
    int compared = 0;
    for (const double density : {0.35, 0.55, 0.7, 0.9, 1.0}) {
        for (const auto& size : {std::pair{1, 1}, {1, 40}, {40, 1}, {7, 9}, {23, 31}, {40, 40}}) {
            const int rows = size.first, cols = size.second;  // named copies: CAPTURE cannot take a binding
            for (int trial = 0; trial < 2; ++trial) {
                const auto m = reference::random_mask(rng, rows, cols, density);
                const auto [r, c] = geodesic_test::random_inside(rng, m);
                if (r < 0) continue;
                const double cell_m = trial == 0 ? 1.0 : 0.3;  // 0.3 is not a binary fraction: real rounding
                CAPTURE(seed);
                CAPTURE(density);
                CAPTURE(rows);
                CAPTURE(cols);
                CAPTURE(trial);
                CHECK(geodesic_test::differences(m, r, c, cell_m) == 0);
                ++compared;
            }
        }
    }
    CHECK(compared >= 55);  // only 1 x 1 masks may be empty
}

TEST_CASE("filter/geodesic_distance: a serpentine corridor and a checkerboard match the reference")
{
    // A serpentine: walls on every other row, each open at one end, alternately east and west; the path from the
    // top-left corner winds through every row, 39 x 20 = 780 steps long.
    reference::mask snake(39, 40, 1);
    for (std::ptrdiff_t r = 1; r < 39; r += 2)
        for (std::ptrdiff_t c = 0; c < 40; ++c) snake(r, c) = (r / 2) % 2 == 0 ? c == 39 : c == 0;
    CHECK(geodesic_test::differences(snake, 0, 0, 1.0) == 0);
    CHECK(geodesic_test::differences(snake, 38, 20, 0.7) == 0);
    const auto d = geodesic_distance(snake, 0, 0, 1.0);
    CHECK(d(38, 39) > 700.0f);  // along the winding corridor, not across it
    // A checkerboard: cells touch at corners only, so every step is diagonal: max(r, c) of them.
    const auto board = reference::checkerboard(25, 31);
    CHECK(geodesic_test::differences(board, 0, 0, 1.0) == 0);
    const auto g = geodesic_distance(board, 0, 0, 1.0);
    for (std::ptrdiff_t r = 0; r < 25; ++r)
        for (std::ptrdiff_t c = 0; c < 31; ++c) {
            CAPTURE(r);
            CAPTURE(c);
            if ((r + c) % 2 == 0)  // float precision: the kernel sums in double and writes a float
                CHECK(g(r, c) ==
                      doctest::Approx(std::numbers::sqrt2 * static_cast<double>(std::max(r, c))).epsilon(1e-6));
            else
                CHECK(g(r, c) == geodesic_test::unreached);
        }
}

TEST_CASE("filter/geodesic_distance: reads a strided window in place; the same as on a contiguous copy")
{
    std::mt19937 rng(41);
    for (int trial = 0; trial < 10; ++trial) {
        const auto big = reference::random_mask(rng, 40, 37, 0.75);
        const auto window = big.view().window(3, 2, 30, 31);  // row_stride 37 != cols 31
        reference::mask copy(30, 31);
        for (std::ptrdiff_t r = 0; r < 30; ++r)
            for (std::ptrdiff_t c = 0; c < 31; ++c) copy(r, c) = window(r, c);
        const auto [r, c] = geodesic_test::random_inside(rng, copy);
        REQUIRE(r >= 0);
        CAPTURE(trial);
        CHECK(geodesic_distance(window, r, c, 2.0) == geodesic_distance(copy, r, c, 2.0));
        CHECK(geodesic_test::differences(window, r, c, 2.0) == 0);
    }
}

TEST_CASE("filter/geodesic_distance: a straight corridor counts cell_m per step; a diagonal one cell_m * sqrt(2)")
{
    reference::mask row(3, 12, 0);
    for (std::ptrdiff_t c = 0; c < 12; ++c) row(1, c) = 1;
    const auto d = geodesic_distance(row, 1, 3, 0.5);
    for (std::ptrdiff_t c = 0; c < 12; ++c) CHECK(d(1, c) == 0.5f * static_cast<float>(std::abs(c - 3)));
    for (std::ptrdiff_t c = 0; c < 12; ++c) {
        CHECK(d(0, c) == geodesic_test::unreached);  // off the mask
        CHECK(d(2, c) == geodesic_test::unreached);
    }
    reference::mask diagonal(6, 6, 0);
    for (std::ptrdiff_t k = 0; k < 6; ++k) diagonal(k, k) = 1;  // cells touching at corners only
    const auto g = geodesic_distance(diagonal, 0, 0, 2.0);
    for (std::ptrdiff_t k = 0; k < 6; ++k) {
        // Float precision (the kernel sums the steps in double, then writes a float).
        CHECK(g(k, k) == doctest::Approx(2.0 * std::numbers::sqrt2 * static_cast<double>(k)).epsilon(1e-6));
        if (k > 0) CHECK(g(k, k - 1) == geodesic_test::unreached);
    }
    // A 1 x 1 mask: the start only.
    CHECK(geodesic_distance(reference::mask(1, 1, 1), 0, 0, 1.0)(0, 0) == 0.0f);
}

TEST_CASE("filter/geodesic_distance: an L-shaped corridor is followed round its corner, which a diagonal cuts")
{
    // Row 0, columns 0..9, then column 9, rows 0..8: 10 + 8 cells wide 1. From (0, 0) to (8, 9) the path runs
    // 8 steps east to (0, 8), one diagonal to (1, 9) (both are in the corridor), and 7 steps south: 15 + sqrt(2)
    // cells, where the straight line would be hypot(8, 9) = 12.04 cells.
    reference::mask l(10, 10, 0);
    for (std::ptrdiff_t c = 0; c < 10; ++c) l(0, c) = 1;
    for (std::ptrdiff_t r = 0; r < 9; ++r) l(r, 9) = 1;
    l(9, 0) = 1;  // a cell of the mask that no path reaches
    const auto d = geodesic_distance(l, 0, 0, 1.5);
    CHECK(d(0, 9) == 13.5f);
    CHECK(d(8, 9) == doctest::Approx(1.5 * (15 + std::numbers::sqrt2)).epsilon(1e-6));
    CHECK(d(1, 9) == doctest::Approx(1.5 * (8 + std::numbers::sqrt2)).epsilon(1e-6));
    CHECK(d(0, 8) == 12.0f);
    CHECK(d(9, 0) == geodesic_test::unreached);
    CHECK(d(1, 0) == geodesic_test::unreached);
    CHECK(d(5, 5) == geodesic_test::unreached);
    // A wall with one gap: the way round is longer than the way through the gap.
    reference::mask wall(5, 7, 1);
    for (std::ptrdiff_t r = 0; r < 4; ++r) wall(r, 3) = 0;  // the gap is (4, 3)
    const auto w = geodesic_distance(wall, 0, 0, 1.0);
    // (0, 0) -> (4, 3) by 3 diagonals and 1 step south, (3, 4) by a diagonal, then 3 north to (0, 4): 4 sqrt(2) + 4.
    CHECK(w(0, 4) == doctest::Approx(4 * std::numbers::sqrt2 + 4).epsilon(1e-6));
    CHECK(w(2, 3) == geodesic_test::unreached);
}

TEST_CASE("filter/geodesic_distance: refuses a start outside the raster or the mask and a cell_m that is not > 0")
{
    reference::mask m(4, 5, 1);
    m(2, 2) = 0;
    for (const auto& start : {std::pair{-1, 0}, {0, -1}, {4, 0}, {0, 5}, {4, 5}}) {
        const int r = start.first, c = start.second;
        CAPTURE(r);
        CAPTURE(c);
        CHECK_THROWS_AS(geodesic_distance(m, r, c, 1.0), invalid_input);
    }
    CHECK_THROWS_AS(geodesic_distance(m, 2, 2, 1.0), invalid_input);
    CHECK_THROWS_AS(geodesic_distance(reference::mask(0, 0), 0, 0, 1.0), invalid_input);
    for (const double bad : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
        CAPTURE(bad);
        CHECK_THROWS_AS(geodesic_distance(m, 0, 0, bad), invalid_input);
    }
    CHECK_NOTHROW(geodesic_distance(m, 3, 4, 1e-3));
}
