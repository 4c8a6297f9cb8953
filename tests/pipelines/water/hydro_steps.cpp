// SPDX-License-Identifier: Apache-2.0
// The steps of hydro_flatten, each on small hand-made rasters: enforce_shorelines, water_heights, lake_level,
// measure_hydro_body_shape, trace_river_profile and hydro_qa.
#include <doctest/doctest.h>

#include <lidarfx/core/error.hpp>
#include <lidarfx/core/grid.hpp>
#include <lidarfx/core/raster.hpp>
#include <lidarfx/kernels/filter/geodesic_distance.hpp>
#include <lidarfx/pipelines/water/enforce_shorelines.hpp>
#include <lidarfx/pipelines/water/hydro_body_shape.hpp>
#include <lidarfx/pipelines/water/hydro_flatten.hpp>
#include <lidarfx/pipelines/water/hydro_qa.hpp>
#include <lidarfx/pipelines/water/lake_level.hpp>
#include <lidarfx/pipelines/water/river_profile.hpp>
#include <lidarfx/pipelines/water/water_heights.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

#include "test_values.hpp"
#include "water_test_rasters.hpp"

using namespace lidarfx;
using water_test::grid_of;

namespace hydro_steps_test {

/// A straight river 6 cells wide and 200 long on 1 m cells, all label 1. Its true water surface falls linearly
/// along the columns from 100 m at the west edge to 99 m at the east edge (0.5 %), or rises when
/// `east_downstream` is false; `water_z` adds normal noise of 1 cm, as the water heights of a survey scatter.
struct river_strip {
    static constexpr std::ptrdiff_t rows = 6, cols = 200;
    raster<std::int32_t> labels{rows, cols, 1};
    raster<float> truth{rows, cols}, water_z{rows, cols};
    cell_box box{0, 0, rows - 1, cols - 1};

    explicit river_strip(bool east_downstream = true, unsigned seed = 11)
    {
        std::mt19937 rng(seed);
        std::normal_distribution<double> noise(0, 0.01);
        for (std::ptrdiff_t r = 0; r < rows; ++r)
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                const double along = (static_cast<double>(c) + 0.5) / static_cast<double>(cols);
                truth(r, c) = static_cast<float>(east_downstream ? 100 - along : 99 + along);
                water_z(r, c) = static_cast<float>(truth(r, c) + noise(rng));
            }
    }
    /// Adds `dz` to the truth and the water heights of columns >= c0 (a weir when negative).
    void step_at(std::ptrdiff_t c0, float dz)
    {
        for (std::ptrdiff_t r = 0; r < rows; ++r)
            for (std::ptrdiff_t c = c0; c < cols; ++c) {
                truth(r, c) += dz;
                water_z(r, c) += dz;
            }
    }
    hydro_body_shape shape() const { return measure_hydro_body_shape(labels, 1, box, 1.0); }
    river_profile profile(const river_profile_options& opt, const hydro_body_shape& s) const
    {
        return trace_river_profile(labels, 1, box, s, water_z, 1.0, opt);
    }
};

/// The river tests hold with trace_river_profile's default options.
constexpr river_profile_options strip_options{};

/// The true level of each section: the median (position n / 2) of the noise-free surface over its cells.
std::vector<double> section_truth(const river_profile& p, const raster<float>& truth)
{
    std::vector<std::vector<float>> cells(p.level_m.size());
    for (std::ptrdiff_t r = 0; r < p.box.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < p.box.cols(); ++c)
            if (const std::int32_t k = p.section(r, c); k >= 0)
                cells[static_cast<std::size_t>(k)].push_back(truth(p.box.row_min + r, p.box.col_min + c));
    std::vector<double> out(cells.size(), NAN);
    for (std::size_t k = 0; k < cells.size(); ++k) {
        auto& v = cells[k];
        if (v.empty()) continue;
        std::sort(v.begin(), v.end());
        out[k] = v[v.size() / 2];
    }
    return out;
}

/// The largest |level - truth| over the sections.
double worst_level_error(const river_profile& p, const raster<float>& truth)
{
    const auto t = section_truth(p, truth);
    double worst = 0;
    for (std::size_t k = 0; k < t.size(); ++k) worst = std::max(worst, std::abs(p.level_m[k] - t[k]));
    return worst;
}

bool non_increasing(const std::vector<double>& level)
{
    for (std::size_t k = 0; k + 1 < level.size(); ++k)
        if (!(level[k + 1] <= level[k])) return false;
    return true;
}

/// The checks of `body` in `qa`, in their order.
std::vector<hydro_check> checks_of(const std::vector<hydro_check>& qa, std::int32_t body)
{
    std::vector<hydro_check> out;
    for (const auto& q : qa)
        if (q.body == body) out.push_back(q);
    return out;
}

}  // namespace hydro_steps_test

// ---------------------------------------------------------------------------------------------------------------
// enforce_shorelines

namespace hydro_steps_test {

/// Water in a 2 x 2 block, its north row at 10 m, its south row at 10.5 m; land at 11 m except the cells named.
struct shore_scene {
    raster<float> water = grid_of<float>({{nan_f, nan_f, nan_f, nan_f, nan_f},
                                          {nan_f, 10.0f, 10.0f, nan_f, nan_f},
                                          {nan_f, 10.5f, 10.5f, nan_f, nan_f},
                                          {nan_f, nan_f, nan_f, nan_f, nan_f},
                                          {nan_f, nan_f, nan_f, nan_f, nan_f}});
    raster<float> ground =
        grid_of<float>({{9.0f, 11.0f, 11.0f, 10.0f, 11.0f},  // (0, 0) beside 10 m only; (0, 3) level with it
                        {11.0f, 5.0f, 5.0f, 10.2f, 11.0f},   // water on 5 m ground; (1, 3) beside 10.5
                        {11.0f, 5.0f, 5.0f, 11.0f, 11.0f},
                        {11.0f, 9.2f, 11.0f, nan_f, 11.0f},    // (3, 1) beside 10.5; NaN ground
                        {11.0f, 11.0f, 11.0f, 11.0f, 2.0f}});  // (4, 4) far from the water
};

}  // namespace hydro_steps_test

TEST_CASE("water/enforce_shorelines: lifts shore ground below the water to the highest water beside it")
{
    hydro_steps_test::shore_scene s;
    const auto check = enforce_shorelines(s.ground, s.water, shoreline_rule::lift);
    CHECK(check.below == 3);                                     // (0, 0), (1, 3) and (3, 1)
    CHECK(check.worst_m == doctest::Approx(1.3).epsilon(1e-6));  // 10.5 - 9.2 in float
    CHECK(check.worst_row == 3);
    CHECK(check.worst_col == 1);
    const float expected[5][5] = {{10.0f, 11.0f, 11.0f, 10.0f, 11.0f},
                                  {11.0f, 5.0f, 5.0f, 10.5f, 11.0f},
                                  {11.0f, 5.0f, 5.0f, 11.0f, 11.0f},
                                  {11.0f, 10.5f, 11.0f, nan_f, 11.0f},
                                  {11.0f, 11.0f, 11.0f, 11.0f, 2.0f}};
    for (std::ptrdiff_t r = 0; r < 5; ++r)
        for (std::ptrdiff_t c = 0; c < 5; ++c) {
            CAPTURE(r);
            CAPTURE(c);
            if (std::isnan(expected[r][c]))
                CHECK(std::isnan(s.ground(r, c)));  // NaN ground is not shore: left alone
            else
                CHECK(s.ground(r, c) == expected[r][c]);  // lifted to the highest water beside, not the nearest;
                                                          // water cells keep their ground; land above stays
        }
    // Lifted shores are no longer below: a second pass finds nothing.
    const auto again = enforce_shorelines(s.ground, s.water);
    CHECK(again.below == 0);
    CHECK(again.worst_m == 0);
    CHECK(again.worst_row == -1);
    CHECK(again.worst_col == -1);
}

