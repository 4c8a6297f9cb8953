// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/kernels/filter/slope_aspect.hpp>

#include "reference/angular_filter.hpp"  // random_raster, with_margin, inner
#include "reference/progress.hpp"
#include "reference/slope_aspect.hpp"
#include "test_values.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace lidarfx;

namespace {

// Error budget against the double reference. Slope: the float atan (relative error 1.4e-7, <= 6.3e-6 deg), the
// float rounding of |grad| (<= 1.7e-6 deg), 90 - a (<= 3.8e-6) and the reference's own rounding (<= 3.8e-6):
// below 2e-5. Aspect adds the reflections 180 - a and 360 - a, each rounded to float (<= 1.5e-5 at 360).
constexpr double slope_tolerance_deg = 3e-5;
constexpr double aspect_tolerance_deg = 6e-5;

double angle_gap(double a, double b)
{
    const double d = std::fabs(a - b);
    return std::min(d, 360.0 - d);
}

// Describes the first disagreement with the reference, or returns "" when every cell agrees.
std::string mismatch(const slope_aspect_result& got, const reference::slope_aspect_rasters& want, double flat_slope_deg)
{
    for (std::ptrdiff_t r = 0; r < want.slope_deg.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < want.slope_deg.cols(); ++c) {
            const double gs = got.slope_deg(r, c), ws = want.slope_deg(r, c);
            const double ga = got.aspect_deg(r, c), wa = want.aspect_deg(r, c);
            const bool near_threshold = std::fabs(ws - flat_slope_deg) <= slope_tolerance_deg;
            bool ok = std::isnan(gs) == std::isnan(ws) && (std::isnan(ws) || std::fabs(gs - ws) <= slope_tolerance_deg);
            if (!near_threshold) {
                ok = ok && got.flat(r, c) == want.flat(r, c) && std::isnan(ga) == std::isnan(wa) &&
                     (std::isnan(wa) || angle_gap(ga, wa) <= aspect_tolerance_deg);
            }
            ok = ok && (std::isnan(ga) || (ga >= 0 && ga < 360)) && (std::isnan(gs) || (gs >= 0 && gs <= 90));
            if (!ok) {
                std::ostringstream os;
                os << "cell (" << r << ", " << c << "): slope " << gs << " vs " << ws << ", aspect " << ga << " vs "
                   << wa << ", flat " << int(got.flat(r, c)) << " vs " << int(want.flat(r, c));
                return os.str();
            }
        }
    }
    return "";
}

bool identical(const slope_aspect_result& a, const slope_aspect_result& b)
{
    const auto same = [](const raster<float>& x, const raster<float>& y) {
        for (std::ptrdiff_t i = 0; i < x.size(); ++i) {
            if (!(x.data()[i] == y.data()[i] || (std::isnan(x.data()[i]) && std::isnan(y.data()[i])))) return false;
        }
        return x.rows() == y.rows() && x.cols() == y.cols();
    };
    return same(a.slope_deg, b.slope_deg) && same(a.aspect_deg, b.aspect_deg) && a.flat == b.flat;
}

// z = z0 + east * x + north * y with x east and y north in metres (cell centres), row 0 north.
raster<float> plane(std::ptrdiff_t rows, std::ptrdiff_t cols, double cell, double east, double north)
{
    raster<float> z(rows, cols);
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c)
            z(r, c) = static_cast<float>(100.0 + east * cell * static_cast<double>(c) -
                                         north * cell * static_cast<double>(r));
    return z;
}

double slope_of(double east, double north)
{
    return std::atan(std::hypot(east, north)) * 180 / std::numbers::pi;
}

double aspect_of(double east, double north)
{
    const double a = std::atan2(-east, -north) * 180 / std::numbers::pi;
    return a < 0 ? a + 360 : a;
}

}  // namespace

