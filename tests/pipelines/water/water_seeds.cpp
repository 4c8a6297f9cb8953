// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/pipelines/water/water_seeds.hpp>

#include <algorithm>
#include <numeric>
#include <random>

#include "reference/components.hpp"
#include "reference/morphology.hpp"
#include "water_test_rasters.hpp"

using namespace lidarfx;

namespace {

/// Seeds by definition: brute-force opening, flood-fill components, stable sort by size, keep >= min.
components reference_seeds(const raster<std::uint8_t>& dropout, int opening, std::size_t min_cells)
{
    auto comps = reference::flood_label(reference::open(dropout, opening, opening), connectivity::eight);
    std::vector<std::int32_t> order(comps.count());
    std::iota(order.begin(), order.end(), 1);
    std::stable_sort(order.begin(), order.end(), [&](auto a, auto b) {
        return comps.sizes[static_cast<std::size_t>(a)] > comps.sizes[static_cast<std::size_t>(b)];
    });
    std::vector<std::int32_t> rank(comps.sizes.size(), 0);
    components out{raster<std::int32_t>(dropout.rows(), dropout.cols(), 0), {0}};
    for (std::size_t k = 0; k < order.size(); ++k) {
        const auto size = comps.sizes[static_cast<std::size_t>(order[k])];
        if (size < min_cells) break;
        rank[static_cast<std::size_t>(order[k])] = static_cast<std::int32_t>(k + 1);
        out.sizes.push_back(size);
    }
    for (std::ptrdiff_t i = 0; i < out.labels.size(); ++i) {
        out.labels.data()[i] = rank[static_cast<std::size_t>(comps.labels.data()[i])];
        out.sizes[0] += out.labels.data()[i] == 0;
    }
    return out;
}

}  // namespace

TEST_CASE("water/water_seeds: opened dropout patches of at least min_cells, largest first")
{
    raster<std::uint8_t> d(12, 14, 0);
    for (std::ptrdiff_t r = 1; r < 6; ++r)
        for (std::ptrdiff_t c = 1; c < 6; ++c) d(r, c) = 1;  // 5 x 5 = 25 cells
    for (std::ptrdiff_t r = 5; r < 11; ++r)
        for (std::ptrdiff_t c = 7; c < 13; ++c) d(r, c) = 1;  // 6 x 6 = 36 cells
    d(9, 2) = d(0, 10) = d(10, 0) = 1;                        // single dropouts, as on land
    d(3, 6) = 1;                                              // a one-cell spur on the small patch
    const auto s = water_seeds(d, {.opening_size_cells = 3, .min_cells = 25});
    REQUIRE(s.count() == 2);
    CHECK(s.sizes[1] == 36);
    CHECK(s.sizes[2] == 25);
    CHECK(s.sizes[0] == static_cast<std::size_t>(12 * 14 - 61));
    CHECK(s.labels(7, 9) == 1);
    CHECK(s.labels(3, 3) == 2);
    CHECK(s.labels(3, 6) == 0);  // opened away
    CHECK(s.labels(9, 2) == 0);
    // min_cells is inclusive: 26 drops the 25-cell patch.
    const auto one = water_seeds(d, {.opening_size_cells = 3, .min_cells = 26});
    CHECK(one.count() == 1);
    CHECK(one.labels(3, 3) == 0);
    CHECK(one.sizes[0] == static_cast<std::size_t>(12 * 14 - 36));
    // Opening 1 keeps every dropout; the single cells are still below min_cells.
    CHECK(water_seeds(d, {.opening_size_cells = 1, .min_cells = 1}).count() == 5);
}

TEST_CASE("water/seed_cells: the cells of every seed in raster-scan order")
{
    components s{water_test::grid_of<std::int32_t>({{0, 2, 2},  //
                                                    {1, 0, 2},
                                                    {1, 1, 0}}),
                 {3, 3, 3}};
    const auto cells = seed_cells(s);
    REQUIRE(cells.size() == 3);
    CHECK(cells[0].empty());
    CHECK(cells[1] == std::vector<std::ptrdiff_t>{3, 6, 7});
    CHECK(cells[2] == std::vector<std::ptrdiff_t>{1, 2, 5});
}

TEST_CASE("water/seed_cells: blocks of empty cells are skipped; sizes that do not match are recounted")
{
    std::mt19937 rng(64);
    for (int trial = 0; trial < 30; ++trial) {
        CAPTURE(trial);
        const std::ptrdiff_t rows = 1 + rng() % 9, cols = 1 + rng() % 300;  // rows longer than a 64-cell block
        const std::int32_t count = 1 + static_cast<std::int32_t>(rng() % 5);
        components s{raster<std::int32_t>(rows, cols, 0),
                     std::vector<std::size_t>(static_cast<std::size_t>(count) + 1, 0)};
        std::vector<std::vector<std::ptrdiff_t>> expected(static_cast<std::size_t>(count) + 1);
        for (std::ptrdiff_t i = 0; i < s.labels.size(); ++i) {
            if (rng() % 23 != 0) continue;  // sparse, so that most blocks are empty
            const auto l = static_cast<std::int32_t>(1 + rng() % static_cast<unsigned>(count));
            s.labels.data()[i] = l;
            expected[static_cast<std::size_t>(l)].push_back(i);
        }
        for (std::size_t l = 1; l < expected.size(); ++l) s.sizes[l] = expected[l].size();
        if (trial % 3 == 1) s.sizes[1] += 2;                         // too large
        if (trial % 3 == 2 && s.sizes.back() > 0) --s.sizes.back();  // too small
        CHECK(seed_cells(s) == expected);
    }
    components bad{water_test::grid_of<std::int32_t>({{0, 3}}), {0, 1}};  // label 3 of 1 seed
    CHECK_THROWS_AS(seed_cells(bad), invalid_input);
}

