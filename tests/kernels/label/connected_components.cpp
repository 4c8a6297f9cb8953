// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/kernels/label/connected_components.hpp>

#include "reference/components.hpp"
#include "reference/morphology.hpp"
#include "reference/progress.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

using namespace lidarfx;

namespace {

constexpr std::array<connectivity, 2> both_connectivities{connectivity::four, connectivity::eight};

const char* name(connectivity c)
{
    return c == connectivity::eight ? "eight" : "four";
}

void check_equal(const components& got, const components& expected)
{
    CHECK(got.labels == expected.labels);
    CHECK(got.sizes == expected.sizes);
}

reference::mask from_rows(const std::vector<std::vector<int>>& rows)
{
    reference::mask m(static_cast<std::ptrdiff_t>(rows.size()), static_cast<std::ptrdiff_t>(rows[0].size()));
    for (std::ptrdiff_t r = 0; r < m.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < m.cols(); ++c) m(r, c) = static_cast<std::uint8_t>(rows[r][c]);
    return m;
}

raster<std::int32_t> labels_from_rows(const std::vector<std::vector<int>>& rows)
{
    raster<std::int32_t> m(static_cast<std::ptrdiff_t>(rows.size()), static_cast<std::ptrdiff_t>(rows[0].size()));
    for (std::ptrdiff_t r = 0; r < m.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < m.cols(); ++c) m(r, c) = rows[r][c];
    return m;
}

}  // namespace

// clang-format off: the small rasters below are laid out as grids
TEST_CASE("label/connected_components: hand-checked labels in raster order of first cells")
{
    const auto m = from_rows({{0, 0, 1, 0, 1}, {1, 0, 0, 1, 0}, {1, 0, 0, 0, 0}, {0, 1, 1, 0, 7}});
    const auto four = connected_components(m, connectivity::four);
    CHECK(four.labels == labels_from_rows({{0, 0, 1, 0, 2}, {3, 0, 0, 4, 0}, {3, 0, 0, 0, 0}, {0, 5, 5, 0, 6}}));
    CHECK(four.sizes == std::vector<std::size_t>{12, 1, 1, 2, 1, 2, 1});
    CHECK(four.count() == 6);
    const auto eight = connected_components(m);
    CHECK(eight.labels == labels_from_rows({{0, 0, 1, 0, 1}, {2, 0, 0, 1, 0}, {2, 0, 0, 0, 0}, {0, 2, 2, 0, 3}}));
    CHECK(eight.sizes == std::vector<std::size_t>{12, 3, 4, 1});

    // A U shape: its arms meet only at the bottom, so two provisional sets merge late.
    const auto u = connected_components(from_rows({{1, 0, 1}, {1, 0, 1}, {1, 1, 1}}), connectivity::four);
    CHECK(u.count() == 1);
    CHECK(u.sizes == std::vector<std::size_t>{2, 7});

    const auto empty = connected_components(reference::mask(0, 4));
    CHECK(empty.count() == 0);
    CHECK(empty.sizes == std::vector<std::size_t>{0});
    CHECK(connected_components(reference::mask(1, 1, 3)).sizes == std::vector<std::size_t>{0, 1});
}
// clang-format on

TEST_CASE("label/connected_components: matches a BFS flood fill on random masks")
{
    const unsigned seed = 424242;
    std::mt19937 rng(seed);
    INFO("seed " << seed);
    const std::vector<std::array<std::ptrdiff_t, 2>> shapes{{1, 1},   {1, 200},  {150, 1},   {7, 13},  {65, 64},
                                                            {64, 65}, {63, 127}, {257, 131}, {600, 70}};
    for (const auto& shape : shapes) {
        const std::ptrdiff_t rows = shape[0], cols = shape[1];
        for (double density : {0.1, 0.5, 0.6, 0.9}) {
            const auto m = reference::random_mask(rng, rows, cols, density);
            for (connectivity c : both_connectivities) {
                INFO(rows << "x" << cols << " density " << density << " " << name(c));
                check_equal(connected_components(m, c), reference::flood_label(m, c));
            }
        }
    }
}

