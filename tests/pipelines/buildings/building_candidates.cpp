// SPDX-License-Identifier: Apache-2.0
// building_candidates on a hand-made box scene: the height, hull, vegetation and area rules, one at a time.
#include <doctest/doctest.h>

#include <lidarfx/pipelines/buildings/building_candidates.hpp>
#include <lidarfx/pipelines/buildings/ground_model.hpp>

#include <cstdint>
#include <limits>

using namespace lidarfx;

namespace {

/// Flat ground at 100 m, 60 x 60 cells, with a box of rows [r0, r1) x cols [c0, c1) at 100 + h.
raster<float> box(std::ptrdiff_t r0, std::ptrdiff_t r1, std::ptrdiff_t c0, std::ptrdiff_t c1, float h)
{
    raster<float> z(60, 60, 100.0f);
    for (std::ptrdiff_t r = r0; r < r1; ++r)
        for (std::ptrdiff_t c = c0; c < c1; ++c) z(r, c) = 100.0f + h;
    return z;
}

std::size_t count_of(const raster<std::int32_t>& id, std::int32_t v)
{
    std::size_t n = 0;
    for (const auto x : id) n += x == v;
    return n;
}

}  // namespace

TEST_CASE("buildings/building_candidates: a box high above the ground is one part of its own cells")
{
    const auto z = box(20, 40, 16, 44, 7.0f);  // 10 m x 14 m at 0.5 m cells
    const auto terrain = ground_model(z, 0.5);
    const auto c = building_candidates(z, terrain, 0.5);
    CHECK(c.count == 1);
    CHECK(count_of(c.building_id, 1) == 560);
    CHECK(c.building_id(30, 30) == 1);
    CHECK(c.building_id(5, 5) == 0);
    // Lower than min_height_m: no candidate.
    CHECK(building_candidates(z, terrain, 0.5, {}, {.min_height_m = 8.0}).count == 0);
}

TEST_CASE("buildings/building_candidates: vegetation is never a building and grows into empty DSM cells")
{
    auto z = box(20, 40, 16, 44, 7.0f);
    z(10, 10) = std::numeric_limits<float>::quiet_NaN();
    const auto terrain = ground_model(z, 0.5);
    raster<std::uint8_t> veg(60, 60, 0);
    for (std::ptrdiff_t r = 20; r < 40; ++r)
        for (std::ptrdiff_t c = 16; c < 44; ++c) veg(r, c) = 1;
    veg(10, 11) = 1;
    const auto c = building_candidates(z, terrain, 0.5, veg);
    CHECK(c.count == 0);
    CHECK(c.vegetation(10, 10) == 1);  // no return, next to vegetation
    CHECK(c.vegetation(10, 12) == 0);  // a return: stays as given
}

TEST_CASE("buildings/building_candidates: parts under min_area_m2 are dropped; shapes are checked")
{
    const auto z = box(20, 30, 20, 30, 7.0f);  // 5 m x 5 m = 25 m^2: a garage, above the default 20 m^2
    const auto terrain = ground_model(z, 0.5);
    CHECK(building_candidates(z, terrain, 0.5).count == 1);
    CHECK(building_candidates(z, terrain, 0.5, {}, {.min_area_m2 = 30}).count == 0);
    const raster<std::uint8_t> wrong(5, 5, 0);
    CHECK_THROWS_AS(building_candidates(z, terrain, 0.5, wrong), invalid_input);
    CHECK_THROWS_AS(building_candidates(z, terrain, 0.0), invalid_input);
}
