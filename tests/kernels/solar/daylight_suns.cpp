// SPDX-License-Identifier: Apache-2.0
// daylight_suns: the same suns, months and irradiances that each solar pipeline computed record by record
// (sun_position at the middle, to_grid_azimuth_deg, sun_vector, record_month), and the refusals.
#include <doctest/doctest.h>

#include <lidarfx/kernels/solar/clear_sky.hpp>
#include <lidarfx/kernels/solar/daylight_suns.hpp>

#include <chrono>
#include <cmath>
#include <cstddef>
#include <vector>

using namespace lidarfx;

TEST_CASE("solar/daylight_suns: one sun per record with the sun up, as computed record by record")
{
    const double lat = 36.1, lon = -79.9;
    auto records = clear_sky_records(2021, lat, lon, {.interval = std::chrono::minutes{30}});
    records[100].dni_w_m2 = 333.0;  // the irradiances are the record's, not the model's
    for (const double convergence : {0.0, 1.7, -3.2}) {
        const solar_site site{.latitude_deg = lat,
                              .longitude_deg = lon,
                              .utc_offset_h = -5.0,
                              .meridian_convergence_deg = convergence,
                              .sun = {.elevation_m = 270.0}};
        const std::vector<daylight_sun> suns = daylight_suns(records, site);
        std::size_t k = 0;
        for (std::size_t i = 0; i < records.size(); ++i) {
            const irradiance_record& r = records[i];
            const sun_position_result s = sun_position(r.middle_utc(), lat, lon, site.sun);
            if (!(s.elevation_deg > 0.0)) continue;
            REQUIRE(k < suns.size());
            const daylight_sun& d = suns[k++];
            INFO("record ", i, " convergence ", convergence);
            CHECK(d.record == i);
            const double azimuth = to_grid_azimuth_deg(s.azimuth_deg, convergence);
            CHECK(d.azimuth_deg == azimuth);  // bit for bit: the pipelines' results must not move
            CHECK(d.elevation_deg == s.elevation_deg);
            const enu_vector v = sun_vector(azimuth, s.elevation_deg);
            CHECK(d.sun.east == v.east);
            CHECK(d.sun.north == v.north);
            CHECK(d.sun.up == v.up);
            CHECK(d.month == record_month(r, -5.0));
            CHECK(d.day_of_year == record_day_of_year(r));
            CHECK(d.kwh_per_w_m2 == static_cast<double>(r.interval.count()) / 3600.0 / 1000.0);
            CHECK(d.dni_w_m2 == r.dni_w_m2);
            CHECK(d.dhi_w_m2 == r.dhi_w_m2);
            CHECK(d.ghi_w_m2 == r.ghi_w_m2);
        }
        CHECK(k == suns.size());
        CHECK(suns.size() > records.size() / 2 - 200);
        CHECK(suns.size() < records.size() / 2 + 200);
    }
}

TEST_CASE("solar/daylight_suns: months in local standard time; refusals name the field")
{
    std::vector<irradiance_record> records(1);
    // 31 December 2021, 22:00-23:00 UTC: still December at UTC - 5, already January at UTC + 3.
    records[0].start_utc = std::chrono::sys_days{std::chrono::year{2021} / 12 / 31} + std::chrono::hours{22};
    records[0].ghi_w_m2 = 100.0;
    CHECK(record_month(records[0], -5.0) == 11);
    CHECK(record_month(records[0], 3.0) == 0);
    CHECK(record_day_of_year(records[0]) == 365);
    // Sydney: the sun is up at 09:30 local on 1 January.
    const auto at_sydney =
        daylight_suns(records, {.latitude_deg = -33.9, .longitude_deg = 151.2, .utc_offset_h = 10.0});
    REQUIRE(at_sydney.size() == 1);
    CHECK(at_sydney[0].month == 0);
    CHECK(daylight_suns(records, {.latitude_deg = 52.5, .longitude_deg = 13.4}).empty());  // night in Berlin

    CHECK_THROWS_WITH_AS(daylight_suns(records, {.latitude_deg = 95.0}), doctest::Contains("latitude_deg"),
                         invalid_input);
    CHECK_THROWS_WITH_AS(daylight_suns(records, {.utc_offset_h = 15.0}), doctest::Contains("site.utc_offset_h"),
                         invalid_input);
    CHECK_THROWS_WITH_AS(daylight_suns(records, {.meridian_convergence_deg = -91.0}),
                         doctest::Contains("site.meridian_convergence_deg"), invalid_input);
    records[0].dhi_w_m2 = -1.0;
    CHECK_THROWS_WITH_AS(daylight_suns(records, {}), doctest::Contains("daylight_suns: records[0]"), invalid_input);
}
