// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/kernels/solar/horizon_map.hpp>
#include <lidarfx/kernels/solar/raylines_shadow.hpp>

#include "reference/angular_filter.hpp"  // random_raster, with_margin, inner
#include "reference/progress.hpp"
#include "reference/solar.hpp"
#include "test_values.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <sstream>
#include <string>

using namespace lidarfx;

namespace {

// The hull sweep rounds the tangent to float (relative 6e-8) and takes lidarfx's float arctangent (relative
// error 1.4e-7, core/fast_math.hpp); the direct search uses std::atan2 in double. At most 2e-7 * 90 = 1.8e-5
// degrees apart, so 1e-4 leaves a margin and still catches a wrong tangent point (>= 1e-3 degrees here).
constexpr double tolerance_deg = 1e-4;

// The first cell where two horizon maps differ by more than the tolerance (or in NaN-ness), or "".
std::string first_difference(const raster<float>& got, const raster<float>& want)
{
    for (std::ptrdiff_t r = 0; r < want.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < want.cols(); ++c) {
            const double g = got(r, c), w = want(r, c);
            if (std::isnan(g) != std::isnan(w) || (!std::isnan(w) && !(std::fabs(g - w) <= tolerance_deg))) {
                std::ostringstream os;
                os << "cell (" << r << ", " << c << "): " << g << " vs " << w;
                return os.str();
            }
        }
    }
    return "";
}

}  // namespace

TEST_CASE("solar/horizon_map: equals a brute-force maximum-angle search on random surfaces")
{
    const unsigned seed = 8128;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> azimuth(-20.0, 380.0);
    for (int trial = 0; trial < 80; ++trial) {
        const double a = trial < 16 ? 22.5 * trial : azimuth(rng);
        const auto small = reference::random_raster(rng, 13 + trial % 11, 29 - trial % 9, 0.0, 20.0, 0.05);
        const auto big = reference::with_margin(small, 2, -1000.0f);
        const auto z = reference::inner(big, 2, small.rows(), small.cols());  // strided: row_stride > cols
        INFO("seed ", seed, " trial ", trial, " azimuth ", a);
        const auto want = reference::horizon_on_lines(small.view(), 1.5, a);
        CHECK(first_difference(horizon_map(z, 1.5, a), want) == "");
        CHECK(first_difference(horizon_map(small, 1.5, a), want) == "");
    }
    std::mt19937 town_rng(seed + 1);
    for (double a : {0.0, 90.0, 131.0, 200.0, 315.0}) {
        const auto z = reference::box_town(town_rng, 70, 80, 20);
        INFO("town, azimuth ", a);
        CHECK(first_difference(horizon_map(z, 1.0, a), reference::horizon_on_lines(z.view(), 1.0, a)) == "");
    }
}

TEST_CASE("solar/horizon_map: a flat or tilted-away plane has horizon 0, also at the borders")
{
    const raster<float> flat(20, 30, 7.0f);
    raster<float> tilted(20, 30);
    for (std::ptrdiff_t r = 0; r < 20; ++r)
        for (std::ptrdiff_t c = 0; c < 30; ++c) tilted(r, c) = static_cast<float>(c);  // rises to the east
    for (double a : {0.0, 45.0, 100.0, 180.0, 270.0, 300.0}) {
        const auto h = horizon_map(flat, 1.0, a);
        bool zero = true;
        for (float v : h) zero = zero && v == 0.0f;
        CHECK(zero);
    }
    // Looking west (downhill) nothing rises; looking east the slope itself is the horizon, 45 degrees at 1 m
    // cells, except in the last column, which has nothing east of it.
    const auto west = horizon_map(tilted, 1.0, 270.0), east = horizon_map(tilted, 1.0, 90.0);
    CHECK(west(10, 15) == 0.0f);
    CHECK(east(10, 15) == doctest::Approx(45.0).epsilon(1e-6));
    CHECK(east(10, 29) == 0.0f);
}

TEST_CASE("solar/horizon_map: a mast's angle is atan(height / distance); NaN cells are NaN and hide nothing")
{
    raster<float> z(3, 40, 0.0f);
    z(1, 30) = 20.0f;
    z(1, 25) = nan_f;
    const auto h = horizon_map(z, 2.0, 90.0);  // looking east towards the mast
    for (std::ptrdiff_t c : {0, 10, 20, 29}) {
        CHECK(h(1, c) ==
              doctest::Approx(std::atan(20.0 / (2.0 * double(30 - c))) * 180.0 / std::numbers::pi).epsilon(1e-6));
    }
    CHECK(std::isnan(h(1, 25)));
    CHECK(h(1, 31) == 0.0f);
    CHECK(h(0, 10) == 0.0f);  // the mast stands in row 1 only
}