TEST_CASE("water/enforce_shorelines: shoreline_rule::flag counts the same cells and changes nothing")
{
    hydro_steps_test::shore_scene s;
    const raster<float> before = s.ground;
    const auto check = enforce_shorelines(s.ground, s.water, shoreline_rule::flag);
    CHECK(check.below == 3);
    CHECK(check.worst_m == doctest::Approx(1.3).epsilon(1e-6));
    CHECK(check.worst_row == 3);
    CHECK(check.worst_col == 1);
    for (std::ptrdiff_t r = 0; r < 5; ++r)
        for (std::ptrdiff_t c = 0; c < 5; ++c)
            CHECK((s.ground(r, c) == before(r, c) || (std::isnan(s.ground(r, c)) && std::isnan(before(r, c)))));
    // No water at all: nothing to compare with.
    raster<float> ground(3, 3, 1.0f);
    const auto none = enforce_shorelines(ground, raster<float>(3, 3, nan_f));
    CHECK(none.below == 0);
    CHECK(none.worst_row == -1);
    raster<float> wrong(3, 4, 1.0f);
    CHECK_THROWS_AS(enforce_shorelines(wrong, raster<float>(4, 3, nan_f)), invalid_input);
}

// ---------------------------------------------------------------------------------------------------------------
// water_heights

TEST_CASE("water/water_heights: lowest return plus the body's median half spread; NaN on land and without returns")
{
    // Body 1: six cells with returns, five spreading 0.25 m and one under a deck's edge (max_z 5 m up), and one
    // cell without returns. Body 2: spreads 0.5 and 1 m, so half spreads 0.25 and 0.5, the median (position
    // n / 2 = 1) 0.5. Body 3: no return at all.
    const auto labels = grid_of<std::int32_t>({{0, 1, 1, 1, 0},  //
                                               {1, 1, 1, 1, 0},
                                               {0, 0, 0, 2, 2},
                                               {3, 0, 0, 0, 0}});
    const auto min_z = grid_of<float>({{7.0f, 10.0f, 10.25f, 10.5f, 7.0f},
                                       {10.0f, 10.0f, nan_f, 9.75f, 7.0f},
                                       {7.0f, 7.0f, 7.0f, 20.0f, 20.5f},
                                       {nan_f, 7.0f, 7.0f, 7.0f, 7.0f}});
    const auto max_z = grid_of<float>({{8.0f, 10.25f, 10.5f, 10.75f, 8.0f},
                                       {10.25f, 15.0f, nan_f, 10.0f, 8.0f},
                                       {8.0f, 8.0f, 8.0f, 20.5f, 21.5f},
                                       {nan_f, 8.0f, 8.0f, 8.0f, 8.0f}});
    const auto h = water_heights(labels, min_z, max_z);
    REQUIRE(h.rows() == 4);
    REQUIRE(h.cols() == 5);
    // Half spreads of body 1: 0.125 x 5 and 2.5 (the deck); position 3 of the 6 sorted: 0.125. The deck raises
    // neither the body's half spread nor its own cell, which stands on its lowest return.
    CHECK(h(0, 1) == 10.125f);
    CHECK(h(0, 2) == 10.375f);
    CHECK(h(0, 3) == 10.625f);
    CHECK(h(1, 0) == 10.125f);
    CHECK(h(1, 1) == 10.125f);  // the deck's cell
    CHECK(h(1, 3) == 9.875f);
    CHECK(std::isnan(h(1, 2)));  // water without a return
    CHECK(h(2, 3) == 20.5f);
    CHECK(h(2, 4) == 21.0f);
    CHECK(std::isnan(h(3, 0)));  // a body without any return
    for (std::ptrdiff_t r = 0; r < 4; ++r)
        for (std::ptrdiff_t c = 0; c < 5; ++c)
            if (labels(r, c) == 0) CHECK(std::isnan(h(r, c)));  // land, though it has returns
}

TEST_CASE("water/water_heights: a deck's max_z does not raise the level; refuses other shapes and negative labels")
{
    // A 6 x 6 body inside land: 16 inner cells (all 8 neighbours in the body), 20 on its edge.
    raster<std::int32_t> labels(8, 8, 0);
    for (std::ptrdiff_t r = 1; r < 7; ++r)
        for (std::ptrdiff_t c = 1; c < 7; ++c) labels(r, c) = 1;
    raster<float> min_z(8, 8, 50.0f), max_z(8, 8, 50.5f);
    const auto open = water_heights(labels, min_z, max_z);
    for (std::ptrdiff_t c = 1; c < 7; ++c) max_z(2, c) = 57.0f;  // a deck over a row: 4 of the 16 inner cells
    const auto decked = water_heights(labels, min_z, max_z);
    for (std::ptrdiff_t r = 0; r < 8; ++r)
        for (std::ptrdiff_t c = 0; c < 8; ++c) {
            CAPTURE(r);
            CAPTURE(c);
            if (labels(r, c) == 0) continue;
            CHECK(open(r, c) == 50.25f);
            CHECK(decked(r, c) == 50.25f);
        }
    CHECK_THROWS_AS(water_heights(labels, raster<float>(8, 9), max_z), invalid_input);
    CHECK_THROWS_AS(water_heights(labels, min_z, raster<float>(7, 8)), invalid_input);
    labels(2, 2) = -1;
    CHECK_THROWS_AS(water_heights(labels, min_z, max_z), invalid_input);
}

TEST_CASE("water/water_heights: the half spread is that of the open water when the body has inner cells")
{
    // Banks in every edge cell spread its returns over 2 m; the 16 inner cells over 0.5 m. Over all 36 cells the
    // median half spread would be the banks' 1 m; over the inner ones it is 0.25 m.
    raster<std::int32_t> labels(8, 8, 0);
    raster<float> min_z(8, 8, 30.0f), max_z(8, 8, 32.0f);
    for (std::ptrdiff_t r = 1; r < 7; ++r)
        for (std::ptrdiff_t c = 1; c < 7; ++c) labels(r, c) = 4;
    for (std::ptrdiff_t r = 2; r < 6; ++r)
        for (std::ptrdiff_t c = 2; c < 6; ++c) max_z(r, c) = 30.5f;
    const auto h = water_heights(labels, min_z, max_z);
    for (std::ptrdiff_t r = 1; r < 7; ++r)
        for (std::ptrdiff_t c = 1; c < 7; ++c) CHECK(h(r, c) == 30.25f);
}