TEST_CASE("filter/slope_aspect: hand-checked planes face the right way")
{
    struct facing {
        const char* name;
        double east, north, aspect;
    };
    // Rising towards the south faces north, and so on; a 1:1 gradient is 45 deg.
    for (const auto& f : {facing{"north", 0, -1, 0}, facing{"east", -1, 0, 90}, facing{"south", 0, 1, 180},
                          facing{"west", 1, 0, 270}, facing{"south-west", 1, 1, 225}}) {
        CAPTURE(f.name);
        const auto z = plane(3, 3, 1.0, f.east, f.north);
        const auto s = slope_aspect(z, 1.0);
        for (std::ptrdiff_t r = 0; r < 3; ++r) {
            for (std::ptrdiff_t c = 0; c < 3; ++c) {
                CHECK(s.slope_deg(r, c) == doctest::Approx(slope_of(f.east, f.north)).epsilon(1e-6));
                CHECK(s.aspect_deg(r, c) == doctest::Approx(f.aspect).epsilon(1e-6));
                CHECK(s.flat(r, c) == 0);
            }
        }
    }
    SUBCASE("Horn weights: the centre row and column count twice")
    {
        // Only the top-right corner is raised: dz/dx = (1 - 0) / 8 per cell, dz/dy (north) = 1 / 8 per cell.
        raster<float> z(3, 3, 0.0f);
        z(0, 2) = 1.0f;
        const auto s = slope_aspect(z, 0.5);
        CHECK(s.slope_deg(1, 1) == doctest::Approx(slope_of(0.25, 0.25)).epsilon(1e-6));
        CHECK(s.aspect_deg(1, 1) == doctest::Approx(225.0).epsilon(1e-6));
    }
    SUBCASE("a flat raster is flat everywhere, with NaN aspect")
    {
        const auto s = slope_aspect(raster<float>(4, 5, 12.5f), 1.0);
        for (std::ptrdiff_t i = 0; i < 20; ++i) {
            CHECK(s.slope_deg.data()[i] == 0.0f);
            CHECK(std::isnan(s.aspect_deg.data()[i]));
            CHECK(s.flat.data()[i] == 1);
        }
    }
}

TEST_CASE("filter/slope_aspect: random planes come out exact at borders and beside NaN holes")
{
    const unsigned seed = 1981;
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> sixty_fourths(-256, 256);  // gradients k/64: every cell value is exact
    std::bernoulli_distribution hole(0.15);
    for (int trial = 0; trial < 40; ++trial) {
        const double east = sixty_fourths(rng) / 64.0, north = sixty_fourths(rng) / 64.0;
        const double cell = trial % 2 ? 0.5 : 2.0;
        const std::ptrdiff_t rows = 2 + trial % 9, cols = 2 + (trial * 7) % 13;
        auto z = plane(rows, cols, cell, east, north);
        if (trial % 3 != 0) {
            for (auto& v : z) v = hole(rng) ? nan_f : v;
        }
        INFO("seed " << seed << ", trial " << trial << ": " << rows << "x" << cols << " east " << east << " north "
                     << north);
        const auto s = slope_aspect(z, cell);
        const auto want = reference::slope_aspect(z, cell, 0.0);
        for (std::ptrdiff_t r = 0; r < rows; ++r) {
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                // NaN exactly where the reference finds no difference along an axis (or a NaN centre).
                REQUIRE(std::isnan(s.slope_deg(r, c)) == std::isnan(want.slope_deg(r, c)));
                if (std::isnan(want.slope_deg(r, c))) continue;
                CHECK(std::fabs(s.slope_deg(r, c) - slope_of(east, north)) <= slope_tolerance_deg);
                if (east == 0 && north == 0) {
                    CHECK(s.flat(r, c) == 1);
                } else {
                    CHECK(angle_gap(s.aspect_deg(r, c), aspect_of(east, north)) <= aspect_tolerance_deg);
                }
            }
        }
    }
}

TEST_CASE("filter/slope_aspect: matches the reference on random rasters, strided views and thread counts")
{
    const unsigned seed = 20240611;
    std::mt19937 rng(seed);
    const std::vector<std::pair<std::ptrdiff_t, std::ptrdiff_t>> shapes = {{1, 1}, {1, 17}, {19, 1},  {2, 2},
                                                                           {3, 3}, {7, 13}, {40, 33}, {257, 131}};
    int trial = 0;
    for (const auto& shape : shapes) {
        const std::ptrdiff_t rows = shape.first, cols = shape.second;
        for (double nan_share : {0.0, 0.05, 0.4}) {
            ++trial;
            INFO("seed " << seed << ", trial " << trial << ": " << rows << "x" << cols << " NaN share " << nan_share);
            const double cell = 0.25 + 0.5 * (trial % 4);
            const double flat_deg = trial % 2 ? 0.0 : 20.0;
            const auto z = reference::random_raster(rng, rows, cols, -5.0, 30.0, nan_share);
            const auto got = slope_aspect(z, cell, {.flat_slope_deg = flat_deg});
            CHECK(mismatch(got, reference::slope_aspect(z, cell, flat_deg), flat_deg) == "");

            const auto big = reference::with_margin(z, 2, 1.0e6f);
            const auto strided = reference::inner(big, 2, rows, cols);
            for (int threads : {1, 2, 3}) {
                const slope_aspect_options opt{.flat_slope_deg = flat_deg, .run = {.threads = threads}};
                CHECK(identical(slope_aspect(strided, cell, opt), got));
            }
        }
    }
}

