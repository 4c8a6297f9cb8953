// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/pipelines/water/join_across_bridges.hpp>

#include "reference/bridges.hpp"
#include "water_test_rasters.hpp"

#include <cmath>
#include <random>

using namespace lidarfx;
using water_test::grid_of;

TEST_CASE("water/water_levels: median min z of each label's cells with a return")
{
    const auto labels = grid_of<std::int32_t>({{1, 1, 0, 2},  //
                                               {1, 1, 0, 2},
                                               {0, 0, 0, 4}});
    const auto z = grid_of<float>({{10.0f, 12.0f, 99.0f, NAN},  //
                                   {11.0f, 13.0f, 99.0f, NAN},
                                   {99.0f, 99.0f, 99.0f, 5.0f}});
    const auto level = water_levels(labels, z);
    REQUIRE(level.size() == 5);
    CHECK(std::isnan(level[0]));  // land has no level
    CHECK(level[1] == 12.0);      // {10, 11, 12, 13}: the element at position 4 / 2 of the sorted values
    CHECK(std::isnan(level[2]));  // no cell with a return
    CHECK(std::isnan(level[3]));  // no cell at all
    CHECK(level[4] == 5.0);
    const raster<std::int32_t> land(2, 2, 0);
    CHECK(water_levels(land, raster<float>(2, 2, 1.0f)).size() == 1);
}

TEST_CASE("water/water_levels: bands of rows on several threads give the medians of all cells at once")
{
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 10.0f);
    // 900 rows: bands of rows, bodies that span several of them, and more labels than a block of medians.
    raster<std::int32_t> labels(900, 23, 0);
    raster<float> z(900, 23);
    for (std::ptrdiff_t r = 0; r < 900; ++r)
        for (std::ptrdiff_t c = 0; c < 23; ++c) {
            labels(r, c) = rng() % 4 == 0 ? 0 : 1 + static_cast<std::int32_t>((r / 23 * 3 + c / 9) % 41);
            z(r, c) = rng() % 9 == 0 ? NAN : u(rng);
        }
    std::vector<std::vector<float>> heights(42);
    for (std::ptrdiff_t r = 0; r < 900; ++r)
        for (std::ptrdiff_t c = 0; c < 23; ++c)
            if (std::isfinite(z(r, c))) heights[static_cast<std::size_t>(labels(r, c))].push_back(z(r, c));
    for (const int threads : {1, 2, 3}) {
        CAPTURE(threads);
        const auto level = water_levels(labels, z, {.threads = threads});
        REQUIRE(level.size() == 42);
        for (std::size_t l = 1; l < 42; ++l) {
            auto h = heights[l];
            REQUIRE(!h.empty());
            std::nth_element(h.begin(), h.begin() + static_cast<std::ptrdiff_t>(h.size() / 2), h.end());
            CHECK(level[l] == static_cast<double>(h[h.size() / 2]));
        }
    }
}

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
        // The span in metres on cells of cell_m metres: span cells.
        const double cell = trial % 2 ? 1.0 : 2.5;
        auto fast = labels, slow = labels;
        join_across_bridges(fast, z, level, cell,
                            {.max_span_m = span * cell,
                             .level_tolerance_m = 0.5,
                             .min_clearance_m = 2.0,
                             .water_tolerance_m = 0.15,
                             .join_touching = false});  // the reference: bridges only
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
    const auto n = join_across_bridges(labels, z, level, 1.0, {.max_span_m = 5, .level_tolerance_m = 1.0});
    CHECK(n == 6);
    for (std::ptrdiff_t r = 3; r < 6; ++r)
        for (std::ptrdiff_t c = 0; c < 14; ++c) CHECK(labels(r, c) == 1);
    CHECK(labels(2, 6) == 0);
    CHECK(labels(6, 6) == 0);
}