// ---------------------------------------------------------------------------------------------------------------
// lake_level

namespace hydro_steps_test {

/// Lake 1 (rows 1-2, columns 1-3) with water heights 10.0 .. 10.4 m and one cell without a return; its shore at
/// 12 m, except two low cells and one NaN cell; lake 2 beside it on 1 m ground (not land, so not shore), and land
/// beyond the shore at 1 m (not shore either).
struct lake_scene {
    raster<std::int32_t> labels = grid_of<std::int32_t>({{0, 0, 0, 0, 0, 0},  //
                                                         {0, 1, 1, 1, 0, 0},
                                                         {0, 1, 1, 1, 0, 0},
                                                         {0, 0, 0, 0, 2, 0},
                                                         {0, 0, 0, 0, 0, 0}});
    cell_box box{1, 1, 2, 3};
    raster<float> water_z = grid_of<float>({{nan_f, nan_f, nan_f, nan_f, nan_f, nan_f},
                                            {nan_f, 10.3f, 10.0f, 10.4f, nan_f, nan_f},
                                            {nan_f, 10.1f, nan_f, 10.2f, nan_f, nan_f},
                                            {nan_f, nan_f, nan_f, nan_f, 50.0f, nan_f},
                                            {nan_f, nan_f, nan_f, nan_f, nan_f, nan_f}});
    raster<float> ground = grid_of<float>({{9.9f, 12.0f, nan_f, 12.0f, 12.0f, 1.0f},
                                           {12.0f, 3.0f, 3.0f, 3.0f, 12.0f, 1.0f},
                                           {12.0f, 3.0f, 3.0f, 3.0f, 12.0f, 1.0f},
                                           {12.0f, 12.0f, 12.0f, 10.05f, 1.0f, 1.0f},
                                           {1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f}});
    double mode_window_m = 1.0;  ///< taller than the heights' spread: the densest window holds them all
    lake_level_result level(lake_level_options opt = {}) const
    {
        opt.mode_window_m = mode_window_m;
        return lake_level(labels, 1, box, water_z, ground, opt);
    }
};

}  // namespace hydro_steps_test

TEST_CASE("water/lake_level: the median of the lake's water heights; cap_at_shore lowers it to the shore quantile")
{
    hydro_steps_test::lake_scene s;  // its mode window holds all heights: the plain median
    // Shore: the 13 land cells 8-adjacent to the lake (rows 0-3, columns 0-4, less the lake and lake 2), one
    // with NaN ground: 12. Its ground sorted: 9.9, 10.05, then 12 x 10.
    const auto plain = s.level();
    CHECK(plain.returns == 5);
    CHECK(plain.shore_cells == 12);
    CHECK(plain.returns_level_m == static_cast<double>(10.2f));  // position 5 / 2 = 2 of 10.0 .. 10.4
    CHECK(plain.level_m == plain.returns_level_m);               // no cap by default
    CHECK(plain.shore_low_m == static_cast<double>(9.9f));       // position floor(0.05 x 11) = 0
    const auto capped = s.level({.cap_at_shore = true});
    CHECK(capped.level_m == static_cast<double>(9.9f));
    CHECK(capped.returns_level_m == static_cast<double>(10.2f));
    // Quantile 0.1: position floor(0.1 x 11) = 1, 10.05; 5 cm below it: 10.0.
    const auto tenth = s.level({.cap_at_shore = true, .shore_quantile = 0.1, .below_shore_m = 0.05});
    CHECK(tenth.shore_low_m == static_cast<double>(10.05f));
    CHECK(tenth.level_m == doctest::Approx(static_cast<double>(10.05f) - 0.05).epsilon(1e-12));
    // A shore above the water does not raise the level: the cap only lowers.
    const auto high = s.level({.cap_at_shore = true, .shore_quantile = 1.0});
    CHECK(high.shore_low_m == 12.0);
    CHECK(high.level_m == static_cast<double>(10.2f));
}

TEST_CASE("water/lake_level: the level is where the heights crowd: banks and reeds taken into the body do not lift it")
{
    // 40 cells of open water at 50.00-50.03 m and 60 cells of bank spread over 50.2-53.0 m: the median of all
    // heights is on the bank; the densest 0.1 m window is the water.
    raster<std::int32_t> labels(10, 10, 1);
    raster<float> water_z(10, 10), ground(10, 10, 60.0f);
    for (std::ptrdiff_t k = 0; k < 100; ++k)
        water_z.data()[k] =
            k < 40 ? 50.0f + 0.01f * static_cast<float>(k % 4) : 50.2f + 0.047f * static_cast<float>(k - 40);
    const cell_box box{0, 0, 9, 9};
    const auto densest = lake_level(labels, 1, box, water_z, ground);
    CHECK(densest.returns == 100);
    CHECK(densest.level_m >= 50.0);
    CHECK(densest.level_m <= 50.03 + 1e-6);
    const auto everything = lake_level(labels, 1, box, water_z, ground, {.mode_window_m = 10.0});
    CHECK(everything.level_m > 50.5);  // the median of all 100 heights lies on the bank
    CHECK_THROWS_AS(lake_level(labels, 1, box, water_z, ground, {.mode_window_m = 0}), invalid_input);
}

TEST_CASE("water/lake_level: a lake without returns takes its shore; without either it has no level")
{
    hydro_steps_test::lake_scene s;
    s.water_z.fill(nan_f);
    const auto shore = s.level({.below_shore_m = 0.25});
    CHECK(shore.returns == 0);
    CHECK(std::isnan(shore.returns_level_m));
    CHECK(shore.level_m == doctest::Approx(static_cast<double>(9.9f) - 0.25).epsilon(1e-12));
    s.ground.fill(nan_f);
    const auto nothing = s.level();
    CHECK(nothing.shore_cells == 0);
    CHECK(std::isnan(nothing.level_m));
    // A lake that fills the raster has no shore but keeps its returns' level, capped or not.
    raster<std::int32_t> all(2, 2, 1);
    raster<float> z = grid_of<float>({{4.0f, 5.0f}, {6.0f, 7.0f}});
    const auto full =
        lake_level(all, 1, {0, 0, 1, 1}, z, raster<float>(2, 2, 0.0f), {.mode_window_m = 10.0, .cap_at_shore = true});
    CHECK(full.shore_cells == 0);
    CHECK(full.level_m == 6.0);  // position 4 / 2 = 2 of the window holding all four
}

TEST_CASE("water/lake_level: refuses other shapes, options out of range and boxes outside the raster")
{
    hydro_steps_test::lake_scene s;
    const raster<float> other(5, 7);
    CHECK_THROWS_AS(lake_level(s.labels, 1, s.box, other, s.ground), invalid_input);
    CHECK_THROWS_AS(lake_level(s.labels, 1, s.box, s.water_z, other), invalid_input);
    for (const double q : {-0.01, 1.01, static_cast<double>(NAN)}) {
        CAPTURE(q);
        CHECK_THROWS_AS(s.level({.shore_quantile = q}), invalid_input);
    }
    for (const double below : {-0.1, static_cast<double>(NAN), static_cast<double>(INFINITY)}) {
        CAPTURE(below);
        CHECK_THROWS_AS(s.level({.below_shore_m = below}), invalid_input);
    }
    for (const cell_box& box : {cell_box{}, cell_box{-1, 0, 2, 3}, cell_box{1, 1, 5, 3}, cell_box{1, 1, 2, 6}}) {
        CHECK_THROWS_AS(lake_level(s.labels, 1, box, s.water_z, s.ground), invalid_input);
    }
    CHECK_NOTHROW(s.level({.shore_quantile = 0.0, .below_shore_m = 0.0}));
}

