// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/kernels/filter/angular_filter.hpp>
#include <lidarfx/kernels/interpolate/idw_fill.hpp>
#include <lidarfx/pipelines/water/water_angles.hpp>

#include <cmath>
#include <cstring>
#include <random>

#include "water_test_rasters.hpp"

using namespace lidarfx;
using water_test::survey;

namespace {

bool same_bits(const raster<float>& a, const raster<float>& b)
{
    return a.rows() == b.rows() && a.cols() == b.cols() &&
           std::memcmp(a.data(), b.data(), static_cast<std::size_t>(a.size()) * sizeof(float)) == 0;
}

}  // namespace

TEST_CASE("water/water_angles: a 1 m step seen from 1 m away is 45 degrees; dropouts join at any threshold")
{
    // One row: ground at 10 m, a 1 m step up at column 3, a dropout at column 5.
    survey s(1, 6);
    s.min_z(0, 3) = s.min_z(0, 4) = 11.0f;
    s.drop(0, 5);
    const auto a = water_angles(s.view(), 1.0, {.radius_cells = 1});
    CHECK(a(0, 0) == 0.0f);
    CHECK(a(0, 1) == 0.0f);
    CHECK(a(0, 2) == doctest::Approx(45.0));
    CHECK(a(0, 3) == doctest::Approx(45.0));
    CHECK(a(0, 4) == 0.0f);  // its NaN neighbour is skipped
    CHECK(std::isnan(a(0, 5)));
    // Cells of 2 m halve the slope: atan(1 / 2).
    CHECK(water_angles(s.view(), 2.0, {.radius_cells = 1})(0, 2) == doctest::Approx(26.565051).epsilon(1e-6));
}

TEST_CASE("water/water_angles: the dissertation's reading gives dropouts an angle")
{
    survey s(1, 6);
    s.drop(0, 5);
    // Literal reading on returns only: the filter has no height for the dropout, so it is as steep as can be.
    const auto literal = water_angles(s.view(), 1.0, {.radius_cells = 1, .dropouts_join_any_threshold = false});
    CHECK(literal(0, 5) == 90.0f);
    CHECK(literal(0, 4) == 0.0f);
    // With IDW-filled heights the dropout has a height (10 m, like its neighbours) and an angle of 0.
    const auto filled = water_angles(
        s.view(), 1.0, {.radius_cells = 1, .input = angular_input::idw_filled, .dropouts_join_any_threshold = false});
    CHECK(filled(0, 5) == 0.0f);
}

TEST_CASE("water/water_angles: equals angular_filter (of the IDW fill) with the dropout rule, on random surveys")
{
    std::mt19937 rng(515);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int trial = 0; trial < 30; ++trial) {
        CAPTURE(trial);
        const std::ptrdiff_t rows = 1 + rng() % 25, cols = 1 + rng() % 25;
        survey s(rows, cols);
        for (std::ptrdiff_t r = 0; r < rows; ++r)
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                s.min_z(r, c) = s.max_z(r, c) = 10.0f + 3.0f * u(rng);
                if (u(rng) < 0.2f) s.drop(r, c);
            }
        const double cell = 0.5 + static_cast<double>(rng() % 4);
        const int radius = 1 + static_cast<int>(rng() % 3);
        const auto input = trial % 2 ? angular_input::idw_filled : angular_input::returns_only;
        const bool join = trial % 4 < 2;
        const auto got =
            water_angles(s.view(), cell, {.radius_cells = radius, .input = input, .dropouts_join_any_threshold = join},
                         {.threads = 1 + trial % 2});
        auto expected = input == angular_input::idw_filled
                            ? angular_filter(idw_fill(s.min_z, cell).filled, cell, radius)
                            : angular_filter(s.min_z, cell, radius);
        for (std::ptrdiff_t r = 0; r < rows; ++r)
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                if (!s.dropout(r, c)) continue;
                if (join) {
                    expected(r, c) = NAN;
                } else if (std::isnan(expected(r, c))) {
                    expected(r, c) = 90.0f;
                }
            }
        CHECK(same_bits(got, expected));
    }
}

TEST_CASE("water/water_angles: progress is monotone and ends at 1; returning false cancels")
{
    survey s(6, 6);
    water_test::check_progress_and_cancel([&](const execution& run) { return water_angles(s.view(), 1.0, {}, run); },
                                          "water_angles");
}

TEST_CASE("water/water_angles: options out of range are refused")
{
    survey s(2, 2);
    CHECK_THROWS_WITH_AS(water_angles(s.view(), 1.0, {.radius_cells = 0}),
                         "water_angles: radius_cells must be >= 1 (got 0)", invalid_input);
    CHECK_THROWS_WITH_AS(water_angles(s.view(), -1.0), "water_angles: cell_m must be finite and > 0 (got -1)",
                         invalid_input);
}
