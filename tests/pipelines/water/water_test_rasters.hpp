// SPDX-License-Identifier: Apache-2.0
// Shared pieces of the waterbody step tests: hand-written rasters, a small owned survey, and the check
// that a step's progress is monotone, ends at 1, and cancels.
#pragma once

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

#include <lidarfx/core/error.hpp>
#include <lidarfx/core/parallel.hpp>
#include <lidarfx/core/raster.hpp>
#include <lidarfx/pipelines/water/water_rasters.hpp>

namespace water_test {

/// A raster written row by row in the source.
template <class T>
lidarfx::raster<T> grid_of(std::initializer_list<std::initializer_list<T>> rows)
{
    lidarfx::raster<T> out(static_cast<std::ptrdiff_t>(rows.size()), static_cast<std::ptrdiff_t>(rows.begin()->size()));
    std::ptrdiff_t r = 0;
    for (const auto& row : rows) {
        std::ptrdiff_t c = 0;
        for (const T v : row) out(r, c++) = v;
        ++r;
    }
    return out;
}

/// An owned survey: flat ground at 10 m, intensity 50, 4 points per cell, no dropout, single returns.
struct survey {
    lidarfx::raster<float> min_z, max_z, intensity;
    lidarfx::raster<std::uint8_t> dropout, multiple;
    lidarfx::raster<std::uint32_t> count;

    survey(std::ptrdiff_t rows, std::ptrdiff_t cols)
        : min_z(rows, cols, 10.0f),
          max_z(rows, cols, 10.0f),
          intensity(rows, cols, 50.0f),
          dropout(rows, cols, 0),
          multiple(rows, cols, 0),
          count(rows, cols, 4)
    {
    }
    /// Makes (r, c) a cell without returns.
    void drop(std::ptrdiff_t r, std::ptrdiff_t c)
    {
        dropout(r, c) = 1;
        min_z(r, c) = max_z(r, c) = NAN;
        intensity(r, c) = 0.0f;
        count(r, c) = 0;
    }
    lidarfx::water_rasters view() const { return {min_z, max_z, intensity, dropout, multiple, count}; }
};

/// Runs `step(execution)` with a recording progress callback: the fractions are monotone, start at 0 and
/// end at 1. Then a callback that returns false throws lidarfx::cancelled naming `function`.
template <class Step>
void check_progress_and_cancel(Step step, const char* function)
{
    std::vector<double> seen;
    step(lidarfx::execution{.threads = 1, .progress = [&](double f) {
                                seen.push_back(f);
                                return true;
                            }});
    REQUIRE(seen.size() >= 2);
    CHECK(seen.front() == 0.0);
    CHECK(seen.back() == 1.0);
    CHECK(std::is_sorted(seen.begin(), seen.end()));
    const std::string expected = std::string(function) + ": cancelled";
    CHECK_THROWS_WITH_AS(step(lidarfx::execution{.threads = 1, .progress = [](double) { return false; }}),
                         expected.c_str(), lidarfx::cancelled);
}

}  // namespace water_test