// ---------------------------------------------------------------------------------------------------------------
// measure_hydro_body_shape

TEST_CASE("water/measure_hydro_body_shape: a straight 3 x 40 channel is 40 cells long and 3 wide")
{
    raster<std::int32_t> labels(6, 44, 0);
    for (std::ptrdiff_t r = 2; r < 5; ++r)
        for (std::ptrdiff_t c = 3; c < 43; ++c) labels(r, c) = 7;
    labels(0, 0) = 1;  // another body
    const cell_box box{2, 3, 4, 42};
    const double cell_m = 2.0;
    const auto s = measure_hydro_body_shape(labels, 7, box, cell_m);
    CHECK(s.area_m2 == 120 * 4.0);
    // The longest path runs corner to corner: 37 steps along, 2 diagonals across, plus one cell.
    CHECK(s.length_m == doctest::Approx(cell_m * (37 + 2 * std::numbers::sqrt2 + 1)).epsilon(1e-6));
    CHECK(std::abs(s.length_m - 40 * cell_m) <= cell_m);
    CHECK(s.width_m == doctest::Approx(3 * cell_m).epsilon(0.03));  // 3 cells, less the corner cut (2 %)
    CHECK(s.width_m == s.area_m2 / s.length_m);
    CHECK(s.elongation() == doctest::Approx(13.9).epsilon(0.01));
    // The ends: farthest from the first cell (2, 3) is the opposite corner, and farthest from it that cell.
    CHECK(s.end_a == std::array<std::ptrdiff_t, 2>{4, 42});
    CHECK(s.end_b == std::array<std::ptrdiff_t, 2>{2, 3});
    const auto mask = body_mask(labels, 7, box);
    REQUIRE(mask.rows() == 3);
    REQUIRE(mask.cols() == 40);
    for (const std::uint8_t m : mask) CHECK(m == 1);
}

TEST_CASE("water/measure_hydro_body_shape: a bend is measured along the channel; a square and a disc stay lakes")
{
    // A U of width 1: down column 0 (rows 0-9), along row 9, up column 9. Its two ends are (0, 0) and (0, 9);
    // the path between them is 8 + sqrt(2) + 7 + sqrt(2) + 8 cells.
    raster<std::int32_t> u(10, 10, 0);
    for (std::ptrdiff_t k = 0; k < 10; ++k) u(k, 0) = u(9, k) = u(k, 9) = 1;
    const auto bend = measure_hydro_body_shape(u, 1, {0, 0, 9, 9}, 1.0);
    CHECK(bend.length_m == doctest::Approx(23 + 2 * std::numbers::sqrt2 + 1).epsilon(1e-6));
    CHECK(bend.area_m2 == 28.0);
    CHECK(bend.elongation() >= hydro_flatten_options{}.min_river_elongation);  // a river by default
    // A square's longest path is its diagonal: elongation = diagonal^2 / area -> 2.
    raster<std::int32_t> square(20, 20, 3);
    const auto sq = measure_hydro_body_shape(square, 3, {0, 0, 19, 19}, 0.5);
    CHECK(sq.length_m == doctest::Approx(0.5 * (19 * std::numbers::sqrt2 + 1)).epsilon(1e-6));
    CHECK(sq.elongation() == doctest::Approx(2).epsilon(0.05));
    // A disc of radius 20 cells: 4 / pi = 1.27 in the plane; the chamfer metric lengthens paths off the axes and
    // diagonals by up to 8 %, so on the raster the disc measures about (1.08 D)^2 / (pi D^2 / 4) = 1.5.
    raster<std::int32_t> disc(41, 41, 0);
    for (std::ptrdiff_t r = 0; r < 41; ++r)
        for (std::ptrdiff_t c = 0; c < 41; ++c)
            if ((r - 20) * (r - 20) + (c - 20) * (c - 20) <= 400) disc(r, c) = 1;
    const auto round = measure_hydro_body_shape(disc, 1, {0, 0, 40, 40}, 1.0);
    CHECK(round.elongation() >= 4 / std::numbers::pi);
    CHECK(round.elongation() <= 1.6);
    CHECK(round.elongation() < hydro_flatten_options{}.min_river_elongation);
}

TEST_CASE("water/measure_hydro_body_shape: refuses a cell_m not > 0, a box outside the raster, a label not in it")
{
    raster<std::int32_t> labels(4, 5, 0);
    labels(1, 1) = labels(1, 2) = 2;
    const cell_box box{1, 1, 1, 2};
    for (const double cell_m : {0.0, -2.0, static_cast<double>(NAN), static_cast<double>(INFINITY)}) {
        CAPTURE(cell_m);
        CHECK_THROWS_AS(measure_hydro_body_shape(labels, 2, box, cell_m), invalid_input);
    }
    for (const cell_box& bad : {cell_box{}, cell_box{-1, 1, 1, 2}, cell_box{1, 1, 4, 2}, cell_box{1, 1, 1, 5}}) {
        CHECK_THROWS_AS(measure_hydro_body_shape(labels, 2, bad, 1.0), invalid_input);
        CHECK_THROWS_AS(body_mask(labels, 2, bad), invalid_input);
    }
    CHECK_THROWS_AS(measure_hydro_body_shape(labels, 3, box, 1.0), invalid_input);
    CHECK_THROWS_AS(measure_hydro_body_shape(labels, 2, cell_box{2, 0, 3, 4}, 1.0), invalid_input);
    const auto two = measure_hydro_body_shape(labels, 2, box, 1.0);  // two cells: one step plus one cell
    CHECK(two.length_m == 2.0);
    CHECK(two.width_m == 1.0);
}

// ---------------------------------------------------------------------------------------------------------------
// trace_river_profile

TEST_CASE("water/trace_river_profile: a steady fall is followed within 2 cm, non-increasing, from the upstream end")
{
    const hydro_steps_test::river_strip river;
    const auto shape = river.shape();
    REQUIRE(shape.end_a == std::array<std::ptrdiff_t, 2>{5, 199});  // end_a is the downstream end here
    const auto p = river.profile(hydro_steps_test::strip_options, shape);
    const std::size_t n = p.level_m.size();
    REQUIRE(n >= 40);  // 202 m of channel in 5 m sections
    CHECK(p.box == river.box);
    CHECK(hydro_steps_test::non_increasing(p.level_m));
    CHECK(hydro_steps_test::worst_level_error(p, river.truth) <= 0.02);
    // Section 0 is upstream (west), the last one downstream (east).
    CHECK(p.section(0, 0) == 0);
    CHECK(p.section(5, 199) == static_cast<std::int32_t>(n - 1));
    CHECK(p.centre.front()[1] < 5);
    CHECK(p.centre.back()[1] > 194);
    CHECK(p.level_m.front() > 99.98);  // the first and last sections are centred 0.2 and 2.8 m from the ends
    CHECK(p.level_m.back() < 99.02);
    // Every cell is in a section; open water: every section is measured, and the fit keeps its median.
    std::size_t cells = 0;
    for (std::size_t k = 0; k < n; ++k) {
        CAPTURE(k);
        cells += p.cells[k];
        CHECK(p.returns[k] > 0);
        CHECK(p.returns[k] <= p.cells[k]);
        CHECK(p.measured_m[k] == doctest::Approx(p.level_m[k]).epsilon(1e-4));  // 1 cm at 100 m
    }
    CHECK(cells == 1200);
    for (const std::int32_t k : p.section) CHECK(k >= 0);
    CHECK(p.weirs == 0);
    CHECK(p.largest_step_m < 0.05);  // 5 m of a 0.5 % fall, plus noise
}

