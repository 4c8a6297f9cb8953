// SPDX-License-Identifier: Apache-2.0
// building_heights and building_outlines on hand-made buildings.
#include <doctest/doctest.h>

#include <lidarfx/pipelines/buildings/building_heights.hpp>
#include <lidarfx/pipelines/buildings/building_outlines.hpp>

#include <cstdint>

using namespace lidarfx;

TEST_CASE("buildings/building_heights: percentiles without interpolation, mean ground, footprint")
{
    raster<float> z(10, 12, 0.0f), ground(10, 12, 2.0f);
    raster<std::int32_t> id(10, 12, 0);
    for (std::ptrdiff_t r = 0; r < 10; ++r)
        for (std::ptrdiff_t c = 0; c < 10; ++c) {
            z(r, c) = static_cast<float>(100 - (r * 10 + c));  // 1 .. 100
            id(r, c) = 1;
        }
    ground(0, 0) = 102.0f;  // mean over 100 cells: 2 + 100 / 100 = 3
    const auto h = building_heights(z, ground, id, 2, 0.5);
    REQUIRE(h.size() == 2);
    CHECK(h[0].eave_z == 5.0);    // sorted[floor(0.05 x 99)] = sorted[4]
    CHECK(h[0].ridge_z == 99.0);  // sorted[floor(0.99 x 99)] = sorted[98]
    CHECK(h[0].ground_z == doctest::Approx(3.0));
    CHECK(h[0].footprint_m2 == 25.0);
    CHECK(h[1].footprint_m2 == 0.0);  // building 2 has no cell
    CHECK_THROWS_AS(building_heights(z, ground, id, 0, 0.5), invalid_input);
}

TEST_CASE("buildings/building_outlines: one closed rectangle per building in the grid's coordinates")
{
    raster<std::int32_t> id(6, 8, 0);
    for (std::ptrdiff_t c = 1; c < 4; ++c) id(1, c) = id(2, c) = 1;
    id(4, 6) = 2;
    const grid g{100.0, 200.0, 2.0, 6, 8};
    const auto o = building_outlines(id, 2, g);
    REQUIRE(o.size() == 2);
    REQUIRE(o[0].size() == 1);
    const auto& ring = o[0][0].rings[0];
    REQUIRE(ring.size() == 5);
    CHECK(ring.front() == ring.back());
    for (const auto& p : ring) {
        CHECK((p[0] == 102.0 || p[0] == 108.0));
        CHECK((p[1] == 198.0 || p[1] == 194.0));
    }
    CHECK(o[1][0].rings[0].size() == 5);
    CHECK_THROWS_AS(building_outlines(id, 1, g), invalid_input);
}
