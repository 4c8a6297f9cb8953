// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/kernels/solar/incidence.hpp>

#include <cmath>
#include <numbers>

using namespace lidarfx;

namespace {

double sin_deg(double x)
{
    return std::sin(x * std::numbers::pi / 180.0);
}

}  // namespace

TEST_CASE("solar/incidence: a horizontal surface gets DNI * sin(elevation) whatever the azimuths")
{
    for (double e : {1.0, 10.0, 33.3, 60.0, 89.0}) {
        for (double a_sun : {0.0, 95.0, 181.0, 270.0}) {
            for (double a_surf : {0.0, 45.0, 180.0, 300.0}) {
                INFO("e ", e, " A_sun ", a_sun, " A_surf ", a_surf);
                const double c = cos_incidence(a_sun, e, 0.0, a_surf);
                CHECK(c == doctest::Approx(sin_deg(e)).epsilon(1e-12));
                CHECK(beam_irradiance_w_m2(800.0, c) == doctest::Approx(800.0 * sin_deg(e)).epsilon(1e-12));
            }
        }
    }
}

TEST_CASE("solar/incidence: cos theta = sin e cos b + cos e sin b cos(A_sun - A_surf)")
{
    const double e = 35.0, b = 30.0, a_sun = 150.0, a_surf = 200.0;
    const double want =
        sin_deg(e) * std::cos(b * std::numbers::pi / 180.0) +
        std::cos(e * std::numbers::pi / 180.0) * sin_deg(b) * std::cos((a_sun - a_surf) * std::numbers::pi / 180.0);
    CHECK(cos_incidence(a_sun, e, b, a_surf) == doctest::Approx(want).epsilon(1e-12));
    // A surface facing the sun square on: theta = 0.
    CHECK(cos_incidence(a_sun, e, 90.0 - e, a_sun) == doctest::Approx(1.0).epsilon(1e-12));
    // A vertical wall facing the sun's azimuth gets cos e; one facing away gets nothing.
    CHECK(cos_incidence(180.0, 40.0, 90.0, 180.0) == doctest::Approx(std::cos(40.0 * std::numbers::pi / 180.0)));
    CHECK(cos_incidence(180.0, 40.0, 90.0, 0.0) < 0.0);
    CHECK(beam_irradiance_w_m2(900.0, cos_incidence(180.0, 40.0, 90.0, 0.0)) == 0.0);
}

TEST_CASE("solar/incidence: a shadowed cell gets no beam; the sun and surface vectors are unit vectors")
{
    CHECK(beam_irradiance_w_m2(900.0, 0.5, false) == 0.0);
    CHECK(beam_irradiance_w_m2(900.0, 0.5, true) == doctest::Approx(450.0));
    const enu_vector s = sun_vector(123.0, 17.0), n = surface_normal(75.0, 250.0);
    CHECK(s.east * s.east + s.north * s.north + s.up * s.up == doctest::Approx(1.0));
    CHECK(n.east * n.east + n.north * n.north + n.up * n.up == doctest::Approx(1.0));
    // East of north: a sun at azimuth 90 lies due east.
    CHECK(sun_vector(90.0, 0.0).east == doctest::Approx(1.0));
    CHECK(surface_normal(90.0, 180.0).north == doctest::Approx(-1.0));
}

TEST_CASE("solar/incidence: bad angles and irradiances are refused with the argument's name")
{
    CHECK_THROWS_WITH_AS(cos_incidence(0.0, 91.0, 0.0, 0.0), doctest::Contains("sun_elevation_deg"), invalid_input);
    CHECK_THROWS_WITH_AS(cos_incidence(0.0, 30.0, -1.0, 0.0), doctest::Contains("tilt_deg"), invalid_input);
    CHECK_THROWS_WITH_AS(cos_incidence(NAN, 30.0, 0.0, 0.0), doctest::Contains("sun_azimuth_deg"), invalid_input);
    CHECK_THROWS_WITH_AS(beam_irradiance_w_m2(-1.0, 0.5), doctest::Contains("dni_w_m2"), invalid_input);
    CHECK_THROWS_WITH_AS(beam_irradiance_w_m2(1.0, 1.5), doctest::Contains("cos_theta"), invalid_input);
}