TEST_CASE("solar/horizon_map: with line families a cell is lit by a sun exactly when its horizon is below the sun")
{
    // raylines_shadow with P families and horizon_map with the same P read every cell along the same line, so for
    // any elevation e the shadow is "horizon > e". Cells within 1e-3 degrees of e are left out (float rounding).
    std::mt19937 rng(4242);
    const auto town = reference::box_town(rng, 90, 110, 30);
    const auto rough = reference::random_raster(rng, 70, 60, 0.0, 6.0, 0.03);  // NaN cells hide nothing
    for (const raster<float>* z : {&town, &rough}) {
        for (int phases : {1, 2, 4}) {
            for (double a : {0.0, 17.0, 45.0, 71.0, 100.0, 160.0, 203.0, 250.0, 300.0, 341.0}) {
                const auto h = horizon_map(*z, 1.0, a, {.line_phases = phases});
                std::size_t wrong = 0, compared = 0;
                for (double e : {3.0, 11.0, 27.0, 52.0}) {
                    const auto lit = raylines_shadow(*z, 1.0, a, e, {.line_phases = phases});
                    for (std::ptrdiff_t r = 0; r < z->rows(); ++r) {
                        for (std::ptrdiff_t c = 0; c < z->cols(); ++c) {
                            if (std::isnan(h(r, c)) || std::fabs(h(r, c) - e) < 1e-3) continue;
                            ++compared;
                            wrong += (lit(r, c) == 1) != (h(r, c) <= e);
                        }
                    }
                }
                CAPTURE(phases);
                CAPTURE(a);
                CHECK(compared > 0);
                CHECK(wrong == 0);
            }
        }
    }
}

TEST_CASE("solar/horizon_map: the same result for any thread count; progress and cancellation")
{
    std::mt19937 rng(2718);
    const auto z = reference::box_town(rng, 600, 500, 200);
    for (double a : {0.0, 60.0, 90.0, 181.0, 250.0}) {
        const auto one = horizon_map(z, 1.0, a, {.line_phases = 4});
        for (int threads : {2, 3, 0}) {
            const auto many = horizon_map(z, 1.0, a, {.line_phases = 4, .run = {.threads = threads}});
            bool same = true;
            for (std::ptrdiff_t r = 0; r < z.rows(); ++r)
                for (std::ptrdiff_t c = 0; c < z.cols(); ++c) same = same && many(r, c) == one(r, c);
            CHECK(same);
        }
    }
    reference::progress_log log;
    horizon_map(z, 1.0, 33.0, {.line_phases = 4, .run = {.threads = 2, .progress = log.callback()}});
    CHECK(log.monotone_to_one());  // with a helper thread the caller may report once
    CHECK_THROWS_AS(horizon_map(z, 1.0, 33.0, {.run = {.progress = reference::cancel_at_once()}}), cancelled);
}

TEST_CASE("solar/horizon_stack: n evenly spaced maps, each the horizon_map of its azimuth")
{
    std::mt19937 rng(77);
    const auto z = reference::box_town(rng, 40, 50, 8);
    reference::progress_log log;
    const auto stack = horizon_stack(z, 0.5, 8, {.run = {.progress = log.callback()}});
    REQUIRE(stack.horizon_deg.size() == 8);
    CHECK(log.monotone_to_one(8));
    for (std::size_t i = 0; i < 8; ++i) {
        CHECK(stack.azimuth_deg[i] == 45.0 * static_cast<double>(i));
        CHECK(first_difference(stack.horizon_deg[i], horizon_map(z, 0.5, stack.azimuth_deg[i])) == "");
    }
    CHECK_THROWS_AS(horizon_stack(z, 0.5, 0), invalid_input);
}

TEST_CASE("solar/horizon_map: bad input is refused with invalid_input")
{
    const raster<float> z(4, 4, 1.0f);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_AS(horizon_map(z, 0.0, 90.0), invalid_input);
    CHECK_THROWS_AS(horizon_map(z, nan, 90.0), invalid_input);
    CHECK_THROWS_AS(horizon_map(z, 1.0, nan), invalid_input);
    CHECK_THROWS_AS(horizon_map(z, 1.0, 90.0, {.run = {.threads = -1}}), invalid_input);
    CHECK_THROWS_AS(horizon_map(z, 1.0, 90.0, {.line_phases = 0}), invalid_input);
    CHECK_THROWS_AS(horizon_stack(z, 1.0, 4, {.line_phases = 65}), invalid_input);
    raster<float> wrong(5, 4);
    CHECK_THROWS_AS(horizon_map(z, wrong, 1.0, 90.0), invalid_input);
    CHECK(horizon_map(raster<float>(0, 3), 1.0, 10.0).rows() == 0);
}
