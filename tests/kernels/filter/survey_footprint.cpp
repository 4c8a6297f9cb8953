// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/kernels/filter/survey_footprint.hpp>

#include "reference/footprint.hpp"
#include "reference/morphology.hpp"
#include "reference/progress.hpp"

#include <cmath>
#include <cstdint>
#include <random>

using namespace lidarfx;

namespace {

/// A 200 x 200 tile whose returns fill a circle of radius 90 cells around its centre ("clipped to a
/// circle"), minus a lake: a disc of radius 20 cells at (100, 100) with no returns.
raster<std::uint8_t> circle_tile_with_lake()
{
    raster<std::uint8_t> m(200, 200, 0);
    for (std::ptrdiff_t r = 0; r < 200; ++r)
        for (std::ptrdiff_t c = 0; c < 200; ++c) {
            const double dr = static_cast<double>(r) - 99.5, dc = static_cast<double>(c) - 99.5;
            const double d2 = dr * dr + dc * dc;
            m(r, c) = d2 <= 90.0 * 90.0 && d2 > 20.0 * 20.0;
        }
    return m;
}

}  // namespace

TEST_CASE("filter/survey_footprint: equals its definition (brute force) on random coverage and radii")
{
    std::mt19937 rng(11);
    for (const double density : {0.0, 0.05, 0.3, 0.8, 1.0}) {
        for (const double radius : {0.5, 1.0, 1.5, 3.0}) {
            const auto m = reference::random_mask(rng, 19, 27, density);
            CAPTURE(density);
            CAPTURE(radius);
            // cell_m = 2: hull_radius_m is twice the radius in cells.
            CHECK(survey_footprint(m, 2.0, {.hull_radius_m = 2.0 * radius}) == reference::footprint(m, radius));
        }
    }
}

TEST_CASE("filter/survey_footprint: empty corners of a circular tile are outside; an enclosed lake is inside")
{
    const auto tile = circle_tile_with_lake();
    const auto inside = survey_footprint(tile, 0.5, {.hull_radius_m = 5.0});  // 10 cells
    CHECK(inside(0, 0) == 0);
    CHECK(inside(199, 199) == 0);
    CHECK(inside(5, 100) == 0);    // beyond the circle's edge, not a corner
    CHECK(inside(100, 100) == 1);  // the lake's centre: no returns, but enclosed by the survey
    CHECK(inside(100, 115) == 1);
    for (std::ptrdiff_t i = 0; i < tile.size(); ++i)
        if (tile.data()[i]) REQUIRE(inside.data()[i] == 1);  // every covered cell is inside
}

TEST_CASE("filter/survey_footprint: a river leaving the tile stays inside only when narrower than the disc")
{
    // Returns everywhere except a vertical channel `width` cells wide running off both edges.
    const auto with_channel = [](std::ptrdiff_t width) {
        raster<std::uint8_t> m(120, 120, 1);
        for (std::ptrdiff_t r = 0; r < 120; ++r)
            for (std::ptrdiff_t c = 60; c < 60 + width; ++c) m(r, c) = 0;
        return m;
    };
    const auto narrow = survey_footprint(with_channel(8), 1.0, {.hull_radius_m = 5.0});  // 8 < 2 R = 10
    CHECK(narrow(60, 63) == 1);
    const auto wide = survey_footprint(with_channel(30), 1.0, {.hull_radius_m = 5.0});
    CHECK(wide(60, 75) == 0);
    // A scan line across the wide channel every few rows (see scan_coverage) closes it again.
    auto crossed = with_channel(30);
    for (std::ptrdiff_t r = 0; r < 120; r += 4)
        for (std::ptrdiff_t c = 60; c < 90; ++c) crossed(r, c) = 1;
    CHECK(survey_footprint(crossed, 1.0, {.hull_radius_m = 5.0})(61, 75) == 1);
}

TEST_CASE("filter/survey_footprint: nothing covered is all outside; bad options are refused; threads agree")
{
    const auto none = survey_footprint(raster<std::uint8_t>(10, 10, 0), 1.0);
    for (const auto v : none) CHECK(v == 0);
    CHECK(survey_footprint(raster<std::uint8_t>(0, 0), 1.0).size() == 0);
    const auto tile = circle_tile_with_lake();
    CHECK_THROWS_AS(survey_footprint(tile, 0.0), invalid_input);
    CHECK_THROWS_AS(survey_footprint(tile, 1.0, {.hull_radius_m = -1.0}), invalid_input);
    CHECK_THROWS_AS(survey_footprint(tile, 1.0, {.hull_radius_m = NAN}), invalid_input);
    const auto one = survey_footprint(tile, 0.5, {.run = {.threads = 1}});
    CHECK(survey_footprint(tile, 0.5, {.run = {.threads = 2}}) == one);
    reference::progress_log log;
    survey_footprint(tile, 0.5, {.run = {.progress = log.callback()}});
    CHECK(log.monotone_to_one(3));
    CHECK_THROWS_AS(survey_footprint(tile, 0.5, {.run = {.progress = reference::cancel_at_once()}}), cancelled);
}