TEST_CASE("label/connected_components: all-0, all-1, checkerboards, spirals and combs")
{
    for (const auto& shape : std::vector<std::array<std::ptrdiff_t, 2>>{{1, 1}, {7, 13}, {64, 65}, {520, 9}}) {
        const std::ptrdiff_t rows = shape[0], cols = shape[1];
        std::vector<reference::mask> masks{
            reference::mask(rows, cols, 0),         reference::mask(rows, cols, 1),
            reference::checkerboard(rows, cols, 1), reference::checkerboard(rows, cols, 2),
            reference::spiral(rows, cols),          reference::comb(rows, cols)};
        for (std::size_t i = 0; i < masks.size(); ++i) {
            for (connectivity c : both_connectivities) {
                INFO(rows << "x" << cols << " mask " << i << " " << name(c));
                check_equal(connected_components(masks[i], c), reference::flood_label(masks[i], c));
            }
        }
    }
    // Known counts: a checkerboard is one component under eight-connectivity and one per cell under four.
    const auto board = reference::checkerboard(9, 8);
    CHECK(connected_components(board, connectivity::eight).count() == 1);
    CHECK(connected_components(board, connectivity::four).count() == 36);
    CHECK(connected_components(reference::spiral(41, 37), connectivity::four).count() == 1);
    CHECK(connected_components(reference::comb(600, 31), connectivity::four).count() == 1);
}

TEST_CASE("label/connected_components: strided sub-views give the contiguous result")
{
    std::mt19937 rng(17);
    for (int trial = 0; trial < 10; ++trial) {
        const auto m = reference::random_mask(rng, 1 + trial * 31, 1 + trial * 7, 0.55);
        for (std::uint8_t fill : {std::uint8_t{0}, std::uint8_t{1}}) {
            const auto e = reference::embed(m, 2, 1 + trial % 3, fill);
            REQUIRE(e.view.row_stride() > e.view.cols());
            for (connectivity c : both_connectivities) {
                INFO("trial " << trial << " fill " << int(fill) << " " << name(c));
                check_equal(connected_components(e.view, c), connected_components(m, c));
            }
        }
    }
}

TEST_CASE("label/connected_components: results are identical for 1, 2 and 3 threads")
{
    std::mt19937 rng(23);
    // 900 rows: several bands of rows, joined along their edges; a spiral crosses every band edge.
    const std::vector<reference::mask> masks{reference::random_mask(rng, 900, 150, 0.6), reference::spiral(900, 60),
                                             reference::random_mask(rng, 300, 260, 0.4)};
    for (const auto& m : masks) {
        for (connectivity c : both_connectivities) {
            const auto expected = reference::flood_label(m, c);
            for (int threads : {1, 2, 3}) {
                INFO(m.rows() << "x" << m.cols() << " " << name(c) << " threads " << threads);
                const connected_components_options opt{.conn = c, .run = {.threads = threads}};
                check_equal(connected_components(m, opt), expected);
            }
        }
    }
}

TEST_CASE("label/connected_components: labels are invariant under transposition up to relabelling")
{
    std::mt19937 rng(31);
    for (int trial = 0; trial < 10; ++trial) {
        const auto m = reference::random_mask(rng, 20 + 13 * trial, 90 - 7 * trial, 0.3 + 0.04 * trial);
        for (connectivity c : both_connectivities) {
            INFO("trial " << trial << " " << name(c));
            const auto direct = connected_components(m, c);
            const auto transposed = connected_components(reference::transpose(m), c);
            CHECK(reference::same_partition(reference::transpose(direct.labels), transposed.labels));
            CHECK(direct.count() == transposed.count());
        }
    }
}

// clang-format off: the small rasters below are laid out as grids
TEST_CASE("label/rank_by_size: label 1 is the largest, ties keep raster order")
{
    const auto m = from_rows({{1, 0, 1, 1, 0, 1}, {0, 0, 0, 0, 0, 1}, {1, 1, 0, 1, 0, 1}});
    auto comps = connected_components(m, connectivity::four);
    rank_by_size(comps);
    CHECK(comps.labels == labels_from_rows({{4, 0, 2, 2, 0, 1}, {0, 0, 0, 0, 0, 1}, {3, 3, 0, 5, 0, 1}}));
    CHECK(comps.sizes == std::vector<std::size_t>{9, 3, 2, 2, 1, 1});

    std::mt19937 rng(41);
    for (int trial = 0; trial < 10; ++trial) {
        const auto mask = reference::random_mask(rng, 40, 50, 0.45);
        const auto before = connected_components(mask);
        auto ranked = before;
        rank_by_size(ranked);
        CHECK(reference::same_partition(before.labels, ranked.labels));
        CHECK(ranked.sizes[0] == before.sizes[0]);
        CHECK(std::is_sorted(ranked.sizes.begin() + 1, ranked.sizes.end(), std::greater<>()));
        // Ties in raster order: among equal sizes, first cells come in scan order.
        std::vector<std::ptrdiff_t> first(ranked.sizes.size(), -1);
        for (std::ptrdiff_t i = 0; i < ranked.labels.size(); ++i) {
            auto& f = first[static_cast<std::size_t>(ranked.labels.data()[i])];
            if (f < 0) f = i;
        }
        for (std::size_t l = 2; l < ranked.sizes.size(); ++l) {
            if (ranked.sizes[l] == ranked.sizes[l - 1]) CHECK(first[l] > first[l - 1]);
        }
    }
}
// clang-format on

