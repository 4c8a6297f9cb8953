// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/core/raster.hpp>
#include <lidarfx/pipelines/water/seed_water_level.hpp>

#include <cmath>
#include <vector>

using namespace lidarfx;

TEST_CASE("water/seed_water_level: the low quantile of the returns around a seed is the water's level")
{
    // 10 x 10 cells: a 4 x 4 seed of dropouts (rows/cols 3-6) in water at 100 m; the land (cols >= 7)
    // stands 0.8 m higher and makes most of the ring.
    raster<float> min_z(10, 10, 100.0f);
    std::vector<std::ptrdiff_t> seed;
    for (std::ptrdiff_t r = 0; r < 10; ++r) {
        for (std::ptrdiff_t c = 0; c < 10; ++c) {
            if (c >= 7 || r <= 1) min_z.view()(r, c) = 100.8f;
            if (r >= 3 && r <= 6 && c >= 3 && c <= 6) {
                min_z.view()(r, c) = NAN;
                seed.push_back(r * 10 + c);
            }
        }
    }
    CHECK(seed_water_level(seed, min_z) == doctest::Approx(100.0));
    CHECK(seed_water_level(seed, min_z, {.ring_cells = 2, .quantile = 1.0}) == doctest::Approx(100.8));
    // Ring 1 reads rows/cols 2-7: row 2 and cols 2-6 water, col 7 land.
    CHECK(seed_water_level(seed, min_z, {.ring_cells = 1, .quantile = 0.5}) == doctest::Approx(100.0));
}

TEST_CASE("water/seed_water_level: no return around the seed gives NaN; bad options throw")
{
    raster<float> min_z(3, 3, NAN);
    const std::vector<std::ptrdiff_t> seed{4};
    CHECK(std::isnan(seed_water_level(seed, min_z)));
    CHECK_THROWS(seed_water_level(seed, min_z, {.ring_cells = 0}));
    CHECK_THROWS(seed_water_level(seed, min_z, {.quantile = 1.5}));
    const std::vector<std::ptrdiff_t> outside{9};
    CHECK_THROWS(seed_water_level(outside, min_z));
}
