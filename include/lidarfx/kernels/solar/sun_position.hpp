// SPDX-License-Identifier: Apache-2.0
// sun_position: azimuth, elevation and zenith of the sun for a UTC time and a place, by NREL's SPA or the
// dissertation's simple model.
#pragma once

#include <chrono>
#include <cmath>
#include <numbers>
#include <span>

#include "lidarfx/core/error.hpp"
#include "lidarfx/kernels/solar/spa_tables.hpp"

namespace lidarfx {

/// The astronomical model of sun_position.
enum class sun_model {
    spa,     ///< NREL's Solar Position Algorithm (Reda & Andreas 2004, rev. 2008): +-0.0003 deg, years -2000..6000
    simple,  ///< the dissertation's model (3.2.2): equation of time, declination 23.45 deg * sin B, hour angle
};

/// Settings of sun_position. The atmosphere (pressure, temperature) only enters the refraction correction.
struct sun_position_options {
    sun_model model = sun_model::spa;  ///< which model
    double delta_t_s = 69.0;           ///< SPA: Delta T = TT - UT in seconds, [-8000, 8000]; about 69 s in 2020-2030
    double pressure_mbar = 1013.25;    ///< annual mean local air pressure, millibar (hPa), (0, 5000]
    double temperature_c = 12.0;       ///< annual mean local air temperature, deg C, [-273, 6000]
    double elevation_m = 0.0;          ///< SPA: observer height above sea level, metres, >= -6500000 (parallax)
    bool refraction = true;            ///< add atmospheric refraction to the elevation (both models)
};

/// Where the sun is, seen from a place on the Earth.
struct sun_position_result {
    double azimuth_deg = 0;    ///< degrees clockwise from true north, [0, 360): 90 east, 180 south, 270 west
    double elevation_deg = 0;  ///< degrees above the horizon, [-90, 90] (refracted when options.refraction)
    double zenith_deg = 0;     ///< degrees from the vertical, 90 - elevation_deg, [0, 180]
};

/// An azimuth from true north turned to grid north: a_grid = a_true - meridian_convergence_deg, in [0, 360).
/// The convergence is > 0 where grid north lies east of true north (east of a transverse Mercator zone's central
/// meridian in the northern hemisphere). A convergence of 0 returns the azimuth unchanged, bit for bit.
inline double to_grid_azimuth_deg(double true_azimuth_deg, double meridian_convergence_deg) noexcept
{
    if (meridian_convergence_deg == 0.0) return true_azimuth_deg;
    double a = true_azimuth_deg - meridian_convergence_deg;
    if (a < 0.0) a += 360.0;
    if (a >= 360.0) a -= 360.0;
    return a;
}

namespace detail {

inline constexpr double spa_deg_per_rad = 180.0 / std::numbers::pi;
inline constexpr double spa_rad_per_deg = std::numbers::pi / 180.0;

/// x reduced to [0, 360).
inline double spa_limit_degrees(double x) noexcept
{
    x = std::fmod(x, 360.0);
    if (x < 0) x += 360.0;
    return x >= 360.0 ? 0.0 : x;
}

/// Days since JD 2451545.0 (2000-01-01 12:00 UTC) of a UTC time; Julian days on the UTC scale, as SPA's
/// JD (its Delta UT1 taken as 0, below a second).
template <class Duration>
double spa_days_since_j2000(std::chrono::sys_time<Duration> time_utc) noexcept
{
    namespace chr = std::chrono;
    constexpr chr::sys_seconds j2000 = chr::sys_days{chr::year{2000} / chr::January / 1} + chr::hours{12};
    // Whole days and their remainder apart, so that sub-second parts keep their precision over millennia.
    const auto since = time_utc - j2000;
    const auto whole = chr::floor<chr::days>(since);
    return static_cast<double>(whole.count()) + chr::duration<double, chr::days::period>(since - whole).count();
}

/// Atmospheric refraction (degrees) at a true elevation of e0 degrees: SPA's equation 42 (Bennett's formula
/// scaled by pressure and temperature), applied while the sun's upper limb may be above the horizon
/// (e0 >= -(0.26667 + 0.5667) deg), 0 below.
inline double spa_refraction_deg(double e0, double pressure_mbar, double temperature_c) noexcept
{
    if (e0 < -(0.26667 + 0.5667)) return 0.0;
    return (pressure_mbar / 1010.0) * (283.0 / (273.0 + temperature_c)) * 1.02 /
           (60.0 * std::tan(spa_rad_per_deg * (e0 + 10.3 / (e0 + 5.11))));
}

/// sum over k of jme^k * (sum of a cos(b + c jme) over the terms of series k) / 1e8: one of SPA's L, B, R.
inline double spa_series(std::span<const std::span<const spa_term>> series, double jme) noexcept
{
    double total = 0.0, power = 1.0;
    for (const auto terms : series) {
        double sum = 0.0;
        for (const auto& t : terms) sum += t.a * std::cos(t.b + t.c * jme);
        total += sum * power;
        power *= jme;
    }
    return total / 1.0e8;
}

/// a + b x + c x^2 + x^3 / d.
inline double spa_cubic(double x, double a, double b, double c, double d) noexcept
{
    return ((x / d + c) * x + b) * x + a;
}

/// Topocentric zenith and azimuth by SPA (Reda & Andreas 2008, section 3, steps 3.1-3.15): Earth's heliocentric
/// position from the VSOP87 terms, nutation, aberration, apparent sidereal time, parallax for the observer's
/// height, refraction. `days` as from spa_days_since_j2000; angles in degrees, longitude east positive.
inline sun_position_result sun_position_spa(double days, double latitude_deg, double longitude_deg,
                                            const sun_position_options& opt) noexcept
{
    const double jd_days = days, jde_days = days + opt.delta_t_s / 86400.0;
    const double jc = jd_days / 36525.0, jce = jde_days / 36525.0, jme = jce / 10.0;

    // 3.2 Earth's heliocentric longitude, latitude (degrees) and radius vector (AU); 3.3 geocentric.
    const double l_deg = spa_limit_degrees(spa_deg_per_rad * spa_series(spa_longitude, jme));
    const double b_deg = spa_deg_per_rad * spa_series(spa_latitude, jme);
    const double r_au = spa_series(spa_radius, jme);
    const double theta = spa_limit_degrees(l_deg + 180.0), beta = -b_deg;

    // 3.4 Nutation in longitude and obliquity from the Moon's and Sun's fundamental arguments (degrees).
    const double x[5] = {
        spa_cubic(jce, 297.85036, 445267.111480, -0.0019142, 189474.0),  // mean elongation of the Moon
        spa_cubic(jce, 357.52772, 35999.050340, -0.0001603, -300000.0),  // mean anomaly of the Sun
        spa_cubic(jce, 134.96298, 477198.867398, 0.0086972, 56250.0),    // mean anomaly of the Moon
        spa_cubic(jce, 93.27191, 483202.017538, -0.0036825, 327270.0),   // Moon's argument of latitude
        spa_cubic(jce, 125.04452, -1934.136261, 0.0020708, 450000.0),    // longitude of the Moon's node
    };
    double dpsi = 0.0, deps = 0.0;
    for (const auto& t : spa_nutation) {
        double arg = 0.0;
        for (int j = 0; j < 5; ++j) arg += x[j] * t.y[j];
        arg *= spa_rad_per_deg;
        dpsi += (t.a + t.b * jce) * std::sin(arg);
        deps += (t.c + t.d * jce) * std::cos(arg);
    }
    dpsi /= 36000000.0;
    deps /= 36000000.0;

    // 3.5 True obliquity of the ecliptic (Laskar's polynomial in U = JME / 10, arcseconds).
    const double u = jme / 10.0;
    double eps0 = 0.0;
    for (const double coeff : {2.45, 5.79, 27.87, 7.12, -39.05, -249.67, -51.38, 1999.25, -1.55, -4680.93, 84381.448})
        eps0 = eps0 * u + coeff;
    const double eps = eps0 / 3600.0 + deps;

    // 3.6-3.7 Aberration; apparent longitude. 3.8 Apparent sidereal time at Greenwich.
    const double lambda = theta + dpsi - 20.4898 / (3600.0 * r_au);
    const double nu0 =
        spa_limit_degrees(280.46061837 + 360.98564736629 * jd_days + 0.000387933 * jc * jc - jc * jc * jc / 38710000.0);
    const double nu = nu0 + dpsi * std::cos(spa_rad_per_deg * eps);

    // 3.9-3.10 Geocentric right ascension and declination.
    const double lambda_r = spa_rad_per_deg * lambda, eps_r = spa_rad_per_deg * eps, beta_r = spa_rad_per_deg * beta;
    const double alpha = spa_limit_degrees(
        spa_deg_per_rad *
        std::atan2(std::sin(lambda_r) * std::cos(eps_r) - std::tan(beta_r) * std::sin(eps_r), std::cos(lambda_r)));
    const double delta_r =
        std::asin(std::sin(beta_r) * std::cos(eps_r) + std::cos(beta_r) * std::sin(eps_r) * std::sin(lambda_r));

    // 3.11 Observer local hour angle. 3.12 Topocentric right ascension and declination (parallax).
    const double h_r = spa_rad_per_deg * spa_limit_degrees(nu + longitude_deg - alpha);
    const double phi_r = spa_rad_per_deg * latitude_deg;
    const double xi_r = spa_rad_per_deg * 8.794 / (3600.0 * r_au);
    const double u_r = std::atan(0.99664719 * std::tan(phi_r));
    const double px = std::cos(u_r) + opt.elevation_m / 6378140.0 * std::cos(phi_r);
    const double py = 0.99664719 * std::sin(u_r) + opt.elevation_m / 6378140.0 * std::sin(phi_r);
    const double denom = std::cos(delta_r) - px * std::sin(xi_r) * std::cos(h_r);
    const double dalpha_r = std::atan2(-px * std::sin(xi_r) * std::sin(h_r), denom);
    const double delta_t_r = std::atan2((std::sin(delta_r) - py * std::sin(xi_r)) * std::cos(dalpha_r), denom);
    const double ht_r = h_r - dalpha_r;  // 3.13 topocentric local hour angle

    // 3.14 Topocentric elevation, refraction, zenith. 3.15 Azimuth, from north clockwise.
    const double e0 = spa_deg_per_rad * std::asin(std::sin(phi_r) * std::sin(delta_t_r) +
                                                  std::cos(phi_r) * std::cos(delta_t_r) * std::cos(ht_r));
    const double e = e0 + (opt.refraction ? spa_refraction_deg(e0, opt.pressure_mbar, opt.temperature_c) : 0.0);
    const double gamma = spa_deg_per_rad * std::atan2(std::sin(ht_r), std::cos(ht_r) * std::sin(phi_r) -
                                                                          std::tan(delta_t_r) * std::cos(phi_r));
    return {spa_limit_degrees(gamma + 180.0), e, 90.0 - e};
}

/// The dissertation's model (3.2.2, after PVEducation): day angle B = 360/365 (d - 81) with d the day of the
/// year of the local mean solar date (1 on 1 January); equation of time EoT = 9.87 sin 2B - 7.53 cos B - 1.5 sin B
/// minutes; declination 23.45 deg sin B; local solar time LST = UTC + longitude/15 h + EoT/60 h (the time zone's
/// LSTM cancels); hour angle H = 15 deg (LST - 12). Elevation asin(sin d sin phi + cos d cos phi cos H); azimuth
/// from north by atan2, which is the printed acos(...) taken as 360 - acos(...) in the afternoon (H > 0).
inline sun_position_result sun_position_simple(double days, double latitude_deg, double longitude_deg,
                                               const sun_position_options& opt) noexcept
{
    // Local mean solar time in days since 2000-01-01 00:00 (days counts from noon).
    const double local_days = days + 0.5 + longitude_deg / 360.0;
    const double local_day = std::floor(local_days);
    // Day of the year, from the civil date of local_day (2000-01-01 is day 0 of the count).
    namespace chr = std::chrono;
    const chr::sys_days day{chr::sys_days{chr::year{2000} / chr::January / 1} +
                            chr::days{static_cast<chr::days::rep>(local_day)}};
    const double d =
        static_cast<double>((day - chr::sys_days{chr::year_month_day{day}.year() / chr::January / 1}).count()) + 1.0;
    const double b_r = spa_rad_per_deg * 360.0 / 365.0 * (d - 81.0);
    const double eot_min = 9.87 * std::sin(2.0 * b_r) - 7.53 * std::cos(b_r) - 1.5 * std::sin(b_r);
    const double decl_r = spa_rad_per_deg * 23.45 * std::sin(b_r);
    const double lst_h = (local_days - local_day) * 24.0 + eot_min / 60.0;
    const double h_r = spa_rad_per_deg * 15.0 * (lst_h - 12.0);
    const double phi_r = spa_rad_per_deg * latitude_deg;
    const double sin_e = std::sin(decl_r) * std::sin(phi_r) + std::cos(decl_r) * std::cos(phi_r) * std::cos(h_r);
    const double e0 = spa_deg_per_rad * std::asin(sin_e < -1.0 ? -1.0 : sin_e > 1.0 ? 1.0 : sin_e);
    const double east = -std::cos(decl_r) * std::sin(h_r);
    const double north = std::sin(decl_r) * std::cos(phi_r) - std::cos(decl_r) * std::sin(phi_r) * std::cos(h_r);
    const double e = e0 + (opt.refraction ? spa_refraction_deg(e0, opt.pressure_mbar, opt.temperature_c) : 0.0);
    return {spa_limit_degrees(spa_deg_per_rad * std::atan2(east, north)), e, 90.0 - e};
}

}  // namespace detail

/// Position of the sun seen from (latitude_deg, longitude_deg) at a UTC time (any std::chrono::sys_time
/// precision; UTC is taken as UT1, within 0.9 s). Model spa: NREL's Solar Position Algorithm (Reda & Andreas 2004,
/// rev. 2008), topocentric with parallax and refraction, +-0.0003 deg for years -2000..6000. Model simple: the
/// dissertation's equation of time / declination 23.45 deg sin B / hour angle model, within about 1.5 deg of SPA.
/// Latitude in degrees north [-90, 90], longitude in degrees east [-180, 180]; azimuth clockwise from true north.
/// O(1) (SPA: about 200 sines); throws invalid_input naming the argument for a place, option or year out of range.
template <class Duration>
sun_position_result sun_position(std::chrono::sys_time<Duration> time_utc, double latitude_deg, double longitude_deg,
                                 const sun_position_options& opt = {})
{
    constexpr auto fn = "sun_position";
    detail::require(latitude_deg >= -90.0 && latitude_deg <= 90.0, fn, "latitude_deg", "in [-90, 90]", latitude_deg);
    detail::require(longitude_deg >= -180.0 && longitude_deg <= 180.0, fn, "longitude_deg", "in [-180, 180]",
                    longitude_deg);
    detail::require(opt.model == sun_model::spa || opt.model == sun_model::simple, fn, "options.model",
                    "sun_model::spa or sun_model::simple", static_cast<int>(opt.model));
    detail::require(opt.delta_t_s >= -8000.0 && opt.delta_t_s <= 8000.0, fn, "options.delta_t_s",
                    "in [-8000, 8000] seconds", opt.delta_t_s);
    detail::require(opt.pressure_mbar > 0.0 && opt.pressure_mbar <= 5000.0, fn, "options.pressure_mbar",
                    "in (0, 5000] millibar", opt.pressure_mbar);
    detail::require(opt.temperature_c >= -273.0 && opt.temperature_c <= 6000.0, fn, "options.temperature_c",
                    "in [-273, 6000] deg C", opt.temperature_c);
    detail::require(opt.elevation_m >= -6500000.0 && opt.elevation_m <= 1.0e8, fn, "options.elevation_m",
                    "in [-6500000, 1e8] metres", opt.elevation_m);
    const double days = detail::spa_days_since_j2000(time_utc);
    // SPA's validity, years -2000..6000, as days from J2000 (365.25 days a year, a day's margin).
    detail::require(days >= -4000.0 * 365.25 && days <= 4000.0 * 365.25, fn, "time_utc",
                    "within the years -2000..6000 (days from 2000-01-01 12:00 UTC)", days);
    return opt.model == sun_model::spa ? detail::sun_position_spa(days, latitude_deg, longitude_deg, opt)
                                       : detail::sun_position_simple(days, latitude_deg, longitude_deg, opt);
}

}  // namespace lidarfx
