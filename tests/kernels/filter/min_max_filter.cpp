// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include "test_values.hpp"

#include <lidarfx/kernels/filter/min_max_filter.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <type_traits>
#include <vector>

using namespace lidarfx;

namespace {

constexpr float inf_f = std::numeric_limits<float>::infinity();

/// The plain definition: scan every cell of the clipped window, skipping NaN; NaN when nothing is left.
template <class T>
min_max_filter_result<T> brute(raster_view<const T> in, int radius)
{
    min_max_filter_result<T> res{raster<T>(in.rows(), in.cols()), raster<T>(in.rows(), in.cols())};
    for (std::ptrdiff_t r = 0; r < in.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < in.cols(); ++c) {
            bool any = false;
            T lo{}, hi{};
            for (std::ptrdiff_t rr = r - radius; rr <= r + radius; ++rr) {
                for (std::ptrdiff_t cc = c - radius; cc <= c + radius; ++cc) {
                    if (rr < 0 || rr >= in.rows() || cc < 0 || cc >= in.cols()) continue;
                    const T x = in(rr, cc);
                    if constexpr (std::is_floating_point_v<T>) {
                        if (std::isnan(x)) continue;
                    }
                    lo = any ? std::min(lo, x) : x;
                    hi = any ? std::max(hi, x) : x;
                    any = true;
                }
            }
            if constexpr (std::is_floating_point_v<T>) {
                if (!any) lo = hi = std::numeric_limits<T>::quiet_NaN();
            }
            res.min(r, c) = lo;
            res.max(r, c) = hi;
        }
    }
    return res;
}

/// Equal cell by cell, NaN equal to NaN (the filter copies values: no tolerance).
template <class T>
bool same(raster_view<const T> a, raster_view<const T> b)
{
    if (a.rows() != b.rows() || a.cols() != b.cols()) return false;
    for (std::ptrdiff_t r = 0; r < a.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < a.cols(); ++c) {
            const T x = a(r, c), y = b(r, c);
            if constexpr (std::is_floating_point_v<T>) {
                if (std::isnan(x) && std::isnan(y)) continue;
            }
            if (!(x == y)) return false;
        }
    }
    return true;
}

/// Random floats with NaN runs, ±inf and repeated values (ties), at `nan_share` NaN.
raster<float> random_floats(std::mt19937& rng, std::ptrdiff_t rows, std::ptrdiff_t cols, double nan_share)
{
    raster<float> z(rows, cols);
    std::uniform_real_distribution<float> value(-50.0f, 50.0f);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const double p = u(rng);
            if (p < nan_share)
                z(r, c) = nan_f;
            else if (p < nan_share + 0.01)
                z(r, c) = u(rng) < 0.5 ? inf_f : -inf_f;
            else if (p < nan_share + 0.1)
                z(r, c) = 1.0f;  // ties
            else
                z(r, c) = value(rng);
        }
    }
    return z;
}

void check_against_brute(raster_view<const float> in, int radius, int threads = 1)
{
    const auto ref = brute(in, radius);
    const auto got = min_max_filter(in, {.radius_cells = radius, .run = {.threads = threads}});
    CHECK(same<float>(got.min, ref.min));
    CHECK(same<float>(got.max, ref.max));
}

}  // namespace

TEST_CASE("filter/min_max_filter: hand-checked 4x5 with NaN and a border")
{
    raster<float> z(4, 5);
    const float v[4][5] = {
        {1, 2, 3, 4, 5}, {6, nan_f, 8, 9, 10}, {11, 12, 13, 14, 15}, {nan_f, nan_f, nan_f, nan_f, 0}};
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 5; ++c) z(r, c) = v[r][c];
    const auto res = min_max_filter(z.view(), {.radius_cells = 1});
    CHECK(res.min(0, 0) == 1);  // corner: the 2 x 2 clipped window, NaN skipped
    CHECK(res.max(0, 0) == 6);
    CHECK(res.min(1, 1) == 1);
    CHECK(res.max(1, 1) == 13);
    CHECK(res.min(3, 0) == 11);
    CHECK(res.max(3, 0) == 12);
    CHECK(res.min(3, 4) == 0);
    CHECK(res.max(3, 4) == 15);
    CHECK(res.min(2, 4) == 0);
    CHECK(res.max(2, 4) == 15);
}