TEST_CASE("water/water_seeds: equals opening + flood fill + ranking by definition on random masks")
{
    std::mt19937 rng(8080);
    int kept_and_dropped = 0;
    raster<std::int32_t> buffer(3, 5, -7);  // the labels form: a buffer of another shape, then reused with garbage
    for (int trial = 0; trial < 50; ++trial) {
        CAPTURE(trial);
        const std::ptrdiff_t rows = 1 + rng() % 50, cols = 1 + rng() % 50;
        // Blocky dropouts: random rectangles over sparse noise.
        auto d = reference::random_mask(rng, rows, cols, 0.08);
        for (int k = 0; k < 4; ++k) {
            const auto r0 = static_cast<std::ptrdiff_t>(rng() % static_cast<unsigned>(rows));
            const auto c0 = static_cast<std::ptrdiff_t>(rng() % static_cast<unsigned>(cols));
            for (std::ptrdiff_t r = r0; r < std::min(rows, r0 + 2 + static_cast<std::ptrdiff_t>(rng() % 9)); ++r)
                for (std::ptrdiff_t c = c0; c < std::min(cols, c0 + 2 + static_cast<std::ptrdiff_t>(rng() % 9)); ++c)
                    d(r, c) = 1;
        }
        const int opening = 1 + 2 * static_cast<int>(rng() % 3);
        const std::size_t min_cells = 1 + rng() % 30;
        const auto got =
            water_seeds(d, {.opening_size_cells = opening, .min_cells = min_cells}, {.threads = 1 + trial % 3});
        const auto expected = reference_seeds(d, opening, min_cells);
        CHECK(got.labels == expected.labels);
        CHECK(got.sizes == expected.sizes);
        auto into = water_seeds(d, {.opening_size_cells = opening, .min_cells = min_cells}, std::move(buffer));
        CHECK(into.labels == expected.labels);
        CHECK(into.sizes == expected.sizes);
        buffer = std::move(into.labels);
        std::fill(buffer.begin(), buffer.end(), trial);
        const auto all = reference_seeds(d, opening, 1);
        kept_and_dropped += got.count() > 0 && all.count() > got.count();
    }
    CHECK(kept_and_dropped > 5);  // the scenes exercise the size threshold
}

TEST_CASE("water/water_seeds: progress is monotone and ends at 1; returning false cancels")
{
    raster<std::uint8_t> d(8, 8, 1);
    water_test::check_progress_and_cancel([&](const execution& run) { return water_seeds(d, {}, run); }, "water_seeds");
}

TEST_CASE("water/water_seeds: options out of range are refused")
{
    raster<std::uint8_t> d(4, 4, 0);
    CHECK_THROWS_WITH_AS(water_seeds(d, {.opening_size_cells = 2}),
                         "water_seeds: opening_size_cells must be odd and >= 1 (got 2)", invalid_input);
    CHECK_THROWS_WITH_AS(water_seeds(d, {.min_cells = 0}), "water_seeds: min_cells must be >= 1 (got 0)",
                         invalid_input);
    CHECK_THROWS_WITH_AS(water_seeds(d, {.line_length_cells = 1}),
                         "water_seeds: line_length_cells must be 0 or in [2, 255] (got 1)", invalid_input);
}

TEST_CASE("water/water_seeds: with line_length_cells a diagonal river two cells wide seeds; scattered dropouts do not")
{
    raster<std::uint8_t> d(60, 60, 0);
    for (std::ptrdiff_t i = 0; i < 50; ++i) d(5 + i, 5 + i) = d(5 + i, 6 + i) = 1;  // 100 cells, no 3 x 3 inside
    std::mt19937 rng(11);
    std::bernoulli_distribution lost(0.15);  // land at a low density: single lost pulses
    for (std::ptrdiff_t r = 0; r < 60; ++r)
        for (std::ptrdiff_t c = 0; c < 60; ++c)
            if (c > r + 10 && lost(rng)) d(r, c) = 1;
    CHECK(water_seeds(d, {.opening_size_cells = 3, .min_cells = 50}).count() == 0);
    const auto s = water_seeds(d, {.opening_size_cells = 3, .min_cells = 50, .line_length_cells = 4});
    REQUIRE(s.count() == 1);
    CHECK(s.labels(30, 30) == 1);
    CHECK(s.labels(30, 31) == 1);
    CHECK(s.sizes[1] >= 100);
    CHECK(s.sizes[1] < 130);  // the scattered land dropouts stay out but for a few touching runs
}
