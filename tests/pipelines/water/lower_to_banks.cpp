// SPDX-License-Identifier: Apache-2.0
// lower_to_banks: a river 6 cells wide and 200 long on 1 m cells between two rows of bank, falling 1 m from west to
// east, with a 0.6 m weir at column 150 and no water returns below it: the profile keeps the upper pool there
// until the banks lower it.
// The test cases stay inside the namespace: in a unity build its short names must not reach the next file.
#include <doctest/doctest.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include <lidarfx/core/error.hpp>
#include <lidarfx/core/raster.hpp>
#include <lidarfx/pipelines/water/hydro_body_shape.hpp>
#include <lidarfx/pipelines/water/lower_to_banks.hpp>
#include <lidarfx/pipelines/water/river_profile.hpp>

using namespace lidarfx;

namespace lower_to_banks_test {

constexpr std::ptrdiff_t rows = 8, cols = 200, weir_col = 150;
constexpr float nan_f = std::numeric_limits<float>::quiet_NaN();

/// The true water level of column c: 1 m of fall over the river, 0.6 m lower from the weir on.
float truth(std::ptrdiff_t c)
{
    return static_cast<float>(100.0 - (static_cast<double>(c) + 0.5) / cols - (c >= weir_col ? 0.6 : 0.0));
}

struct river_with_banks {
    raster<std::int32_t> labels{rows, cols, 0};
    raster<float> water_z{rows, cols, nan_f}, ground{rows, cols, nan_f};
    cell_box box{1, 0, rows - 2, cols - 1};

    /// Banks `bank_rise_m` above the water beside them; water returns west of `returns_until` only.
    river_with_banks(float bank_rise_m, std::ptrdiff_t returns_until)
    {
        for (std::ptrdiff_t r = 0; r < rows; ++r)
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                if (r == 0 || r == rows - 1) {
                    ground(r, c) = truth(c) + bank_rise_m;
                    continue;
                }
                labels(r, c) = 1;
                ground(r, c) = truth(c);
                if (c < returns_until) water_z(r, c) = truth(c);
            }
    }
    river_profile profile() const
    {
        return trace_river_profile(labels, 1, box, measure_hydro_body_shape(labels, 1, box, 1.0), water_z, 1.0);
    }
};

/// The largest |level − truth| over the cells of the river's sections that `measured` did not measure (all of
/// them when `unmeasured_only` is false).
double worst_error(const river_profile& p, const river_profile& measured, bool unmeasured_only = true)
{
    double worst = 0;
    for (std::ptrdiff_t r = 0; r < p.box.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < p.box.cols(); ++c)
            if (const std::int32_t k = p.section(r, c); k >= 0)
                if (!unmeasured_only || measured.returns[static_cast<std::size_t>(k)] == 0)
                    worst = std::max(worst, std::abs(p.level_m[static_cast<std::size_t>(k)] - truth(c)));
    return worst;
}

bool non_increasing(const river_profile& p)
{
    for (std::size_t k = 0; k + 1 < p.level_m.size(); ++k)
        if (!(p.level_m[k + 1] <= p.level_m[k])) return false;
    return true;
}

TEST_CASE("water/lower_to_banks: a stretch without returns below a weir comes down to its banks")
{
    river_with_banks river(0.02f, weir_col);
    river_profile p = river.profile();
    const river_profile measured = p;
    REQUIRE(worst_error(p, measured) > 0.5);  // the unmeasured stretch kept the upper pool's level
    const lower_to_banks_result lowered = lower_to_banks(p, river.labels, 1, river.ground);
    CHECK(lowered.sections_lowered >= 9);
    CHECK(lowered.largest_drop_m > 0.5);
    CHECK(worst_error(p, measured) <= 0.05);
    CHECK(non_increasing(p));
    CHECK(p.weirs == 1);
    for (std::size_t k = 0; k < p.level_m.size(); ++k)
        if (measured.returns[k] > 0) CHECK(p.level_m[k] == measured.level_m[k]);  // measured sections stay
}

/// lower_to_banks leaves the river's profile as trace_river_profile made it.
bool changes_nothing(const river_with_banks& river)
{
    river_profile p = river.profile();
    const river_profile before = p;
    return lower_to_banks(p, river.labels, 1, river.ground).sections_lowered == 0 && p.level_m == before.level_m;
}

TEST_CASE("water/lower_to_banks: banks above the water, measured water and a section without banks change nothing")
{
    CHECK(changes_nothing(river_with_banks(1.0f, weir_col)));  // banks 1 m above the water
    CHECK(changes_nothing(river_with_banks(0.0f, cols)));      // every section measured, banks at the water
    river_with_banks without_ground(0.02f, weir_col);
    for (const std::ptrdiff_t r : {std::ptrdiff_t{0}, rows - 1})
        for (std::ptrdiff_t c = 0; c < cols; ++c) without_ground.ground(r, c) = nan_f;
    CHECK(changes_nothing(without_ground));
}

TEST_CASE("water/lower_to_banks: never below the measured section downstream of the stretch")
{
    // Returns again from column 180: the stretch 150-179 lies between measured sections, and its banks dip 2 m at
    // columns 160-169 (a ditch beside the river). The stretch comes down to the lower pool, not into the ditch:
    // beside the ditch it stops at the level of the first measured section downstream.
    river_with_banks river(0.02f, weir_col);
    for (std::ptrdiff_t r = 1; r < rows - 1; ++r)
        for (std::ptrdiff_t c = 180; c < cols; ++c) river.water_z(r, c) = truth(c);
    for (const std::ptrdiff_t r : {std::ptrdiff_t{0}, rows - 1})
        for (std::ptrdiff_t c = 160; c < 170; ++c) river.ground(r, c) = truth(c) - 2.0f;
    river_profile p = river.profile();
    const river_profile measured = p;
    lower_to_banks(p, river.labels, 1, river.ground);
    CHECK(non_increasing(p));
    std::size_t last_unmeasured = 0;
    for (std::size_t k = 0; k < p.level_m.size(); ++k)
        if (measured.returns[k] == 0) last_unmeasured = k;
    REQUIRE(last_unmeasured + 1 < p.level_m.size());
    const double floor = measured.level_m[last_unmeasured + 1];
    for (std::size_t k = 0; k <= last_unmeasured; ++k) CHECK(p.level_m[k] >= floor);
    CHECK(worst_error(p, measured) <= 0.15);  // the fall from the ditch to the measured section: 0.1 m
}

TEST_CASE("water/lower_to_banks: refuses other shapes, a quantile out of [0, 1] and a profile of another box")
{
    river_with_banks river(0.02f, weir_col);
    river_profile p = river.profile();
    const raster<float> small(rows - 1, cols, 0.0f);
    CHECK_THROWS_AS(lower_to_banks(p, river.labels, 1, small), invalid_input);
    for (const double q : {-0.1, 1.5, std::numeric_limits<double>::quiet_NaN()})
        CHECK_THROWS_AS(lower_to_banks(p, river.labels, 1, river.ground, {}, {.bank_quantile = q}), invalid_input);
    river_profile other = p;
    other.box = {0, 0, rows - 1, cols - 1};
    CHECK_THROWS_AS(lower_to_banks(other, river.labels, 1, river.ground), invalid_input);
}

}  // namespace lower_to_banks_test
