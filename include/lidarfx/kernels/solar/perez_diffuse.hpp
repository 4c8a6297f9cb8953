// SPDX-License-Identifier: Apache-2.0
// perez_diffuse: the Perez et al. (1990) anisotropic sky, diffuse irradiance on a tilted surface split into an
// isotropic background, a circumsolar disc and a horizon band (beyond the dissertation's isotropic DHI * SVF).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>

#include "lidarfx/core/error.hpp"

namespace lidarfx {

/// Settings of perez_sky_coefficients and perez_diffuse.
struct perez_diffuse_options {
    /// Solar constant of the extraterrestrial irradiance, W/m^2 (1366.1: Gueymard 2004, as pvlib's Spencer).
    double solar_constant_w_m2 = 1366.1;
    /// true (the default): F1 capped at 1 and F2 floored at 0, so every component is >= 0 and any combination
    /// weighted by a lit state and a sky view factor in [0, 1] stays >= 0. This departs from the published model
    /// only where F1 > 1 (a few very clear, high-sun hours) or F2 < 0 (a horizon darker than the sky, mostly in
    /// the overcast bins 1-2, where F2 >= about -0.1). false: the published model (as pvlib), F1 >= 0 only and F2
    /// signed; the isotropic and horizon components can then be < 0 and a caller clamps its sum at 0.
    bool nonnegative = true;
};

/// The sky's state in the Perez model for one hour: clearness bin and brightness, and the two reduced
/// brightness coefficients.
struct perez_sky {
    double clearness = 1;   ///< epsilon = ((DHI + DNI) / DHI + k z^3) / (1 + k z^3), k = 1.041, z in radians
    double brightness = 0;  ///< delta = DHI * air mass / extraterrestrial normal irradiance (dimensionless)
    int bin = 1;            ///< clearness bin 1 (overcast, epsilon < 1.065) ... 8 (clear, epsilon >= 6.2)
    double f1 = 0;          ///< circumsolar brightening F1 = max(0, F11 + F12 delta + F13 z)
    double f2 = 0;          ///< horizon brightening F2 = F21 + F22 delta + F23 z
};

/// Diffuse sky irradiance on a surface by components, W/m^2. Each takes its own obstruction factor: the
/// circumsolar part comes from around the sun's disc, so it is beam-like (times the cell's lit state); the
/// isotropic part times the sky view factor; the horizon band times the sky view factor too (it is sky near the
/// horizon, which terrain and buildings hide first, so SVF is the nearest single-number estimate; the band is 0 on
/// horizontal cells).
struct perez_diffuse_result {
    double isotropic_w_m2 = 0;    ///< DHI (1 - F1) (1 + cos b) / 2
    double circumsolar_w_m2 = 0;  ///< DHI F1 a / c, a = max(0, cos theta), c = max(cos 85 deg, cos z)
    double horizon_w_m2 = 0;      ///< DHI F2 sin b
    perez_sky sky = {};           ///< the coefficients used

