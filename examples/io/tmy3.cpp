// SPDX-License-Identifier: Apache-2.0
#include "io/tmy3.hpp"

#include <lidarfx/core/error.hpp>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

namespace lidarfx::io {

namespace {

// The fields of one CSV line; double quotes group a field (no quotes inside a field in TMY3 files).
std::vector<std::string_view> csv_fields(std::string_view line)
{
    std::vector<std::string_view> out;
    std::size_t i = 0;
    while (true) {
        if (i < line.size() && line[i] == '"') {
            const std::size_t close = line.find('"', i + 1);
            const std::size_t end = close == std::string_view::npos ? line.size() : close;
            out.push_back(line.substr(i + 1, end - i - 1));
            i = line.find(',', end);
        } else {
            const std::size_t comma = line.find(',', i);
            out.push_back(line.substr(i, comma == std::string_view::npos ? std::string_view::npos : comma - i));
            i = comma;
        }
        if (i == std::string_view::npos) break;
        ++i;
    }
    return out;
}

std::string_view trim(std::string_view s)
{
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
    return s;
}

bool to_number(std::string_view s, double& v)
{
    s = trim(s);
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    return ec == std::errc{} && end == s.data() + s.size() && std::isfinite(v);
}

std::string fixed0(double v)
{
    return std::to_string(std::llround(v));
}

bool to_int(std::string_view s, int& v)
{
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    return ec == std::errc{} && end == s.data() + s.size();
}

// The column name before any " (unit)": "GHI (W/m^2)" -> "GHI", "Date (MM/DD/YYYY)" -> "Date".
std::string_view column_name(std::string_view header)
{
    header = trim(header);
    const std::size_t paren = header.find(" (");
    return trim(paren == std::string_view::npos ? header : header.substr(0, paren));
}

[[noreturn]] void fail_at(const std::string& source, std::size_t line_no, const std::string& what)
{
    throw invalid_input(source + ": line " + std::to_string(line_no) + ": " + what);
}

// Days before each month in a year of 365 days (a TMY year).
constexpr int days_before_month[13] = {0, 31, 59, 90, 120, 151, 181, 212, 243, 273, 304, 334, 365};

// "MM/DD HH:00" of hour `index` (0 .. 8759) of a TMY year, hour-ending like the rows' stamps (01:00 .. 24:00).
std::string hour_stamp(int index)
{
    const int day = index / 24, hour = index % 24 + 1;
    int month = 1;
    while (days_before_month[month] <= day) ++month;
    const auto two = [](int v) { return std::string(v < 10 ? "0" : "") + std::to_string(v); };
    return two(month) + "/" + two(day - days_before_month[month - 1] + 1) + " " + two(hour) + ":00";
}

}  // namespace

tmy3_data parse_tmy3(std::string_view text, const std::string& source)
{
    std::size_t line_no = 0, pos = 0;
    const auto fail = [&](const std::string& what) { fail_at(source, line_no, what); };
    const auto next_line = [&](std::string_view& line) {
        if (pos >= text.size()) return false;
        const std::size_t nl = text.find('\n', pos);
        line = text.substr(pos, (nl == std::string_view::npos ? text.size() : nl) - pos);
        pos = nl == std::string_view::npos ? text.size() : nl + 1;
        ++line_no;
        return true;
    };

    tmy3_data out;
    std::string_view line;
    if (!next_line(line)) {
        fail("empty file: expected the TMY3 station line (id, name, state, zone, lat, lon, elevation)");
    }
    {
        const auto f = csv_fields(trim(line));
        if (f.size() < 7)
            fail("the station line needs 7 fields (id, name, state, zone, lat, lon, elevation), got " +
                 std::to_string(f.size()));
        tmy3_station& s = out.station;
        s.id = std::string(trim(f[0]));
        s.name = std::string(trim(f[1]));
        s.state = std::string(trim(f[2]));
        if (!to_number(f[3], s.utc_offset_h) || !(s.utc_offset_h >= -14.0 && s.utc_offset_h <= 14.0))
            fail("bad time zone offset '" + std::string(f[3]) + "' (hours from UTC, -14..14)");
        if (!to_number(f[4], s.latitude_deg) || !(s.latitude_deg >= -90.0 && s.latitude_deg <= 90.0))
            fail("bad latitude '" + std::string(f[4]) + "' (degrees, -90..90)");
        if (!to_number(f[5], s.longitude_deg) || !(s.longitude_deg >= -180.0 && s.longitude_deg <= 180.0))
            fail("bad longitude '" + std::string(f[5]) + "' (degrees, -180..180)");
        if (!to_number(f[6], s.elevation_m)) fail("bad elevation '" + std::string(f[6]) + "' (metres)");
    }
    if (!next_line(line)) fail("missing the column header line (Date, Time, ..., GHI, DNI, DHI, ...)");
    std::ptrdiff_t col_date = -1, col_time = -1, col_ghi = -1, col_dni = -1, col_dhi = -1;
    {
        const auto f = csv_fields(trim(line));
        for (std::size_t i = 0; i < f.size(); ++i) {
            const std::string_view n = column_name(f[i]);
            std::ptrdiff_t* slot = n == "Date"   ? &col_date
                                   : n == "Time" ? &col_time
                                   : n == "GHI"  ? &col_ghi
                                   : n == "DNI"  ? &col_dni
                                   : n == "DHI"  ? &col_dhi
                                                 : nullptr;
            if (slot != nullptr && *slot < 0) *slot = static_cast<std::ptrdiff_t>(i);
        }
        const std::pair<std::ptrdiff_t, const char*> need[] = {
            {col_date, "Date"}, {col_time, "Time"}, {col_ghi, "GHI"}, {col_dni, "DNI"}, {col_dhi, "DHI"}};
        for (const auto& [col, name] : need) {
            if (col < 0) fail(std::string("no column named '") + name + "' in the header line (is this a TMY3 file?)");
        }
    }
    const std::ptrdiff_t needed = std::max({col_date, col_time, col_ghi, col_dni, col_dhi}) + 1;
    const auto offset = std::chrono::seconds{std::llround(out.station.utc_offset_h * 3600.0)};
    // The line of the row of each hour of the year: 0 none yet, negative when the row is marked missing.
    std::vector<std::ptrdiff_t> line_of_hour(static_cast<std::size_t>(tmy3_hours_of_year), 0);
    while (next_line(line)) {
        if (trim(line).empty()) continue;
        const auto f = csv_fields(trim(line));
        if (static_cast<std::ptrdiff_t>(f.size()) < needed)
            fail("expected at least " + std::to_string(needed) + " fields, got " + std::to_string(f.size()));
        const std::string_view date = trim(f[static_cast<std::size_t>(col_date)]);
        const std::string_view time = trim(f[static_cast<std::size_t>(col_time)]);
        int mm = 0, dd = 0, yyyy = 0, hh = 0, mi = 0;
        if (date.size() != 10 || date[2] != '/' || date[5] != '/' || !to_int(date.substr(0, 2), mm) ||
            !to_int(date.substr(3, 2), dd) || !to_int(date.substr(6, 4), yyyy))
            fail("bad date '" + std::string(date) + "' (expected MM/DD/YYYY)");
        const std::chrono::year_month_day ymd{std::chrono::year{yyyy}, std::chrono::month{static_cast<unsigned>(mm)},
                                              std::chrono::day{static_cast<unsigned>(dd)}};
        if (!ymd.ok()) fail("no such date '" + std::string(date) + "'");
        if (time.size() != 5 || time[2] != ':' || !to_int(time.substr(0, 2), hh) || !to_int(time.substr(3, 2), mi) ||
            hh < 0 || hh > 24 || mi < 0 || mi > 59 || (hh == 24 && mi != 0))
            fail("bad time '" + std::string(time) + "' (expected HH:MM, 01:00 .. 24:00, hour-ending)");
        if (mi != 0) fail("bad time '" + std::string(time) + "' (TMY3 rows are hourly: expected HH:00)");
        // The hour of the TMY year the row describes: its written month, day and hour-ending stamp, the year
        // ignored (a TMY takes each month from a different year); 00:00 is the previous day's 24:00.
        if (mm == 2 && dd == 29) {
            fail("'" + std::string(date) + "' is 29 February, which a TMY year (365 days, " +
                 std::to_string(tmy3_hours_of_year) + " hours) does not have");
        }
        const int hour_index = (days_before_month[mm - 1] + dd - 1) * 24 + hh - 1;
        const int hour = (hour_index + tmy3_hours_of_year) % tmy3_hours_of_year;
        std::ptrdiff_t& row_of_hour = line_of_hour[static_cast<std::size_t>(hour)];
        if (row_of_hour != 0) {
            fail("the hour " + hour_stamp(hour) + " ('" + std::string(date) + "," + std::string(time) +
                 "') is already on line " + std::to_string(std::abs(row_of_hour)) +
                 ": each hour of the year may be on one row only (is the year repeated, or a row copied?)");
        }
        row_of_hour = static_cast<std::ptrdiff_t>(line_no);
        irradiance_record rec;
        const std::chrono::sys_seconds stamp_local =
            std::chrono::sys_days{ymd} + std::chrono::hours{hh} + std::chrono::minutes{mi};
        rec.interval = std::chrono::seconds{3600};
        rec.start_utc = stamp_local - rec.interval - offset;
        struct column {
            std::ptrdiff_t index;
            const char* name;
            double* value;
            double max_w_m2;
            const char* why;
        };
        const column values[] = {
            {col_ghi, "GHI", &rec.ghi_w_m2, tmy3_max_ghi_dhi_w_m2, "no clear sky gives that as an hourly mean"},
            {col_dni, "DNI", &rec.dni_w_m2, tmy3_max_dni_w_m2, "the solar constant 1367 W/m^2 x 1.035 at perihelion"},
            {col_dhi, "DHI", &rec.dhi_w_m2, tmy3_max_ghi_dhi_w_m2, "no clear sky gives that as an hourly mean"}};
        bool marked_missing = false;
        for (const column& c : values) {
            const std::string_view s = trim(f[static_cast<std::size_t>(c.index)]);
            if (!to_number(s, *c.value)) {
                fail("bad irradiance '" + std::string(s) + "': " + c.name + " must be a number (W/m^2)");
            }
            if (*c.value == tmy3_missing_value) {
                marked_missing = true;
            } else if (*c.value < 0.0) {
                fail("bad irradiance '" + std::string(s) + "': " + c.name + " must be >= 0 W/m^2 (or -9900, missing)");
            } else if (*c.value > c.max_w_m2) {
                fail(std::string(c.name) + " " + std::string(s) + " W/m^2 is above " + fixed0(c.max_w_m2) + " W/m^2 (" +
                     c.why + ")");
            }
        }
        if (marked_missing) {
            ++out.coverage.rows_marked_missing;
            row_of_hour = -row_of_hour;  // on a row, but without values
        } else {
            out.records.push_back(rec);
        }
    }
    if (out.records.empty() && out.coverage.rows_marked_missing == 0) fail("no data rows after the two header lines");
    tmy3_coverage& cov = out.coverage;
    cov.hours_present = static_cast<int>(out.records.size());
    cov.hours_missing = tmy3_hours_of_year - cov.hours_present;
    for (int h = 0; h < tmy3_hours_of_year && cov.first_missing.empty(); ++h) {
        if (line_of_hour[static_cast<std::size_t>(h)] <= 0) cov.first_missing = hour_stamp(h);
    }
    if (cov.hours_missing > tmy3_max_missing_hours) {
        throw invalid_input(source + ": " + std::to_string(cov.hours_present) + " of " +
                            std::to_string(tmy3_hours_of_year) + " hours of the year have values, " +
                            std::to_string(cov.hours_missing) + " are missing (the first " + cov.first_missing + ", " +
                            std::to_string(cov.rows_marked_missing) + " marked -9900): at most " +
                            std::to_string(tmy3_max_missing_hours) + " (1 %) may be missing");
    }
    return out;
}

std::string coverage_line(const tmy3_data& data, const std::string& source)
{
    const tmy3_coverage& c = data.coverage;
    std::string line = "weather: " + source + " covers " + std::to_string(c.hours_present) + " of " +
                       std::to_string(tmy3_hours_of_year) + " hours of the year";
    if (c.hours_missing > 0) {
        line += " (" + std::to_string(c.hours_missing) + " missing, the first " + c.first_missing;
        if (c.rows_marked_missing > 0) line += ", " + std::to_string(c.rows_marked_missing) + " marked -9900";
        line += ": they add nothing; at most " + std::to_string(tmy3_max_missing_hours) + " may be missing)";
    }
    return line;
}

tmy3_data read_tmy3(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": cannot open (expected a TMY3 CSV file)");
    std::error_code ec;
    const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
    if (!ec && bytes > tmy3_max_file_bytes) {
        throw invalid_input(path + ": " + std::to_string(bytes) + " bytes, more than one TMY3 year can hold (at most " +
                            std::to_string(tmy3_max_file_bytes >> 20) + " MiB; a year is about 1.7 MB)");
    }
    std::ostringstream text;
    text << in.rdbuf();
    return parse_tmy3(text.str(), path);
}

}  // namespace lidarfx::io