TEST_CASE(
    "water/trace_river_profile: sections are cut from the geodesic distance and numbered from upstream either way")
{
    const hydro_steps_test::river_strip river;
    auto shape = river.shape();
    std::swap(shape.end_a, shape.end_b);  // now end_a = (0, 0), the upstream end: no renumbering
    const auto p = river.profile(hydro_steps_test::strip_options, shape);
    const auto d = geodesic_distance(body_mask(river.labels, 1, river.box), 0, 0, 1.0);
    for (std::ptrdiff_t r = 0; r < river.rows; ++r)
        for (std::ptrdiff_t c = 0; c < river.cols; ++c)
            CHECK(p.section(r, c) == static_cast<std::int32_t>(std::floor(d(r, c) / 5.0)));
    CHECK(p.centre.front()[1] < 5);
    CHECK(hydro_steps_test::non_increasing(p.level_m));
    CHECK(hydro_steps_test::worst_level_error(p, river.truth) <= 0.02);
    // A river flowing west: section 0 is now at the east end, whichever end end_a is.
    const hydro_steps_test::river_strip west(false);
    for (const bool swapped : {false, true}) {
        auto s = west.shape();
        if (swapped) std::swap(s.end_a, s.end_b);
        const auto q = west.profile(hydro_steps_test::strip_options, s);
        CAPTURE(swapped);
        CHECK(q.section(5, 199) == 0);
        CHECK(q.section(0, 0) == static_cast<std::int32_t>(q.level_m.size() - 1));
        CHECK(q.centre.front()[1] > 194);
        CHECK(hydro_steps_test::non_increasing(q.level_m));
        CHECK(hydro_steps_test::worst_level_error(q, west.truth) <= 0.02);
    }
}

TEST_CASE("water/trace_river_profile: a deck is not measured; the level under it is interpolated within 2 cm")
{
    hydro_steps_test::river_strip river;
    const std::ptrdiff_t deck0 = 60, deck1 = 70;  // a deck 5 m above the water over columns 60-69
    for (std::ptrdiff_t r = 0; r < river.rows; ++r)
        for (std::ptrdiff_t c = deck0; c < deck1; ++c) river.water_z(r, c) += 5.0f;
    const auto p = river.profile(hydro_steps_test::strip_options, river.shape());
    const double strip_share = hydro_steps_test::strip_options.min_return_share;
    CHECK(hydro_steps_test::non_increasing(p.level_m));
    CHECK(hydro_steps_test::worst_level_error(p, river.truth) <= 0.02);
    std::size_t hidden = 0;
    for (std::size_t k = 0; k < p.level_m.size(); ++k) {
        std::size_t on_deck = 0;
        for (std::ptrdiff_t r = 0; r < river.rows; ++r)
            for (std::ptrdiff_t c = deck0; c < deck1; ++c) on_deck += p.section(r, c) == static_cast<std::int32_t>(k);
        CAPTURE(k);
        CHECK(p.returns[k] <= p.cells[k] - on_deck);  // no deck cell is a water return
        const double open = static_cast<double>(p.cells[k] - on_deck);
        if (open < strip_share * static_cast<double>(p.cells[k])) {  // too little open water: not measured
            ++hidden;
            CHECK(p.returns[k] == 0);
            CHECK(std::isnan(p.measured_m[k]));
        }
    }
    CHECK(hidden >= 1);
    CHECK(p.weirs == 0);
}

TEST_CASE("water/trace_river_profile: a deck longer than half the level window is found by its clearance")
{
    // 40 m of deck over a 50 m level window: most of the sections near it stand on the deck, so only the deck's
    // clearance above the low water within 100 m (deck_clearance_m, 2 m) tells it from the water.
    hydro_steps_test::river_strip river;
    for (std::ptrdiff_t r = 0; r < river.rows; ++r)
        for (std::ptrdiff_t c = 60; c < 100; ++c) river.water_z(r, c) += 5.0f;
    const auto p = river.profile(hydro_steps_test::strip_options, river.shape());
    CHECK(hydro_steps_test::non_increasing(p.level_m));
    CHECK(hydro_steps_test::worst_level_error(p, river.truth) <= 0.02);
    for (std::size_t k = 0; k < p.level_m.size(); ++k)
        if (p.centre[k][1] > 65 && p.centre[k][1] < 95) {
            CAPTURE(k);
            CHECK(p.returns[k] == 0);
        }
    CHECK(p.weirs == 0);
}

TEST_CASE("water/trace_river_profile: a few returns of something floating in a dropout stretch do not hold it up")
{
    // Columns 110-159 lost 6 of every 7 pulses to dropout; what returned there floats 0.5 m above the water. The
    // first fit pools these sections with the ones upstream; those further than level_tolerance_m from the fit
    // are dropped and the rest fitted again.
    hydro_steps_test::river_strip river;
    for (std::ptrdiff_t r = 0; r < river.rows; ++r)
        for (std::ptrdiff_t c = 110; c < 160; ++c)
            river.water_z(r, c) = (r * 200 + c) % 7 == 0 ? river.water_z(r, c) + 0.5f : nan_f;
    const auto p = river.profile(hydro_steps_test::strip_options, river.shape());
    CHECK(hydro_steps_test::non_increasing(p.level_m));
    CHECK(hydro_steps_test::worst_level_error(p, river.truth) <= 0.02);
}

TEST_CASE("water/trace_river_profile: a weir stays a step; the sections either side are within 2 cm")
{
    hydro_steps_test::river_strip river;
    river.step_at(100, -0.5f);
    const auto p = river.profile(hydro_steps_test::strip_options, river.shape());
    CHECK(hydro_steps_test::non_increasing(p.level_m));
    CHECK(p.weirs == 1);
    CHECK(p.largest_step_m == doctest::Approx(0.5 + 0.025).epsilon(0.05));  // the weir plus 5 m of fall
    const auto truth = hydro_steps_test::section_truth(p, river.truth);
    for (std::size_t k = 0; k < p.level_m.size(); ++k) {
        CAPTURE(k);
        CHECK(std::abs(p.level_m[k] - truth[k]) <= 0.02);
    }
}

