// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/kernels/filter/vegetation_mask.hpp>
#include <lidarfx/pipelines/water/water_vegetation.hpp>

#include <random>

#include "water_test_rasters.hpp"

using namespace lidarfx;
using water_test::grid_of;
using water_test::survey;

TEST_CASE("water/water_vegetation: height spread above h, plus multiple returns on cells with returns")
{
    survey s(4, 5);
    s.max_z(0, 0) = 12.5f;  // spread 2.5 m > 2 m: canopy
    s.max_z(0, 4) = 12.0f;  // spread exactly 2 m: not above h
    s.multiple(2, 1) = 1;   // multiple-return pulse over ground
    s.drop(3, 3);
    s.multiple(3, 3) = 1;  // a flag on a cell without returns does not count
    const auto v = water_vegetation(s.view(), {.closing_size_cells = 1});
    CHECK(v == grid_of<std::uint8_t>({{1, 0, 0, 0, 0},  //
                                      {0, 0, 0, 0, 0},
                                      {0, 1, 0, 0, 0},
                                      {0, 0, 0, 0, 0}}));
    const auto heights_only = water_vegetation(s.view(), {.closing_size_cells = 1, .from_multiple_returns = false});
    CHECK(heights_only(2, 1) == 0);
    CHECK(heights_only(0, 0) == 1);
    // Without the multiple_returns raster only heights count.
    water_rasters in = s.view();
    in.multiple_returns = {};
    CHECK(water_vegetation(in, {.closing_size_cells = 1}) == heights_only);
    // h is an option: 1 m catches the 2 m spread too.
    CHECK(water_vegetation(s.view(), {.height_m = 1.0, .closing_size_cells = 1})(0, 4) == 1);
}

TEST_CASE("water/water_vegetation: the closing fills gaps between canopy cells before the returns are added")
{
    survey s(5, 7);
    s.max_z(2, 1) = s.max_z(2, 3) = 20.0f;  // two crowns one cell apart
    s.multiple(4, 6) = 1;
    const auto v = water_vegetation(s.view(), {.closing_size_cells = 3});
    CHECK(v(2, 2) == 1);  // closed gap
    CHECK(v(2, 1) == 1);
    CHECK(v(2, 3) == 1);
    CHECK(v(4, 6) == 1);  // multiple returns, not closed with anything
    CHECK(v(4, 5) == 0);
    CHECK(v(0, 0) == 0);
}

TEST_CASE("water/water_vegetation: equals vegetation_mask OR multiple returns on random surveys, any threads")
{
    std::mt19937 rng(4242);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int trial = 0; trial < 30; ++trial) {
        CAPTURE(trial);
        const std::ptrdiff_t rows = 1 + rng() % 30, cols = 1 + rng() % 30;
        survey s(rows, cols);
        for (std::ptrdiff_t r = 0; r < rows; ++r)
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                s.max_z(r, c) = 10.0f + 4.0f * u(rng) * u(rng);
                s.multiple(r, c) = u(rng) < 0.1f;
                if (u(rng) < 0.15f) s.drop(r, c);
            }
        const int closing = 1 + 2 * static_cast<int>(rng() % 3);
        const auto v = water_vegetation(s.view(), {.closing_size_cells = closing}, {.threads = 1 + trial % 3});
        auto expected =
            vegetation_mask(s.min_z, s.max_z, vegetation_mask_options{.height_m = 2.0, .closing_size_cells = closing});
        for (std::ptrdiff_t r = 0; r < rows; ++r)
            for (std::ptrdiff_t c = 0; c < cols; ++c) expected(r, c) |= s.multiple(r, c) && !s.dropout(r, c);
        CHECK(v == expected);
    }
}

TEST_CASE("water/water_vegetation: progress is monotone and ends at 1; returning false cancels")
{
    survey s(6, 6);
    water_test::check_progress_and_cancel([&](const execution& run) { return water_vegetation(s.view(), {}, run); },
                                          "water_vegetation");
}

TEST_CASE("water/water_vegetation: options out of range are refused")
{
    survey s(2, 2);
    CHECK_THROWS_WITH_AS(water_vegetation(s.view(), {.height_m = 0}), "water_vegetation: height_m must be > 0 (got 0)",
                         invalid_input);
    CHECK_THROWS_WITH_AS(water_vegetation(s.view(), {.closing_size_cells = 4}),
                         "water_vegetation: closing_size_cells must be odd and >= 1 (got 4)", invalid_input);
    CHECK_THROWS_AS(water_vegetation(s.view(), {}, {.threads = -1}), invalid_input);
}
