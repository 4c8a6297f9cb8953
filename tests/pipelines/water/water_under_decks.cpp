// SPDX-License-Identifier: Apache-2.0
// water_under_decks: a river 20 cells wide along the columns, falling 0.1 m, crossed by a deck 6 cells long that
// also spans its banks; beside the deck the waterbodies lost a strip of water at the river's level.
// The test cases stay inside the namespace: in a unity build its short names must not reach the next file.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include <lidarfx/core/error.hpp>
#include <lidarfx/core/raster.hpp>
#include <lidarfx/pipelines/water/water_under_decks.hpp>

using namespace lidarfx;

namespace water_under_decks_test {

constexpr std::ptrdiff_t rows = 40, cols = 60;
constexpr std::ptrdiff_t river_top = 10, river_bottom = 29;  // river rows
constexpr std::ptrdiff_t deck_first = 28, deck_last = 33;    // deck columns; it spans rows 8..31

double level_at(std::ptrdiff_t c)
{
    return 10.0 - 0.1 * static_cast<double>(c) / (cols - 1);
}

bool on_river(std::ptrdiff_t r)
{
    return r >= river_top && r <= river_bottom;
}

bool on_deck(std::ptrdiff_t r, std::ptrdiff_t c)
{
    return c >= deck_first && c <= deck_last && r >= river_top - 2 && r <= river_bottom + 2;
}

/// Rows 10..12 beside the deck (3 columns each side) lost to the waterbodies, their returns at the water.
bool lost_beside_deck(std::ptrdiff_t r, std::ptrdiff_t c)
{
    return r >= river_top && r <= river_top + 2 &&
           ((c >= deck_first - 3 && c < deck_first) || (c > deck_last && c <= deck_last + 3));
}

/// Rows 10..11 at columns 4..5, far from the deck, lost the same way.
bool lost_far(std::ptrdiff_t r, std::ptrdiff_t c)
{
    return r >= river_top && r <= river_top + 1 && (c == 4 || c == 5);
}

struct scene {
    raster<std::int32_t> body{rows, cols, 0};
    raster<float> water{rows, cols, NAN};
    raster<float> min_z{rows, cols, 11.0f};  // banks 1 m above the water
};

scene make()
{
    scene s;
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            if (on_deck(r, c)) {
                s.min_z(r, c) = 14.0f;
                continue;
            }
            if (!on_river(r)) continue;
            s.min_z(r, c) = static_cast<float>(level_at(c) - 0.03);
            if (lost_beside_deck(r, c) || lost_far(r, c)) continue;
            s.body(r, c) = 1;
            s.water(r, c) = static_cast<float>(level_at(c));
        }
    return s;
}

/// Whether water_under_decks on `s` with these rivers adds no cell and changes no body.
bool adds_nothing(scene s, std::vector<std::int32_t> rivers)
{
    const raster<std::int32_t> before = s.body;
    const auto got = water_under_decks(s.body, s.water, s.min_z, rivers, 1.0);
    return got.level_cells + got.deck_cells == 0 && s.body == before;
}

TEST_CASE("water/water_under_decks: the river continues under its deck at the level interpolated across it")
{
    scene s = make();
    const std::vector<std::int32_t> rivers{1};
    const auto got = water_under_decks(s.body, s.water, s.min_z, rivers, 1.0);
    CHECK(got.level_cells == 18);  // the strip beside the deck
    CHECK(got.deck_cells == static_cast<std::size_t>((river_bottom - river_top + 1) * (deck_last - deck_first + 1)));
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            CAPTURE(r);
            CAPTURE(c);
            if (lost_beside_deck(r, c)) {  // back at the level of a river cell beside it (within 3 columns)
                CHECK(s.body(r, c) == 1);
                CHECK(std::abs(s.water(r, c) - level_at(c)) <= 3 * 0.1 / (cols - 1) + 1e-6);
            } else if (on_deck(r, c) && on_river(r)) {  // j of 7 steps from the water west of it to the water east
                REQUIRE(s.body(r, c) == 1);
                const double from = s.water(r, deck_first - 1), to = s.water(r, deck_last + 1);
                const double j = static_cast<double>(c - deck_first + 1);
                CHECK(s.water(r, c) == static_cast<float>(from + (to - from) * j / 7.0));
                if (r > river_top + 2) CHECK(from == static_cast<float>(level_at(deck_first - 1)));
            } else if (on_deck(r, c) || lost_far(r, c) || !on_river(r)) {  // the deck over the banks, the far strip
                CHECK(s.body(r, c) == 0);
                CHECK(std::isnan(s.water(r, c)));
            }
        }
}

