// SPDX-License-Identifier: Apache-2.0
// irradiance_record: one interval of weather (a TMY hour, a clear-sky hour): when, and how much sun and sky.
#pragma once

#include <chrono>

namespace lidarfx {

/// Irradiance over one interval of time, as weather files give it (TMY3: hourly means).
struct irradiance_record {
    std::chrono::sys_seconds start_utc{};     ///< start of the interval, UTC; the sun is taken at its middle
    std::chrono::seconds interval{3600};      ///< length of the interval, > 0 (3600 = hourly records)
    double dni_w_m2 = 0;                      ///< direct normal irradiance, mean over the interval, W/m^2, >= 0
    double dhi_w_m2 = 0;                      ///< diffuse horizontal irradiance, mean over the interval, W/m^2, >= 0
    double ghi_w_m2 = 0;                      ///< global horizontal irradiance, mean over the interval, W/m^2, >= 0

    /// The middle of the interval, where the sun position is taken.
    constexpr std::chrono::sys_seconds middle_utc() const noexcept { return start_utc + interval / 2; }
};

}  // namespace lidarfx