// clang-format off: the small rasters below are laid out as grids
TEST_CASE("label/component_bounds: inclusive boxes per label, background included")
{
    const auto comps = connected_components(from_rows({{0, 1, 0, 0}, {0, 1, 1, 0}, {0, 0, 0, 0}, {1, 0, 0, 0}}));
    const auto boxes = component_bounds(comps);
    REQUIRE(boxes.size() == 3);
    CHECK(boxes[0] == cell_box{0, 0, 3, 3});
    CHECK(boxes[1] == cell_box{0, 1, 1, 2});
    CHECK(boxes[2] == cell_box{3, 0, 3, 0});
    CHECK(component_bounds(connected_components(reference::mask(2, 2, 1)))[0].empty());

    std::mt19937 rng(43);
    const auto m = reference::random_mask(rng, 70, 80, 0.5);
    const auto c = connected_components(m);
    const auto b = component_bounds(c);
    for (std::ptrdiff_t r = 0; r < m.rows(); ++r) {
        for (std::ptrdiff_t col = 0; col < m.cols(); ++col) {
            const auto& box = b[static_cast<std::size_t>(c.labels(r, col))];
            CHECK((r >= box.row_min && r <= box.row_max && col >= box.col_min && col <= box.col_max));
        }
    }
    for (std::size_t l = 0; l < b.size(); ++l) {  // every box edge holds a cell of its label
        bool top = false, bottom = false, left = false, right = false;
        for (std::ptrdiff_t col = b[l].col_min; col <= b[l].col_max; ++col) {
            top = top || c.labels(b[l].row_min, col) == static_cast<std::int32_t>(l);
            bottom = bottom || c.labels(b[l].row_max, col) == static_cast<std::int32_t>(l);
        }
        for (std::ptrdiff_t r = b[l].row_min; r <= b[l].row_max; ++r) {
            left = left || c.labels(r, b[l].col_min) == static_cast<std::int32_t>(l);
            right = right || c.labels(r, b[l].col_max) == static_cast<std::int32_t>(l);
        }
        CHECK((top && bottom && left && right));
    }
}
// clang-format on

TEST_CASE("label/remove_small_components: keeps exactly the components of at least min_cells")
{
    std::mt19937 rng(47);
    for (int trial = 0; trial < 12; ++trial) {
        const auto m = reference::random_mask(rng, 33 + trial, 61, 0.35);
        const auto c = trial % 2 == 0 ? connectivity::eight : connectivity::four;
        const std::size_t min_cells = static_cast<std::size_t>(trial);
        const auto ref = reference::flood_label(m, c);
        const auto kept = remove_small_components(m, min_cells, c);
        for (std::ptrdiff_t i = 0; i < m.size(); ++i) {
            const auto l = static_cast<std::size_t>(ref.labels.data()[i]);
            const int expected = l != 0 && ref.sizes[l] >= min_cells ? 1 : 0;
            REQUIRE(kept.data()[i] == expected);
        }
    }
}

