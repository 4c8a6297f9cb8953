// SPDX-License-Identifier: Apache-2.0
// The TMY3 reader on generated years (each hour of the year at most once, coverage, physical bounds), and (when
// LIDARFX_DATA_DIR holds it) on Greensboro's TMY3 year with the energy closure of irradiance_maps on open flat ground.
#include <doctest/doctest.h>

#include "io/tmy3.hpp"

#include <lidarfx/pipelines/solar/irradiance_maps.hpp>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "io_test_util.hpp"

using namespace lidarfx;
using namespace lidarfx::io;
using io_test::contains;
using io_test::runtime_error_of;

namespace {

namespace chr = std::chrono;

const char* const station_line = "723170,\"GREENSBORO PIEDMONT TRIAD INT\",NC,-5.0,36.100,-79.950,273\n";
// The real header's first columns, with GHI, DNI and DHI where TMY3 has them.
const char* const header_line =
    "Date (MM/DD/YYYY),Time (HH:MM),ETR (W/m^2),ETRN (W/m^2),GHI (W/m^2),GHI source,GHI uncert (%),DNI (W/m^2),"
    "DNI source,DNI uncert (%),DHI (W/m^2),DHI source,DHI uncert (%)\n";
// The whole header line of NREL's TMY3 files (723170TYA.CSV), 71 columns.
const char* const full_header_line =
    "Date (MM/DD/YYYY),Time (HH:MM),ETR (W/m^2),ETRN (W/m^2),GHI (W/m^2),GHI source,GHI uncert (%)"
    ",DNI (W/m^2),DNI source,DNI uncert (%),DHI (W/m^2),DHI source,DHI uncert (%),GH illum (lx)"
    ",GH illum source,Global illum uncert (%),DN illum (lx),DN illum source,DN illum uncert (%)"
    ",DH illum (lx),DH illum source,DH illum uncert (%),Zenith lum (cd/m^2),Zenith lum source"
    ",Zenith lum uncert (%),TotCld (tenths),TotCld source,TotCld uncert (code),OpqCld (tenths)"
    ",OpqCld source,OpqCld uncert (code),Dry-bulb (C),Dry-bulb source,Dry-bulb uncert (code)"
    ",Dew-point (C),Dew-point source,Dew-point uncert (code),RHum (%),RHum source,RHum uncert (code)"
    ",Pressure (mbar),Pressure source,Pressure uncert (code),Wdir (degrees),Wdir source"
    ",Wdir uncert (code),Wspd (m/s),Wspd source,Wspd uncert (code),Hvis (m),Hvis source"
    ",Hvis uncert (code),CeilHgt (m),CeilHgt source,CeilHgt uncert (code),Pwat (cm),Pwat source"
    ",Pwat uncert (code),AOD (unitless),AOD source,AOD uncert (code),Alb (unitless),Alb source"
    ",Alb uncert (code),Lprecip depth (mm),Lprecip quantity (hr),Lprecip source,Lprecip uncert (code)"
    ",PresWth (METAR code),PresWth source,PresWth uncert (code)\n";

std::string row(const std::string& date, const std::string& time, int ghi, int dni, int dhi)
{
    return date + "," + time + ",0,0," + std::to_string(ghi) + ",1,0," + std::to_string(dni) + ",1,0," +
           std::to_string(dhi) + ",1,0\n";
}

// A row as NREL writes it: the 13 columns above, then the illuminance and meteorological columns of 06/16 14:00.
std::string full_row(const std::string& date, const std::string& time, int ghi, int dni, int dhi)
{
    return date + "," + time + ",1244,1324," + std::to_string(ghi) + ",1,9," + std::to_string(dni) + ",1,9," +
           std::to_string(dhi) +
           ",1,13,355,1,9,1,1,9,354,1,13,1393,1,18,10,A,7,10,A,7,21.7,A,7,20.6,A,7,93,A,7,"
           "986,A,7,220,A,7,3.1,A,7,11300,B,7,1370,A,7,3.6,E,8,0.000,F,8,0.00,?,0,18,1,D,9,80,C,8\n";
}

using row_format = std::function<std::string(const std::string& date, const std::string& time, int, int, int)>;

// Two digits: 7 -> "07".
std::string two(int v)
{
    std::string s = std::to_string(v);
    if (s.size() < 2) s.insert(s.begin(), '0');
    return s;
}

// The 8760 rows of a TMY year in file order (01/01 01:00 .. 12/31 24:00), all dated `year` (a common year):
// GHI 500, DNI 600, DHI 100 W/m^2 from 08:00 to 17:00 local, 0 at the other hours.
std::vector<std::string> year_rows(const row_format& format = row, int year = 2001)
{
    static const int days_in[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    std::vector<std::string> rows;
    for (int m = 1; m <= 12; ++m) {
        for (int d = 1; d <= days_in[m - 1]; ++d) {
            for (int h = 1; h <= 24; ++h) {
                const bool day = h >= 8 && h <= 17;
                rows.push_back(format(two(m) + "/" + two(d) + "/" + std::to_string(year), two(h) + ":00", day ? 500 : 0,
                                      day ? 600 : 0, day ? 100 : 0));
            }
        }
    }
    return rows;
}

// The file text: station, header, then the rows.
std::string text_of(const std::vector<std::string>& rows, const char* header = header_line)
{
    std::string text = std::string(station_line) + header;
    for (const auto& r : rows) text += r;
    return text;
}

// The index of the row of MM/DD HH:00 in year_rows(): the hour of the year (0 .. 8759).
std::size_t hour_of(int month, int day, int hour)
{
    static const int days_before[12] = {0, 31, 59, 90, 120, 151, 181, 212, 243, 273, 304, 334};
    return static_cast<std::size_t>((days_before[month - 1] + day - 1) * 24 + hour - 1);
}

std::string write(const io_test::temp_dir& dir, const std::string& text)
{
    const std::string path = dir.file("tmy3.csv");
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

}  // namespace

TEST_CASE("io/tmy3: reads the station line and hour-ending local standard time rows as UTC records")
{
    io_test::temp_dir dir;
    std::vector<std::string> rows = year_rows();
    rows[hour_of(1, 1, 1)] = row("01/01/1988", "01:00", 0, 0, 0);
    rows[hour_of(7, 4, 13)] = row("07/04/1991", "13:00", 850, 700, 150);
    rows[hour_of(12, 31, 24)] = row("12/31/1988", "24:00", 0, 0, 0);
    const std::string path = write(dir, text_of(rows));
    const tmy3_data d = read_tmy3(path);
    CHECK(d.station.id == "723170");
    CHECK(d.station.name == "GREENSBORO PIEDMONT TRIAD INT");
    CHECK(d.station.state == "NC");
    CHECK(d.station.utc_offset_h == -5.0);
    CHECK(d.station.latitude_deg == 36.1);
    CHECK(d.station.longitude_deg == -79.95);
    CHECK(d.station.elevation_m == 273.0);
    REQUIRE(d.records.size() == 8760);
    CHECK(d.coverage.hours_present == 8760);
    CHECK(d.coverage.hours_missing == 0);
    CHECK(d.coverage.first_missing.empty());
    // 01/01 01:00 EST ends the hour 00:00..01:00 EST = 05:00..06:00 UTC.
    const irradiance_record& first = d.records[hour_of(1, 1, 1)];
    CHECK(first.start_utc == chr::sys_days{chr::year{1988} / 1 / 1} + chr::hours{5});
    CHECK(first.interval == chr::hours{1});
    CHECK(first.middle_utc() == chr::sys_days{chr::year{1988} / 1 / 1} + chr::hours{5} + chr::minutes{30});
    // 07/04 13:00 EST: 12:00..13:00 EST = 17:00..18:00 UTC; the values go to their fields.
    const irradiance_record& july = d.records[hour_of(7, 4, 13)];
    CHECK(july.start_utc == chr::sys_days{chr::year{1991} / 7 / 4} + chr::hours{17});
    CHECK(july.ghi_w_m2 == 850.0);
    CHECK(july.dni_w_m2 == 700.0);
    CHECK(july.dhi_w_m2 == 150.0);
    // 24:00 is the last hour of the day: 23:00..24:00 EST = 04:00..05:00 UTC the next day.
    CHECK(d.records[hour_of(12, 31, 24)].start_utc == chr::sys_days{chr::year{1989} / 1 / 1} + chr::hours{4});
}

TEST_CASE("io/tmy3: columns are found by name, and a zone east of Greenwich moves stamps back")
{
    const auto reordered = [](const std::string& date, const std::string& time, int ghi, int dni, int dhi) {
        return std::to_string(dhi) + "," + time + "," + std::to_string(dni) + "," + date + "," + std::to_string(ghi) +
               "\r\n";
    };
    std::vector<std::string> rows = year_rows(reordered);
    rows[hour_of(3, 1, 6)] = reordered("03/01/2001", "06:00", 200, 400, 30);
    const std::string text =
        "1,\"X\",ZZ,+2.5,10,20,5\r\n"
        "DHI (W/m^2),Time (HH:MM),DNI (W/m^2),Date (MM/DD/YYYY),GHI (W/m^2)\r\n" +
        [&] {
            std::string t;
            for (const auto& r : rows) t += r;
            return t;
        }();
    const tmy3_data d = parse_tmy3(text, "east.csv");
    REQUIRE(d.records.size() == 8760);
    CHECK(d.station.utc_offset_h == 2.5);
    const irradiance_record& r = d.records[hour_of(3, 1, 6)];
    CHECK(r.start_utc == chr::sys_days{chr::year{2001} / 3 / 1} + chr::hours{5} - chr::hours{2} - chr::minutes{30});
    CHECK(r.dhi_w_m2 == 30.0);
    CHECK(r.dni_w_m2 == 400.0);
    CHECK(r.ghi_w_m2 == 200.0);
}

TEST_CASE("io/tmy3: bad files are refused with the file, the line and what is wrong")
{
    io_test::temp_dir dir;
    const auto error = [&](const std::string& text) {
        const std::string path = write(dir, text);
        return io_test::invalid_input_of([&] { read_tmy3(path); });
    };
    CHECK(contains(runtime_error_of([&] { read_tmy3(dir.file("missing.csv")); }), "missing.csv: cannot open"));
    CHECK(contains(error(""), "line 0: empty file"));
    CHECK(contains(error("1,2,3\n"), "line 1: the station line needs 7 fields"));
    CHECK(contains(error("1,\"X\",ZZ,-5,95,20,5\n"), "bad latitude"));
    CHECK(contains(error(std::string(station_line) + "Date,Time,GHI,DNI\n"), "line 2: no column named 'DHI'"));
    CHECK(contains(error(std::string(station_line) + header_line), "no data rows"));
    CHECK(contains(error(std::string(station_line) + header_line + row("13/01/1988", "01:00", 0, 0, 0)),
                   "line 3: no such date '13/01/1988'"));
    CHECK(contains(error(std::string(station_line) + header_line + row("01/01/1988", "25:00", 0, 0, 0)),
                   "line 3: bad time '25:00'"));
    CHECK(contains(error(std::string(station_line) + header_line + row("01/01/1988", "12:00", 10, -2, 0)),
                   "bad irradiance '-2'"));
    CHECK(contains(error(std::string(station_line) + header_line + "01/01/1988,12:00,0\n"), "expected at least"));
    CHECK(contains(error(std::string(station_line) + header_line + row("01/01/1988", "12:00", 0, 0, 0) +
                         row("01/01/1988", "1300", 0, 0, 0)),
                   "tmy3.csv: line 4: bad time '1300'"));
    // Rows are hourly: a stamp off the hour has no hour of the year.
    CHECK(contains(error(std::string(station_line) + header_line + row("01/01/1988", "12:30", 0, 0, 0)),
                   "line 3: bad time '12:30' (TMY3 rows are hourly"));
}

TEST_CASE("io/tmy3: a file larger than any year is refused before it is read")
{
    io_test::temp_dir dir;
    const std::string path = dir.file("huge.csv");
    std::ofstream(path, std::ios::binary) << station_line << header_line;
    std::filesystem::resize_file(path, tmy3_max_file_bytes + 1);  // sparse: no disk, and nothing to read
    const std::string e = io_test::invalid_input_of([&] { read_tmy3(path); });
    CHECK(contains(e, "huge.csv: " + std::to_string(tmy3_max_file_bytes + 1) + " bytes, more than one TMY3 year"));
}

TEST_CASE("io/tmy3: a year given twice (or twelve times) is refused at its first repeated hour")
{
    const std::vector<std::string> year = year_rows();
    std::vector<std::string> twice = year;
    twice.insert(twice.end(), year.begin(), year.end());
    // Line 3 holds 01/01 01:00; the second year starts on line 3 + 8760.
    const std::string e = io_test::invalid_input_of([&] { parse_tmy3(text_of(twice), "twice.csv"); });
    CHECK(contains(e, "twice.csv: line 8763: the hour 01/01 01:00 ('01/01/2001,01:00') is already on line 3"));
    std::vector<std::string> twelve;
    for (int i = 0; i < 12; ++i) twelve.insert(twelve.end(), year.begin(), year.end());
    CHECK(contains(io_test::invalid_input_of([&] { parse_tmy3(text_of(twelve), "twelve.csv"); }),
                   "twelve.csv: line 8763: the hour 01/01 01:00"));
    // The year of the row does not make it another hour: a TMY takes each month from a different year.
    std::vector<std::string> other_year = year;
    other_year.push_back(row("07/04/1991", "13:00", 850, 700, 150));
    CHECK(contains(io_test::invalid_input_of([&] { parse_tmy3(text_of(other_year), "extra.csv"); }),
                   "extra.csv: line 8763: the hour 07/04 13:00 ('07/04/1991,13:00') is already on line " +
                       std::to_string(hour_of(7, 4, 13) + 3)));
}

TEST_CASE("io/tmy3: one extra row is a repeated hour, wherever it is")
{
    std::vector<std::string> rows = year_rows();
    const std::size_t h = hour_of(6, 21, 12);
    rows.insert(rows.begin() + static_cast<std::ptrdiff_t>(h) + 1, rows[h]);  // the row twice, one after the other
    CHECK(contains(io_test::invalid_input_of([&] { parse_tmy3(text_of(rows), "extra.csv"); }),
                   "extra.csv: line " + std::to_string(h + 4) +
                       ": the hour 06/21 12:00 ('06/21/2001,12:00') is "
                       "already on line " +
                       std::to_string(h + 3)));
    // 00:00 is the previous day's 24:00: with both, the hour is there twice.
    std::vector<std::string> midnight = year_rows();
    midnight.push_back(row("03/01/2001", "00:00", 0, 0, 0));
    CHECK(contains(io_test::invalid_input_of([&] { parse_tmy3(text_of(midnight), "midnight.csv"); }),
                   "line 8763: the hour 02/28 24:00 ('03/01/2001,00:00') is already on line " +
                       std::to_string(hour_of(2, 28, 24) + 3)));
    // 29 February has no hour in a TMY year (TMY3 files leave it out), even in a leap year.
    std::vector<std::string> leap = year_rows();
    leap[hour_of(2, 28, 12)] = row("02/29/1996", "12:00", 500, 600, 100);
    CHECK(contains(io_test::invalid_input_of([&] { parse_tmy3(text_of(leap), "leap.csv"); }),
                   "leap.csv: line " + std::to_string(hour_of(2, 28, 12) + 3) +
                       ": '02/29/1996' is 29 February, which a TMY year (365 days, 8760 hours) does not have"));
}

TEST_CASE("io/tmy3: up to 88 missing hours are reported and add nothing; more are refused")
{
    // 8759 rows: the last hour missing.
    std::vector<std::string> rows = year_rows();
    rows.pop_back();
    const tmy3_data d = parse_tmy3(text_of(rows), "short.csv");
    CHECK(d.records.size() == 8759);
    CHECK(d.coverage.hours_present == 8759);
    CHECK(d.coverage.hours_missing == 1);
    CHECK(d.coverage.rows_marked_missing == 0);
    CHECK(d.coverage.first_missing == "12/31 24:00");
    CHECK(coverage_line(d, "short.csv") ==
          "weather: short.csv covers 8759 of 8760 hours of the year (1 missing, the first 12/31 24:00: they add "
          "nothing; at most 88 may be missing)");
    CHECK(coverage_line(parse_tmy3(text_of(year_rows()), "full.csv"), "full.csv") ==
          "weather: full.csv covers 8760 of 8760 hours of the year");

    // 88 missing (the 88 daylight hours of 8 days in May): accepted, the first named; 89: refused.
    std::vector<std::string> gaps = year_rows();
    std::vector<std::string> kept;
    int dropped = 0;
    for (std::size_t i = 0; i < gaps.size(); ++i) {
        const bool may = i >= hour_of(5, 10, 1) && i < hour_of(5, 20, 1) && gaps[i].find(",500,") != std::string::npos;
        if (may && dropped < 88) {
            ++dropped;
        } else {
            kept.push_back(gaps[i]);
        }
    }
    REQUIRE(dropped == 88);
    const tmy3_data g = parse_tmy3(text_of(kept), "gaps.csv");
    CHECK(g.coverage.hours_present == 8672);
    CHECK(g.coverage.hours_missing == 88);
    CHECK(g.coverage.first_missing == "05/10 08:00");
    kept.erase(kept.begin() + static_cast<std::ptrdiff_t>(hour_of(1, 2, 3)));  // one more: 01/02 03:00
    CHECK(contains(io_test::invalid_input_of([&] { parse_tmy3(text_of(kept), "gaps.csv"); }),
                   "gaps.csv: 8671 of 8760 hours of the year have values, 89 are missing (the first 01/02 03:00, 0 "
                   "marked -9900): at most 88 (1 %) may be missing"));
    // A month alone is far from a year.
    const std::vector<std::string> january(rows.begin(), rows.begin() + 31 * 24);
    CHECK(contains(io_test::invalid_input_of([&] { parse_tmy3(text_of(january), "january.csv"); }),
                   "january.csv: 744 of 8760 hours of the year have values, 8016 are missing (the first 02/01 01:00"));
}

TEST_CASE("io/tmy3: -9900 (TMY3's missing value) makes the hour missing")
{
    std::vector<std::string> rows = year_rows();
    rows[hour_of(4, 2, 11)] = row("04/02/2001", "11:00", 500, -9900, 100);
    const tmy3_data d = parse_tmy3(text_of(rows), "marked.csv");
    CHECK(d.records.size() == 8759);
    CHECK(d.coverage.hours_missing == 1);
    CHECK(d.coverage.rows_marked_missing == 1);
    CHECK(d.coverage.first_missing == "04/02 11:00");
    CHECK(contains(coverage_line(d, "marked.csv"),
                   "covers 8759 of 8760 hours of the year (1 missing, the first "
                   "04/02 11:00, 1 marked -9900: they add nothing"));
    // A marked hour is still on its row: a second row for it is a repeat.
    rows.push_back(row("04/02/2001", "11:00", 500, 600, 100));
    CHECK(contains(
        io_test::invalid_input_of([&] { parse_tmy3(text_of(rows), "marked.csv"); }),
        "the hour 04/02 11:00 ('04/02/2001,11:00') is already on line " + std::to_string(hour_of(4, 2, 11) + 3)));
    // 89 marked: refused like 89 absent rows.
    std::vector<std::string> many = year_rows();
    for (int i = 0; i < 89; ++i) {
        const std::string date = "01/" + two(i / 24 + 1) + "/2001";
        many[static_cast<std::size_t>(i)] = row(date, two(i % 24 + 1) + ":00", -9900, 0, 0);
    }
    CHECK(contains(io_test::invalid_input_of([&] { parse_tmy3(text_of(many), "many.csv"); }),
                   "many.csv: 8671 of 8760 hours of the year have values, 89 are missing (the first 01/01 01:00, 89 "
                   "marked -9900)"));
}

TEST_CASE("io/tmy3: irradiances beyond physical bounds are refused, naming the line and the value")
{
    const std::size_t h = hour_of(6, 21, 13);
    const auto with = [&](int ghi, int dni, int dhi) {
        std::vector<std::string> rows = year_rows();
        rows[h] = row("06/21/2001", "13:00", ghi, dni, dhi);
        return io_test::invalid_input_of([&] { parse_tmy3(text_of(rows), "bounds.csv"); });
    };
    const std::string line = "bounds.csv: line " + std::to_string(h + 3) + ": ";
    CHECK(contains(with(900, 5000, 100), line + "DNI 5000 W/m^2 is above 1415 W/m^2 (the solar constant"));
    CHECK(contains(with(900, 1415, 100), line + "DNI 1415 W/m^2 is above 1415 W/m^2"));  // 1367 x 1.035 = 1414.8
    CHECK(with(900, 1414, 100) == "<no error>");
    CHECK(contains(with(1501, 800, 100), line + "GHI 1501 W/m^2 is above 1500 W/m^2"));
    CHECK(contains(with(1000, 800, 1600), line + "DHI 1600 W/m^2 is above 1500 W/m^2"));
    CHECK(with(1500, 800, 1500) == "<no error>");
    CHECK(contains(with(900, 800, -1), line + "bad irradiance '-1': DHI must be >= 0 W/m^2 (or -9900, missing)"));
}

TEST_CASE("io/tmy3: a year in NREL's full 71-column format is read whole")
{
    io_test::temp_dir dir;
    const std::string path = write(dir, text_of(year_rows(full_row, 1989), full_header_line));
    const tmy3_data d = read_tmy3(path);
    CHECK(d.records.size() == 8760);
    CHECK(d.coverage.hours_present == 8760);
    CHECK(d.coverage.hours_missing == 0);
    CHECK(coverage_line(d, "tmy3.csv") == "weather: tmy3.csv covers 8760 of 8760 hours of the year");
    double ghi_wh = 0.0;
    for (const auto& r : d.records) ghi_wh += r.ghi_w_m2;
    CHECK(ghi_wh == 365.0 * 10.0 * 500.0);  // 10 daylight hours of 500 W/m^2 a day, counted once
}

TEST_CASE("io/tmy3: Greensboro's TMY3 year (723170TYA.CSV) reads as 8760 hours and closes the energy balance")
{
    const std::string path = std::string(LIDARFX_DATA_DIR) + "/723170TYA.CSV";
    if (!std::filesystem::exists(path)) {
        MESSAGE("skipped: " << path << " not found (set LIDARFX_DATA_DIR)");
        return;
    }
    const tmy3_data d = read_tmy3(path);
    REQUIRE(d.records.size() == 8760);
    CHECK(d.coverage.hours_present == 8760);
    CHECK(d.coverage.rows_marked_missing == 0);
    CHECK(d.station.utc_offset_h == -5.0);
    CHECK(d.station.latitude_deg == doctest::Approx(36.1));
    // On open flat ground the year's beam on the horizontal plus diffuse equals the year's GHI within 1 %.
    const raster<float> flat(6, 7, 270.0f);
    const auto res = irradiance_maps(flat, 1.0,
                                     {.latitude_deg = d.station.latitude_deg,
                                      .longitude_deg = d.station.longitude_deg,
                                      .utc_offset_h = d.station.utc_offset_h,
                                      .sun = {.elevation_m = d.station.elevation_m}},
                                     d.records);
    const double closure = res.annual_kwh_m2(3, 3) / res.ghi_kwh_m2 - 1.0;
    MESSAGE("Greensboro TMY3: GHI ", res.ghi_kwh_m2, " kWh/m^2, open flat cell ", res.annual_kwh_m2(3, 3),
            " kWh/m^2, closure error ", 100.0 * closure, " %");
    CHECK(res.ghi_kwh_m2 > 1300.0);
    CHECK(res.ghi_kwh_m2 < 1900.0);
    CHECK(std::fabs(closure) < 0.01);
    double months = 0.0;
    for (const auto& m : res.month_kwh_m2) months += m(3, 3);
    CHECK(months == doctest::Approx(res.annual_kwh_m2(3, 3)).epsilon(1e-5));
    CHECK(res.month_kwh_m2[6](3, 3) > 2.0 * res.month_kwh_m2[11](3, 3));  // July over December
}
