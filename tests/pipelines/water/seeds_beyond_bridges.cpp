// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/core/raster.hpp>
#include <lidarfx/pipelines/water/seeds_beyond_bridges.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>

using namespace lidarfx;

namespace {

/// A river along the rows of a 40 x 15 raster (2 m cells): columns 4-10 water at `level` rising 1 mm per row
/// (upstream at row 0), banks at level + 1.5 m; a deck across rows 18-21 at level + 5 m. The stretch above
/// the deck is body 1; the stretch below it was found by no seed.
struct river_with_bridge {
    raster<float> min_z{40, 15};
    raster<std::int32_t> labels{40, 15, 0};
    raster<std::uint8_t> eligible{40, 15, 1};
    explicit river_with_bridge(float level = 100.0f, float beyond_offset = 0.0f, float deck_rise = 5.0f)
    {
        for (std::ptrdiff_t r = 0; r < 40; ++r) {
            for (std::ptrdiff_t c = 0; c < 15; ++c) {
                const bool channel = c >= 4 && c <= 10;
                float z = level - 0.001f * static_cast<float>(r) + (channel ? 0.0f : 1.5f);
                if (channel && r > 21) z += beyond_offset;
                if (r >= 18 && r <= 21) z = level + deck_rise;
                min_z(r, c) = z;
                if (channel && r < 18) labels(r, c) = 1;
            }
        }
    }
    std::ptrdiff_t seeds_below_deck(const raster<std::uint8_t>& s) const
    {
        std::ptrdiff_t n = 0;
        for (std::ptrdiff_t r = 22; r < 40; ++r)
            for (std::ptrdiff_t c = 0; c < 15; ++c) n += s(r, c);
        return n;
    }
};

}  // namespace

TEST_CASE("water/seeds_beyond_bridges: the stretch cut off by a deck gets seeds at the found stretch's level")
{
    const river_with_bridge river;
    const auto seeds = seeds_beyond_bridges(river.labels, river.min_z, river.eligible, 2.0);
    // Straight walks down the 7 channel columns mark beyond_cells = 4 rows past the deck; diagonal walks
    // from the channel's edge columns end on the banks (1.5 m up) and mark nothing.
    CHECK(river.seeds_below_deck(seeds) > 0);
    for (std::ptrdiff_t r = 0; r < 40; ++r) {
        for (std::ptrdiff_t c = 0; c < 15; ++c) {
            if (!seeds(r, c)) continue;
            INFO("seed at " << r << ", " << c);
            CHECK(r >= 22);
            CHECK(r < 22 + 4 + 2);       // within beyond_cells of the deck (a diagonal step reaches one further)
            CHECK((c >= 4 && c <= 10));  // never on a bank
            CHECK(river.labels(r, c) == 0);
        }
    }
    for (std::ptrdiff_t c = 4; c <= 10; ++c) CHECK(seeds(22, c) == 1);
}

