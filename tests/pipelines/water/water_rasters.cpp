// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/pipelines/water/assess_water_inputs.hpp>
#include <lidarfx/pipelines/water/measure_waterbodies.hpp>
#include <lidarfx/pipelines/water/water_angles.hpp>
#include <lidarfx/pipelines/water/water_rasters.hpp>
#include <lidarfx/pipelines/water/water_vegetation.hpp>

#include "water_test_rasters.hpp"

using namespace lidarfx;

TEST_CASE("water/to_water_rasters: views the six rasters of rasterize() without copying")
{
    point_rasters pr;
    pr.g = grid{0, 0, 2.0, 3, 4};
    pr.min_z = pr.max_z = pr.mean_intensity = raster<float>(3, 4, 1.0f);
    pr.count = raster<std::uint32_t>(3, 4, 2);
    pr.dropout = pr.multiple_returns = raster<std::uint8_t>(3, 4, 0);
    const water_rasters in = to_water_rasters(pr);
    CHECK(in.min_z.data() == pr.min_z.data());
    CHECK(in.max_z.data() == pr.max_z.data());
    CHECK(in.mean_intensity.data() == pr.mean_intensity.data());
    CHECK(in.dropout.data() == pr.dropout.data());
    CHECK(in.multiple_returns.data() == pr.multiple_returns.data());
    CHECK(in.count.data() == pr.count.data());
}

TEST_CASE("water/water_rasters: every step that reads the survey refuses mismatched or empty rasters")
{
    raster<float> z(4, 4, 1.0f), z2(4, 5, 1.0f);
    raster<std::uint8_t> d(4, 4), d2(3, 4);
    raster<std::uint32_t> n2(4, 3);
    CHECK_THROWS_WITH_AS(assess_water_inputs(water_rasters{z, z2, z, d}, 2.0),
                         "assess_water_inputs: min_z and max_z must have the same shape (got 4x4 and 4x5)",
                         invalid_input);
    CHECK_THROWS_WITH_AS(water_vegetation(water_rasters{z, z, z2, d}),
                         "water_vegetation: min_z and mean_intensity must have the same shape (got 4x4 and 4x5)",
                         invalid_input);
    CHECK_THROWS_WITH_AS(water_angles(water_rasters{z, z, z, d2}, 1.0),
                         "water_angles: min_z and dropout must have the same shape (got 4x4 and 3x4)", invalid_input);
    // The optional rasters are checked only when given.
    CHECK_NOTHROW(assess_water_inputs(water_rasters{z, z, z, d}, 2.0));
    CHECK_THROWS_WITH_AS(assess_water_inputs(water_rasters{z, z, z, d, d2}, 2.0),
                         "assess_water_inputs: min_z and multiple_returns must have the same shape (got 4x4 and 3x4)",
                         invalid_input);
    CHECK_THROWS_WITH_AS(assess_water_inputs(water_rasters{z, z, z, d, {}, n2}, 2.0),
                         "assess_water_inputs: min_z and count must have the same shape (got 4x4 and 4x3)",
                         invalid_input);
    const raster<float> none(0, 0);
    const raster<std::uint8_t> no_mask(0, 0);
    CHECK_THROWS_WITH_AS(assess_water_inputs(water_rasters{none, none, none, no_mask}, 2.0),
                         "assess_water_inputs: the rasters are empty (0 cells)", invalid_input);
    std::vector<waterbody> bodies;
    raster<std::int32_t> labels(4, 4, 0);
    CHECK_THROWS_AS(measure_waterbodies(labels, bodies, water_rasters{z, z2, z, d}, 1.0), invalid_input);
}
