// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/kernels/points/rasterize.hpp>
#include <lidarfx/pipelines/water/assess_water_inputs.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <string>

#include "water_test_rasters.hpp"

using namespace lidarfx;
using water_test::survey;

TEST_CASE("water/assess_water_inputs: good data has no issue and its measures are reported")
{
    survey s(4, 5);  // 1 m cells, 4 points each
    s.intensity(1, 1) = 80.0f;
    s.multiple(2, 2) = 1;
    s.drop(3, 4);
    s.drop(3, 3);
    const auto d = assess_water_inputs(s.view(), 1.0);
    CHECK(d.issues.empty());
    CHECK(d.usable());
    CHECK(d.has_intensity);
    CHECK(d.has_multiple_returns);
    CHECK(d.points_per_cell == doctest::Approx(72.0 / 20.0));  // 18 cells of 4 points over 20 cells
    CHECK(d.dropout_fraction == doctest::Approx(0.1));
    // 3.6 points/m² reach 2 points per cell from a cell of sqrt(2 / 3.6) = 0.75 m; 0.5 m steps -> 1 m,
    // never below the cell in use.
    CHECK(d.suggested_cell_m == 1.0);
    CHECK(d.messages(water_severity::problem).empty());
}

TEST_CASE("water/assess_water_inputs: one intensity everywhere is a coded problem with its value")
{
    survey s(3, 3);
    s.intensity.fill(37.0f);
    s.drop(0, 0);  // the dropout's intensity 0 does not count
    s.multiple(1, 1) = 1;
    const auto d = assess_water_inputs(s.view(), 1.0);
    REQUIRE(d.issues.size() == 1);
    const auto& i = d.issues[0];
    CHECK(i.kind == water_issue_kind::intensity_constant);
    CHECK(i.severity == water_severity::problem);
    CHECK(i.intensity == 37.0);
    CHECK(std::isnan(i.points_per_cell));
    CHECK(i.message() ==
          "intensity is the same (37) in every cell with returns: the KS test that stops region growing compares "
          "intensity distributions and cannot work");
    CHECK_FALSE(d.usable());
    CHECK_FALSE(d.has_intensity);
}

TEST_CASE("water/assess_water_inputs: no return at all is its own problem")
{
    survey s(2, 2);
    for (std::ptrdiff_t r = 0; r < 2; ++r)
        for (std::ptrdiff_t c = 0; c < 2; ++c) s.drop(r, c);
    const auto d = assess_water_inputs(s.view(), 1.0);
    REQUIRE(d.issues.size() >= 2);
    CHECK(d.issues[0].kind == water_issue_kind::no_returns);
    CHECK(d.issues[0].message() == "no cell has a return: nothing to analyse");
    // Zero points: the density is too low and no cell size would help.
    CHECK(d.issues[1].kind == water_issue_kind::density_too_low);
    CHECK(d.issues[1].points_per_m2 == 0.0);
    CHECK(std::isnan(d.issues[1].suggested_cell_m));
    CHECK(d.dropout_fraction == 1.0);
}

TEST_CASE("water/assess_water_inputs: sparse data gets the density values and the suggested cell")
{
    // 4 x 5 cells of 2 m, 7 of them with one point: 0.35 points per cell, 7 / 80 m² = 0.0875 points/m².
    survey s(4, 5);
    s.intensity(0, 0) = 20.0f;
    for (std::ptrdiff_t r = 0; r < 4; ++r)
        for (std::ptrdiff_t c = 0; c < 5; ++c) {
            if (r * 5 + c < 7) {
                s.count(r, c) = 1;
            } else {
                s.drop(r, c);
            }
        }
    s.multiple(0, 1) = 1;
    const auto d = assess_water_inputs(s.view(), 2.0);
    REQUIRE(d.issues.size() == 1);
    const auto& i = d.issues[0];
    CHECK(i.kind == water_issue_kind::density_too_low);
    CHECK(i.severity == water_severity::problem);
    CHECK(i.points_per_m2 == doctest::Approx(0.0875));
    CHECK(i.points_per_cell == doctest::Approx(0.35));
    CHECK(i.cell_m == 2.0);
    CHECK(i.min_points_per_cell == 2.0);
    CHECK(i.dropout_fraction == doctest::Approx(0.65));
    // 2 points per cell need cells of sqrt(2 / 0.0875) = 4.78 m: 5.0 m in 0.5 m steps.
    CHECK(i.suggested_cell_m == 5.0);
    CHECK(d.suggested_cell_m == 5.0);
    CHECK(i.message() ==
          "point density 0.09 points/m² gives 0.35 points per 2.0 m cell (below 2.0): 65 % of cells are empty by "
          "sparse sampling, so dropouts no longer mark water; use a cell of at least 5.0 m");
    CHECK(d.messages(water_severity::problem) == std::vector<std::string>{i.message()});
}