TEST_CASE("filter/min_max_filter: windows without data give NaN; ±inf are values")
{
    raster<float> z(3, 7, nan_f);
    z(1, 6) = inf_f;
    const auto res = min_max_filter(z.view(), {.radius_cells = 1});
    CHECK(std::isnan(res.min(1, 0)));
    CHECK(std::isnan(res.max(1, 4)));
    CHECK(res.min(0, 5) == inf_f);  // a window holding only +inf: both +inf, not NaN
    CHECK(res.max(0, 5) == inf_f);
    raster<float> all_nan(1, 1, nan_f);
    const auto one = min_max_filter(all_nan.view(), {.radius_cells = 3});
    CHECK(std::isnan(one.min(0, 0)));
    CHECK(std::isnan(one.max(0, 0)));
}

TEST_CASE("filter/min_max_filter: 1x1, empty, 1xN, Nx1 and radius 0")
{
    raster<float> one(1, 1, 4.5f);
    const auto a = min_max_filter(one.view(), {.radius_cells = 5});
    CHECK(a.min(0, 0) == 4.5f);
    CHECK(a.max(0, 0) == 4.5f);

    raster<float> empty(0, 3);
    const auto e = min_max_filter(empty.view(), {.radius_cells = 2});
    CHECK(e.min.rows() == 0);
    CHECK(e.max.cols() == 3);

    std::mt19937 rng(20261202);
    for (int radius : {0, 1, 2, 3, 7, 40}) {
        const auto row = random_floats(rng, 1, 37, 0.2);
        check_against_brute(row.view(), radius);
        const auto col = random_floats(rng, 29, 1, 0.2);
        check_against_brute(col.view(), radius);
    }
    const auto z = random_floats(rng, 9, 11, 0.2);
    const auto same_in = min_max_filter(z.view(), {.radius_cells = 0});
    CHECK(same<float>(same_in.min, z));
    CHECK(same<float>(same_in.max, z));
}

TEST_CASE("filter/min_max_filter: matches brute force on random rasters, strided windows and threads")
{
    std::mt19937 rng(20261203);
    for (int trial = 0; trial < 50; ++trial) {
        CAPTURE(trial);
        std::uniform_int_distribution<int> side(1, 60);
        const std::ptrdiff_t rows = side(rng), cols = side(rng);
        const int radius = trial % 10 == 9 ? 70 : trial % 7;  // also radii larger than the raster
        CAPTURE(rows);
        CAPTURE(cols);
        CAPTURE(radius);
        const double nan_share = trial % 5 == 4 ? 0.9 : 0.15;  // sparse data: many windows without any
        const auto big = random_floats(rng, rows + 5, cols + 4, nan_share);
        const auto window = big.view().window(2, 3, rows, cols);  // row_stride != cols
        check_against_brute(window, radius, trial % 3);
        const raster<float> copy(window);
        check_against_brute(copy.view(), radius);
    }
}

TEST_CASE("filter/min_max_filter: tall rasters cross strips; same result for any thread count")
{
    std::mt19937 rng(20261204);
    const auto z = random_floats(rng, 700, 13, 0.3);
    for (int radius : {1, 4, 33}) {
        check_against_brute(z.view(), radius, 1);
        check_against_brute(z.view(), radius, 3);
    }
}

TEST_CASE("filter/min_max_filter: integer rasters (no NaN rule)")
{
    std::mt19937 rng(20261205);
    std::uniform_int_distribution<std::int32_t> value(-1000, 1000);
    for (int trial = 0; trial < 20; ++trial) {
        raster<std::int32_t> m(1 + trial % 9, 3 + trial);
        for (std::ptrdiff_t r = 0; r < m.rows(); ++r)
            for (std::ptrdiff_t c = 0; c < m.cols(); ++c)
                m(r, c) = trial == 0 ? std::numeric_limits<std::int32_t>::max() : value(rng);
        const int radius = trial % 4;
        const auto ref = brute<std::int32_t>(m.view(), radius);
        const auto got = min_max_filter(m.view(), {.radius_cells = radius});
        CHECK(got.min == ref.min);
        CHECK(got.max == ref.max);
    }
}

TEST_CASE("filter/min_max_filter: refuses bad options, shapes and overlapping outputs")
{
    raster<float> z(4, 4, 1.0f), lo(4, 4), hi(4, 3);
    CHECK_THROWS_AS(min_max_filter(z.view(), {.radius_cells = -1}), invalid_input);
    CHECK_THROWS_AS(min_max_filter(z.view(), lo.view(), hi.view()), invalid_input);
    raster<float> hi2(4, 4);
    CHECK_THROWS_AS(min_max_filter(z.view(), z.view(), hi2.view()), invalid_input);
    CHECK_THROWS_AS(min_max_filter(z.view(), lo.view(), lo.view()), invalid_input);
    CHECK_THROWS_AS(min_max_filter(z.view(), {.run = {.threads = -1}}), invalid_input);
    min_max_filter(z.view(), lo.view(), hi2.view());
    CHECK(lo(3, 3) == 1.0f);
}
