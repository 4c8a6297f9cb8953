// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/kernels/solar/sky_view_factor.hpp>

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

// The dissertation's count by brute force: one reference shadow pass (direct search over each cell's ray
// line) per sky source, (lit sources + zenith) / (15 * directions + 1).
raster<float> source_share_brute(const raster<float>& z, double cell_m, int directions)
{
    raster<int> count(z.rows(), z.cols(), 1);  // the zenith lights every cell
    for (int i = 0; i < directions; ++i) {
        for (int j = 0; j < 15; ++j) {
            const auto lit =
                reference::shadow_on_lines(z.view(), cell_m, 360.0 * i / directions, 15.0 + 5.0 * j, 255, 1);
            for (std::ptrdiff_t r = 0; r < z.rows(); ++r)
                for (std::ptrdiff_t c = 0; c < z.cols(); ++c) count(r, c) += lit(r, c) == 1;
        }
    }
    raster<float> out(z.rows(), z.cols());
    for (std::ptrdiff_t r = 0; r < z.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < z.cols(); ++c)
            out(r, c) =
                std::isnan(z(r, c)) ? nan_f : static_cast<float>(count(r, c) * (1.0 / (15.0 * directions + 1.0)));
    return out;
}

// The first cell where two rasters differ by more than tol (or in NaN-ness), or "".
std::string first_difference(const raster<float>& got, const raster<float>& want, double tol)
{
    for (std::ptrdiff_t r = 0; r < want.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < want.cols(); ++c) {
            const double g = got(r, c), w = want(r, c);
            if (std::isnan(g) != std::isnan(w) || (!std::isnan(w) && !(std::fabs(g - w) <= tol))) {
                std::ostringstream os;
                os << "cell (" << r << ", " << c << "): " << g << " vs " << w;
                return os.str();
            }
        }
    }
    return "";
}

}  // namespace

TEST_CASE("solar/sky_view_factor: the source share equals a brute-force count of lit sky sources")
{
    const unsigned seed = 1081;
    std::mt19937 rng(seed);
    for (int trial = 0; trial < 3; ++trial) {
        const auto z = trial == 0 ? reference::random_raster(rng, 12, 15, 0.0, 10.0, 0.05)
                                  : reference::box_town(rng, 16, 18, 3, 0.3, 2, 5);
        INFO("seed ", seed, " trial ", trial);
        for (int directions : {72, 8}) {
            CHECK(first_difference(sky_view_factor(z, 1.0, {.directions = directions}),
                                   source_share_brute(z, 1.0, directions), 0.0) == "");
        }
    }
}

TEST_CASE("solar/sky_view_factor: the cosine-weighted factor is the mean cos^2 of brute-force horizons")
{
    std::mt19937 rng(1987);
    const auto small = reference::random_raster(rng, 14, 17, 0.0, 10.0, 0.05);
    const auto big = reference::with_margin(small, 1, -5.0f);
    const auto z = reference::inner(big, 1, small.rows(), small.cols());  // strided
    raster<float> want(small.rows(), small.cols(), 0.0f);
    for (int i = 0; i < 72; ++i) {
        const auto h = reference::horizon_on_lines(small.view(), 0.5, 5.0 * i);
        for (std::ptrdiff_t r = 0; r < small.rows(); ++r) {
            for (std::ptrdiff_t c = 0; c < small.cols(); ++c) {
                const double cos_h = std::cos(h(r, c) * std::numbers::pi / 180.0);
                want(r, c) += static_cast<float>(cos_h * cos_h / 72.0);
            }
        }
    }
    // Float sums of 72 terms against double: 1e-5 covers the rounding.
    CHECK(first_difference(sky_view_factor(z, 0.5, {.method = sky_view_factor_method::cosine_weighted}), want, 1e-5) ==
          "");
}