TEST_CASE("filter/slope_aspect: the flat flag compares the float slope with the double threshold exactly")
{
    // The kernel compares in float against the largest float <= flat_slope_deg; for a threshold that is no
    // float (20 + 1e-9, just above the float 20, and one just below the next float) every flag must still be
    // exactly (double)slope <= flat_slope_deg. A surface of slopes spread around 20 degrees hits both sides.
    const std::ptrdiff_t rows = 64, cols = 64;
    raster<float> z(rows, cols);
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const auto x = static_cast<double>(c), y = static_cast<double>(r);
            z(r, c) = static_cast<float>(0.30 * x + 0.001 * x * x + 0.0005 * y * x);
        }
    }
    const double next_float_above_20 = std::nextafter(20.0f, 30.0f);
    for (double flat_deg : {20.0 + 1e-9, (20.0 + next_float_above_20) / 2, next_float_above_20 - 1e-12, 20.0}) {
        INFO("flat_slope_deg " << flat_deg);
        const auto got = slope_aspect(z, 1.0, {.flat_slope_deg = flat_deg});
        int flat = 0, steep = 0;
        for (std::ptrdiff_t r = 0; r < rows; ++r) {
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                const bool expected = static_cast<double>(got.slope_deg(r, c)) <= flat_deg;
                CHECK(got.flat(r, c) == (expected ? 1 : 0));
                CHECK(std::isnan(got.aspect_deg(r, c)) == expected);
                (expected ? flat : steep) += 1;
            }
        }
        CHECK(flat > 0);
        CHECK(steep > 0);
    }
}

TEST_CASE("filter/slope_aspect: adversarial rasters")
{
    SUBCASE("a single row or column has no gradient across it: NaN, never flat")
    {
        for (const auto& z : {raster<float>(1, 6, 3.0f), raster<float>(5, 1, 3.0f), raster<float>(1, 1, 3.0f)}) {
            const auto s = slope_aspect(z, 1.0);
            for (float v : s.slope_deg) CHECK(std::isnan(v));
            for (float v : s.aspect_deg) CHECK(std::isnan(v));
            for (auto v : s.flat) CHECK(v == 0);
        }
    }
    SUBCASE("NaN centres give NaN; an isolated cell has no gradient")
    {
        raster<float> z(5, 5, nan_f);
        z(2, 2) = 1.0f;
        const auto s = slope_aspect(z, 1.0);
        CHECK(std::isnan(s.slope_deg(2, 2)));
        CHECK(std::isnan(s.slope_deg(0, 0)));
        CHECK(s.flat(2, 2) == 0);
    }
    SUBCASE("checkerboards and steps agree with the reference")
    {
        raster<float> board(9, 10), step(8, 8, 0.0f);
        for (std::ptrdiff_t r = 0; r < board.rows(); ++r)
            for (std::ptrdiff_t c = 0; c < board.cols(); ++c) board(r, c) = static_cast<float>((r + c) % 2);
        for (std::ptrdiff_t r = 0; r < step.rows(); ++r)
            for (std::ptrdiff_t c = 4; c < step.cols(); ++c) step(r, c) = 1000.0f;
        for (const auto* z : {&board, &step}) {
            CHECK(mismatch(slope_aspect(*z, 1.0), reference::slope_aspect(*z, 1.0, 0.0), 0.0) == "");
        }
    }
    SUBCASE("a NaN patch on the border")
    {
        std::mt19937 rng(3);
        auto z = reference::random_raster(rng, 20, 17, 0.0, 2.0);
        for (std::ptrdiff_t r = 0; r < 6; ++r)
            for (std::ptrdiff_t c = 10; c < 17; ++c) z(r, c) = nan_f;
        CHECK(mismatch(slope_aspect(z, 1.0), reference::slope_aspect(z, 1.0, 0.0), 0.0) == "");
    }
}

