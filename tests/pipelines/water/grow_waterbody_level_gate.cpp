// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/core/error.hpp>
#include <lidarfx/core/raster.hpp>
#include <lidarfx/pipelines/water/grow_waterbody.hpp>

#include <cmath>
#include <vector>

using namespace lidarfx;

namespace {

/// A flat field (angle 0 everywhere, all eligible, one intensity bin) with the given min z.
water_field flat_field(const raster<float>& min_z)
{
    water_field f{raster<float>(min_z.rows(), min_z.cols(), 0.0f), raster<std::uint8_t>(min_z.rows(), min_z.cols(), 1),
                  raster<std::int32_t>(min_z.rows(), min_z.cols(), 0), 1, min_z};
    for (std::ptrdiff_t i = 0; i < min_z.size(); ++i)
        if (std::isnan(min_z.data()[i])) f.intensity_bin.data()[i] = -1;
    return f;
}

}  // namespace

TEST_CASE("water/grow_waterbody level gate: a pond's flood stops where the field stands 0.7 m above its level")
{
    // 20 x 20: water at 100 m in rows/cols 6-13, its middle 4 x 4 a seed of dropouts; grass at 100.7 m around.
    raster<float> min_z(20, 20, 100.7f);
    std::vector<std::ptrdiff_t> seed;
    for (std::ptrdiff_t r = 6; r <= 13; ++r) {
        for (std::ptrdiff_t c = 6; c <= 13; ++c) {
            const bool in_seed = r >= 8 && r <= 11 && c >= 8 && c <= 11;
            min_z.view()(r, c) = in_seed ? NAN : 100.0f;
            if (in_seed) seed.push_back(r * 20 + c);
        }
    }
    const auto field = flat_field(min_z);
    grow_waterbody_workspace workspace;
    const auto gated = grow_waterbody(field, seed, {}, workspace);
    CHECK(gated.cells.size() == 64);

    grow_waterbody_options no_gate;
    no_gate.level_gate_m = 0;
    const auto flooded = grow_waterbody(field, seed, no_gate, workspace);
    CHECK(flooded.cells.size() == 400);  // the untested first step takes the whole flat field
}

TEST_CASE("water/grow_waterbody level gate: the level drifts along a falling river, not up a bank")
{
    // 12 x 80: a river in rows 4-7 falling 0.004 m per column from 100 m, banks 0.5 m above it; a seed of
    // dropouts at its west end (cols 0-3).
    raster<float> min_z(12, 80);
    std::vector<std::ptrdiff_t> seed;
    for (std::ptrdiff_t r = 0; r < 12; ++r) {
        for (std::ptrdiff_t c = 0; c < 80; ++c) {
            const float level = 100.0f - 0.004f * static_cast<float>(c);
            const bool river = r >= 4 && r <= 7;
            min_z.view()(r, c) = river ? level : level + 0.5f;
            if (river && c <= 3) {
                min_z.view()(r, c) = NAN;
                seed.push_back(r * 80 + c);
            }
        }
    }
    const auto field = flat_field(min_z);
    grow_waterbody_workspace workspace;
    CHECK(grow_waterbody(field, seed, {}, workspace).cells.size() == 4 * 80);

    grow_waterbody_options fixed_level;
    fixed_level.level_drift_m = 0;  // the seed's level only: the flood ends ~0.15 / 0.004 columns downstream
    const auto short_reach = grow_waterbody(field, seed, fixed_level, workspace);
    CHECK(short_reach.cells.size() < 4 * 45);
    CHECK(short_reach.cells.size() > 4 * 30);
}