TEST_CASE("water/trace_river_profile: an oblique weir is followed cell by cell; no section straddles it")
{
    // A 0.6 m weir whose crest crosses the channel obliquely, `slope` columns per row. Truth: the upper level up
    // to the crest at each cell's centre. Water heights come from the lowest return, so a cell the crest crosses
    // reads the lower pool. Cutting the sections along the crest leaves off by more than 10 cm only crossed cells
    // that the crest line, placed from them, puts on the wrong side: fewer than one per row.
    for (const double slope : {0.6, 1.7, 3.1}) {
        CAPTURE(slope);
        hydro_steps_test::river_strip river;
        constexpr double crest_at = 95.3;  // where the crest meets row 0's north edge, in columns
        for (std::ptrdiff_t r = 0; r < river.rows; ++r)
            for (std::ptrdiff_t c = 0; c < river.cols; ++c) {
                const auto row = static_cast<double>(r), col = static_cast<double>(c);
                if (col + 0.5 > crest_at + slope * (row + 0.5)) river.truth(r, c) -= 0.6f;
                if (col + 1 > crest_at + slope * row) river.water_z(r, c) -= 0.6f;
            }
        const auto cells_off = [&](const river_profile& p) {
            std::size_t off = 0;
            for (std::ptrdiff_t r = 0; r < river.rows; ++r)
                for (std::ptrdiff_t c = 0; c < river.cols; ++c)
                    off += std::abs(p.level_m[static_cast<std::size_t>(p.section(r, c))] - river.truth(r, c)) > 0.1;
            return off;
        };
        const auto p = river.profile(hydro_steps_test::strip_options, river.shape());
        CHECK(hydro_steps_test::non_increasing(p.level_m));
        CHECK(p.weirs == 1);
        CHECK(cells_off(p) < static_cast<std::size_t>(river.rows));
        std::size_t cells = 0;
        for (const std::size_t n : p.cells) cells += n;
        CHECK(cells == static_cast<std::size_t>(river.rows * river.cols));
        auto straddling = hydro_steps_test::strip_options;
        straddling.cut_sections_at_weirs = false;
        CHECK(cells_off(river.profile(straddling, river.shape())) > static_cast<std::size_t>(river.rows));
    }
}

TEST_CASE("water/trace_river_profile: a dropout patch over part of a weir's crest takes the side of the crest line")
{
    // The oblique weir of the test above on a channel 16 cells wide, and no returns from 2 cells above the crest
    // to 10 cells below it in the north half. Those cells take the side of the crest fitted to the cells with heights:
    // its direction from every cell of both pools, not only from the south half's crossed cells. Taking the side of the
    // nearest cell with a height would put a wedge of the patch on the wrong side.
    constexpr std::ptrdiff_t rows = 16, cols = 200;
    constexpr double crest_at = 90.3, slope = 1.7;
    hydro_steps_test::river_strip strip;
    raster<std::int32_t> labels(rows, cols, 1);
    raster<float> truth(rows, cols), water_z(rows, cols);
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const auto row = static_cast<double>(r), col = static_cast<double>(c);
            truth(r, c) = strip.truth(r % strip.rows, c);
            water_z(r, c) = strip.water_z(r % strip.rows, c);
            if (col + 0.5 > crest_at + slope * (row + 0.5)) truth(r, c) -= 0.6f;
            if (col + 1 > crest_at + slope * row) water_z(r, c) -= 0.6f;
            const double crest = crest_at + slope * (row + 0.5);
            if (r < rows / 2 && col + 0.5 - crest >= -2 && col + 0.5 - crest <= 10) water_z(r, c) = nan_f;
        }
    const cell_box box{0, 0, rows - 1, cols - 1};
    const auto p = trace_river_profile(labels, 1, box, measure_hydro_body_shape(labels, 1, box, 1.0), water_z, 1.0);
    CHECK(hydro_steps_test::non_increasing(p.level_m));
    CHECK(p.weirs == 1);
    std::size_t off = 0;
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c)
            off += std::abs(p.level_m[static_cast<std::size_t>(p.section(r, c))] - truth(r, c)) > 0.1;
    CHECK(off < static_cast<std::size_t>(rows));
}

TEST_CASE("water/trace_river_profile: a steep river is no weir; a stray low return beside a weir stays in its pool")
{
    SUBCASE("a 2 % fall: every step is 10 cm, none is a weir, nothing is re-cut")
    {
        hydro_steps_test::river_strip river;
        for (std::ptrdiff_t r = 0; r < river.rows; ++r)
            for (std::ptrdiff_t c = 0; c < river.cols; ++c) {
                river.truth(r, c) = 100.0f - 0.02f * static_cast<float>(c);
                river.water_z(r, c) = river.truth(r, c);
            }
        const auto p = river.profile(hydro_steps_test::strip_options, river.shape());
        CHECK(p.weirs == 0);
        CHECK(std::count(p.cells.begin(), p.cells.end(), std::size_t{0}) == 0);
        auto uncut = hydro_steps_test::strip_options;
        uncut.cut_sections_at_weirs = false;
        const auto q = river.profile(uncut, river.shape());
        CHECK(p.level_m == q.level_m);  // no section re-cut
        CHECK(p.section == q.section);
    }
    SUBCASE("a 0.4 m weir at column 100 and a cell 8 m upstream reading 30 cm low, nearer the lower pool")
    {
        hydro_steps_test::river_strip river;
        river.step_at(100, -0.4f);
        river.water_z(2, 92) -= 0.3f;
        const auto p = river.profile(hydro_steps_test::strip_options, river.shape());
        CHECK(p.weirs == 1);
        const auto level = [&](std::ptrdiff_t r, std::ptrdiff_t c) {
            return p.level_m[static_cast<std::size_t>(p.section(r, c))];
        };
        CHECK(level(2, 92) == level(1, 92));
        CHECK(std::abs(level(2, 92) - river.truth(2, 92)) <= 0.03);
    }
}

TEST_CASE("water/trace_river_profile: a level field taken into the body beside the channel does not lift its level")
{
    // The 6-cell channel of river_strip, and beside it along columns 50-149 a field 10 cells wide, 0.5 m above
    // the water at its highest: more cells of field than of water in those sections.
    const hydro_steps_test::river_strip river;
    constexpr std::ptrdiff_t rows = 16;
    raster<std::int32_t> labels(rows, river.cols, 0);
    raster<float> water_z(rows, river.cols, NAN);
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < river.cols; ++c) {
            if (r < river.rows) {
                labels(r, c) = 1;
                water_z(r, c) = river.water_z(r, c);
            } else if (c >= 50 && c < 150) {
                labels(r, c) = 1;
                water_z(r, c) = 100.5f + 0.01f * static_cast<float>((r + c) % 3 - 1);
            }
        }
    const cell_box box{0, 0, rows - 1, river.cols - 1};
    const auto shape = measure_hydro_body_shape(labels, 1, box, 1.0);
    const auto worst_in_channel = [&](const river_profile& p) {
        double worst = 0;
        for (std::ptrdiff_t r = 0; r < river.rows; ++r)
            for (std::ptrdiff_t c = 0; c < river.cols; ++c)
                worst =
                    std::max(worst, std::abs(p.level_m[static_cast<std::size_t>(p.section(r, c))] - river.truth(r, c)));
        return worst;
    };
    const auto p = trace_river_profile(labels, 1, box, shape, water_z, 1.0);
    CHECK(hydro_steps_test::non_increasing(p.level_m));
    CHECK(worst_in_channel(p) <= 0.03);
    river_profile_options densest;
    densest.lowest_mode_share = 1;
    CHECK(worst_in_channel(trace_river_profile(labels, 1, box, shape, water_z, 1.0, densest)) > 0.2);
}

