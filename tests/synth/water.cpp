// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/synth/water.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

using namespace lidarfx::synth;

TEST_CASE("synth/lake_outline: radius matches the harmonic series and stays within its bounds")
{
    rng r(31);
    for (int trial = 0; trial < 20; ++trial) {
        const double irregularity = r.uniform(0.0, 0.6);
        const auto lake =
            lake_outline::random(r, r.uniform(-50, 50), r.uniform(-50, 50), r.uniform(20, 200), irregularity);
        double lo = 1e300, hi = 0, worst = 0;
        for (int k = 0; k < 3600; ++k) {
            const double theta = k * 0.0017453292519943296;
            double series = 1;
            for (int h = 0; h < 6; ++h)
                series += lake.a[h] * std::cos((h + 2) * theta) + lake.b[h] * std::sin((h + 2) * theta);
            const double radius = lake.radius_toward(std::cos(theta), std::sin(theta));
            worst = std::max(worst, std::abs(radius - lake.mean_radius_m * series));
            lo = std::min(lo, radius);
            hi = std::max(hi, radius);
        }
        CHECK(worst < 1e-9 * lake.mean_radius_m);
        CHECK(lo >= lake.mean_radius_m * (1 - irregularity) - 1e-9);
        CHECK(hi <= lake.mean_radius_m * (1 + irregularity) + 1e-9);
        CHECK(hi <= lake.max_radius() + 1e-9);
        // Shore distance: r - R(theta) along any ray, negative inside.
        const double theta = r.uniform(0, 2 * std::numbers::pi), c = std::cos(theta), s = std::sin(theta);
        const double radius = lake.radius_toward(c, s);
        CHECK(lake.shore_distance(lake.x + (radius - 3) * c, lake.y + (radius - 3) * s) == doctest::Approx(-3));
        CHECK(lake.shore_distance(lake.x + (radius + 5) * c, lake.y + (radius + 5) * s) == doctest::Approx(5));
        CHECK(lake.shore_distance(lake.x, lake.y) < 0);
    }
}

TEST_CASE("synth/river_channel: centre line, slope, width range, level and offsets")
{
    river_channel ch;
    ch.meander_phase = {0.4, 1.9};
    ch.width_phase = {2.2, 0.3};
    double wmin = 1e9, wmax = 0, worst_slope = 0;
    for (double x = 0; x <= 640; x += 0.5) {
        const double w = ch.width(x);
        wmin = std::min(wmin, w);
        wmax = std::max(wmax, w);
        const double numeric = (ch.centre_y(x + 1e-5) - ch.centre_y(x - 1e-5)) / 2e-5;
        worst_slope = std::max(worst_slope, std::abs(numeric - ch.centre_slope(x)));
    }
    CHECK(wmin >= 15.0);
    CHECK(wmax <= 40.0);
    CHECK(wmax - wmin > 10.0);
    CHECK(worst_slope < 1e-6);
    CHECK(ch.level(0) == ch.level_west_z);
    CHECK(ch.level(640) == doctest::Approx(ch.level_west_z - 1.5));
    // The offset is the vertical distance to the centre line scaled to the perpendicular (first order).
    const double x = 123, y = ch.centre_y(x);
    CHECK(ch.offset(x, y) == doctest::Approx(0).epsilon(1e-12));
    const double s = ch.centre_slope(x);
    CHECK(ch.offset(x, y + 10) == doctest::Approx(10 / std::sqrt(1 + s * s)));
    CHECK(ch.offset(x, y - 10) < 0);
}

TEST_CASE("synth/island_truth: dome from the rim to the top, nothing outside")
{
    const island_truth isl{10, 20, 8, 2.5};
    CHECK(isl.area_m2() == doctest::Approx(std::numbers::pi * 64));
    CHECK(isl.height_above_water(10, 20) == doctest::Approx(island_truth::shore_rise_m + 2.5));
    CHECK(isl.height_above_water(18, 20) == doctest::Approx(island_truth::shore_rise_m));
    CHECK(isl.height_above_water(18.01, 20) < 0);
    CHECK(isl.height_above_water(14, 20) > isl.height_above_water(16, 20));
}

TEST_CASE("synth/water_returns: dropout and glint probabilities, bimodal intensities")
{
    const water_returns w;
    CHECK(w.pulse_drop_probability(0, 15) == doctest::Approx(w.pulse_drop_nadir));
    CHECK(w.pulse_drop_probability(-15, 15) == doctest::Approx(w.pulse_drop_edge));
    CHECK(w.pulse_drop_probability(7.5, 15) ==
          doctest::Approx(0.5 * (w.pulse_drop_nadir + w.pulse_drop_edge)).epsilon(0.3));
    CHECK(w.specular_probability(0) == doctest::Approx(w.specular_floor + w.specular_peak));
    CHECK(w.specular_probability(10) == doctest::Approx(w.specular_floor).epsilon(0.01));
    rng r(32);
    for (const double angle : {0.0, 1.5, 10.0}) {
        constexpr int n = 100000;
        int glints = 0, low = 0, low_under_8 = 0;
        for (int k = 0; k < n; ++k) {
            const double i = w.intensity(angle, r);
            if (i >= w.glint_min && i <= w.glint_max) ++glints;
            if (i >= w.low_min && i <= w.low_max) ++low;
            if (i < 8) ++low_under_8;
        }
        CHECK(glints + low == n);  // nothing in between: bimodal
        const double p = w.specular_probability(angle);
        CHECK(std::abs(glints - p * n) < 5 * std::sqrt(p * (1 - p) * n));  // 5 standard deviations
        // Skewed towards low_min: P(i < 8) = sqrt((8 - 2) / 18) = 0.577 of the low returns.
        CHECK(static_cast<double>(low_under_8) / low == doctest::Approx(std::sqrt(6.0 / 18.0)).epsilon(0.02));
    }
}