TEST_CASE("water/grow_waterbody level gate: with level_rise_m 0 the level does not creep up a gentle slope")
{
    // 40 x 40: a pond at 100 m in the west columns 0-5 (its columns 0-1 a dropout seed), then land from
    // 2 cm above it rising 4 mm per column eastward (gentler than the drift limit of 5 mm per cell).
    raster<float> min_z(40, 40);
    std::vector<std::ptrdiff_t> seed;
    for (std::ptrdiff_t r = 0; r < 40; ++r) {
        for (std::ptrdiff_t c = 0; c < 40; ++c) {
            min_z.view()(r, c) = c <= 5 ? 100.0f : 100.02f + 0.004f * static_cast<float>(c - 5);
            if (c <= 1) {
                min_z.view()(r, c) = NAN;
                seed.push_back(r * 40 + c);
            }
        }
    }
    const auto field = flat_field(min_z);
    grow_waterbody_workspace workspace;
    grow_waterbody_options creep;
    creep.level_rise_m = -1;  // rises like it falls (5 mm per cell): the flood climbs the whole slope
    CHECK(grow_waterbody(field, seed, creep, workspace).cells.size() == 40 * 40);
    grow_waterbody_options flat;
    flat.level_rise_m = 0;  // the level passed on never rises: the flood stops 0.15 m above the pond
    const auto held = grow_waterbody(field, seed, flat, workspace);
    // Land joins while 0.02 + 0.004 (c − 5) <= 0.15 m above the pond: columns up to 37, not 38 and 39.
    CHECK(held.cells.size() == 40 * 38);
}

TEST_CASE("water/grow_waterbody level gate: the level follows no cell of land intensity (level_follow_max_intensity)")
{
    // The gentle slope above (land from 2 cm above the pond rising 4 mm per column), now a lawn of intensity
    // 80 against the pond's 10. The level follows the lawn up when allowed to; with
    // level_follow_max_intensity 50 the lawn's cells pass the pond's level on unchanged, so the flood ends
    // 0.15 m above the pond as with a level that never rises.
    raster<float> min_z(40, 40), intensity(40, 40, 10.0f);
    std::vector<std::ptrdiff_t> seed;
    for (std::ptrdiff_t r = 0; r < 40; ++r) {
        for (std::ptrdiff_t c = 0; c < 40; ++c) {
            min_z.view()(r, c) = c <= 5 ? 100.0f : 100.02f + 0.004f * static_cast<float>(c - 5);
            if (c > 5) intensity.view()(r, c) = 80.0f;
            if (c <= 1) {
                min_z.view()(r, c) = NAN;
                intensity.view()(r, c) = NAN;
                seed.push_back(r * 40 + c);
            }
        }
    }
    auto field = flat_field(min_z);
    field.mean_intensity = intensity;
    grow_waterbody_workspace workspace;
    CHECK(grow_waterbody(field, seed, {}, workspace).cells.size() == 40 * 40);
    grow_waterbody_options hold;
    hold.level_follow_max_intensity = 50;
    CHECK(grow_waterbody(field, seed, hold, workspace).cells.size() == 40 * 38);
    hold.level_follow_max_intensity = 90;  // the lawn is below it: it leads the level up again
    CHECK(grow_waterbody(field, seed, hold, workspace).cells.size() == 40 * 40);
    // A field without intensities ignores the option; one of another shape is refused.
    field.mean_intensity = {};
    hold.level_follow_max_intensity = 50;
    CHECK(grow_waterbody(field, seed, hold, workspace).cells.size() == 40 * 40);
    const raster<float> wrong(3, 3, 0.0f);
    field.mean_intensity = wrong;
    CHECK_THROWS_AS(grow_waterbody(field, seed, hold, workspace), invalid_input);
}

