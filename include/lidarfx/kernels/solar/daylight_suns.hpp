// SPDX-License-Identifier: Apache-2.0
// daylight_suns: weather records and a site turned into the daylight suns of a period -- where the sun stands on
// the grid, how much beam and sky it brings, and which month it belongs to -- the one input of every hourly
// solar accumulation (irradiance_maps, roof_yield, surface_energy).
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/kernels/solar/incidence.hpp"
#include "lidarfx/kernels/solar/irradiance_record.hpp"
#include "lidarfx/kernels/solar/sun_position.hpp"

namespace lidarfx {

/// Where a solar computation stands: the place the sun is seen from, the local time its months and quarters are
/// counted in, and how the grid is turned against true north. Fields in this order (designated initializers).
struct solar_site {
    double latitude_deg = 0;   ///< degrees north, [-90, 90]
    double longitude_deg = 0;  ///< degrees east, [-180, 180]
    /// Months (and quarters) are those of local standard time UTC + this many hours (TMY3's zone), in [-14, 14];
    /// 0 = UTC months. Sun positions always use the records' UTC times.
    double utc_offset_h = 0.0;
    /// Meridian convergence at the grid, degrees in [-90, 90]: the angle from true north to the grid's north (up,
    /// row 0), positive when grid north lies east (clockwise) of true north, as east of the central meridian of a
    /// transverse Mercator zone in the northern hemisphere. Sun azimuths are turned to grid azimuths
    /// a_grid = a_true - meridian_convergence_deg (to_grid_azimuth_deg), so surface azimuths are taken clockwise
    /// from grid north too. 0 (the default): grid north is true north.
    double meridian_convergence_deg = 0.0;
    /// Sun model, including the site's height above sea level (sun.elevation_m) and its mean air pressure and
    /// temperature; default NREL SPA with refraction at sea level.
    sun_position_options sun = {};
};

/// One record with the sun above the horizon at its middle, seen on the grid.
struct daylight_sun {
    std::size_t record = 0;    ///< index of the record in the records given
    int month = 0;             ///< 0 (January) .. 11: record_month in UTC + site.utc_offset_h
    int day_of_year = 1;       ///< 1..366 of the record's middle, UTC (record_day_of_year; the Perez sky's)
    double azimuth_deg = 0;    ///< sun azimuth clockwise from grid north, [0, 360) (meridian convergence applied)
    double elevation_deg = 0;  ///< sun elevation above the horizon, (0, 90] degrees (refracted per site.sun)
    enu_vector sun = {};      ///< unit vector towards the sun in grid east / north / up: sun_vector(azimuth, elevation)
    double kwh_per_w_m2 = 0;  ///< interval in hours / 1000: a mean irradiance in W/m^2 times this is kWh/m^2
    double dni_w_m2 = 0;      ///< the record's direct normal irradiance, W/m^2
    double dhi_w_m2 = 0;      ///< the record's diffuse horizontal irradiance, W/m^2
    double ghi_w_m2 = 0;      ///< the record's global horizontal irradiance, W/m^2
};

/// The daylight suns of a period: for every record, in the records' order, whose sun (sun_position at the middle
/// of its interval, site.sun's model, site's latitude and longitude) stands above the horizon (elevation > 0), one
/// daylight_sun with the azimuth turned from true to grid north by site.meridian_convergence_deg, the sun vector
/// in grid coordinates, the month of the record's middle in UTC + site.utc_offset_h, and the record's irradiances.
/// Records with the sun at or below the horizon give none. Records may come in any order. Cost: one sun_position
/// per record (about 2 us with SPA). Every sun is computed before a caller starts any long work, so a bad place or
/// time fails fast.
/// @throws invalid_input if a record has a non-positive interval or a DNI, DHI or GHI outside [0, 1e6] W/m^2 (or
/// NaN), site.utc_offset_h is outside [-14, 14], site.meridian_convergence_deg is outside [-90, 90], or
/// sun_position refuses the place, the sun options or a time.
inline std::vector<daylight_sun> daylight_suns(std::span<const irradiance_record> records, const solar_site& site);

// ---- implementation ----

inline std::vector<daylight_sun> daylight_suns(std::span<const irradiance_record> records, const solar_site& site)
{
    constexpr const char* fn = "daylight_suns";
    detail::require(site.utc_offset_h >= -14.0 && site.utc_offset_h <= 14.0, fn, "site.utc_offset_h",
                    "in [-14, 14] hours", site.utc_offset_h);
    detail::require(site.meridian_convergence_deg >= -90.0 && site.meridian_convergence_deg <= 90.0, fn,
                    "site.meridian_convergence_deg", "in [-90, 90] degrees", site.meridian_convergence_deg);
    detail::require_records(records, fn);
    std::vector<daylight_sun> suns;
    for (std::size_t i = 0; i < records.size(); ++i) {
        const irradiance_record& r = records[i];
        const sun_position_result s = sun_position(r.middle_utc(), site.latitude_deg, site.longitude_deg, site.sun);
        if (!(s.elevation_deg > 0.0)) continue;
        daylight_sun d;
        d.record = i;
        d.month = record_month(r, site.utc_offset_h);
        d.day_of_year = record_day_of_year(r);
        d.azimuth_deg = to_grid_azimuth_deg(s.azimuth_deg, site.meridian_convergence_deg);
        d.elevation_deg = s.elevation_deg;
        d.sun = detail::sun_vector_unchecked(d.azimuth_deg, d.elevation_deg);
        d.kwh_per_w_m2 = static_cast<double>(r.interval.count()) / 3600.0 / 1000.0;
        d.dni_w_m2 = r.dni_w_m2;
        d.dhi_w_m2 = r.dhi_w_m2;
        d.ghi_w_m2 = r.ghi_w_m2;
        suns.push_back(d);
    }
    return suns;
}

}  // namespace lidarfx
