// SPDX-License-Identifier: Apache-2.0
// incidence: the angle between the sun and a surface's normal, and the beam irradiance that reaches the surface
// (dissertation 3.2.5, with the angle conventions of docs/solar-irradiance.md).
#pragma once

#include <cmath>
#include <numbers>

#include "lidarfx/core/error.hpp"

namespace lidarfx {

/// A unit vector in local east / north / up coordinates.
struct enu_vector {
    double east = 0;
    double north = 0;
    double up = 1;
};

namespace detail {

inline constexpr double incidence_rad_per_deg = std::numbers::pi / 180.0;

inline void require_incidence_angles(double azimuth_deg, double angle_deg, double lo, double hi, const char* fn,
                                     const char* azimuth_name, const char* angle_name)
{
    require(std::isfinite(azimuth_deg), fn, azimuth_name, "finite", azimuth_deg);
    require(angle_deg >= lo && angle_deg <= hi, fn, angle_name,
            lo == 0.0 ? "in [0, 180] degrees" : "in [-90, 90] degrees", angle_deg);
}

/// sun_vector without checks.
inline enu_vector sun_vector_unchecked(double azimuth_deg, double elevation_deg) noexcept
{
    const double a = azimuth_deg * incidence_rad_per_deg, e = elevation_deg * incidence_rad_per_deg;
    return {std::cos(e) * std::sin(a), std::cos(e) * std::cos(a), std::sin(e)};
}

/// surface_normal without checks.
inline enu_vector surface_normal_unchecked(double tilt_deg, double azimuth_deg) noexcept
{
    const double b = tilt_deg * incidence_rad_per_deg, a = azimuth_deg * incidence_rad_per_deg;
    return {std::sin(b) * std::sin(a), std::sin(b) * std::cos(a), std::cos(b)};
}

}  // namespace detail

/// Dot product of two east / north / up vectors: u.east v.east + u.north v.north + u.up v.up (for unit vectors
/// the cosine of the angle between them; enu_dot(sun_vector, surface_normal) is cos_incidence). No checks.
inline double enu_dot(const enu_vector& u, const enu_vector& v) noexcept
{
    return u.east * v.east + u.north * v.north + u.up * v.up;
}

/// Unit vector towards the sun: (cos e sin A, cos e cos A, sin e) in (east, north, up), with A the sun azimuth in
/// degrees clockwise from north and e its elevation above the horizon in degrees ([-90, 90]).
/// @throws invalid_input if the azimuth is not finite or the elevation is outside [-90, 90].
inline enu_vector sun_vector(double sun_azimuth_deg, double sun_elevation_deg)
{
    detail::require_incidence_angles(sun_azimuth_deg, sun_elevation_deg, -90.0, 90.0, "sun_vector", "sun_azimuth_deg",
                                     "sun_elevation_deg");
    return detail::sun_vector_unchecked(sun_azimuth_deg, sun_elevation_deg);
}

/// Unit normal of a plane surface: (sin b sin A, sin b cos A, cos b) in (east, north, up), with b the tilt from
/// horizontal in degrees ([0, 180]; 0 faces up, 90 is a vertical wall) and A the azimuth the surface faces,
/// degrees clockwise from north (for terrain: the down-slope aspect of slope_aspect; 180 faces south).
/// @throws invalid_input if the azimuth is not finite or the tilt is outside [0, 180].
inline enu_vector surface_normal(double tilt_deg, double surface_azimuth_deg)
{
    detail::require_incidence_angles(surface_azimuth_deg, tilt_deg, 0.0, 180.0, "surface_normal", "surface_azimuth_deg",
                                     "tilt_deg");
    return detail::surface_normal_unchecked(tilt_deg, surface_azimuth_deg);
}

/// Cosine of the incidence angle theta between the sun and a surface's normal:
///   cos theta = sin e cos b + cos e sin b cos(A_sun - A_surf)
/// (e sun elevation, b surface tilt, azimuths clockwise from north; the dot product of sun_vector and
/// surface_normal). In [-1, 1]; negative when the sun is behind the surface. A horizontal surface (b = 0) gets
/// sin e. All angles in degrees. @throws invalid_input as sun_vector and surface_normal.
inline double cos_incidence(double sun_azimuth_deg, double sun_elevation_deg, double tilt_deg,
                            double surface_azimuth_deg)
{
    return enu_dot(sun_vector(sun_azimuth_deg, sun_elevation_deg), surface_normal(tilt_deg, surface_azimuth_deg));
}

/// Beam (direct) irradiance on a surface, W/m^2: DNI * max(0, cos theta) * lit, with dni_w_m2 the direct normal
/// irradiance (W/m^2, >= 0), cos_theta from cos_incidence and lit 1 when the cell sees the sun (raylines_shadow),
/// 0 in shadow. A sun behind the surface (cos theta < 0) gives 0. @throws invalid_input if dni_w_m2 is negative
/// or not finite, or cos_theta is outside [-1, 1].
inline double beam_irradiance_w_m2(double dni_w_m2, double cos_theta, bool lit = true)
{
    constexpr const char* fn = "beam_irradiance_w_m2";
    detail::require(dni_w_m2 >= 0.0 && dni_w_m2 <= 1.0e300, fn, "dni_w_m2", "finite and >= 0", dni_w_m2);
    detail::require(cos_theta >= -1.0 && cos_theta <= 1.0, fn, "cos_theta", "in [-1, 1]", cos_theta);
    return lit && cos_theta > 0.0 ? dni_w_m2 * cos_theta : 0.0;
}

}  // namespace lidarfx
