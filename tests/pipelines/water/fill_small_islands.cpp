// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/pipelines/water/fill_small_islands.hpp>

#include "reference/islands.hpp"
#include "water_test_rasters.hpp"

#include <algorithm>
#include <random>
#include <vector>

using namespace lidarfx;

TEST_CASE("water/fill_small_islands: small holes of one body fill, large ones and shared ones stay")
{
    raster<std::int32_t> labels(12, 12, 0);
    for (std::ptrdiff_t r = 1; r < 11; ++r)
        for (std::ptrdiff_t c = 1; c < 11; ++c) labels(r, c) = 1;
    labels(3, 3) = 0;  // 1-cell hole: filled
    for (std::ptrdiff_t r = 5; r < 9; ++r)
        for (std::ptrdiff_t c = 5; c < 9; ++c) labels(r, c) = 0;  // 16-cell island: stays
    labels(2, 8) = 0;
    labels(2, 9) = 2;  // hole touching another body: stays
    // 1 m cells: islands of 10 m² and more stay land.
    CHECK(fill_small_islands(labels, 1.0, {.island_min_area_m2 = 10.0}) == 1);
    CHECK(labels(3, 3) == 1);
    CHECK(labels(6, 6) == 0);
    CHECK(labels(2, 8) == 0);
    CHECK(labels(0, 0) == 0);  // land touching the border is never a hole
}

TEST_CASE("water/fill_small_islands: island_min_area_m2 is inclusive and in square metres")
{
    // A 2 x 2 hole in a body of 2 m cells is 16 m².
    const auto make = [] {
        raster<std::int32_t> labels(6, 6, 3);
        labels(2, 2) = labels(2, 3) = labels(3, 2) = labels(3, 3) = 0;
        return labels;
    };
    auto labels = make();
    CHECK(fill_small_islands(labels, 2.0, {.island_min_area_m2 = 16.0}) == 0);  // 16 m² >= 16 m²: an island
    CHECK(labels == make());
    CHECK(fill_small_islands(labels, 2.0, {.island_min_area_m2 = 16.5}) == 4);
    CHECK(labels == raster<std::int32_t>(6, 6, 3));
    labels = make();
    CHECK(fill_small_islands(labels, 2.0, {.island_min_area_m2 = 0}) == 0);  // 0 keeps every hole
    // Holes are 4-connected: a diagonal gap in the ring does not let the land out.
    raster<std::int32_t> ring(5, 5, 0);
    for (std::ptrdiff_t k = 1; k < 4; ++k) ring(1, k) = ring(3, k) = ring(k, 1) = ring(k, 3) = 5;
    ring(1, 1) = 0;  // corner open diagonally to (0, 0)
    CHECK(fill_small_islands(ring, 1.0, {.island_min_area_m2 = 2.0}) == 1);
    CHECK(ring(2, 2) == 5);
}

TEST_CASE("water/fill_small_islands: equals a whole-raster search for holes on random bodies")
{
    std::mt19937 rng(91);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    int filled_scenes = 0;
    for (int trial = 0; trial < 80; ++trial) {
        CAPTURE(trial);
        const std::ptrdiff_t rows = 1 + rng() % 45, cols = 1 + rng() % 45;
        raster<std::int32_t> labels(rows, cols);
        const double density = 0.5 + 0.45 * u(rng);
        for (std::ptrdiff_t r = 0; r < rows; ++r)
            for (std::ptrdiff_t c = 0; c < cols; ++c)
                labels(r, c) = u(rng) < density ? 1 + static_cast<std::int32_t>((r / 15 + c / 17) % 3) : 0;
        const std::size_t max_hole = 1 + rng() % 12;
        // Cells of 0.5 m: max_hole cells are max_hole / 4 m².
        auto fast = labels, slow = labels;
        const auto n = fill_small_islands(fast, 0.5, {.island_min_area_m2 = 0.25 * static_cast<double>(max_hole)},
                                          {.threads = 1 + trial % 3});
        reference::fill_small_islands(slow, max_hole);
        CHECK(fast == slow);
        filled_scenes += !(fast == labels);
        // Both ways of finding holes (per body, or all at once) give the same labels and count.
        std::vector<cell_box> boxes(4, cell_box{rows, cols, -1, -1});
        cell_box all{rows, cols, -1, -1};
        for (std::ptrdiff_t r = 0; r < rows; ++r)
            for (std::ptrdiff_t c = 0; c < cols; ++c)
                if (labels(r, c) > 0) {
                    boxes[static_cast<std::size_t>(labels(r, c))].extend(r, c);
                    all.extend(r, c);
                }
        if (all.empty()) continue;
        auto per_body = labels, at_once = labels;
        CHECK(detail::fill_holes_per_body(per_body, max_hole, boxes, 1) == n);
        const cell_box grown{std::max<std::ptrdiff_t>(0, all.row_min - 1), std::max<std::ptrdiff_t>(0, all.col_min - 1),
                             std::min(rows - 1, all.row_max + 1), std::min(cols - 1, all.col_max + 1)};
        CHECK(detail::fill_holes_at_once(at_once, max_hole, grown, 2) == n);
        CHECK(per_body == slow);
        CHECK(at_once == slow);
    }
    CHECK(filled_scenes > 40);
}