TEST_CASE("water/trace_river_profile: a few high cells (a pier) leave their section's level where it was")
{
    const hydro_steps_test::river_strip clean;
    const auto shape = clean.shape();
    const auto a = clean.profile(hydro_steps_test::strip_options, shape);
    const std::vector<std::pair<std::ptrdiff_t, std::ptrdiff_t>> piles{{2, 150}, {3, 150}, {2, 151}};
    // 1 m up: under the deck clearance, left out as further than return_tolerance_m from the local level;
    // 3 m up: a deck.
    for (const float height : {1.0f, 3.0f}) {
        hydro_steps_test::river_strip pier;
        for (const auto& [r, c] : piles) pier.water_z(r, c) += height;
        const auto b = pier.profile(hydro_steps_test::strip_options, shape);
        CAPTURE(height);
        REQUIRE(a.level_m.size() == b.level_m.size());
        CHECK(a.section == b.section);
        for (std::size_t s = 0; s < b.level_m.size(); ++s) {
            std::size_t on_pier = 0;
            for (const auto& [r, c] : piles) on_pier += b.section(r, c) == static_cast<std::int32_t>(s);
            CAPTURE(s);
            CHECK(b.returns[s] == a.returns[s] - on_pier);         // the piles are not water returns
            CHECK(std::abs(b.level_m[s] - a.level_m[s]) <= 0.01);  // the median of a few returns fewer
        }
        CHECK(hydro_steps_test::worst_level_error(b, pier.truth) <= 0.02);
    }
}

TEST_CASE("water/trace_river_profile: refuses other shapes, options out of range, bad boxes and a foreign end_a")
{
    const hydro_steps_test::river_strip river;
    const auto shape = river.shape();
    const auto trace = [&](const river_profile_options& opt) {
        return trace_river_profile(river.labels, 1, river.box, shape, river.water_z, 1.0, opt);
    };
    CHECK_THROWS_AS(trace_river_profile(river.labels, 1, river.box, shape, raster<float>(6, 199), 1.0), invalid_input);
    for (const double cell_m : {0.0, -1.0, static_cast<double>(NAN)})
        CHECK_THROWS_AS(trace_river_profile(river.labels, 1, river.box, shape, river.water_z, cell_m), invalid_input);
    const double nan = NAN;
    for (const double bad : {0.0, -1.0, nan}) {
        CAPTURE(bad);
        CHECK_THROWS_AS(trace({.section_spacing_m = bad}), invalid_input);
        CHECK_THROWS_AS(trace({.deck_clearance_m = bad}), invalid_input);
        CHECK_THROWS_AS(trace({.floor_window_m = bad}), invalid_input);
        CHECK_THROWS_AS(trace({.level_window_m = bad}), invalid_input);
        CHECK_THROWS_AS(trace({.return_tolerance_m = bad}), invalid_input);
        CHECK_THROWS_AS(trace({.level_tolerance_m = bad}), invalid_input);
        CHECK_THROWS_AS(trace({.weir_min_drop_m = bad}), invalid_input);
    }
    for (const double share : {-0.1, 1.1, nan}) CHECK_THROWS_AS(trace({.min_return_share = share}), invalid_input);
    for (const double share : {0.0, 1.1, nan}) CHECK_THROWS_AS(trace({.lowest_mode_share = share}), invalid_input);
    CHECK_THROWS_AS(trace_river_profile(river.labels, 1, cell_box{0, 0, 6, 199}, shape, river.water_z, 1.0),
                    invalid_input);
    CHECK_THROWS_AS(trace_river_profile(river.labels, 1, cell_box{}, shape, river.water_z, 1.0), invalid_input);
    auto foreign = shape;
    foreign.end_a = {0, 200};  // outside the box
    CHECK_THROWS_AS(trace_river_profile(river.labels, 1, river.box, foreign, river.water_z, 1.0), invalid_input);
    raster<std::int32_t> labels = river.labels;
    labels(5, 199) = 0;  // end_a is no longer a cell of the body
    CHECK_THROWS_AS(trace_river_profile(labels, 1, river.box, shape, river.water_z, 1.0), invalid_input);
    CHECK_NOTHROW(trace({.min_return_share = 0.0}));
}

// ---------------------------------------------------------------------------------------------------------------
// hydro_qa

namespace hydro_steps_test {

/// A 3 x 30 river (body 2, rows 1-3, columns 1-30) in three 10-column sections at 10.3, 10.2 and 10.25 m: its
/// third section lies above the second. Hand-made, as trace_river_profile would never make it.
river_profile uphill_profile()
{
    river_profile p;
    p.box = {1, 1, 3, 30};
    p.section = raster<std::int32_t>(3, 30, 0);
    for (std::ptrdiff_t r = 0; r < 3; ++r)
        for (std::ptrdiff_t c = 0; c < 30; ++c) p.section(r, c) = static_cast<std::int32_t>(c / 10);
    p.level_m = {10.3, 10.2, 10.25};
    p.measured_m = p.level_m;
    p.returns = {30, 30, 30};
    p.cells = {30, 30, 30};
    p.centre = {{{2.0, 5.5}, {2.0, 15.5}, {2.0, 25.5}}};
    return p;
}

/// A DEM flattened as hydro_flatten would: lake 1 (rows 6-8, columns 2-4) at 9 m, river 2 at its section levels,
/// land at 12 m around.
struct qa_scene {
    river_profile profile = uphill_profile();
    raster<float> dem{10, 33, 12.0f}, water{10, 33, nan_f};
    raster<std::int32_t> body{10, 33, 0};
    qa_scene()
    {
        for (std::ptrdiff_t r = 6; r <= 8; ++r)
            for (std::ptrdiff_t c = 2; c <= 4; ++c) {
                body(r, c) = 1;
                dem(r, c) = water(r, c) = 9.0f;
            }
        for (std::ptrdiff_t r = 1; r <= 3; ++r)
            for (std::ptrdiff_t c = 1; c <= 30; ++c) {
                body(r, c) = 2;
                dem(r, c) = water(r, c) =
                    static_cast<float>(profile.level_m[static_cast<std::size_t>(profile.section(r - 1, c - 1))]);
            }
    }
    std::vector<hydro_check> qa(double lake_area_m2 = 9000, double river_width_m = 40) const
    {
        const std::vector<hydro_qa_body> bodies{
            {.id = 1, .river = false, .size = lake_area_m2, .min_size = 8093.71},
            {.id = 2, .river = true, .size = river_width_m, .min_size = 30.48, .profile = &profile}};
        return hydro_qa(dem, water, body, bodies);
    }
};

}  // namespace hydro_steps_test

