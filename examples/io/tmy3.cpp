// SPDX-License-Identifier: Apache-2.0
#include "io/tmy3.hpp"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstddef>
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
    throw std::runtime_error(source + ": line " + std::to_string(line_no) + ": " + what);
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
        if (f.size() < 7) fail("the station line needs 7 fields (id, name, state, zone, lat, lon, elevation), got " +
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
            std::ptrdiff_t* slot = n == "Date" ? &col_date : n == "Time" ? &col_time : n == "GHI" ? &col_ghi
                                 : n == "DNI"  ? &col_dni  : n == "DHI"  ? &col_dhi  : nullptr;
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
        irradiance_record rec;
        const std::chrono::sys_seconds stamp_local =
            std::chrono::sys_days{ymd} + std::chrono::hours{hh} + std::chrono::minutes{mi};
        rec.interval = std::chrono::seconds{3600};
        rec.start_utc = stamp_local - rec.interval - offset;
        const std::pair<std::ptrdiff_t, double*> values[] = {
            {col_ghi, &rec.ghi_w_m2}, {col_dni, &rec.dni_w_m2}, {col_dhi, &rec.dhi_w_m2}};
        for (const auto& [col, value] : values) {
            const std::string_view s = f[static_cast<std::size_t>(col)];
            if (!to_number(s, *value) || *value < 0.0)
                fail("bad irradiance '" + std::string(s) + "' (W/m^2, a number >= 0)");
        }
        out.records.push_back(rec);
    }
    if (out.records.empty()) fail("no data rows after the two header lines");
    return out;
}

tmy3_data read_tmy3(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": cannot open (expected a TMY3 CSV file)");
    std::ostringstream text;
    text << in.rdbuf();
    return parse_tmy3(text.str(), path);
}

}  // namespace lidarfx::io
