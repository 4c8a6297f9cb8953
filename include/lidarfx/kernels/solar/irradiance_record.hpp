// SPDX-License-Identifier: Apache-2.0
// irradiance_record: one interval of weather (a TMY hour, a clear-sky hour): when, and how much sun and sky.
#pragma once

#include <chrono>
#include <cmath>
#include <cstddef>
#include <span>

#include "lidarfx/core/error.hpp"

namespace lidarfx {

/// Irradiance over one interval of time, as weather files give it (TMY3: hourly means).
struct irradiance_record {
    std::chrono::sys_seconds start_utc{};  ///< start of the interval, UTC; the sun is taken at its middle
    std::chrono::seconds interval{3600};   ///< length of the interval, > 0 (3600 = hourly records)
    double dni_w_m2 = 0;                   ///< direct normal irradiance, mean over the interval, W/m^2, >= 0
    double dhi_w_m2 = 0;                   ///< diffuse horizontal irradiance, mean over the interval, W/m^2, >= 0
    double ghi_w_m2 = 0;                   ///< global horizontal irradiance, mean over the interval, W/m^2, >= 0

    /// The middle of the interval, where the sun position is taken.
    constexpr std::chrono::sys_seconds middle_utc() const noexcept { return start_utc + interval / 2; }
};

/// Month index 0 (January) .. 11 (December) of a record: the month of its middle in local standard time
/// UTC + utc_offset_h (hours, rounded to the second). No checks.
inline int record_month(const irradiance_record& rec, double utc_offset_h)
{
    namespace chr = std::chrono;
    const auto local = rec.middle_utc() + chr::seconds{static_cast<long long>(std::llround(utc_offset_h * 3600.0))};
    const chr::year_month_day ymd{chr::floor<chr::days>(local)};
    return static_cast<int>(static_cast<unsigned>(ymd.month())) - 1;
}

/// Day of the year 1..366 of a record's middle, UTC (for the extraterrestrial irradiance of the Perez sky).
inline int record_day_of_year(const irradiance_record& rec)
{
    namespace chr = std::chrono;
    const chr::sys_days day = chr::floor<chr::days>(rec.middle_utc());
    const chr::year_month_day ymd{day};
    return static_cast<int>((day - chr::sys_days{ymd.year() / chr::January / 1}).count()) + 1;
}

namespace detail {

/// Refuses records with a non-positive interval or a DNI, DHI or GHI outside [0, 1e6] W/m^2 (or NaN).
inline void require_records(std::span<const irradiance_record> records, const char* fn)
{
    for (std::size_t i = 0; i < records.size(); ++i) {
        const irradiance_record& r = records[i];
        const auto bad = [&](double v) { return !(v >= 0.0 && v <= 1.0e6); };
        if (r.interval.count() <= 0 || bad(r.dni_w_m2) || bad(r.dhi_w_m2) || bad(r.ghi_w_m2)) {
            throw invalid_input(concat(fn, ": records[", i, "] must have interval > 0 and DNI, DHI, GHI in ",
                                       "[0, 1e6] W/m^2 (got interval ", r.interval.count(), " s, DNI ", r.dni_w_m2,
                                       ", DHI ", r.dhi_w_m2, ", GHI ", r.ghi_w_m2, ")"));
        }
    }
}

}  // namespace detail

}  // namespace lidarfx