TEST_CASE("water/hydro_qa: per body in order, flatness, monotonic_fall (rivers), shoreline, minimum_size")
{
    hydro_steps_test::qa_scene s;
    s.profile.level_m = {10.3, 10.25, 10.2};  // falling: a clean DEM
    for (std::ptrdiff_t r = 1; r <= 3; ++r)
        for (std::ptrdiff_t c = 1; c <= 30; ++c)
            s.dem(r, c) = s.water(r, c) = static_cast<float>(s.profile.level_m[static_cast<std::size_t>((c - 1) / 10)]);
    const auto qa = s.qa();
    REQUIRE(qa.size() == 7);
    const std::vector<std::pair<std::int32_t, hydro_check_kind>> order{
        {1, hydro_check_kind::flatness},    {1, hydro_check_kind::shoreline},      {1, hydro_check_kind::minimum_size},
        {2, hydro_check_kind::flatness},    {2, hydro_check_kind::monotonic_fall}, {2, hydro_check_kind::shoreline},
        {2, hydro_check_kind::minimum_size}};
    for (std::size_t k = 0; k < qa.size(); ++k) {
        CAPTURE(k);
        CHECK(qa[k].body == order[k].first);
        CHECK(qa[k].kind == order[k].second);
        CHECK(qa[k].pass);
        if (qa[k].kind != hydro_check_kind::minimum_size) {
            CHECK(qa[k].value == 0);  // per section, so the river's fall between sections is not unflatness
            CHECK(qa[k].worst_row == -1);
        }
    }
    CHECK(qa[0].limit == 0.001);  // the default flat tolerance
    CHECK(hydro_check_name(hydro_check_kind::flatness) == "flatness");
    CHECK(hydro_check_name(hydro_check_kind::monotonic_fall) == "monotonic_fall");
    CHECK(hydro_check_name(hydro_check_kind::shoreline) == "shoreline");
    CHECK(hydro_check_name(hydro_check_kind::minimum_size) == "minimum_size");
}

TEST_CASE("water/hydro_qa: a lake that is not flat fails flatness at its highest cell")
{
    hydro_steps_test::qa_scene s;
    s.dem(7, 3) = 9.004f;
    s.dem(8, 2) = 8.999f;
    const auto lake = hydro_steps_test::checks_of(s.qa(), 1);
    REQUIRE(lake.size() == 3);
    CHECK(lake[0].kind == hydro_check_kind::flatness);
    CHECK_FALSE(lake[0].pass);
    CHECK(lake[0].value == doctest::Approx(0.005).epsilon(1e-3));  // max - min, to float rounding
    CHECK(lake[0].worst_row == 7);
    CHECK(lake[0].worst_col == 3);
    // Within the tolerance it passes.
    const std::vector<hydro_qa_body> one{{.id = 1, .size = 9000, .min_size = 8093.71}};
    const auto loose = hydro_qa(s.dem, s.water, s.body, one, 0.01);
    CHECK(loose[0].pass);
    CHECK(loose[0].limit == 0.01);
}

TEST_CASE("water/hydro_qa: a river with a section above the one upstream fails monotonic_fall there")
{
    hydro_steps_test::qa_scene s;  // sections at 10.3, 10.2, 10.25
    const auto river = hydro_steps_test::checks_of(s.qa(), 2);
    REQUIRE(river.size() == 4);
    CHECK(river[0].kind == hydro_check_kind::flatness);
    CHECK(river[0].pass);  // each section is flat
    CHECK(river[1].kind == hydro_check_kind::monotonic_fall);
    CHECK_FALSE(river[1].pass);
    CHECK(river[1].value == 1);
    CHECK(river[1].worst_row == 2);  // the centre of section 2, rounded
    CHECK(river[1].worst_col == 26);
    // A section that is not flat fails flatness at its highest cell, although the levels between sections differ.
    s.dem(2, 12) = 10.21f;
    const auto bumpy = hydro_steps_test::checks_of(s.qa(), 2);
    CHECK_FALSE(bumpy[0].pass);
    CHECK(bumpy[0].value == doctest::Approx(0.01).epsilon(1e-3));
    CHECK(bumpy[0].worst_row == 2);
    CHECK(bumpy[0].worst_col == 12);
    std::vector<hydro_qa_body> no_profile{{.id = 2, .river = true, .size = 40, .min_size = 30.48}};
    CHECK_THROWS_AS(hydro_qa(s.dem, s.water, s.body, no_profile), invalid_input);
}

TEST_CASE("water/hydro_qa: shore ground below the water fails shoreline, the deepest cell reported")
{
    hydro_steps_test::qa_scene s;
    s.dem(5, 1) = 8.9f;    // beside the lake (9 m), 0.1 m below
    s.dem(9, 5) = 8.5f;    // beside the lake, 0.5 m below: the worst
    s.dem(9, 7) = 1.0f;    // far from any water
    s.dem(0, 15) = 10.2f;  // beside the river's section 1 (10.2 m): level with it, not below
    s.dem(4, 25) = 10.2f;  // beside section 2 (10.25 m): below
    const auto qa = s.qa();
    const auto lake = hydro_steps_test::checks_of(qa, 1);
    CHECK(lake[1].kind == hydro_check_kind::shoreline);
    CHECK_FALSE(lake[1].pass);
    CHECK(lake[1].value == 2);
    CHECK(lake[1].worst_row == 9);
    CHECK(lake[1].worst_col == 5);
    const auto river = hydro_steps_test::checks_of(qa, 2);
    CHECK(river[2].kind == hydro_check_kind::shoreline);
    CHECK(river[2].value == 1);
    CHECK(river[2].worst_row == 4);
    CHECK(river[2].worst_col == 25);
}

TEST_CASE("water/hydro_qa: minimum_size passes at the minimum and fails under it; refuses other shapes")
{
    hydro_steps_test::qa_scene s;
    const auto at = s.qa(8093.71, 30.48);
    CHECK(hydro_steps_test::checks_of(at, 1)[2].kind == hydro_check_kind::minimum_size);
    CHECK(hydro_steps_test::checks_of(at, 1)[2].pass);
    CHECK(hydro_steps_test::checks_of(at, 1)[2].value == 8093.71);
    CHECK(hydro_steps_test::checks_of(at, 1)[2].limit == 8093.71);
    CHECK(hydro_steps_test::checks_of(at, 2)[3].pass);
    const auto under = s.qa(8093.70, 30.47);
    CHECK_FALSE(hydro_steps_test::checks_of(under, 1)[2].pass);
    CHECK_FALSE(hydro_steps_test::checks_of(under, 2)[3].pass);
    CHECK(hydro_steps_test::checks_of(under, 2)[3].value == 30.47);
    CHECK(hydro_steps_test::checks_of(under, 2)[3].limit == 30.48);
    const std::vector<hydro_qa_body> lake{{.id = 1, .size = 9000, .min_size = 8093.71}};
    CHECK_THROWS_AS(hydro_qa(raster<float>(10, 32), s.water, s.body, lake), invalid_input);
    CHECK_THROWS_AS(hydro_qa(s.dem, s.water, raster<std::int32_t>(9, 33), lake), invalid_input);
    CHECK(hydro_qa(s.dem, s.water, s.body, {}).empty());
}
