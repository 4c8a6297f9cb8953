// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/kernels/filter/angular_filter.hpp>

#include "reference/angular_filter.hpp"
#include "reference/progress.hpp"
#include "test_values.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

using namespace lidarfx;

namespace {

double deg(double rad)
{
    return rad * 180.0 / std::numbers::pi;
}

// The kernel takes the max ratio |dz|/d in float and one float atan; the reference takes atan per neighbour in
// double. The float ratio carries at most 3 roundings (|dz|, 1/d, the product): relative error <= 3 * 2^-24,
// and atan moves by at most x/(1+x^2) <= 1/2 times a relative change of x: <= 9e-8 rad = 5.2e-6 deg. The float
// atan has relative error 1.4e-7 (<= 6.3e-6 deg at 45 deg); 90 - a and the conversion to degrees round once
// each (<= 3.8e-6 deg), and so does the reference (<= 3.8e-6 deg). Sum: 2.3e-5 deg.
constexpr double angle_tolerance_deg = 3e-5;

// Cells equal within the tolerance, NaN exactly where the reference has NaN.
bool close_to(const raster<float>& got, const raster<float>& want, double tolerance = angle_tolerance_deg)
{
    if (got.rows() != want.rows() || got.cols() != want.cols()) return false;
    for (std::ptrdiff_t r = 0; r < got.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < got.cols(); ++c) {
            const float g = got(r, c), w = want(r, c);
            if (std::isnan(g) != std::isnan(w)) return false;
            if (!std::isnan(w) && std::fabs(double(g) - double(w)) > tolerance) return false;
        }
    }
    return true;
}

bool same_cells(const raster<float>& a, const raster<float>& b)
{
    if (a.rows() != b.rows() || a.cols() != b.cols()) return false;
    for (std::ptrdiff_t i = 0; i < a.size(); ++i) {
        const float x = a.data()[i], y = b.data()[i];
        if (!(x == y || (std::isnan(x) && std::isnan(y)))) return false;
    }
    return true;
}

// A host raster that is neither a lidarfx type nor strided: read through one converted copy.
struct host_grid {
    using value_type = double;
    std::ptrdiff_t n;
    std::ptrdiff_t rows() const { return n; }
    std::ptrdiff_t cols() const { return n; }
    double operator()(std::ptrdiff_t r, std::ptrdiff_t c) const { return static_cast<double>(r * r + 3 * c); }
};

}  // namespace

