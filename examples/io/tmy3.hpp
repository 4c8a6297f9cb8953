// SPDX-License-Identifier: Apache-2.0
// TMY3 weather files (NREL's Typical Meteorological Year, version 3) read into UTC irradiance records.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <lidarfx/kernels/solar/irradiance_record.hpp>

namespace lidarfx::io {

/// The station line of a TMY3 file (its first line).
struct tmy3_station {
    std::string id;            ///< USAF station number, e.g. "723170"
    std::string name;          ///< station name, e.g. "GREENSBORO PIEDMONT TRIAD INT"
    std::string state;         ///< state or province, e.g. "NC"
    double utc_offset_h = 0;   ///< time zone of the stamps: local standard time = UTC + this many hours (-5 = EST)
    double latitude_deg = 0;   ///< degrees north
    double longitude_deg = 0;  ///< degrees east (negative west)
    double elevation_m = 0;    ///< metres above sea level
};

/// Hours of a TMY year: 365 days of 24 hours (a TMY has no 29 February).
inline constexpr int tmy3_hours_of_year = 8760;
/// Hours of the year a TMY3 file may lack (no row, or a row marked missing): 1 % of 8760. Missing hours add
/// nothing to the year's sums and are reported; a file lacking more is refused.
inline constexpr int tmy3_max_missing_hours = 88;
/// The largest DNI taken, W/m^2: the solar constant 1367 W/m^2 x 1.035 (the Earth nearest the Sun, early
/// January: (1 / 0.983)^2 = 1.035). No beam at the ground exceeds it; a larger value is refused.
inline constexpr double tmy3_max_dni_w_m2 = 1367.0 * 1.035;
/// The largest GHI and DHI taken, W/m^2: an hourly mean above it exceeds any clear sky (at most about
/// 1100 W/m^2 at sea level) even with cloud-edge enhancement (peaks of minutes, not hours); refused.
inline constexpr double tmy3_max_ghi_dhi_w_m2 = 1500.0;
/// The largest weather file read, bytes: NREL's 71-column TMY3 year is about 1.7 MB, and a year holds 8760
/// rows at most, so a larger file cannot be one year; it is refused before it is read (whatever --memory).
inline constexpr std::uintmax_t tmy3_max_file_bytes = 64ull << 20;
/// The TMY3 manual's marker of a missing value (Wilcox & Marion 2008): an hour with GHI, DNI or DHI = -9900
/// is a missing hour (no record).
inline constexpr double tmy3_missing_value = -9900.0;

/// How much of the TMY year a file covers: every hour of the year (month, day, hour; the rows' years are
/// ignored) is on at most one row; the hours without a row, or with a row marked missing, are missing.
struct tmy3_coverage {
    int hours_present = 0;        ///< hours of the 8760 with values (= records.size())
    int hours_missing = 0;        ///< tmy3_hours_of_year - hours_present, <= tmy3_max_missing_hours
    int rows_marked_missing = 0;  ///< rows whose GHI, DNI or DHI is tmy3_missing_value (counted in hours_missing)
    std::string first_missing;    ///< "MM/DD HH:00" (hour-ending, local standard time) of the first missing
                                  ///< hour, "" if none
};

/// A TMY3 file: its station, one record per data row with values, in file order, and its coverage of the year.
struct tmy3_data {
    tmy3_station station;
    std::vector<irradiance_record> records;  ///< hourly, UTC; DNI, DHI, GHI in W/m^2
    tmy3_coverage coverage;
};

/// Parses TMY3 text (see read_tmy3); `source` names it in error messages.
tmy3_data parse_tmy3(std::string_view text, const std::string& source);

/// Reads a TMY3 CSV file (NREL, Wilcox & Marion 2008): line 1 is the station (id, "name", state, time zone
/// offset in hours, latitude, longitude, elevation in m); line 2 names the columns; then one row per hour,
/// "MM/DD/YYYY,HH:MM,...", stamped at the END of the hour in local standard time (01:00 .. 24:00; 00:00 is the
/// previous day's 24:00). Columns are found by name: "Date", "Time", "GHI", "DNI", "DHI" (the name before any
/// " (unit)"), irradiances in W/m^2. Each row becomes a record starting one hour before its stamp, moved to UTC
/// with the zone of line 1 (UTC = local - utc_offset_h), so the sun is taken at the middle of the hour it
/// describes. The months of a TMY year come from different years; the dates are kept as written.
/// The year's rule: each hour of the year (month/day/hour, the year ignored) on at most one row; no 29 February;
/// at most tmy3_max_missing_hours missing (no row, or -9900); 0 <= DNI <= tmy3_max_dni_w_m2 and
/// 0 <= GHI, DHI <= tmy3_max_ghi_dhi_w_m2. O(file size).
/// @throws std::runtime_error naming the file for a missing file; invalid_input naming the file (and the line,
/// the stamp or the value) for a missing column, a bad date, time or number, an hour already on an earlier
/// line, 29 February, an irradiance out of bounds, or more than tmy3_max_missing_hours hours missing.
tmy3_data read_tmy3(const std::string& path);

/// One line saying how much of the year `data` covers, for the commands' stderr:
/// "weather: FILE covers 8759 of 8760 hours of the year (1 missing, the first 12/31 24:00; ...)".
std::string coverage_line(const tmy3_data& data, const std::string& source);

}  // namespace lidarfx::io
