// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/kernels/solar/incidence.hpp>
#include <lidarfx/kernels/solar/perez_diffuse.hpp>

#include <cmath>
#include <numbers>

using namespace lidarfx;

namespace {

double cos_deg(double x)
{
    return std::cos(x * std::numbers::pi / 180.0);
}

}  // namespace

TEST_CASE("solar/perez_diffuse: extraterrestrial irradiance and air mass at known points")
{
    // Spencer (1971) with S = 1366.1: g = 0 on 1 January, E0 = S (1.00011 + 0.034221 + 0.000719) = 1413.8 W/m^2.
    CHECK(extraterrestrial_normal_w_m2(1) == doctest::Approx(1366.1 * 1.03505).epsilon(1e-12));
    // Aphelion in early July: about 3.3 % below S.
    CHECK(extraterrestrial_normal_w_m2(185) == doctest::Approx(1366.1 * 0.967).epsilon(2e-3));
    CHECK(extraterrestrial_normal_w_m2(1, 1000.0) == doctest::Approx(1035.05).epsilon(1e-12));
    // Kasten & Young (1989): 1.0 at the zenith (0.50572 * 96.07995^-1.6364 = 2.9e-4), 2.0 at 30 deg elevation
    // (1 / (0.5 + 0.50572 * 36.07995^-1.6364) = 1.9943), about 38 at the horizon (1 / (0.50572 * 6.07995^-1.6364)).
    CHECK(kasten_young_air_mass(90.0) == doctest::Approx(0.99971).epsilon(1e-5));
    CHECK(kasten_young_air_mass(30.0) == doctest::Approx(1.99429).epsilon(1e-5));
    CHECK(kasten_young_air_mass(0.0) == doctest::Approx(37.92).epsilon(1e-3));
}

TEST_CASE("solar/perez_diffuse: a clear hour reproduces the model worked by hand")
{
    // DHI 120, DNI 750 W/m^2, sun 40 deg high due south on day 172 (21 June); surface tilted 30 deg facing south,
    // so theta = 50 - 30 = 20 deg. By hand (each step from the formulas of Perez et al. 1990, Table 6):
    //   z = 50 deg = 0.872665 rad, 1.041 z^3 = 0.691820
    //   epsilon = (870 / 120 + 0.691820) / 1.691820 = 4.694247               -> bin 7 (4.5 <= epsilon < 6.2)
    //   E0 (Spencer, day 172) = 1321.624 W/m^2, AM (Kasten-Young, z = 50) = 1.553407
    //   delta = 120 * 1.553407 / 1321.624 = 0.141045
    //   F1 = 1.0601591 - 1.5999137 * 0.141045 - 0.3589221 * 0.872665 = 0.521280
    //   F2 = 0.2642124 - 1.1272340 * 0.141045 + 0.1310694 * 0.872665 = 0.219601
    //   isotropic   = 120 * (1 - 0.521280) * (1 + cos 30) / 2   = 53.598 W/m^2
    //   circumsolar = 120 * 0.521280 * cos 20 / cos 50          = 91.447 W/m^2
    //   horizon     = 120 * 0.219601 * sin 30                   = 13.176 W/m^2   (total 158.222)
    // The isotropic model gives 120 * (1 + cos 30) / 2 = 111.96 W/m^2: a clear sky sends 41 % more to a surface
    // that faces the sun.
    const double cos_theta = cos_incidence(180.0, 40.0, 30.0, 180.0);
    CHECK(cos_theta == doctest::Approx(cos_deg(20.0)).epsilon(1e-12));
    const perez_diffuse_result r = perez_diffuse(120.0, 750.0, 40.0, cos_theta, 30.0, 172);
    CHECK(r.sky.clearness == doctest::Approx(4.694247).epsilon(1e-6));
    CHECK(r.sky.bin == 7);
    CHECK(r.sky.brightness == doctest::Approx(0.141045).epsilon(1e-5));
    CHECK(r.sky.f1 == doctest::Approx(0.521280).epsilon(1e-5));
    CHECK(r.sky.f2 == doctest::Approx(0.219601).epsilon(1e-5));
    CHECK(r.isotropic_w_m2 == doctest::Approx(53.598).epsilon(1e-5));
    CHECK(r.circumsolar_w_m2 == doctest::Approx(91.447).epsilon(1e-5));
    CHECK(r.horizon_w_m2 == doctest::Approx(13.176).epsilon(1e-5));
    CHECK(r.total_w_m2() == doctest::Approx(158.222).epsilon(1e-5));
    // The coefficients alone are the same sky.
    const perez_sky s = perez_sky_coefficients(120.0, 750.0, 40.0, 172);
    CHECK(s.f1 == r.sky.f1);
    CHECK(s.f2 == r.sky.f2);
}

