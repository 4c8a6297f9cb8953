// SPDX-License-Identifier: Apache-2.0
// The TMY3 reader on small generated files, and (when LIDARFX_DATA_DIR holds it) on Greensboro's TMY3 year with
// the energy closure of irradiance_maps on open flat ground.
#include <doctest/doctest.h>

#include "io/tmy3.hpp"

#include <lidarfx/pipelines/solar/irradiance_maps.hpp>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

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

std::string row(const std::string& date, const std::string& time, int ghi, int dni, int dhi)
{
    return date + "," + time + ",0,0," + std::to_string(ghi) + ",1,0," + std::to_string(dni) + ",1,0," +
           std::to_string(dhi) + ",1,0\n";
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
    const std::string path = write(dir, std::string(station_line) + header_line +
                                            row("01/01/1988", "01:00", 0, 0, 0) +
                                            row("07/04/1991", "13:00", 850, 700, 150) +
                                            row("12/31/1988", "24:00", 0, 0, 0));
    const tmy3_data d = read_tmy3(path);
    CHECK(d.station.id == "723170");
    CHECK(d.station.name == "GREENSBORO PIEDMONT TRIAD INT");
    CHECK(d.station.state == "NC");
    CHECK(d.station.utc_offset_h == -5.0);
    CHECK(d.station.latitude_deg == 36.1);
    CHECK(d.station.longitude_deg == -79.95);
    CHECK(d.station.elevation_m == 273.0);
    REQUIRE(d.records.size() == 3);
    // 01/01 01:00 EST ends the hour 00:00..01:00 EST = 05:00..06:00 UTC.
    CHECK(d.records[0].start_utc == chr::sys_days{chr::year{1988} / 1 / 1} + chr::hours{5});
    CHECK(d.records[0].interval == chr::hours{1});
    CHECK(d.records[0].middle_utc() == chr::sys_days{chr::year{1988} / 1 / 1} + chr::hours{5} + chr::minutes{30});
    // 07/04 13:00 EST: 12:00..13:00 EST = 17:00..18:00 UTC; the values go to their fields.
    CHECK(d.records[1].start_utc == chr::sys_days{chr::year{1991} / 7 / 4} + chr::hours{17});
    CHECK(d.records[1].ghi_w_m2 == 850.0);
    CHECK(d.records[1].dni_w_m2 == 700.0);
    CHECK(d.records[1].dhi_w_m2 == 150.0);
    // 24:00 is the last hour of the day: 23:00..24:00 EST = 04:00..05:00 UTC the next day.
    CHECK(d.records[2].start_utc == chr::sys_days{chr::year{1989} / 1 / 1} + chr::hours{4});
}

TEST_CASE("io/tmy3: columns are found by name, and a zone east of Greenwich moves stamps back")
{
    io_test::temp_dir dir;
    const std::string path = write(dir, "1,\"X\",ZZ,+2.5,10,20,5\r\n"
                                        "DHI (W/m^2),Time (HH:MM),DNI (W/m^2),Date (MM/DD/YYYY),GHI (W/m^2)\r\n"
                                        "30,06:00,400,03/01/2001,200\r\n");
    const tmy3_data d = read_tmy3(path);
    REQUIRE(d.records.size() == 1);
    CHECK(d.station.utc_offset_h == 2.5);
    CHECK(d.records[0].start_utc == chr::sys_days{chr::year{2001} / 3 / 1} + chr::hours{5} - chr::hours{2} -
                                        chr::minutes{30});
    CHECK(d.records[0].dhi_w_m2 == 30.0);
    CHECK(d.records[0].dni_w_m2 == 400.0);
    CHECK(d.records[0].ghi_w_m2 == 200.0);
}

TEST_CASE("io/tmy3: bad files are refused with the file, the line and what is wrong")
{
    io_test::temp_dir dir;
    const auto error = [&](const std::string& text) {
        const std::string path = write(dir, text);
        return runtime_error_of([&] { read_tmy3(path); });
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
    CHECK(d.station.utc_offset_h == -5.0);
    CHECK(d.station.latitude_deg == doctest::Approx(36.1));
    // On open flat ground the year's beam on the horizontal plus diffuse equals the year's GHI within 1 %.
    const raster<float> flat(6, 7, 270.0f);
    const auto res = irradiance_maps(flat, 1.0, d.station.latitude_deg, d.station.longitude_deg, d.records,
                                     {.sun = {.elevation_m = d.station.elevation_m},
                                      .month_utc_offset_h = d.station.utc_offset_h});
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
