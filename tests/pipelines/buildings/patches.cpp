// SPDX-License-Identifier: Apache-2.0
// surface_patches and facade_patches: the patch model of a box building, a tilted roof and the refusals.
#include <doctest/doctest.h>

#include <lidarfx/pipelines/buildings/facade_patches.hpp>
#include <lidarfx/pipelines/buildings/surface_patches.hpp>

#include <cmath>
#include <map>

#include "../../reference/facades.hpp"

using namespace lidarfx;

TEST_CASE("buildings/surface_patches: a box on flat ground gives flat roof and ground quads of cell_m^2")
{
    // 12 x 14 raster, a 4 x 5 box at (3, 4), 2 m cells.
    const auto s = reference::one_box(12, 14, 3, 4, 4, 5, 10.0f, 22.0f);
    const auto patches = surface_patches(s.dsm, s.ids, 2.0);
    std::size_t roofs = 0, grounds = 0;
    for (const surface_patch& p : patches) {
        CHECK(p.tilt_deg == doctest::Approx(0.0));
        CHECK(p.area_m2 == doctest::Approx(4.0));
        if (p.kind == patch_kind::roof) {
            ++roofs;
            CHECK(p.building_id == 1);
            CHECK(p.height_m == 22.0);
        } else {
            ++grounds;
            CHECK(p.building_id == 0);
            CHECK(p.height_m == 10.0);
        }
    }
    CHECK(roofs == 3 * 4);              // quads inside the 4 x 5 box
    CHECK(grounds == 11 * 13 - 5 * 6);  // quads with no box cell
    CHECK(surface_patches(s.dsm, s.ids, 2.0, {.ground = false}).size() == roofs);
}

TEST_CASE("buildings/surface_patches: a plane sloping down to the south faces 180 with its tilt and 3D area")
{
    // z falls 1 m per 2 m cell southwards (rows grow south): slope 26.565 degrees.
    raster<float> z(5, 6);
    raster<std::int32_t> ids(5, 6, 7);
    for (std::ptrdiff_t r = 0; r < 5; ++r)
        for (std::ptrdiff_t c = 0; c < 6; ++c) z(r, c) = static_cast<float>(20.0 - static_cast<double>(r));
    const auto patches = surface_patches(z, ids, 2.0);
    REQUIRE(patches.size() == 4 * 5);
    for (const surface_patch& p : patches) {
        CHECK(p.kind == patch_kind::roof);
        CHECK(p.building_id == 7);
        CHECK(p.tilt_deg == doctest::Approx(std::atan(0.5) * 180.0 / std::numbers::pi));
        CHECK(p.azimuth_deg == doctest::Approx(180.0));
        CHECK(p.area_m2 == doctest::Approx(2.0 * std::sqrt(4.0 + 1.0)));
        CHECK(p.normal.up > 0.0);
    }
    // Falling to the east instead: azimuth 90.
    for (std::ptrdiff_t r = 0; r < 5; ++r)
        for (std::ptrdiff_t c = 0; c < 6; ++c) z(r, c) = static_cast<float>(20.0 - static_cast<double>(c));
    CHECK(surface_patches(z, ids, 2.0).front().azimuth_deg == doctest::Approx(90.0));
}

TEST_CASE("buildings/facade_patches: a box has one wall per outline edge, 8 levels from ground to roof")
{
    const auto s = reference::one_box(12, 14, 3, 4, 4, 5, 10.0f, 22.0f);
    const auto subs = facade_patches(s.dsm, s.ids, 2.0);
    REQUIRE(subs.size() == 8u * 2 * (4 + 5));
    std::map<double, int> walls_facing;
    for (const facade_patch& p : subs) {
        CHECK(p.building_id == 1);
        CHECK(p.bottom_m == 10.0);
        CHECK(p.top_m == 22.0);
        CHECK(p.area_m2 == doctest::Approx(2.0 * 12.0 / 8));
        CHECK(p.height_m == doctest::Approx(10.0 + (p.level + 0.5) * 1.5));
        CHECK(s.ids(p.front_row, p.front_col) == 0);
        CHECK(std::abs(p.front_row - p.row) + std::abs(p.front_col - p.col) == 1);
        // The facing azimuth points from the building cell to the front cell (row 0 north).
        const double a = p.facing_azimuth_deg;
        CHECK(p.front_row - p.row == (a == 0.0 ? -1 : a == 180.0 ? 1 : 0));
        CHECK(p.front_col - p.col == (a == 90.0 ? 1 : a == 270.0 ? -1 : 0));
        if (p.level == 0) ++walls_facing[a];
    }
    CHECK(walls_facing[0.0] == 5);
    CHECK(walls_facing[180.0] == 5);
    CHECK(walls_facing[90.0] == 4);
    CHECK(walls_facing[270.0] == 4);
    // Wall ids run 0, 1, ... with each wall's levels 0..7 in order.
    for (std::size_t i = 0; i < subs.size(); ++i) {
        CHECK(subs[i].wall_id == static_cast<std::int32_t>(i / 8));
        CHECK(subs[i].level == static_cast<int>(i % 8));
    }
    CHECK(facade_patches(s.dsm, s.ids, 2.0, {.levels = 3}).size() == 3u * 18);
}

TEST_CASE("buildings/facade_patches: low steps, building neighbours, NaN fronts and the raster border make no wall")
{
    auto s = reference::one_box(6, 6, 0, 0, 2, 2, 10.0f, 10.5f);  // 0.5 m high, at the north-west corner
    CHECK(facade_patches(s.dsm, s.ids, 1.0).empty());             // 0.5 m <= min_height_m
    CHECK(facade_patches(s.dsm, s.ids, 1.0, {.min_height_m = 0.4}).size() == 8u * 4);  // only E and S walls
    s.dsm(2, 0) = std::numeric_limits<float>::quiet_NaN();
    s.ids(0, 2) = 2;  // a neighbouring building (same height as ground here) hides the east wall of (0, 1)
    CHECK(facade_patches(s.dsm, s.ids, 1.0, {.min_height_m = 0.4}).size() == 8u * 2);
}

TEST_CASE("buildings/patches: bad input is refused with invalid_input")
{
    const auto s = reference::one_box(6, 6, 1, 1, 2, 2, 10.0f, 20.0f);
    const raster<std::int32_t> other(5, 6, 0);
    CHECK_THROWS_AS(surface_patches(s.dsm, other, 1.0), invalid_input);
    CHECK_THROWS_AS(surface_patches(s.dsm, s.ids, 0.0), invalid_input);
    CHECK_THROWS_AS(facade_patches(s.dsm, other, 1.0), invalid_input);
    CHECK_THROWS_AS(facade_patches(s.dsm, s.ids, -1.0), invalid_input);
    CHECK_THROWS_AS(facade_patches(s.dsm, s.ids, 1.0, {.levels = 0}), invalid_input);
    CHECK_THROWS_AS(facade_patches(s.dsm, s.ids, 1.0, {.min_height_m = -1.0}), invalid_input);
}