TEST_CASE("water/water_under_decks: a deck longer than max_span_m, a body that is no river, no deck: nothing crossed")
{
    {
        scene s = make();
        const std::vector<std::int32_t> rivers{1};
        const auto got = water_under_decks(s.body, s.water, s.min_z, rivers, 1.0, {.max_span_m = 5.9});
        CHECK(got.deck_cells == 0);
        CHECK(got.level_cells == 18);  // the strip beside it still joins
        CHECK(s.body(river_top + 5, deck_first) == 0);
    }
    CHECK(adds_nothing(make(), {2}));  // body 1 is a lake here
    scene dam = make();
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = deck_first; c <= deck_last; ++c)
            if (on_river(r)) dam.min_z(r, c) = 11.0f;  // a dam of ground, 1 m above the water: no deck
    CHECK(adds_nothing(dam, {1}));
    {
        // A deck whose every cell lacks returns is no deck: a gap of dropouts is not crossed.
        scene s = make();
        for (std::ptrdiff_t r = 0; r < rows; ++r)
            for (std::ptrdiff_t c = deck_first; c <= deck_last; ++c)
                if (on_deck(r, c)) s.min_z(r, c) = NAN;
        const std::vector<std::int32_t> rivers{1};
        const auto got = water_under_decks(s.body, s.water, s.min_z, rivers, 1.0);
        CHECK(got.deck_cells == 0);
    }
}

TEST_CASE("water/water_under_decks: a high island the river encloses is no deck: it stays land")
{
    scene s = make();
    for (std::ptrdiff_t r = 17; r <= 22; ++r)
        for (std::ptrdiff_t c = 45; c <= 50; ++c) {
            s.min_z(r, c) = 14.0f;  // 4 m above the water, 6 cells across: a deck by height and span
            s.body(r, c) = 0;
            s.water(r, c) = NAN;
        }
    const std::vector<std::int32_t> rivers{1};
    const auto got = water_under_decks(s.body, s.water, s.min_z, rivers, 1.0);
    CHECK(got.deck_cells == static_cast<std::size_t>((river_bottom - river_top + 1) * (deck_last - deck_first + 1)));
    for (std::ptrdiff_t r = 17; r <= 22; ++r)
        for (std::ptrdiff_t c = 45; c <= 50; ++c) CHECK(s.body(r, c) == 0);
}

TEST_CASE("water/water_under_decks: reach_m bounds the level cells; cells without returns on a deck are crossed")
{
    {
        scene s = make();
        const std::vector<std::int32_t> rivers{1};
        const auto got = water_under_decks(s.body, s.water, s.min_z, rivers, 1.0, {.reach_m = 0});
        CHECK(got.level_cells == 0);
        // The strip's rows then hold no run from water to water: only rows 13..29 are crossed.
        CHECK(got.deck_cells ==
              static_cast<std::size_t>((river_bottom - river_top - 2) * (deck_last - deck_first + 1)));
    }
    {
        scene s = make();
        for (std::ptrdiff_t r = river_top; r <= river_bottom; ++r) s.min_z(r, deck_first + 2) = NAN;  // shadowed
        const std::vector<std::int32_t> rivers{1};
        const auto got = water_under_decks(s.body, s.water, s.min_z, rivers, 1.0);
        CHECK(got.deck_cells ==
              static_cast<std::size_t>((river_bottom - river_top + 1) * (deck_last - deck_first + 1)));
    }
}

TEST_CASE("water/water_under_decks: refuses other shapes, a cell_m not > 0, options out of range, negative ids")
{
    scene s = make();
    const std::vector<std::int32_t> rivers{1};
    raster<float> small(rows, cols - 1, 0.0f);
    CHECK_THROWS_AS(water_under_decks(s.body, s.water, small, rivers, 1.0), invalid_input);
    CHECK_THROWS_AS(water_under_decks(s.body, small, s.min_z, rivers, 1.0), invalid_input);
    CHECK_THROWS_AS(water_under_decks(s.body, s.water, s.min_z, rivers, 0.0), invalid_input);
    CHECK_THROWS_AS(water_under_decks(s.body, s.water, s.min_z, rivers, NAN), invalid_input);
    CHECK_THROWS_AS(water_under_decks(s.body, s.water, s.min_z, rivers, 1.0, {.deck_clearance_m = 0}), invalid_input);
    CHECK_THROWS_AS(water_under_decks(s.body, s.water, s.min_z, rivers, 1.0, {.level_tolerance_m = -1}), invalid_input);
    CHECK_THROWS_AS(water_under_decks(s.body, s.water, s.min_z, rivers, 1.0, {.reach_m = INFINITY}), invalid_input);
    CHECK_THROWS_AS(water_under_decks(s.body, s.water, s.min_z, rivers, 1.0, {.max_span_m = NAN}), invalid_input);
    const std::vector<std::int32_t> negative{-1};
    CHECK_THROWS_AS(water_under_decks(s.body, s.water, s.min_z, negative, 1.0), invalid_input);
    s.body(0, 0) = -3;
    CHECK_THROWS_AS(water_under_decks(s.body, s.water, s.min_z, rivers, 1.0), invalid_input);
}

}  // namespace water_under_decks_test