TEST_CASE("filter/angular_filter: hand-checked small rasters")
{
    SUBCASE("a raised centre: 45 deg towards edge neighbours, atan(1/sqrt 2) towards corners")
    {
        raster<float> z(3, 3, 0.0f);
        z(1, 1) = 1.0f;
        const auto a = angular_filter(z, 1.0, 1);
        CHECK(a(1, 1) == doctest::Approx(45.0).epsilon(1e-6));
        CHECK(a(0, 1) == doctest::Approx(45.0).epsilon(1e-6));
        CHECK(a(1, 0) == doctest::Approx(45.0).epsilon(1e-6));
        CHECK(a(0, 0) == doctest::Approx(deg(std::atan(1.0 / std::sqrt(2.0)))).epsilon(1e-6));
        CHECK(a(2, 2) == doctest::Approx(deg(std::atan(1.0 / std::sqrt(2.0)))).epsilon(1e-6));
    }
    SUBCASE("cell size scales distances")
    {
        raster<float> z(1, 2);
        z(0, 1) = 1.0f;
        const auto a = angular_filter(z, 2.0);
        CHECK(a(0, 0) == doctest::Approx(deg(std::atan(0.5))).epsilon(1e-6));
        CHECK(a(0, 1) == doctest::Approx(deg(std::atan(0.5))).epsilon(1e-6));
    }
    SUBCASE("the second tier counts with its own distance")
    {
        raster<float> z(1, 5, 0.0f);
        z(0, 4) = 4.0f;  // seen from column 2 at distance 2: atan(2) > 45 deg
        const auto a = angular_filter(z, 1.0, 2);
        CHECK(a(0, 2) == doctest::Approx(deg(std::atan(2.0))).epsilon(1e-6));
        CHECK(a(0, 1) == doctest::Approx(0.0));  // column 4 lies 3 cells away, outside radius 2
        CHECK(angular_filter(z, 1.0, 3)(0, 1) == doctest::Approx(deg(std::atan(4.0 / 3.0))).epsilon(1e-6));
        // A window far wider than the raster sees the same cells as one just covering it.
        CHECK(angular_filter(z, 1.0, 1'000'000'000) == angular_filter(z, 1.0, 4));
    }
    SUBCASE("NaN neighbours are skipped, a NaN centre gives NaN, no valid neighbour gives 0")
    {
        raster<float> z(1, 3);
        z(0, 0) = 0.0f;
        z(0, 1) = nan_f;
        z(0, 2) = 5.0f;
        const auto a = angular_filter(z, 1.0, 2);
        CHECK(a(0, 0) == doctest::Approx(deg(std::atan(2.5))).epsilon(1e-6));
        CHECK(std::isnan(a(0, 1)));
        CHECK(a(0, 2) == doctest::Approx(deg(std::atan(2.5))).epsilon(1e-6));
        CHECK(angular_filter(z, 1.0, 1)(0, 0) == 0.0f);
        CHECK(angular_filter(raster<float>(1, 1, 7.0f), 1.0)(0, 0) == 0.0f);
    }
    SUBCASE("an infinite step is a vertical wall")
    {
        raster<float> z(1, 2, 0.0f);
        z(0, 1) = std::numeric_limits<float>::infinity();
        const auto a = angular_filter(z, 1.0);
        CHECK(a(0, 0) == 90.0f);
    }
}

TEST_CASE("filter/angular_filter: matches the per-neighbour reference on random rasters")
{
    const unsigned seed = 20240611;
    std::mt19937 rng(seed);
    const std::vector<std::pair<std::ptrdiff_t, std::ptrdiff_t>> shapes = {{1, 1},  {1, 17}, {19, 1},  {2, 2},
                                                                           {7, 13}, {13, 7}, {40, 33}, {257, 131}};
    int trial = 0;
    for (const auto& shape : shapes) {
        const std::ptrdiff_t rows = shape.first, cols = shape.second;
        for (int radius : {1, 2, 3, 5}) {  // 5: no unrolled kernel, the clipped passes do every cell
            if (rows * cols > 10000 && radius != 2) continue;  // keeps the brute force quick
            ++trial;
            INFO("seed " << seed << ", trial " << trial << ": " << rows << "x" << cols << " radius " << radius);
            const double nan_share = (trial % 3 == 0) ? 0.0 : (trial % 3 == 1 ? 0.1 : 0.5);
            const double cell = 0.25 + 0.5 * (trial % 4);
            const auto z = reference::random_raster(rng, rows, cols, -5.0, 30.0, nan_share);
            const auto want = reference::angular_filter(z, cell, radius);
            const auto got = angular_filter(z, cell, radius);
            CHECK(close_to(got, want));

            // The same cells behind a row stride, with far-off poison outside the window: identical output.
            const auto big = reference::with_margin(z, 3, 1.0e6f);
            const auto strided = reference::inner(big, 3, rows, cols);
            REQUIRE(strided.row_stride() > strided.cols());
            for (int threads : {1, 2, 3}) {
                const angular_filter_options opt{.radius_cells = radius, .run = {.threads = threads}};
                CHECK(same_cells(angular_filter(strided, cell, opt), got));
            }
        }
    }
}

TEST_CASE("filter/angular_filter: adversarial rasters")
{
    SUBCASE("constant rasters are flat everywhere")
    {
        for (float v : {0.0f, 1.0f, -250.5f}) {
            const auto a = angular_filter(raster<float>(9, 11, v), 0.5);
            for (float x : a) CHECK(x == 0.0f);
        }
    }
    SUBCASE("a checkerboard of 0/1 at 1 m cells is 45 deg everywhere")
    {
        raster<float> z(8, 9);
        for (std::ptrdiff_t r = 0; r < z.rows(); ++r)
            for (std::ptrdiff_t c = 0; c < z.cols(); ++c) z(r, c) = static_cast<float>((r + c) % 2);
        const auto a = angular_filter(z, 1.0, 2);
        for (float x : a) CHECK(x == doctest::Approx(45.0).epsilon(1e-6));
    }
    SUBCASE("all NaN stays NaN; one valid cell among NaN gives 0")
    {
        raster<float> z(6, 6, nan_f);
        for (float x : angular_filter(z, 1.0)) CHECK(std::isnan(x));
        z(3, 2) = 12.0f;
        const auto a = angular_filter(z, 1.0);
        CHECK(a(3, 2) == 0.0f);
    }
    SUBCASE("NaN patches and borders agree with the reference")
    {
        std::mt19937 rng(77);
        auto z = reference::random_raster(rng, 31, 29, 0.0, 3.0);
        for (std::ptrdiff_t r = 5; r < 14; ++r)
            for (std::ptrdiff_t c = 0; c < 9; ++c) z(r, c) = nan_f;  // a hole touching the west border
        CHECK(close_to(angular_filter(z, 1.0, 2), reference::angular_filter(z, 1.0, 2)));
    }
    SUBCASE("infinite cells: the window kernel agrees with the per-neighbour reference")
    {
        // Inside the raster the unrolled window kernel runs, at the borders the per-offset passes: both must
        // give 90 next to an infinite step and 0 where every difference is inf - inf (skipped like NaN).
        std::mt19937 rng(91);
        auto z = reference::random_raster(rng, 17, 19, 0.0, 3.0, 0.1);
        const float inf = std::numeric_limits<float>::infinity();
        std::uniform_int_distribution<int> pick(0, 9);
        for (auto& v : z) v = pick(rng) == 0 ? inf : (pick(rng) == 0 ? -inf : v);
        for (std::ptrdiff_t r = 6; r < 13; ++r)
            for (std::ptrdiff_t c = 6; c < 13; ++c) z(r, c) = inf;  // a block where all neighbours are inf
        for (int radius : {1, 2, 3})
            CHECK(close_to(angular_filter(z, 0.5, radius), reference::angular_filter(z, 0.5, radius)));
        CHECK(angular_filter(z, 0.5, 2)(9, 9) == 0.0f);
    }
}

TEST_CASE("filter/angular_filter: a larger window never gives a smaller angle")
{
    std::mt19937 rng(5);
    const auto z = reference::random_raster(rng, 23, 27, 0.0, 4.0, 0.1);
    const auto small = angular_filter(z, 1.0, 1), large = angular_filter(z, 1.0, 3);
    for (std::ptrdiff_t i = 0; i < z.size(); ++i) {
        if (std::isnan(z.data()[i])) continue;
        CHECK(large.data()[i] >= small.data()[i]);
        CHECK(large.data()[i] <= 90.0f);
    }
}

TEST_CASE("filter/angular_filter: accepts host rasters and writes into any output")
{
    // The spelling the library promises (docs/conventions.md).
    raster<float> z(4, 5, 1.0f);
    z(2, 2) = 3.0f;
    const raster_view<const float> view = z.view();
    const raster<float> a = angular_filter(view, 1.0, 2);
    CHECK(a(2, 2) == doctest::Approx(deg(std::atan(2.0))).epsilon(1e-6));

    // A non-strided double raster is converted once; the result equals filtering the float copy.
    const host_grid host{6};
    CHECK(same_cells(angular_filter(host, 0.5), angular_filter(raster<float>(host), 0.5)));

    // Into a raster, a view and a strided window of a larger buffer.
    raster<float> out(4, 5, -1.0f);
    angular_filter(z, out, 1.0);
    CHECK(same_cells(out, a));
    raster<float> big(6, 9, -7.0f);
    angular_filter(z, big.view().window(1, 2, 4, 5), 1.0, {.radius_cells = 2, .run = {.threads = 2}});
    CHECK(same_cells(raster<float>(big.view().window(1, 2, 4, 5)), a));
    CHECK(big(0, 0) == -7.0f);
    CHECK(big(5, 8) == -7.0f);
}

TEST_CASE("filter/angular_filter: progress is monotone and ends at 1; returning false cancels")
{
    std::mt19937 rng(8);
    const auto z = reference::random_raster(rng, 300, 40, -5.0, 30.0, 0.05);  // five blocks of 64 rows
    const auto want = angular_filter(z, 0.5);
    for (int threads : {1, 2}) {
        CAPTURE(threads);
        const reference::progress_log log;
        CHECK(same_cells(angular_filter(z, 0.5, {.run = {.threads = threads, .progress = log.callback()}}), want));
        CHECK(log.monotone_to_one(threads == 1 ? 5 : 1));
        const angular_filter_options stop{.run = {.threads = threads, .progress = reference::cancel_at_once()}};
        CHECK_THROWS_WITH_AS(angular_filter(z, 0.5, stop), "angular_filter: cancelled", cancelled);
    }
}

TEST_CASE("filter/angular_filter: rejects bad arguments with a clear message")
{
    raster<float> z(3, 3, 0.0f);
    CHECK_THROWS_WITH_AS(angular_filter(z, 0.0), "angular_filter: cell_m must be finite and > 0 (got 0)",
                         invalid_input);
    CHECK_THROWS_WITH_AS(angular_filter(z, -2.0), "angular_filter: cell_m must be finite and > 0 (got -2)",
                         invalid_input);
    CHECK_THROWS_AS(angular_filter(z, std::nan("")), invalid_input);
    CHECK_THROWS_AS(angular_filter(z, std::numeric_limits<double>::infinity()), invalid_input);
    CHECK_THROWS_WITH_AS(angular_filter(z, 1.0, 0), "angular_filter: radius_cells must be >= 1 (got 0)", invalid_input);
    CHECK_THROWS_WITH_AS(angular_filter(z, 1.0, {.run = {.threads = -1}}),
                         "angular_filter: run.threads must be >= 0 (got -1)", invalid_input);
    raster<float> wrong(3, 4);
    CHECK_THROWS_WITH_AS(angular_filter(z, wrong, 1.0),
                         "angular_filter: z and out must have the same shape (got 3x3 and 3x4)", invalid_input);
    raster<float> shared(4, 4);
    CHECK_THROWS_WITH_AS(angular_filter(shared.view().window(0, 0, 3, 3), shared.view().window(1, 1, 3, 3), 1.0),
                         "angular_filter: out must not overlap z", invalid_input);
}
