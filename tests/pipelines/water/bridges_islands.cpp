// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/pipelines/water/waterbodies.hpp>

#include "reference/bridges.hpp"
#include "reference/islands.hpp"

#include <random>

using namespace lidarfx;

TEST_CASE("water/join_across_bridges: one sweep equals walking every land cell's four lines")
{
    std::mt19937 rng(77);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    int merged_scenes = 0;
    for (int trial = 0; trial < 80; ++trial) {
        CAPTURE(trial);
        const std::ptrdiff_t rows = 1 + rng() % 40, cols = 1 + rng() % 40;
        const int bodies = 1 + static_cast<int>(rng() % 5);
        raster<std::int32_t> labels(rows, cols);
        raster<float> z(rows, cols);
        for (std::ptrdiff_t r = 0; r < rows; ++r)
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                // Blocky bodies so that runs between different bodies are common.
                const auto block = ((r / 5) * 7 + (c / 6) * 3) % (bodies + 2);
                labels(r, c) = u(rng) < 0.25f ? 0 : static_cast<std::int32_t>(block > bodies ? 0 : block);
                const float pick = u(rng);
                z(r, c) = pick < 0.2f ? NAN : pick < 0.5f ? 10.0f + 0.1f * u(rng) : 10.0f + 6.0f * u(rng);
            }
        std::vector<double> level(static_cast<std::size_t>(bodies) + 1, 10.0);
        for (std::size_t b = 1; b < level.size(); ++b) level[b] = 10.0 + 0.8 * u(rng);
        const int span = 1 + static_cast<int>(rng() % 8);
        auto fast = labels, slow = labels;
        detail::join_across_bridges(fast, z, level, span, 0.5, 2.0, 0.15);
        reference::join_across_bridges(slow, z, level, span, 0.5, 2.0, 0.15);
        CHECK(fast == slow);
        merged_scenes += !(fast == labels);
    }
    CHECK(merged_scenes > 20);  // the random scenes do bridge
}

TEST_CASE("water/join_across_bridges: a deck joins the two halves of a river, a low bank does not")
{
    // Rows 0-2 land, rows 3-5 river, rows 6-8 land; columns 6-7 are a bridge deck over the river.
    raster<std::int32_t> labels(9, 14, 0);
    raster<float> z(9, 14, 12.0f);
    for (std::ptrdiff_t r = 3; r < 6; ++r)
        for (std::ptrdiff_t c = 0; c < 14; ++c) {
            labels(r, c) = c < 6 ? 1 : c > 7 ? 2 : 0;
            z(r, c) = c == 6 || c == 7 ? 16.0f : 10.0f;  // deck 6 m above the water
        }
    z(2, 6) = z(2, 7) = 10.5f;  // low bank beside the deck
    const std::vector<double> level{0.0, 10.0, 10.05};
    const auto n = detail::join_across_bridges(labels, z, level, 5, 1.0, 2.0, 0.15);
    CHECK(n == 6);
    for (std::ptrdiff_t r = 3; r < 6; ++r)
        for (std::ptrdiff_t c = 0; c < 14; ++c) CHECK(labels(r, c) == 1);
    CHECK(labels(2, 6) == 0);
    CHECK(labels(6, 6) == 0);
}

TEST_CASE("water/fill_small_islands: small holes of one body fill, large ones and shared ones stay")
{
    raster<std::int32_t> labels(12, 12, 0);
    for (std::ptrdiff_t r = 1; r < 11; ++r)
        for (std::ptrdiff_t c = 1; c < 11; ++c) labels(r, c) = 1;
    labels(3, 3) = 0;                                       // 1-cell hole: filled
    for (std::ptrdiff_t r = 5; r < 9; ++r)
        for (std::ptrdiff_t c = 5; c < 9; ++c) labels(r, c) = 0;  // 16-cell island: stays
    labels(2, 8) = 0;
    labels(2, 9) = 2;                                       // hole touching another body: stays
    detail::fill_small_islands(labels, 10);
    CHECK(labels(3, 3) == 1);
    CHECK(labels(6, 6) == 0);
    CHECK(labels(2, 8) == 0);
    CHECK(labels(0, 0) == 0);                               // land touching the border is never a hole
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
        auto fast = labels, slow = labels;
        detail::fill_small_islands(fast, max_hole);
        reference::fill_small_islands(slow, max_hole);
        CHECK(fast == slow);
        filled_scenes += !(fast == labels);
    }
    CHECK(filled_scenes > 40);
}