    /// Unobstructed sum, W/m^2: isotropic + circumsolar + horizon.
    double total_w_m2() const noexcept { return isotropic_w_m2 + circumsolar_w_m2 + horizon_w_m2; }
};

/// cos 85 deg, the floor of the circumsolar term's denominator: circumsolar = DHI F1 max(0, cos theta) /
/// max(perez_cos_85, sin e).
inline constexpr double perez_cos_85 = 0.08715574274765814;

namespace detail {

inline constexpr double perez_rad_per_deg = std::numbers::pi / 180.0;

/// Perez et al. (1990) Table 6, "all sites composite": per clearness bin F11, F12, F13, F21, F22, F23.
inline constexpr std::array<std::array<double, 6>, 8> perez_1990_coefficients = {{
    {-0.0083117, 0.5877285, -0.0620636, -0.0596012, 0.0721249, -0.0220216},
    {0.1299457, 0.6825954, -0.1513752, -0.0189325, 0.0659650, -0.0288748},
    {0.3296958, 0.4868735, -0.2210958, 0.0554140, -0.0639588, -0.0260542},
    {0.5682053, 0.1874525, -0.2951290, 0.1088631, -0.1519229, -0.0139754},
    {0.8730280, -0.3920403, -0.3616149, 0.2255647, -0.4620442, 0.0012448},
    {1.1326077, -1.2367284, -0.4118494, 0.2877813, -0.8230357, 0.0558651},
    {1.0601591, -1.5999137, -0.3589221, 0.2642124, -1.1272340, 0.1310694},
    {0.6777470, -0.3272588, -0.2504286, 0.1561313, -1.3765031, 0.2506212},
}};

/// Lower clearness bound of bins 2..8 (bin 1 starts at 1).
inline constexpr std::array<double, 7> perez_1990_bin_edges = {1.065, 1.230, 1.500, 1.950, 2.800, 4.500, 6.200};

inline double extraterrestrial_unchecked(int day_of_year, double solar_constant) noexcept
{
    const double g = 2.0 * std::numbers::pi * (day_of_year - 1) / 365.0;
    return solar_constant * (1.00011 + 0.034221 * std::cos(g) + 0.00128 * std::sin(g) + 0.000719 * std::cos(2.0 * g) +
                             0.000077 * std::sin(2.0 * g));
}

inline double kasten_young_unchecked(double sun_elevation_deg) noexcept
{
    const double z = 90.0 - sun_elevation_deg;
    return 1.0 / (std::cos(z * perez_rad_per_deg) + 0.50572 * std::pow(96.07995 - z, -1.6364));
}

/// perez_sky_coefficients without checks.
inline perez_sky perez_sky_unchecked(double dhi, double dni, double sun_elevation_deg, int day_of_year,
                                     const perez_diffuse_options& opt) noexcept
{
    perez_sky s;
    if (!(dhi > 0.0) || !(sun_elevation_deg > 0.0)) return s;  // no sky light or no sun: isotropic
    const double z = (90.0 - sun_elevation_deg) * perez_rad_per_deg;
    const double kz3 = 1.041 * z * z * z;
    s.clearness = ((dhi + dni) / dhi + kz3) / (1.0 + kz3);
    s.brightness = dhi * kasten_young_unchecked(sun_elevation_deg) /
                   extraterrestrial_unchecked(day_of_year, opt.solar_constant_w_m2);
    s.bin =
        1 + static_cast<int>(std::upper_bound(perez_1990_bin_edges.begin(), perez_1990_bin_edges.end(), s.clearness) -
                             perez_1990_bin_edges.begin());
    const auto& f = perez_1990_coefficients[static_cast<std::size_t>(s.bin - 1)];
    s.f1 = std::max(0.0, f[0] + f[1] * s.brightness + f[2] * z);
    s.f2 = f[3] + f[4] * s.brightness + f[5] * z;
    if (opt.nonnegative) {
        s.f1 = std::min(s.f1, 1.0);
        s.f2 = std::max(s.f2, 0.0);
    }
    return s;
}

/// perez_diffuse from the sky's coefficients, without checks: sin_e the sine of the sun elevation, cos_theta the
/// incidence cosine, cos_b and sin_b of the surface tilt.
inline perez_diffuse_result perez_diffuse_unchecked(const perez_sky& s, double dhi, double sin_e, double cos_theta,
                                                    double cos_b, double sin_b) noexcept
{
    perez_diffuse_result r;
    r.sky = s;
    r.isotropic_w_m2 = dhi * (1.0 - s.f1) * (1.0 + cos_b) / 2.0;
    r.circumsolar_w_m2 = dhi * s.f1 * std::max(0.0, cos_theta) / std::max(perez_cos_85, sin_e);
    r.horizon_w_m2 = dhi * s.f2 * sin_b;
    return r;
}

inline void require_perez_inputs(double dhi, double dni, double sun_elevation_deg, int day_of_year,
                                 const perez_diffuse_options& opt, const char* fn)
{
    require(dhi >= 0.0 && dhi <= 1.0e6, fn, "dhi_w_m2", "in [0, 1e6] W/m^2", dhi);
    require(dni >= 0.0 && dni <= 1.0e6, fn, "dni_w_m2", "in [0, 1e6] W/m^2", dni);
    require(sun_elevation_deg >= -90.0 && sun_elevation_deg <= 90.0, fn, "sun_elevation_deg", "in [-90, 90] degrees",
            sun_elevation_deg);
    require(day_of_year >= 1 && day_of_year <= 366, fn, "day_of_year", "in [1, 366]", day_of_year);
    require(opt.solar_constant_w_m2 > 0.0 && opt.solar_constant_w_m2 <= 1.0e6, fn, "solar_constant_w_m2",
            "in (0, 1e6] W/m^2", opt.solar_constant_w_m2);
}

}  // namespace detail

/// Extraterrestrial normal irradiance on day_of_year (1..366), W/m^2, by Spencer (1971):
///   E0 = S (1.00011 + 0.034221 cos g + 0.00128 sin g + 0.000719 cos 2g + 0.000077 sin 2g), g = 2 pi (doy - 1) / 365
/// with S the solar constant (W/m^2, default 1366.1). About S * 1.035 in early January, S * 0.967 in early July.
/// @throws invalid_input if day_of_year is outside [1, 366] or the solar constant is not finite and > 0.
inline double extraterrestrial_normal_w_m2(int day_of_year, double solar_constant_w_m2 = 1366.1)
{
    constexpr const char* fn = "extraterrestrial_normal_w_m2";
    detail::require(day_of_year >= 1 && day_of_year <= 366, fn, "day_of_year", "in [1, 366]", day_of_year);
    detail::require_positive(solar_constant_w_m2, fn, "solar_constant_w_m2");
    return detail::extraterrestrial_unchecked(day_of_year, solar_constant_w_m2);
}

/// Relative (not pressure-corrected) optical air mass by Kasten & Young (1989), dimensionless:
///   AM = 1 / (cos z + 0.50572 (96.07995 - z)^-1.6364), z = 90 - e the zenith angle in degrees
/// (1 with the sun at the zenith, about 38 at the horizon). @throws invalid_input if sun_elevation_deg is outside
/// [0, 90].
inline double kasten_young_air_mass(double sun_elevation_deg)
{
    detail::require(sun_elevation_deg >= 0.0 && sun_elevation_deg <= 90.0, "kasten_young_air_mass", "sun_elevation_deg",
                    "in [0, 90] degrees", sun_elevation_deg);
    return detail::kasten_young_unchecked(sun_elevation_deg);
}

/// The Perez et al. (1990) sky of one hour from its diffuse horizontal and direct normal irradiance (W/m^2, >= 0),
/// the sun elevation e (degrees) and the day of the year (1..366, for the extraterrestrial irradiance):
///   z       = 90 deg - e, in radians
///   epsilon = ((DHI + DNI) / DHI + 1.041 z^3) / (1 + 1.041 z^3)              sky clearness -> bin 1..8 at
///             1.065, 1.23, 1.5, 1.95, 2.8, 4.5, 6.2
///   delta   = DHI * AM / E0    (AM kasten_young_air_mass, E0 extraterrestrial_normal_w_m2)   sky brightness
///   F1 = max(0, F11 + F12 delta + F13 z),  F2 = F21 + F22 delta + F23 z   (Table 6 "all sites composite")
/// with F1 capped at 1 and F2 floored at 0 when opt.nonnegative (the default). DHI = 0 or the sun at or below the
/// horizon (e <= 0) gives the isotropic sky: bin 1, delta 0, F1 = F2 = 0.
/// @throws invalid_input if an irradiance is negative or not finite (> 1e6), e is outside [-90, 90], day_of_year
/// outside [1, 366] or the solar constant not finite and > 0.
inline perez_sky perez_sky_coefficients(double dhi_w_m2, double dni_w_m2, double sun_elevation_deg, int day_of_year,
                                        const perez_diffuse_options& opt = {})
{
    detail::require_perez_inputs(dhi_w_m2, dni_w_m2, sun_elevation_deg, day_of_year, opt, "perez_sky_coefficients");
    return detail::perez_sky_unchecked(dhi_w_m2, dni_w_m2, sun_elevation_deg, day_of_year, opt);
}

/// Diffuse sky irradiance on a surface tilted b degrees ([0, 180]) by the Perez et al. (1990) model, W/m^2, by
/// components (see perez_diffuse_result for which obstruction factor multiplies which):
///   isotropic   = DHI (1 - F1) (1 + cos b) / 2
///   circumsolar = DHI F1 a / c,   a = max(0, cos theta),  c = max(cos 85 deg, cos z)
///   horizon     = DHI F2 sin b
/// with F1, F2 from perez_sky_coefficients, cos_theta the cosine of the sun's incidence angle on the surface
/// (cos_incidence; in [-1, 1]) and z the sun zenith angle. A horizontal surface gets no horizon band and
/// DHI (1 - F1) + DHI F1 cos z / c, which is DHI when e >= 5 deg. Without sun or sky light: the isotropic
/// DHI (1 + cos b) / 2. Irradiances in W/m^2, angles in degrees.
/// @throws invalid_input as perez_sky_coefficients, or if cos_theta is outside [-1, 1] or tilt_deg outside
/// [0, 180].
inline perez_diffuse_result perez_diffuse(double dhi_w_m2, double dni_w_m2, double sun_elevation_deg, double cos_theta,
                                          double tilt_deg, int day_of_year, const perez_diffuse_options& opt = {})
{
    constexpr const char* fn = "perez_diffuse";
    detail::require_perez_inputs(dhi_w_m2, dni_w_m2, sun_elevation_deg, day_of_year, opt, fn);
    detail::require(cos_theta >= -1.0 && cos_theta <= 1.0, fn, "cos_theta", "in [-1, 1]", cos_theta);
    detail::require(tilt_deg >= 0.0 && tilt_deg <= 180.0, fn, "tilt_deg", "in [0, 180] degrees", tilt_deg);
    const perez_sky s = detail::perez_sky_unchecked(dhi_w_m2, dni_w_m2, sun_elevation_deg, day_of_year, opt);
    const double b = tilt_deg * detail::perez_rad_per_deg;
    return detail::perez_diffuse_unchecked(s, dhi_w_m2, std::sin(sun_elevation_deg * detail::perez_rad_per_deg),
                                           cos_theta, std::cos(b), std::sin(b));
}

}  // namespace lidarfx