TEST_CASE("water/assess_water_inputs: min_points_per_cell is inclusive")
{
    survey s(2, 2);  // 4 points per cell
    s.intensity(0, 0) = 1.0f;
    s.multiple(0, 0) = 1;
    CHECK(assess_water_inputs(s.view(), 1.0, {.min_points_per_cell = 4.0}).usable());
    const auto d = assess_water_inputs(s.view(), 1.0, {.min_points_per_cell = 4.5});
    REQUIRE(d.issues.size() == 1);
    CHECK(d.issues[0].kind == water_issue_kind::density_too_low);
    CHECK(d.issues[0].min_points_per_cell == 4.5);
    // Density 4 points/m² reaches 4.5 per cell from sqrt(4.5 / 4) = 1.06 m: 1.5 m.
    CHECK(d.issues[0].suggested_cell_m == 1.5);
}

TEST_CASE("water/assess_water_inputs: missing count and single returns are warnings, not problems")
{
    survey s(2, 3);
    s.intensity(1, 2) = 60.0f;
    water_rasters in = s.view();
    in.count = {};
    const auto d = assess_water_inputs(in, 1.0);
    REQUIRE(d.issues.size() == 2);
    CHECK(d.issues[0].kind == water_issue_kind::density_unchecked);
    CHECK(d.issues[0].message() == "no count raster: point density was not checked");
    CHECK(d.issues[1].kind == water_issue_kind::no_multiple_returns);
    CHECK(d.issues[1].message() == "no pulse has multiple returns: vegetation comes from max z - min z alone");
    for (const auto& i : d.issues) CHECK(i.severity == water_severity::warning);
    CHECK(d.usable());
    CHECK(std::isnan(d.points_per_cell));
    CHECK(d.messages(water_severity::warning).size() == 2);
    // A multiple-return flag on a dropout cell does not count; without the raster nothing is said.
    s.drop(0, 0);
    s.multiple(0, 0) = 1;
    CHECK(assess_water_inputs(s.view(), 1.0).issues.back().kind == water_issue_kind::no_multiple_returns);
    in = s.view();
    in.multiple_returns = {};
    CHECK(assess_water_inputs(in, 1.0).issues.empty());
}

TEST_CASE("water/assess_water_inputs: every kind renders its own sentence")
{
    std::set<std::string> texts;
    for (const auto k :
         {water_issue_kind::no_returns, water_issue_kind::intensity_constant, water_issue_kind::density_too_low,
          water_issue_kind::density_unchecked, water_issue_kind::no_multiple_returns}) {
        const auto text = water_issue{.kind = k}.message();
        CHECK_FALSE(text.empty());
        texts.insert(text);
    }
    CHECK(texts.size() == 5);
}

