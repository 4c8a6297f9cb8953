// SPDX-License-Identifier: Apache-2.0
// local_planes, plane_tolerance, is_planar and drop_rough_buildings on hand-made planes and a rough part.
#include <doctest/doctest.h>

#include <lidarfx/pipelines/buildings/local_planes.hpp>

#include <cmath>
#include <cstdint>

using namespace lidarfx;

namespace {

/// Building 1: a plane rising 0.3 m per metre east and 0.1 m per metre north over cols [2, 12); building 2: a
/// checkerboard of +-1 m over cols [14, 24); rows [2, 12), 1 m cells.
void scene(raster<float>& z, raster<std::int32_t>& id)
{
    z = raster<float>(14, 26, 0.0f);
    id = raster<std::int32_t>(14, 26, 0);
    for (std::ptrdiff_t r = 2; r < 12; ++r) {
        for (std::ptrdiff_t c = 2; c < 12; ++c) {
            z(r, c) = static_cast<float>(10.0 + 0.3 * static_cast<double>(c) - 0.1 * static_cast<double>(r));
            id(r, c) = 1;
        }
        for (std::ptrdiff_t c = 14; c < 24; ++c) {
            z(r, c) = (r + c) % 2 == 0 ? 11.0f : 9.0f;
            id(r, c) = 2;
        }
    }
}

}  // namespace

TEST_CASE("buildings/local_planes: a plane's slope east and north, and NaN outside buildings")
{
    raster<float> z;
    raster<std::int32_t> id;
    scene(z, id);
    const auto lp = local_planes(z, id, 1.0);
    // float storage of a fit over exact plane values: a few ulps.
    CHECK(lp.a(6, 6) == doctest::Approx(0.3).epsilon(1e-5));
    CHECK(lp.b(6, 6) == doctest::Approx(0.1).epsilon(1e-5));
    CHECK(lp.rms(6, 6) < 1e-4f);
    CHECK(std::isnan(lp.a(0, 0)));
    CHECK(is_planar(lp, 6, 6, 1.0, {}));
    CHECK_FALSE(is_planar(lp, 6, 18, 1.0, {}));
    CHECK_THROWS_AS(local_planes(z, raster<std::int32_t>(3, 3), 1.0), invalid_input);
}

TEST_CASE("buildings/plane_tolerance: plane_rms_m x (1 + g2) + slope_rms_share x tan(tilt) x cell_m")
{
    const local_planes_options o{.plane_rms_m = 0.1, .slope_rms_share = 0.2};
    CHECK(plane_tolerance(o, 0.0, 1.0) == doctest::Approx(0.1));
    CHECK(plane_tolerance(o, 1.0, 0.5) == doctest::Approx(0.1 * 2.0 + 0.2 * 1.0 * 0.5));
}

TEST_CASE("buildings/drop_rough_buildings: the rough part goes, the planar one stays and keeps id 1")
{
    raster<float> z;
    raster<std::int32_t> id;
    scene(z, id);
    const auto lp = local_planes(z, id, 1.0);
    const auto [kept, dropped] = drop_rough_buildings(id, 2, lp, 1.0);
    CHECK(kept == 1);
    CHECK(dropped == 1);
    CHECK(id(6, 6) == 1);
    CHECK(id(6, 18) == 0);
    // With min_planar_share 0 nothing is rough.
    scene(z, id);
    CHECK(drop_rough_buildings(id, 2, lp, 1.0, {.min_planar_share = 0.0})[0] == 2);
}