TEST_CASE("solar/perez_diffuse: an overcast hour is close to isotropic; the published model darkens its horizon")
{
    // DHI 300, DNI 30, sun 30 deg high, day 350, surface tilted 60 deg with theta 30 deg. By hand:
    //   z = 60 deg = 1.047198 rad, 1.041 z^3 = 1.195464, epsilon = (330 / 300 + 1.195464) / 2.195464 = 1.045548
    //   -> bin 1; E0 (day 350) = 1411.544 W/m^2, AM = 1.994293, delta = 0.423854
    //   F1 = -0.0083117 + 0.5877285 * 0.423854 - 0.0620636 * 1.047198 = 0.175806
    //   F2 = -0.0596012 + 0.0721249 * 0.423854 - 0.0220216 * 1.047198 = -0.052092
    //   isotropic = 300 * 0.824194 * 0.75 = 185.444, circumsolar = 300 * 0.175806 * cos 30 / cos 60 = 91.352,
    //   horizon (published) = 300 * -0.052092 * sin 60 = -13.534 W/m^2.
    const double cos_theta = cos_deg(30.0);
    const perez_diffuse_result pub = perez_diffuse(300.0, 30.0, 30.0, cos_theta, 60.0, 350, {.nonnegative = false});
    CHECK(pub.sky.bin == 1);
    CHECK(pub.sky.f1 == doctest::Approx(0.175806).epsilon(1e-5));
    CHECK(pub.sky.f2 == doctest::Approx(-0.052092).epsilon(1e-5));
    CHECK(pub.isotropic_w_m2 == doctest::Approx(185.444).epsilon(1e-5));
    CHECK(pub.circumsolar_w_m2 == doctest::Approx(91.352).epsilon(1e-5));
    CHECK(pub.horizon_w_m2 == doctest::Approx(-13.534).epsilon(1e-4));
    // The default floors F2 at 0: same isotropic and circumsolar parts, no horizon band.
    const perez_diffuse_result def = perez_diffuse(300.0, 30.0, 30.0, cos_theta, 60.0, 350);
    CHECK(def.sky.f2 == 0.0);
    CHECK(def.horizon_w_m2 == 0.0);
    CHECK(def.isotropic_w_m2 == pub.isotropic_w_m2);
    CHECK(def.circumsolar_w_m2 == pub.circumsolar_w_m2);
    // A thick overcast (DNI 0, sun high, low brightness): F1 and F2 near 0, within 3 % of the isotropic sky.
    const double iso = 150.0 * (1.0 + cos_deg(45.0)) / 2.0;
    const perez_diffuse_result thick = perez_diffuse(150.0, 0.0, 60.0, 0.7, 45.0, 100);
    CHECK(thick.sky.bin == 1);
    CHECK(thick.sky.f1 < 0.05);
    CHECK(std::abs(thick.sky.f2) < 0.05);
    CHECK(thick.total_w_m2() == doctest::Approx(iso).epsilon(0.03));
}

TEST_CASE("solar/perez_diffuse: a horizontal surface has no horizon band and gets DHI (1 - F1) + DHI F1 cos z / c")
{
    for (double e : {2.0, 5.0, 20.0, 45.0, 80.0}) {
        for (double dni : {0.0, 100.0, 400.0, 900.0}) {
            INFO("e ", e, " DNI ", dni);
            const double dhi = 110.0;
            const double cos_z = std::sin(e * std::numbers::pi / 180.0);
            const perez_diffuse_result r = perez_diffuse(dhi, dni, e, cos_incidence(123.0, e, 0.0, 0.0), 0.0, 200);
            CHECK(r.horizon_w_m2 == 0.0);
            const double c = std::max(cos_deg(85.0), cos_z);
            CHECK(r.isotropic_w_m2 == doctest::Approx(dhi * (1.0 - r.sky.f1)).epsilon(1e-12));
            CHECK(r.circumsolar_w_m2 == doctest::Approx(dhi * r.sky.f1 * cos_z / c).epsilon(1e-12));
            // Above 5 deg the circumsolar share is carried whole: the sum is DHI, as the isotropic sky's.
            if (e >= 5.0) CHECK(r.total_w_m2() == doctest::Approx(dhi).epsilon(1e-12));
            if (e < 5.0 && r.sky.f1 > 0.0) CHECK(r.total_w_m2() < dhi);
        }
    }
}