TEST_CASE(
    "water/join_across_bridges: bodies that touch at one level merge; at levels apart, or with join_touching off, not")
{
    // Two stretches of one river grown from two seeds (labels 1 and 2) meet at column 5 (8-adjacent only
    // diagonally in row 1); a pond (label 3) touches stretch 2 at row 4 but lies 3 m higher.
    raster<std::int32_t> labels(6, 10, 0);
    raster<float> z(6, 10, 10.0f);
    for (std::ptrdiff_t c = 0; c < 10; ++c) labels(2, c) = labels(3, c) = c < 5 ? 1 : 2;
    labels(1, 4) = 1;
    labels(1, 6) = 2;  // no row/column contact in row 1; columns 4 and 6 are two cells apart
    for (std::ptrdiff_t c = 6; c < 10; ++c) labels(4, c) = 3, z(4, c) = 13.0f;
    const std::vector<double> level{0.0, 10.0, 9.9, 13.0};
    auto joined = labels;
    join_across_bridges(joined, z, level, 1.0, {.max_span_m = 0.5});  // span below a cell: no bridge
    CHECK(joined(2, 7) == 1);                                         // stretch 2 merged into 1
    CHECK(joined(1, 6) == 1);
    CHECK(joined(4, 7) == 3);  // the pond stays apart: 3 m above the river (tolerance 1 m)
    CHECK(joined(0, 0) == 0);
    auto apart = labels;
    join_across_bridges(apart, z, level, 1.0, {.max_span_m = 0.5, .join_touching = false});
    CHECK(apart == labels);
}

TEST_CASE("water/join_across_bridges: the span is in metres and inclusive, the tolerances too")
{
    // One row: body 1, a gap of 5 cells of 2 m (10 m) of deck, body 2.
    const auto make = [] { return grid_of<std::int32_t>({{1, 1, 0, 0, 0, 0, 0, 2, 2}}); };
    const auto deck = grid_of<float>({{10.0f, 10.0f, 13.0f, 13.0f, 13.0f, 13.0f, 13.0f, 11.0f, 11.0f}});
    const std::vector<double> level{NAN, 10.0, 11.0};
    auto labels = make();
    CHECK(join_across_bridges(labels, deck, level, 2.0, {.max_span_m = 10.0}) == 5);  // 5 cells · 2 m <= 10 m
    CHECK(labels == raster<std::int32_t>(1, 9, 1));
    labels = make();
    CHECK(join_across_bridges(labels, deck, level, 2.0, {.max_span_m = 9.99}) == 0);
    CHECK(labels == make());
    // Levels 1 m apart: bridged at a tolerance of 1 m, not below.
    labels = make();
    CHECK(join_across_bridges(labels, deck, level, 2.0, {.max_span_m = 10.0, .level_tolerance_m = 0.99}) == 0);
    // The deck stands 2 m above the higher level: clearance 2 m bridges it, 2.5 m does not.
    labels = make();
    CHECK(join_across_bridges(labels, deck, level, 2.0, {.max_span_m = 10.0, .min_clearance_m = 2.5}) == 0);
    // Water seen past the deck's edges: cells between the levels widened by water_tolerance_m. 10.4 m and
    // 11.4 m lie 0.4 m from a level, above the lower and the higher.
    const auto past = grid_of<float>({{10.0f, 10.0f, 10.4f, 13.0f, 13.0f, 11.4f, 11.4f, 11.0f, 11.0f}});
    labels = make();
    CHECK(join_across_bridges(labels, past, level, 2.0, {.max_span_m = 10.0, .water_tolerance_m = 0.5}) == 5);
    labels = make();  // at 0.3 m the 11.4 m cells are a bank: they stay land, the deck still joins the bodies
    CHECK(join_across_bridges(labels, past, level, 2.0, {.max_span_m = 10.0, .water_tolerance_m = 0.3}) == 3);
    CHECK(labels == grid_of<std::int32_t>({{1, 1, 1, 1, 1, 0, 0, 1, 1}}));
    // Without a deck it is land at the water's level, not a bridge; a cell without a return there is a gap in it.
    auto flat = grid_of<float>({{10.0f, 10.0f, 10.2f, 10.2f, 10.8f, 10.8f, 10.8f, 11.0f, 11.0f}});
    labels = make();
    CHECK(join_across_bridges(labels, flat, level, 2.0, {.max_span_m = 10.0, .water_tolerance_m = 0.3}) == 0);
    flat(0, 4) = NAN;
    labels = make();
    CHECK(join_across_bridges(labels, flat, level, 2.0, {.max_span_m = 10.0, .water_tolerance_m = 0.3}) == 5);
    // Two decks with ground at the water's level between them (roofs and a street between two canals): land.
    const auto two_decks = grid_of<float>({{10.0f, 10.0f, 13.0f, 10.1f, 13.0f, 13.0f, 13.0f, 11.0f, 11.0f}});
    labels = make();
    CHECK(join_across_bridges(labels, two_decks, level, 2.0, {.max_span_m = 10.0, .water_tolerance_m = 0.3}) == 0);
    // A bank between deck and water is left out of the order: the run is still one deck.
    const auto bank = grid_of<float>({{10.0f, 10.0f, 10.1f, 11.8f, 13.0f, 13.0f, 10.9f, 11.0f, 11.0f}});
    labels = make();
    CHECK(join_across_bridges(labels, bank, level, 2.0, {.max_span_m = 10.0, .water_tolerance_m = 0.3}) == 4);
    CHECK(labels(0, 3) == 0);
}