TEST_CASE("water/assess_water_inputs: strided views give the same diagnostics")
{
    survey big(7, 9);
    big.intensity(3, 4) = 99.0f;
    big.count(2, 2) = 1;
    big.drop(5, 6);
    const auto win = [](const auto& r) { return r.view().window(1, 2, 5, 6); };
    const water_rasters in{win(big.min_z),   win(big.max_z),    win(big.intensity),
                           win(big.dropout), win(big.multiple), win(big.count)};
    survey small(5, 6);
    for (std::ptrdiff_t r = 0; r < 5; ++r)
        for (std::ptrdiff_t c = 0; c < 6; ++c) {
            small.min_z(r, c) = big.min_z(r + 1, c + 2);
            small.max_z(r, c) = big.max_z(r + 1, c + 2);
            small.intensity(r, c) = big.intensity(r + 1, c + 2);
            small.dropout(r, c) = big.dropout(r + 1, c + 2);
            small.count(r, c) = big.count(r + 1, c + 2);
        }
    const auto a = assess_water_inputs(in, 1.0), b = assess_water_inputs(small.view(), 1.0);
    CHECK(a.points_per_cell == b.points_per_cell);
    CHECK(a.dropout_fraction == b.dropout_fraction);
    CHECK(a.has_intensity == b.has_intensity);
    REQUIRE(a.issues.size() == b.issues.size());
    for (std::size_t k = 0; k < a.issues.size(); ++k) CHECK(a.issues[k].message() == b.issues[k].message());
}

TEST_CASE("water/assess_water_inputs: bad arguments are refused")
{
    survey s(2, 2);
    CHECK_THROWS_WITH_AS(assess_water_inputs(s.view(), 0.0),
                         "assess_water_inputs: cell_m must be finite and > 0 (got 0)", invalid_input);
    CHECK_THROWS_WITH_AS(assess_water_inputs(s.view(), 1.0, {.min_points_per_cell = -1}),
                         "assess_water_inputs: min_points_per_cell must be >= 0 (got -1)", invalid_input);
}

TEST_CASE(
    "water/assess_water_inputs: the intensity range and dropout share equal a plain loop, with NaN, inf, "
    "signed zeros and a footprint")
{
    std::mt19937 rng(31);
    const float specials[] = {NAN, INFINITY, -INFINITY, 0.0f, -0.0f, -5.5f, 1e30f};
    for (int trial = 0; trial < 88; ++trial) {
        CAPTURE(trial);
        // The last trials are tall: bands of rows on 1-3 threads.
        const bool tall = trial >= 80;
        const std::ptrdiff_t rows = tall ? 250 + rng() % 500 : 1 + rng() % 9, cols = 1 + rng() % (tall ? 9 : 70);
        survey s(rows, cols);
        raster<std::uint8_t> footprint(rows, cols, 1);
        const int one_value = trial % 4 == 0;  // constant intensity: the range must collapse
        for (std::ptrdiff_t r = 0; r < rows; ++r) {
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                s.intensity(r, c) = one_value ? 12.0f : static_cast<float>(rng() % 200) - 50.0f;
                if (rng() % 9 == 0) s.intensity(r, c) = specials[rng() % 7];
                if (rng() % 5 == 0) s.drop(r, c);
                if (trial % 2 && rng() % 4 == 0) footprint(r, c) = 0;
            }
        }
        auto in = s.view();
        if (trial % 2) in.footprint = footprint;
        // The definition, one cell at a time.
        float lo = INFINITY, hi = -INFINITY;
        std::size_t inside = 0, dropouts = 0;
        for (std::ptrdiff_t r = 0; r < rows; ++r) {
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                if (trial % 2 && !footprint(r, c)) continue;
                ++inside;
                if (s.dropout(r, c)) {
                    ++dropouts;
                    continue;
                }
                const float v = s.intensity(r, c);
                if (std::isnan(v)) continue;
                lo = std::min(lo, v);
                hi = std::max(hi, v);
            }
        }
        const auto d = assess_water_inputs(in, 1.0, {}, {.threads = 1 + trial % 3});
        CHECK(d.has_intensity == (hi > lo));
        const double cells = static_cast<double>(std::max<std::size_t>(inside, 1));
        CHECK(d.dropout_fraction == doctest::Approx(static_cast<double>(dropouts) / cells));
        const bool constant = !d.issues.empty() && d.issues[0].kind == water_issue_kind::intensity_constant;
        const bool none = !d.issues.empty() && d.issues[0].kind == water_issue_kind::no_returns;
        CHECK(constant == (lo == hi));
        CHECK(none == (lo > hi));
        if (constant) CHECK(d.issues[0].intensity == lo);
    }
}