TEST_CASE("solar/perez_diffuse: under a clear sky with the sun south a south wall gets more diffuse than a north one")
{
    for (double e : {15.0, 35.0, 60.0}) {
        INFO("e ", e);
        const double south_cos = cos_incidence(180.0, e, 90.0, 180.0), north_cos = cos_incidence(180.0, e, 90.0, 0.0);
        const perez_diffuse_result south = perez_diffuse(90.0, 850.0, e, south_cos, 90.0, 172);
        const perez_diffuse_result north = perez_diffuse(90.0, 850.0, e, north_cos, 90.0, 172);
        CHECK(south.sky.bin >= 6);
        CHECK(south.circumsolar_w_m2 > 0.0);
        CHECK(north.circumsolar_w_m2 == 0.0);
        CHECK(south.total_w_m2() > north.total_w_m2() + 10.0);
        // Isotropic and horizon parts do not depend on the wall's azimuth.
        CHECK(south.isotropic_w_m2 == north.isotropic_w_m2);
        CHECK(south.horizon_w_m2 == north.horizon_w_m2);
    }
}

TEST_CASE("solar/perez_diffuse: every component is finite and >= 0 for DHI >= 0 (default options)")
{
    int cases = 0;
    for (double dhi : {0.0, 1.0, 50.0, 200.0, 500.0}) {
        for (double dni : {0.0, 10.0, 300.0, 1000.0}) {
            for (double e : {-10.0, 0.0, 0.5, 4.0, 10.0, 30.0, 60.0, 89.9, 90.0}) {
                for (double tilt : {0.0, 30.0, 90.0, 135.0, 180.0}) {
                    for (double cos_theta : {-1.0, -0.2, 0.0, 0.5, 1.0}) {
                        for (int doy : {1, 100, 185, 366}) {
                            const perez_diffuse_result r = perez_diffuse(dhi, dni, e, cos_theta, tilt, doy);
                            const bool ok = std::isfinite(r.total_w_m2()) && r.isotropic_w_m2 >= 0.0 &&
                                            r.circumsolar_w_m2 >= 0.0 && r.horizon_w_m2 >= 0.0 && r.sky.f1 >= 0.0 &&
                                            r.sky.f1 <= 1.0 && r.sky.bin >= 1 && r.sky.bin <= 8;
                            if (!ok) {
                                FAIL_CHECK("DHI ", dhi, " DNI ", dni, " e ", e, " tilt ", tilt, " cos ", cos_theta,
                                           " doy ", doy, ": ", r.isotropic_w_m2, " ", r.circumsolar_w_m2, " ",
                                           r.horizon_w_m2);
                            }
                            ++cases;
                        }
                    }
                }
            }
        }
    }
    CHECK(cases == 5 * 4 * 9 * 5 * 5 * 4);
    // No sun or no sky light: the isotropic sky.
    const perez_diffuse_result night = perez_diffuse(40.0, 0.0, -3.0, -0.5, 90.0, 10);
    CHECK(night.sky.f1 == 0.0);
    CHECK(night.total_w_m2() == doctest::Approx(20.0).epsilon(1e-12));
    CHECK(perez_diffuse(0.0, 800.0, 50.0, 0.9, 20.0, 10).total_w_m2() == 0.0);
}

TEST_CASE("solar/perez_diffuse: invalid inputs throw and name the parameter")
{
    CHECK_THROWS_WITH_AS(perez_diffuse(-1.0, 0.0, 30.0, 0.5, 10.0, 1), doctest::Contains("dhi_w_m2"), invalid_input);
    CHECK_THROWS_WITH_AS(perez_diffuse(1.0, NAN, 30.0, 0.5, 10.0, 1), doctest::Contains("dni_w_m2"), invalid_input);
    CHECK_THROWS_WITH_AS(perez_diffuse(1.0, 0.0, 91.0, 0.5, 10.0, 1), doctest::Contains("sun_elevation_deg"),
                         invalid_input);
    CHECK_THROWS_WITH_AS(perez_diffuse(1.0, 0.0, 30.0, 1.5, 10.0, 1), doctest::Contains("cos_theta"), invalid_input);
    CHECK_THROWS_WITH_AS(perez_diffuse(1.0, 0.0, 30.0, 0.5, 181.0, 1), doctest::Contains("tilt_deg"), invalid_input);
    CHECK_THROWS_WITH_AS(perez_diffuse(1.0, 0.0, 30.0, 0.5, 10.0, 0), doctest::Contains("day_of_year"), invalid_input);
    CHECK_THROWS_WITH_AS(perez_sky_coefficients(1.0, 0.0, 30.0, 367), doctest::Contains("day_of_year"), invalid_input);
    CHECK_THROWS_WITH_AS(perez_sky_coefficients(1.0, 0.0, 30.0, 1, {.solar_constant_w_m2 = 0.0}),
                         doctest::Contains("solar_constant_w_m2"), invalid_input);
    CHECK_THROWS_WITH_AS(kasten_young_air_mass(-1.0), doctest::Contains("sun_elevation_deg"), invalid_input);
    CHECK_THROWS_WITH_AS(extraterrestrial_normal_w_m2(0), doctest::Contains("day_of_year"), invalid_input);
}