TEST_CASE("solar/sky_view_factor: the cosine-weighted factor before a long wall equals its integral within 1e-3")
{
    // A wall of height H along the north edge, 1.8 km long, and cells at distance d from it (wall cell centres
    // to cell centre). The view factor of a horizontal surface is (1 / 2 pi) x the integral over the azimuths of
    // cos^2 h; facing the wall tan h = (H / d) cos(azimuth from the wall's normal), elsewhere h = 0, so
    // SVF = 1/2 + 1 / (2 sqrt(1 + (H / d)^2)) (the wall ends 900 m away on each side: beyond it the missing
    // horizon is under 2.6 degrees and changes the integral by less than 1e-4).
    raster<float> z(100, 1801, 0.0f);
    for (std::ptrdiff_t r = 0; r < 10; ++r)
        for (std::ptrdiff_t c = 0; c < z.cols(); ++c) z(r, c) = 40.0f;
    for (const int directions : {72, 360}) {
        CAPTURE(directions);
        const auto svf =
            sky_view_factor(z, 1.0, {.method = sky_view_factor_method::cosine_weighted, .directions = directions});
        for (const double k : {0.5, 1.0, 2.0}) {  // H / d
            CAPTURE(k);
            const auto row = static_cast<std::ptrdiff_t>(9 + 40.0 / k);
            const double integral = 0.5 + 0.5 / std::sqrt(1.0 + k * k);
            CHECK(std::abs(static_cast<double>(svf(row, 900)) - integral) < 1e-3);
        }
    }
}

TEST_CASE("solar/sky_view_factor: 1 on a flat plane, in [0, 1] everywhere, small at the bottom of a shaft")
{
    const raster<float> flat(20, 25, 3.0f);
    for (auto method : {sky_view_factor_method::source_share, sky_view_factor_method::cosine_weighted}) {
        bool ones = true;
        for (float v : sky_view_factor(flat, 1.0, {.method = method})) ones = ones && v == 1.0f;
        CHECK(ones);
    }
    std::mt19937 rng(5);
    const auto town = reference::box_town(rng, 80, 90, 25);
    for (auto method : {sky_view_factor_method::source_share, sky_view_factor_method::cosine_weighted}) {
        bool in_range = true;
        for (float v : sky_view_factor(town, 1.0, {.method = method})) in_range = in_range && v >= 0.0f && v <= 1.0f;
        CHECK(in_range);
    }
    // A 3 x 3 m shaft 60 m deep in a plateau: from its centre every azimuth meets a wall within 2.9 m (the
    // diagonals), so the horizon is above atan(60 / 2.9) = 87 degrees all round.
    raster<float> plateau(21, 21, 100.0f);
    for (std::ptrdiff_t r = 9; r <= 11; ++r)
        for (std::ptrdiff_t c = 9; c <= 11; ++c) plateau(r, c) = 40.0f;
    const auto share = sky_view_factor(plateau, 1.0);
    const auto cosine = sky_view_factor(plateau, 1.0, {.method = sky_view_factor_method::cosine_weighted});
    CHECK(share(10, 10) == doctest::Approx(1.0 / 1081.0));  // only the zenith
    CHECK(cosine(10, 10) < 0.005f);
    CHECK(share(0, 0) > 0.9f);
}

TEST_CASE("solar/sky_view_factor: NaN cells, thread count, progress, cancellation and bad input")
{
    std::mt19937 rng(8);
    auto z = reference::box_town(rng, 150, 130, 30);
    z(5, 5) = nan_f;
    const auto one = sky_view_factor(z, 1.0, {.directions = 16});
    CHECK(std::isnan(one(5, 5)));
    const auto two = sky_view_factor(z, 1.0, {.directions = 16, .run = {.threads = 2}});
    CHECK(first_difference(two, one, 0.0) == "");
    reference::progress_log log;
    sky_view_factor(z, 1.0, {.directions = 8, .run = {.progress = log.callback()}});
    CHECK(log.monotone_to_one(8));
    CHECK_THROWS_AS(sky_view_factor(z, 1.0, {.run = {.progress = reference::cancel_at_once()}}), cancelled);
    CHECK_THROWS_AS(sky_view_factor(z, 0.0), invalid_input);
    CHECK_THROWS_AS(sky_view_factor(z, 1.0, {.directions = 3}), invalid_input);
    CHECK_THROWS_AS(sky_view_factor(z, 1.0, {.run = {.threads = -2}}), invalid_input);
    raster<float> wrong(3, 3);
    CHECK_THROWS_AS(sky_view_factor(z, wrong, 1.0), invalid_input);
}

TEST_CASE("solar/sky_view_factor: the design spelling compiles")
{
    const raster<float> dem(4, 4, 1.0f);
    const raster_view<const float> dsm = dem.view();
    const raster<float> svf = sky_view_factor(dsm, 1.0, sky_view_factor_options{});
    CHECK(svf(2, 2) == 1.0f);
}