TEST_CASE("water/grow_waterbody first-step test: a bright meadow 0.1 m above the pond, within the gate, stays out")
{
    // 30 x 30: a pond at 100 m in rows/cols 8-21 (its middle 4 x 4 a seed of dropouts), intensity bins 0-9
    // (dark); a flat meadow at 100.1 m around it, within the 0.15 m gate, intensity bins 30-39 (bright). The
    // angles are 0: everything joins at the first step, which had no test before.
    const std::ptrdiff_t n = 30;
    raster<float> min_z(n, n, 100.1f);
    std::vector<std::ptrdiff_t> seed;
    for (std::ptrdiff_t r = 8; r <= 21; ++r) {
        for (std::ptrdiff_t c = 8; c <= 21; ++c) {
            const bool in_seed = r >= 13 && r <= 16 && c >= 13 && c <= 16;
            min_z.view()(r, c) = in_seed ? NAN : 100.0f;
            if (in_seed) seed.push_back(r * n + c);
        }
    }
    auto field = flat_field(min_z);
    field.bins = 40;
    for (std::ptrdiff_t r = 0; r < n; ++r) {
        for (std::ptrdiff_t c = 0; c < n; ++c) {
            if (std::isnan(min_z(r, c))) continue;
            const bool pond = r >= 8 && r <= 21 && c >= 8 && c <= 21;
            field.intensity_bin.view()(r, c) = static_cast<std::int32_t>((pond ? 0 : 30) + (r * 7 + c * 3) % 10);
        }
    }
    grow_waterbody_workspace workspace;
    const auto tested = grow_waterbody(field, seed, {}, workspace);
    CHECK(tested.cells.size() == 14 * 14);  // the pond, nothing of the meadow

    grow_waterbody_options untested;
    untested.test_first_step = false;
    const auto flooded = grow_waterbody(field, seed, untested, workspace);
    CHECK(flooded.cells.size() == static_cast<std::size_t>(n * n));  // the meadow is within the gate

    // A meadow as dark as the pond is the same water to the test: it joins.
    auto dark = field;
    for (std::ptrdiff_t i = 0; i < dark.intensity_bin.size(); ++i)
        if (dark.intensity_bin.data()[i] >= 30) dark.intensity_bin.data()[i] -= 30;
    CHECK(grow_waterbody(dark, seed, {}, workspace).cells.size() == static_cast<std::size_t>(n * n));
}

TEST_CASE(
    "water/grow_waterbody level gate: with level_any_angle_m a channel narrower than the angular window is "
    "followed to its end")
{
    // 9 x 60: a channel two cells wide (rows 3-4) at 100 m, falling 0.002 m per column; banks 1.5 m above it.
    // Every channel cell sees a bank within the angular window: its angle (40°) exceeds θ max (30°), the banks'
    // own angles are 0. A seed of dropouts at the west end (cols 0-2).
    const std::ptrdiff_t rows = 9, cols = 60;
    raster<float> min_z(rows, cols);
    std::vector<std::ptrdiff_t> seed;
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const bool channel = r == 3 || r == 4;
            const float level = 100.0f - 0.002f * static_cast<float>(c);
            min_z.view()(r, c) = channel ? (c <= 2 ? NAN : level) : level + 1.5f;
            if (channel && c <= 2) seed.push_back(r * cols + c);
        }
    auto field = flat_field(min_z);
    for (std::ptrdiff_t c = 0; c < cols; ++c)  // the seed's dropouts join at any angle, as water_angles gives them
        field.angle_deg.view()(3, c) = field.angle_deg.view()(4, c) = c <= 2 ? NAN : 40.0f;
    grow_waterbody_workspace workspace;
    const auto by_angle = grow_waterbody(field, seed, {}, workspace);
    CHECK(by_angle.cells.size() == seed.size());  // the angles keep every channel cell with a return out

    grow_waterbody_options by_level;
    by_level.level_any_angle_m = 0.05;
    const auto followed = grow_waterbody(field, seed, by_level, workspace);
    CHECK(followed.cells.size() == static_cast<std::size_t>(2 * cols));  // the whole channel, no bank cell
    for (const auto i : followed.cells) CHECK((i / cols == 3 || i / cols == 4));

    // A step of 0.1 m in the channel at column 30 is beyond 0.05 m of the level: the flood ends there.
    for (std::ptrdiff_t c = 30; c < cols; ++c) min_z.view()(3, c) = min_z.view()(4, c) = min_z.view()(3, c) + 0.1f;
    field.min_z = min_z;
    CHECK(grow_waterbody(field, seed, by_level, workspace).cells.size() == static_cast<std::size_t>(2 * 30));
    by_level.level_any_angle_m = NAN;
    CHECK_THROWS_AS(grow_waterbody(field, seed, by_level, workspace), invalid_input);
}