TEST_CASE(
    "water/seeds_beyond_bridges: no seed across a low structure, to another level, into ineligible cells "
    "or next to water already found")
{
    SUBCASE("the water beyond lies 0.5 m lower (a weir, another river): not the found stretch's level")
    {
        const river_with_bridge river(100.0f, -0.5f);
        CHECK(river.seeds_below_deck(seeds_beyond_bridges(river.labels, river.min_z, river.eligible, 2.0)) == 0);
    }
    SUBCASE("a structure 1 m high is no deck at the default clearance of 2 m; with 0.5 m it is")
    {
        const river_with_bridge river(100.0f, 0.0f, 1.0f);
        CHECK(river.seeds_below_deck(seeds_beyond_bridges(river.labels, river.min_z, river.eligible, 2.0)) == 0);
        const seeds_beyond_bridges_options low{.min_clearance_m = 0.5};
        CHECK(river.seeds_below_deck(seeds_beyond_bridges(river.labels, river.min_z, river.eligible, 2.0, low)) > 0);
    }
    SUBCASE("beyond the deck the cells are vegetation or outside the survey (not eligible)")
    {
        river_with_bridge river;
        for (std::ptrdiff_t r = 22; r < 40; ++r)
            for (std::ptrdiff_t c = 0; c < 15; ++c) river.eligible(r, c) = 0;
        CHECK(river.seeds_below_deck(seeds_beyond_bridges(river.labels, river.min_z, river.eligible, 2.0)) == 0);
    }
    SUBCASE("the stretch beyond was found already: its banks are no seed")
    {
        river_with_bridge river;
        for (std::ptrdiff_t r = 24; r < 40; ++r)
            for (std::ptrdiff_t c = 4; c <= 10; ++c) river.labels(r, c) = 2;
        const auto seeds = seeds_beyond_bridges(river.labels, river.min_z, river.eligible, 2.0);
        CHECK(river.seeds_below_deck(seeds) == 0);
    }
    SUBCASE("a deck longer than max_span_m is not crossed")
    {
        const river_with_bridge river;
        const seeds_beyond_bridges_options short_span{.max_span_m = 6.0};  // 3 cells: the deck is 4
        CHECK(river.seeds_below_deck(
                  seeds_beyond_bridges(river.labels, river.min_z, river.eligible, 2.0, short_span)) == 0);
    }
    SUBCASE("a level surface is required beyond the deck when a surface slope is given")
    {
        const river_with_bridge river;
        raster<float> sloped(40, 15, 0.05f), level(40, 15, 0.001f);
        CHECK(river.seeds_below_deck(
                  seeds_beyond_bridges(river.labels, river.min_z, river.eligible, 2.0, {}, sloped)) == 0);
        CHECK(river.seeds_below_deck(seeds_beyond_bridges(river.labels, river.min_z, river.eligible, 2.0, {}, level)) >
              0);
    }
    SUBCASE("bad arguments")
    {
        const river_with_bridge river;
        CHECK_THROWS_AS(seeds_beyond_bridges(river.labels, river.min_z, river.eligible, 0.0), invalid_input);
        CHECK_THROWS_AS(seeds_beyond_bridges(river.labels, river.min_z, river.eligible, 2.0, {.beyond_cells = 0}),
                        invalid_input);
        const raster<float> other(3, 3, 0.0f);
        CHECK_THROWS_AS(seeds_beyond_bridges(river.labels, other, river.eligible, 2.0), invalid_input);
    }
}

TEST_CASE("water/seeds_beyond_bridges: a deck across the border of two bands of rows, on 1-3 threads")
{
    // The river above placed so that its body ends in the first band of rows (128 rows each) and the water
    // beyond the deck lies in the second: the marks cross from one band into the other.
    const river_with_bridge river;
    const std::ptrdiff_t shift = 128 - 20;  // the deck's rows 18-21 become 126-129
    raster<float> min_z(200, 15);
    raster<std::int32_t> labels(200, 15, 0);
    raster<std::uint8_t> eligible(200, 15, 1);
    for (std::ptrdiff_t r = 0; r < 200; ++r)
        for (std::ptrdiff_t c = 0; c < 15; ++c) {
            const std::ptrdiff_t from = std::clamp<std::ptrdiff_t>(r - shift, 0, 39);
            min_z(r, c) = river.min_z(from, c);
            labels(r, c) = river.labels(from, c);
        }
    const auto one = seeds_beyond_bridges(labels, min_z, eligible, 2.0);
    std::ptrdiff_t below = 0;
    for (std::ptrdiff_t r = 0; r < 200; ++r)
        for (std::ptrdiff_t c = 0; c < 15; ++c) {
            if (!one(r, c)) continue;
            CHECK(r >= 130);
            ++below;
        }
    CHECK(below >= 7 * 4);  // every channel column, beyond_cells deep
    for (const int threads : {2, 3})
        CHECK(seeds_beyond_bridges(labels, min_z, eligible, 2.0, {}, {}, {.threads = threads}) == one);
}