TEST_CASE("water/join_across_bridges: without levels it takes water_levels' medians")
{
    std::mt19937 rng(31);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int trial = 0; trial < 20; ++trial) {
        raster<std::int32_t> labels(25, 30);
        raster<float> z(25, 30);
        for (std::ptrdiff_t r = 0; r < 25; ++r)
            for (std::ptrdiff_t c = 0; c < 30; ++c) {
                labels(r, c) = u(rng) < 0.35f ? 0 : 1 + static_cast<std::int32_t>((c / 6) % 4);
                z(r, c) = u(rng) < 0.3f ? NAN : 10.0f + (labels(r, c) ? 0.5f * u(rng) : 6.0f * u(rng));
            }
        auto given = labels, derived = labels;
        const auto n = join_across_bridges(given, z, water_levels(labels, z), 2.0, {.max_span_m = 8});
        CHECK(join_across_bridges(derived, z, 2.0, {.max_span_m = 8}) == n);
        CHECK(derived == given);
    }
    raster<std::int32_t> negative(2, 2, 0);
    negative(1, 1) = -3;
    CHECK_THROWS_WITH_AS(join_across_bridges(negative, raster<float>(2, 2, 1.0f), 1.0),
                         "join_across_bridges: labels must be >= 0 (got -3)", invalid_input);
}

TEST_CASE("water/join_across_bridges: strided views give the result of contiguous rasters")
{
    std::mt19937 rng(12);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    raster<std::int32_t> big(30, 40, 9);
    raster<float> big_z(30, 40, -50.0f);
    raster<std::int32_t> labels(20, 25);
    raster<float> z(20, 25);
    for (std::ptrdiff_t r = 0; r < 20; ++r)
        for (std::ptrdiff_t c = 0; c < 25; ++c) {
            labels(r, c) = u(rng) < 0.4f ? 0 : 1 + static_cast<std::int32_t>((c / 5) % 3);
            z(r, c) = u(rng) < 0.5f ? NAN : 10.0f + 5.0f * u(rng);
            big(r + 3, c + 4) = labels(r, c);
            big_z(r + 3, c + 4) = z(r, c);
        }
    const std::vector<double> level{NAN, 10.0, 10.2, 10.4};
    const auto view = big.view().window(3, 4, 20, 25);
    const auto n = join_across_bridges(view, big_z.view().window(3, 4, 20, 25), level, 1.0);
    CHECK(n == join_across_bridges(labels, z, level, 1.0));
    CHECK(n > 0);
    for (std::ptrdiff_t r = 0; r < 20; ++r)
        for (std::ptrdiff_t c = 0; c < 25; ++c) CHECK(view(r, c) == labels(r, c));
    CHECK(big(0, 0) == 9);
}

TEST_CASE("water/join_across_bridges: bad arguments are refused")
{
    raster<std::int32_t> labels(2, 2, 0);
    const raster<float> z(2, 2, 1.0f);
    const std::vector<double> level{NAN, 1.0};
    labels(0, 0) = 2;
    CHECK_THROWS_WITH_AS(join_across_bridges(labels, z, level, 1.0),
                         "join_across_bridges: labels must be < level.size() (got 2)", invalid_input);
    labels(0, 0) = -1;
    CHECK_THROWS_WITH_AS(join_across_bridges(labels, z, level, 1.0),
                         "join_across_bridges: labels must be >= 0 (got -1)", invalid_input);
    CHECK_THROWS_WITH_AS(water_levels(labels, z), "water_levels: labels must be >= 0 (got -1)", invalid_input);
    labels(0, 0) = 1;
    CHECK_THROWS_WITH_AS(join_across_bridges(labels, z, level, 0.0),
                         "join_across_bridges: cell_m must be finite and > 0 (got 0)", invalid_input);
    CHECK_THROWS_WITH_AS(join_across_bridges(labels, z, level, 1.0, {.max_span_m = -1}),
                         "join_across_bridges: max_span_m must be >= 0 (got -1)", invalid_input);
    CHECK_THROWS_AS(join_across_bridges(labels, raster<float>(2, 3), level, 1.0), invalid_input);
}
