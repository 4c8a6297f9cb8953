// SPDX-License-Identifier: Apache-2.0
// clear_sky_records: hourly irradiance records of a cloudless year for a place, for callers with no weather
// file (Haurwitz's global irradiance, split into beam and diffuse by Erbs' correlation).
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/kernels/solar/irradiance_record.hpp"
#include "lidarfx/kernels/solar/sun_position.hpp"

namespace lidarfx {

/// Settings of clear_sky_records.
struct clear_sky_options {
    std::chrono::seconds interval{3600};  ///< record length, > 0 and dividing a day (3600 = hourly)
    sun_position_options sun = {};        ///< sun model for the records (use the same in irradiance_maps)
};

namespace detail {

/// Erbs, Klein & Duffie (1982): diffuse fraction of global horizontal irradiance from the clearness index kt.
inline double erbs_diffuse_fraction(double kt) noexcept
{
    if (kt <= 0.22) return 1.0 - 0.09 * kt;
    if (kt <= 0.80) return 0.9511 + kt * (-0.1604 + kt * (4.388 + kt * (-16.638 + kt * 12.336)));
    return 0.165;
}

}  // namespace detail

/// Clear-sky irradiance for a sun at elevation_deg on day_of_year (1..366), W/m^2, DNI * sin e + DHI = GHI
/// exactly. GHI by Haurwitz (1945; the simplest model in Reno, Hansen & Stein 2012):
///   GHI = 1098 sin e exp(-0.057 / sin e) for e > 0, else 0.
/// Split by Erbs et al. (1982): clearness index kt = GHI / (E0 sin e), E0 = 1367 (1 + 0.033 cos(2 pi doy / 365))
/// W/m^2 the extraterrestrial normal irradiance; DHI = kd(kt) GHI; DNI = (GHI - DHI) / sin e.
/// @throws invalid_input if elevation_deg is outside [-90, 90] or day_of_year outside [1, 366].
inline irradiance_record clear_sky_irradiance(double elevation_deg, int day_of_year)
{
    constexpr const char* fn = "clear_sky_irradiance";
    detail::require(elevation_deg >= -90.0 && elevation_deg <= 90.0, fn, "elevation_deg", "in [-90, 90]",
                    elevation_deg);
    detail::require(day_of_year >= 1 && day_of_year <= 366, fn, "day_of_year", "in [1, 366]", day_of_year);
    irradiance_record out;
    const double sin_e = std::sin(elevation_deg * (std::numbers::pi / 180.0));
    if (sin_e <= 0.0) return out;
    const double ghi = 1098.0 * sin_e * std::exp(-0.057 / sin_e);
    const double e0 = 1367.0 * (1.0 + 0.033 * std::cos(2.0 * std::numbers::pi * day_of_year / 365.0));
    const double kt = std::clamp(ghi / (e0 * sin_e), 0.0, 1.0);
    const double dhi = detail::erbs_diffuse_fraction(kt) * ghi;
    out.ghi_w_m2 = ghi;
    out.dhi_w_m2 = dhi;
    out.dni_w_m2 = (ghi - dhi) / sin_e;
    return out;
}

/// Clear-sky records covering the calendar year `year` (UTC) at (latitude_deg, longitude_deg): one record per
/// `opt.interval` from 1 January 00:00 UTC, each from clear_sky_irradiance with the sun at the middle of the
/// interval (sun_position with opt.sun); night records hold zeros. 8760 (8784 in a leap year) hourly records.
/// @throws invalid_input for a place or year sun_position refuses, or an interval that does not divide a day.
inline std::vector<irradiance_record> clear_sky_records(int year, double latitude_deg, double longitude_deg,
                                                        const clear_sky_options& opt = {})
{
    namespace chr = std::chrono;
    constexpr const char* fn = "clear_sky_records";
    detail::require(opt.interval.count() > 0 && 86400 % opt.interval.count() == 0, fn, "interval",
                    "> 0 seconds and divide a day", opt.interval.count());
    detail::require(year >= -2000 && year <= 6000, fn, "year", "in [-2000, 6000]", year);
    const chr::sys_days first{chr::year{year} / chr::January / 1}, last{chr::year{year + 1} / chr::January / 1};
    std::vector<irradiance_record> out;
    out.reserve(static_cast<std::size_t>((last - first).count() * (86400 / opt.interval.count())));
    for (chr::sys_seconds t = first; t < chr::sys_seconds{last}; t += opt.interval) {
        const auto middle = t + opt.interval / 2;
        const sun_position_result sun = sun_position(middle, latitude_deg, longitude_deg, opt.sun);
        const int doy = static_cast<int>((chr::floor<chr::days>(middle) - first).count()) + 1;
        irradiance_record rec = clear_sky_irradiance(sun.elevation_deg, doy);
        rec.start_utc = t;
        rec.interval = opt.interval;
        out.push_back(rec);
    }
    return out;
}

}  // namespace lidarfx