TEST_CASE("filter/slope_aspect: turning the raster a quarter turn turns the aspect by 90 deg")
{
    std::mt19937 rng(11);
    const auto z = reference::random_raster(rng, 23, 19, 0.0, 5.0);
    raster<float> turned(z.cols(), z.rows());  // clockwise: what faced north now faces east
    for (std::ptrdiff_t r = 0; r < turned.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < turned.cols(); ++c) turned(r, c) = z(z.rows() - 1 - c, r);
    const auto a = slope_aspect(z, 1.0), b = slope_aspect(turned, 1.0);
    for (std::ptrdiff_t r = 0; r < z.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < z.cols(); ++c) {
            const std::ptrdiff_t tr = c, tc = z.rows() - 1 - r;
            CHECK(std::fabs(b.slope_deg(tr, tc) - a.slope_deg(r, c)) <= slope_tolerance_deg);
            CHECK(angle_gap(b.aspect_deg(tr, tc), std::fmod(a.aspect_deg(r, c) + 90.0, 360.0)) <=
                  2 * aspect_tolerance_deg);
        }
    }
}

TEST_CASE("filter/slope_aspect: progress is monotone and ends at 1; returning false cancels")
{
    std::mt19937 rng(9);
    const auto z = reference::random_raster(rng, 300, 40, -5.0, 30.0, 0.05);  // five blocks of 64 rows
    const auto want = slope_aspect(z, 0.5);
    for (int threads : {1, 2}) {
        CAPTURE(threads);
        const reference::progress_log log;
        CHECK(identical(slope_aspect(z, 0.5, {.run = {.threads = threads, .progress = log.callback()}}), want));
        CHECK(log.monotone_to_one(threads == 1 ? 5 : 1));
        const slope_aspect_options stop{.run = {.threads = threads, .progress = reference::cancel_at_once()}};
        CHECK_THROWS_WITH_AS(slope_aspect(z, 0.5, stop), "slope_aspect: cancelled", cancelled);
    }
}

TEST_CASE("filter/slope_aspect: into any outputs; bad arguments throw with a clear message")
{
    const auto z = plane(6, 7, 1.0, 0.5, -0.25);
    const auto want = slope_aspect(z, 1.0);
    raster<float> slope_big(8, 9, -1.0f), aspect(6, 7);
    raster<std::uint8_t> flat(6, 7);
    slope_aspect(z, slope_big.view().window(1, 1, 6, 7), aspect, flat.view(), 1.0);
    CHECK(raster<float>(slope_big.view().window(1, 1, 6, 7)) == want.slope_deg);
    CHECK(slope_big(0, 0) == -1.0f);
    CHECK(aspect == want.aspect_deg);

    CHECK_THROWS_WITH_AS(slope_aspect(z, 0.0), "slope_aspect: cell_m must be finite and > 0 (got 0)", invalid_input);
    CHECK_THROWS_WITH_AS(slope_aspect(z, 1.0, {.flat_slope_deg = 90.0}),
                         "slope_aspect: flat_slope_deg must be in [0, 90) (got 90)", invalid_input);
    CHECK_THROWS_AS(slope_aspect(z, 1.0, {.flat_slope_deg = -1.0}), invalid_input);
    CHECK_THROWS_AS(slope_aspect(z, 1.0, {.flat_slope_deg = std::nan("")}), invalid_input);
    CHECK_THROWS_WITH_AS(slope_aspect(z, 1.0, {.run = {.threads = -2}}),
                         "slope_aspect: run.threads must be >= 0 (got -2)", invalid_input);
    raster<float> small(6, 6);
    CHECK_THROWS_WITH_AS(slope_aspect(z, small, aspect, flat, 1.0),
                         "slope_aspect: z and slope_deg must have the same shape (got 6x7 and 6x6)", invalid_input);
    raster<float> shared(6, 7);
    CHECK_THROWS_WITH_AS(slope_aspect(z, shared, shared, flat, 1.0),
                         "slope_aspect: outputs must not overlap z or each other", invalid_input);
}