// clang-format off: the small rasters below are laid out as grids
TEST_CASE("label/fill_holes: fills enclosed background of at most max_hole_cells")
{
    const auto ring = from_rows({{0, 0, 0, 0, 0, 0, 0},
                                 {0, 1, 1, 1, 1, 1, 0},
                                 {0, 1, 0, 1, 0, 0, 1},
                                 {0, 1, 1, 1, 0, 0, 1},
                                 {0, 0, 0, 0, 1, 1, 0}});
    // Eight-connected foreground: holes are four-connected, so the 1-cell and the 4-cell holes are both
    // enclosed (the 4-cell one only through diagonal links of its wall).
    CHECK(fill_holes(ring, 1) == from_rows({{0, 0, 0, 0, 0, 0, 0},
                                            {0, 1, 1, 1, 1, 1, 0},
                                            {0, 1, 1, 1, 0, 0, 1},
                                            {0, 1, 1, 1, 0, 0, 1},
                                            {0, 0, 0, 0, 1, 1, 0}}));
    CHECK(fill_holes(ring, 0) == ring);                 // inclusive: no hole has at most 0 cells
    CHECK(fill_holes(ring, 3) == fill_holes(ring, 1));  // inclusive: the 4-cell hole needs max_hole_cells 4
    CHECK(fill_holes(ring, 4) == from_rows({{0, 0, 0, 0, 0, 0, 0},
                                            {0, 1, 1, 1, 1, 1, 0},
                                            {0, 1, 1, 1, 1, 1, 1},
                                            {0, 1, 1, 1, 1, 1, 1},
                                            {0, 0, 0, 0, 1, 1, 0}}));
    // Four-connected foreground: background is eight-connected and the 4-cell hole leaks out diagonally.
    CHECK(fill_holes(ring, 100, connectivity::four) == fill_holes(ring, 1));
    CHECK(fill_holes(reference::mask(3, 3, 0), 100) == reference::mask(3, 3, 0));  // touches the border
    CHECK(fill_holes(reference::mask(0, 3), 100).rows() == 0);

    std::mt19937 rng(53);
    for (int trial = 0; trial < 12; ++trial) {
        const auto m = reference::random_mask(rng, 30 + trial, 41, 0.6);
        const auto c = trial % 2 == 0 ? connectivity::eight : connectivity::four;
        const auto holes_conn = c == connectivity::eight ? connectivity::four : connectivity::eight;
        const std::size_t max_cells = static_cast<std::size_t>(trial);
        const auto background = reference::complement(m);
        const auto ref = reference::flood_label(background, holes_conn);
        std::vector<bool> on_border(ref.sizes.size(), false);
        for (std::ptrdiff_t r = 0; r < m.rows(); ++r)
            for (std::ptrdiff_t col = 0; col < m.cols(); ++col)
                if (r == 0 || col == 0 || r == m.rows() - 1 || col == m.cols() - 1)
                    on_border[static_cast<std::size_t>(ref.labels(r, col))] = true;
        const auto filled = fill_holes(m, max_cells, c);
        for (std::ptrdiff_t i = 0; i < m.size(); ++i) {
            const auto l = static_cast<std::size_t>(ref.labels.data()[i]);
            const bool fill = l != 0 && !on_border[l] && ref.sizes[l] <= max_cells;
            REQUIRE(filled.data()[i] == ((m.data()[i] != 0 || fill) ? 1 : 0));
        }
    }
}
// clang-format on

TEST_CASE("label/connected_components: the into form writes labels into a caller's strided raster")
{
    std::mt19937 rng(59);
    const auto m = reference::random_mask(rng, 300, 77, 0.5);
    raster<std::int32_t> big(302, 90, -7);
    const auto window = big.view().window(1, 5, 300, 77);
    const auto sizes = connected_components(m, window, {.conn = connectivity::four, .run = {.threads = 2}});
    const auto expected = reference::flood_label(m, connectivity::four);
    CHECK(sizes == expected.sizes);
    CHECK(raster<std::int32_t>(window) == expected.labels);
    CHECK(big(0, 0) == -7);  // cells outside the window are untouched
    CHECK(big(301, 89) == -7);
    CHECK(big(1, 4) == -7);
    CHECK(big(1, 82) == -7);
}

TEST_CASE("label/connected_components: progress is monotone and ends at 1; returning false cancels")
{
    std::mt19937 rng(61);
    const auto m = reference::random_mask(rng, 900, 70, 0.5);  // four bands of 256 rows, two passes over them
    const auto want = connected_components(m);
    for (int threads : {1, 2}) {
        CAPTURE(threads);
        const reference::progress_log log;
        check_equal(connected_components(m, {.run = {.threads = threads, .progress = log.callback()}}), want);
        CHECK(log.monotone_to_one(threads == 1 ? 8 : 2));
        const connected_components_options stop{.run = {.threads = threads, .progress = reference::cancel_at_once()}};
        CHECK_THROWS_WITH_AS(connected_components(m, stop), "connected_components: cancelled", cancelled);
    }
    const reference::progress_log empty;  // nothing to do is done at once
    connected_components(reference::mask(0, 5), {.run = {.progress = empty.callback()}});
    CHECK(empty.monotone_to_one());
}

TEST_CASE("label/connected_components: bad input throws invalid_input naming the argument")
{
    const reference::mask m(3, 3, 1);
    CHECK_THROWS_WITH_AS(connected_components(m, connected_components_options{.run = {.threads = -2}}),
                         "connected_components: run.threads must be >= 0 (got -2)", invalid_input);
    raster<std::int32_t> labels(2, 3);
    CHECK_THROWS_WITH_AS(connected_components(m, labels),
                         "connected_components: m and labels must have the same shape (got 3x3 and 2x3)",
                         invalid_input);
}
