// SPDX-License-Identifier: Apache-2.0
// TMY3 weather files (NREL's Typical Meteorological Year, version 3) read into UTC irradiance records.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <lidarfx/kernels/solar/irradiance_record.hpp>

namespace lidarfx::io {

/// The station line of a TMY3 file (its first line).
struct tmy3_station {
    std::string id;             ///< USAF station number, e.g. "723170"
    std::string name;           ///< station name, e.g. "GREENSBORO PIEDMONT TRIAD INT"
    std::string state;          ///< state or province, e.g. "NC"
    double utc_offset_h = 0;    ///< time zone of the stamps: local standard time = UTC + this many hours (-5 = EST)
    double latitude_deg = 0;    ///< degrees north
    double longitude_deg = 0;   ///< degrees east (negative west)
    double elevation_m = 0;     ///< metres above sea level
};

/// A TMY3 file: its station and one record per data row, in file order.
struct tmy3_data {
    tmy3_station station;
    std::vector<irradiance_record> records;  ///< hourly, UTC; DNI, DHI, GHI in W/m^2
};

/// Parses TMY3 text (see read_tmy3); `source` names it in error messages.
tmy3_data parse_tmy3(std::string_view text, const std::string& source);

/// Reads a TMY3 CSV file (NREL, Wilcox & Marion 2008): line 1 is the station (id, "name", state, time zone
/// offset in hours, latitude, longitude, elevation in m); line 2 names the columns; then one row per hour,
/// "MM/DD/YYYY,HH:MM,...", stamped at the END of the hour in local standard time (01:00 .. 24:00). Columns
/// are found by name: "Date", "Time", "GHI", "DNI", "DHI" (the name before any " (unit)"), irradiances in
/// W/m^2. Each row becomes a record starting one hour before its stamp, moved to UTC with the zone of line 1
/// (UTC = local - utc_offset_h), so the sun is taken at the middle of the hour it describes. The months of a
/// TMY year come from different years; the dates are kept as written. O(file size).
/// @throws std::runtime_error naming the file (and the line) for a missing file, a missing column, a bad
/// date, time or number, or a negative irradiance.
tmy3_data read_tmy3(const std::string& path);

}  // namespace lidarfx::io