TEST_CASE("water/fill_small_islands: many bodies searched on several threads give the one-thread labels")
{
    // 100 random blob bodies (more than one block of bodies), many with holes, some nested in others' boxes.
    std::mt19937 rng(17);
    raster<std::int32_t> labels(120, 130, 0);
    for (std::int32_t k = 1; k <= 100; ++k) {
        const std::ptrdiff_t r0 = rng() % 110, c0 = rng() % 120, h = 3 + rng() % 8, w = 3 + rng() % 8;
        for (std::ptrdiff_t r = r0; r < std::min<std::ptrdiff_t>(120, r0 + h); ++r)
            for (std::ptrdiff_t c = c0; c < std::min<std::ptrdiff_t>(130, c0 + w); ++c)
                labels(r, c) = rng() % 6 == 0 ? 0 : k;
    }
    auto slow = labels;
    reference::fill_small_islands(slow, 3);
    std::vector<std::size_t> counts;
    for (const int threads : {1, 2, 3}) {
        auto fast = labels;
        counts.push_back(fill_small_islands(fast, 1.0, {.island_min_area_m2 = 3.0}, {.threads = threads}));
        CHECK(fast == slow);
    }
    CHECK(counts[0] > 20);
    CHECK(counts[1] == counts[0]);
    CHECK(counts[2] == counts[0]);
}

TEST_CASE("water/fill_small_islands: nested ring bodies, each with a small hole")
{
    // Concentric square rings of bodies 1..5; the innermost encloses 3 x 3 land cells. The boxes nest, so
    // they cover more than the raster and the holes are found in one labelling of the land. The land
    // between two rings touches both and stays.
    raster<std::int32_t> labels(23, 23, 0);
    for (std::int32_t k = 1; k <= 5; ++k) {
        const std::ptrdiff_t lo = 2 * k - 1, hi = 23 - 2 * k;
        for (std::ptrdiff_t i = lo; i <= hi; ++i) labels(lo, i) = labels(hi, i) = labels(i, lo) = labels(i, hi) = k;
    }
    labels(5, 11) = 0;  // a one-cell gap in ring 3, between rings 2 and 4: next to three bodies, stays land
    auto slow = labels;
    reference::fill_small_islands(slow, 10);
    CHECK(fill_small_islands(labels, 1.0, {.island_min_area_m2 = 10.0}) == 9);
    CHECK(labels == slow);
    CHECK(labels(11, 11) == 5);  // the centre, inside ring 5
    CHECK(labels(5, 11) == 0);
}

TEST_CASE("water/fill_small_islands: strided views give the result of contiguous rasters")
{
    std::mt19937 rng(5);
    raster<std::int32_t> big(40, 50, 7);
    raster<std::int32_t> labels(30, 33);
    for (std::ptrdiff_t r = 0; r < 30; ++r)
        for (std::ptrdiff_t c = 0; c < 33; ++c) big(r + 4, c + 6) = labels(r, c) = rng() % 5 == 0 ? 0 : 1 + (c > 16);
    const auto view = big.view().window(4, 6, 30, 33);
    const auto n = fill_small_islands(view, 1.0, {.island_min_area_m2 = 4});
    CHECK(n == fill_small_islands(labels, 1.0, {.island_min_area_m2 = 4}));
    CHECK(n > 0);
    for (std::ptrdiff_t r = 0; r < 30; ++r)
        for (std::ptrdiff_t c = 0; c < 33; ++c) CHECK(view(r, c) == labels(r, c));
    CHECK(big(0, 0) == 7);
}

TEST_CASE("water/fill_small_islands: progress is monotone and ends at 1; returning false cancels")
{
    raster<std::int32_t> labels(8, 8, 1);
    labels(4, 4) = 0;
    water_test::check_progress_and_cancel(
        [&](const execution& run) {
            auto copy = labels;
            return fill_small_islands(copy, 1.0, {}, run);
        },
        "fill_small_islands");
}

TEST_CASE("water/fill_small_islands: bad arguments are refused")
{
    raster<std::int32_t> labels(3, 3, 0);
    CHECK_THROWS_WITH_AS(fill_small_islands(labels, 0.0), "fill_small_islands: cell_m must be finite and > 0 (got 0)",
                         invalid_input);
    CHECK_THROWS_WITH_AS(fill_small_islands(labels, 1.0, {.island_min_area_m2 = -1}),
                         "fill_small_islands: island_min_area_m2 must be >= 0 (got -1)", invalid_input);
    labels(1, 1) = -2;
    CHECK_THROWS_WITH_AS(fill_small_islands(labels, 1.0), "fill_small_islands: labels must be >= 0 (got -2)",
                         invalid_input);
}
