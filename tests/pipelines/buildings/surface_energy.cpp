// SPDX-License-Identifier: Apache-2.0
// surface_energy, surface_class_table and bill_savings on an isolated box building under a clear-sky year: the
// pattern of the dissertation's Table 1, the rooftop closure with GHI, the southern hemisphere, Table 2's formula.
#include <doctest/doctest.h>

#include <lidarfx/kernels/solar/clear_sky.hpp>
#include <lidarfx/kernels/solar/raylines_shadow.hpp>
#include <lidarfx/pipelines/buildings/facade_lit.hpp>
#include <lidarfx/pipelines/buildings/surface_class_table.hpp>
#include <lidarfx/pipelines/buildings/surface_energy.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <span>
#include <utility>
#include <vector>

#include "../../reference/facades.hpp"
#include "../../reference/progress.hpp"

using namespace lidarfx;

namespace {

constexpr auto north_row = static_cast<std::size_t>(surface_class::north_facade);
constexpr auto south_row = static_cast<std::size_t>(surface_class::south_facade);
constexpr auto east_row = static_cast<std::size_t>(surface_class::east_facade);
constexpr auto west_row = static_cast<std::size_t>(surface_class::west_facade);
constexpr auto roof_row = static_cast<std::size_t>(surface_class::rooftop);

/// Table 1 of a 12 x 10 m, 10 m tall box alone on flat ground at (lat, lon) under a clear-sky year.
std::array<surface_class_row, 5> box_table(double lat, double lon, double utc_offset_h,
                                           surface_energy_result* out = nullptr)
{
    const auto s = reference::one_box(60, 60, 25, 24, 10, 12, 100.0f, 110.0f);
    const auto records = clear_sky_records(2021, lat, lon);
    auto res = surface_energy(s.dsm, s.ids, 1.0,
                              {.latitude_deg = lat, .longitude_deg = lon, .utc_offset_h = utc_offset_h}, records);
    const auto table = surface_class_table(res);
    if (out) *out = std::move(res);
    return table;
}

}  // namespace

TEST_CASE("buildings/surface_energy: a box at 40 N under clear sky -- the pattern of the dissertation's Table 1")
{
    surface_energy_result res;
    const auto t = box_table(40.0, -75.2, -5.0, &res);  // Philadelphia
    for (const auto& row : t) {
        MESSAGE(static_cast<int>(row.kind), ": ", row.quarter_kwh_m2_day[0], " ", row.quarter_kwh_m2_day[1], " ",
                row.quarter_kwh_m2_day[2], " ", row.quarter_kwh_m2_day[3], " kWh/m2/day, ", row.annual_kwh_m2,
                " kWh/m2/yr, area ", row.area_m2, " m2");
    }
    CHECK(t[south_row].area_m2 == doctest::Approx(12 * 10.0));
    CHECK(t[east_row].area_m2 == doctest::Approx(10 * 10.0));
    CHECK(t[roof_row].area_m2 == doctest::Approx(11 * 9.0));
    // South > east ~ west > north over the year.
    CHECK(t[south_row].annual_kwh_m2 > t[east_row].annual_kwh_m2);
    CHECK(t[south_row].annual_kwh_m2 > t[west_row].annual_kwh_m2);
    CHECK(t[east_row].annual_kwh_m2 == doctest::Approx(t[west_row].annual_kwh_m2).epsilon(0.03));
    CHECK(t[east_row].annual_kwh_m2 > t[north_row].annual_kwh_m2);
    CHECK(t[west_row].annual_kwh_m2 > t[north_row].annual_kwh_m2);
    // The south facade beats the rooftop in the winter quarters and falls below it in summer.
    CHECK(t[south_row].quarter_kwh_m2_day[0] > t[roof_row].quarter_kwh_m2_day[0]);
    CHECK(t[south_row].quarter_kwh_m2_day[3] > t[roof_row].quarter_kwh_m2_day[3]);
    CHECK(t[south_row].quarter_kwh_m2_day[1] < t[roof_row].quarter_kwh_m2_day[1]);
    CHECK(t[south_row].quarter_kwh_m2_day[2] < t[roof_row].quarter_kwh_m2_day[2]);
    // The flat open roof receives the year's GHI (clear-sky records are consistent: DNI sin e + DHI = GHI).
    CHECK(t[roof_row].annual_kwh_m2 == doctest::Approx(res.ghi_kwh_m2).epsilon(1e-9));
    for (std::size_t q = 0; q < 4; ++q) {
        CHECK(t[roof_row].quarter_kwh_m2_day[q] == doctest::Approx(res.quarter_ghi_kwh_m2_day[q]).epsilon(1e-9));
    }
    CHECK(res.quarter_days[0] == doctest::Approx(90.0));
    CHECK(res.quarter_days[0] + res.quarter_days[1] + res.quarter_days[2] + res.quarter_days[3] ==
          doctest::Approx(365.0));
    // Quarterly daily means times days add up to the annual sum, per sub-patch.
    for (std::size_t i = 0; i < res.facades.size(); i += 37) {
        double sum = 0.0;
        for (std::size_t q = 0; q < 4; ++q) sum += res.facade_energy[i].quarter_kwh_m2_day[q] * res.quarter_days[q];
        CHECK(sum == doctest::Approx(res.facade_energy[i].annual_kwh_m2).epsilon(1e-9));
    }
}

TEST_CASE("buildings/surface_energy: in the southern hemisphere the north facade is the sunniest")
{
    const auto t = box_table(-33.9, 151.2, 10.0);  // Sydney
    CHECK(t[north_row].annual_kwh_m2 > t[east_row].annual_kwh_m2);
    CHECK(t[north_row].annual_kwh_m2 > t[west_row].annual_kwh_m2);
    CHECK(t[north_row].annual_kwh_m2 > t[south_row].annual_kwh_m2);
    CHECK(t[east_row].annual_kwh_m2 > t[south_row].annual_kwh_m2);
    // Winter there is the middle of the year: the north facade beats the roof in Apr-Jun and Jul-Sep.
    CHECK(t[north_row].quarter_kwh_m2_day[1] > t[roof_row].quarter_kwh_m2_day[1]);
    CHECK(t[north_row].quarter_kwh_m2_day[0] < t[roof_row].quarter_kwh_m2_day[0]);
}

TEST_CASE("buildings/surface_energy: a neighbour's shadow lowers the lower levels; results independent of threads")
{
    std::mt19937 rng(7);
    const auto s = reference::box_town_ids(rng, 70, 64, 24);
    const auto records = clear_sky_records(2021, 40.0, -75.0, {.interval = std::chrono::hours{3}});
    const auto one = surface_energy(s.dsm, s.ids, 1.0, {40.0, -75.0}, records, {.run = {.threads = 1}});
    REQUIRE(one.facades.size() > 200);
    // Bit for bit at 2 and 3 threads: the sweeps of a batch go to whichever thread is free, the sums never do.
    for (const int threads : {2, 3}) {
        CAPTURE(threads);
        const auto other = surface_energy(s.dsm, s.ids, 1.0, {40.0, -75.0}, records, {.run = {.threads = threads}});
        CHECK(other.roof_sky_view == one.roof_sky_view);
        CHECK(other.facade_sky_view == one.facade_sky_view);
        REQUIRE(one.facade_energy.size() == other.facade_energy.size());
        REQUIRE(one.roof_energy.size() == other.roof_energy.size());
        for (std::size_t i = 0; i < one.facade_energy.size(); ++i) {
            CHECK(one.facade_energy[i].annual_kwh_m2 == other.facade_energy[i].annual_kwh_m2);
            CHECK(one.facade_energy[i].quarter_kwh_m2_day == other.facade_energy[i].quarter_kwh_m2_day);
        }
        for (std::size_t i = 0; i < one.roof_energy.size(); ++i) {
            CHECK(one.roof_energy[i].annual_kwh_m2 == other.roof_energy[i].annual_kwh_m2);
            CHECK(one.roof_energy[i].quarter_kwh_m2_day == other.roof_energy[i].quarter_kwh_m2_day);
        }
    }
    // In a town the lowest level of a wall never gets more than its top level (more horizon, more shadow).
    std::size_t walls = 0, less = 0;
    for (std::size_t i = 0; i + 7 < one.facades.size(); i += 8) {
        REQUIRE(one.facades[i].level == 0);
        ++walls;
        CHECK(one.facade_energy[i].annual_kwh_m2 <= one.facade_energy[i + 7].annual_kwh_m2 + 1e-9);
        less += one.facade_energy[i].annual_kwh_m2 < 0.95 * one.facade_energy[i + 7].annual_kwh_m2;
    }
    CHECK(less > walls / 10);
}

TEST_CASE("buildings/bill_savings: the dissertation's Table 1 gives its Table 2 with the default system")
{
    // Table 1 (kWh/m^2/day per quarter, kWh/m^2/yr) and Table 2 ($/day, $/yr) of the dissertation.
    const double t1[5][5] = {{0.74, 1.45, 1.23, 0.65, 374.05},
                             {2.98, 1.98, 2.23, 3.17, 944.49},
                             {1.93, 2.66, 2.89, 1.82, 850.21},
                             {1.58, 2.64, 2.42, 1.50, 743.32},
                             {3.67, 6.27, 6.18, 3.38, 1780.80}};
    const double t2[5][5] = {{0.23, 0.45, 0.38, 0.20, 114.99},
                             {0.92, 0.61, 0.69, 0.97, 290.36},
                             {0.59, 0.82, 0.89, 0.56, 261.37},
                             {0.49, 0.81, 0.74, 0.46, 228.51},
                             {1.13, 1.93, 1.90, 1.04, 547.45}};
    std::array<surface_class_row, 5> table{};
    for (std::size_t k = 0; k < 5; ++k) {
        table[k].kind = static_cast<surface_class>(k);
        for (std::size_t q = 0; q < 4; ++q) table[k].quarter_kwh_m2_day[q] = t1[k][q];
        table[k].annual_kwh_m2 = t1[k][4];
    }
    const auto bill = bill_savings(table);
    for (std::size_t k = 0; k < 5; ++k) {
        CHECK(bill[k].kind == table[k].kind);
        for (std::size_t q = 0; q < 4; ++q)
            CHECK(std::fabs(bill[k].quarter_per_day[q] - t2[k][q]) <
                  0.01);  // 2 printed decimals; South Q4 is off by 0.008
        CHECK(bill[k].annual == doctest::Approx(t2[k][4]).epsilon(0.005));
    }
    // Twice the tariff, twice the saving; no modules' loss, more saving.
    const auto dear = bill_savings(table, {.tariff_per_kwh = 0.22});
    CHECK(dear[4].annual == doctest::Approx(2.0 * bill[4].annual));
    CHECK(bill_savings(table, {.temperature_loss = 0.0})[4].annual > bill[4].annual);
    CHECK_THROWS_AS(bill_savings(table, {.module_efficiency = 0.0}), invalid_input);
    CHECK_THROWS_AS(bill_savings(table, {.inverter_efficiency = 1.5}), invalid_input);
    CHECK_THROWS_AS(bill_savings(table, {.temperature_loss = 1.0}), invalid_input);
    CHECK_THROWS_AS(bill_savings(table, {.modules = 0}), invalid_input);
    CHECK_THROWS_AS(bill_savings(table, {.module_width_in = -65.0}), invalid_input);
    CHECK_THROWS_AS(bill_savings(table, {.tariff_per_kwh = -0.1}), invalid_input);
}

TEST_CASE("buildings/facade_class: facing-azimuth quadrants")
{
    CHECK(facade_class(0.0) == surface_class::north_facade);
    CHECK(facade_class(44.9) == surface_class::north_facade);
    CHECK(facade_class(45.0) == surface_class::east_facade);
    CHECK(facade_class(180.0) == surface_class::south_facade);
    CHECK(facade_class(225.0) == surface_class::west_facade);
    CHECK(facade_class(315.0) == surface_class::north_facade);
    CHECK(facade_class(-90.0) == surface_class::west_facade);
}

namespace {

/// The largest relative difference between surface_energy's annual sums and its formula added sun by sun with the
/// public kernels: beam from raylines_shadow's single family (roofs) and facade_lit (walls), diffuse from the sky
/// views surface_energy reports.
double worst_against_formula(const raster<float>& dsm, const raster<std::int32_t>& ids,
                             const std::vector<irradiance_record>& records, const solar_site& site, int threads)
{
    const auto res = surface_energy(dsm, ids, 1.0, site, records, {.run = {.threads = threads}});
    std::vector<double> roof(res.roofs.size(), 0.0), facade(res.facades.size(), 0.0);
    for (const daylight_sun& d : daylight_suns(records, site)) {
        const double dni = d.dni_w_m2 * d.kwh_per_w_m2, dhi = d.dhi_w_m2 * d.kwh_per_w_m2;
        const auto lit = raylines_shadow(dsm, 1.0, d.azimuth_deg, d.elevation_deg, {.nan_cell = 0, .line_phases = 1});
        for (std::size_t i = 0; i < res.roofs.size(); ++i) {
            const surface_patch& p = res.roofs[i];
            const double share =
                0.25 * (lit(p.row, p.col) + lit(p.row, p.col + 1) + lit(p.row + 1, p.col) + lit(p.row + 1, p.col + 1));
            const double cos_t = enu_dot(d.sun, p.normal);
            roof[i] += (cos_t > 0.0 ? dni * cos_t * share : 0.0) + dhi * res.roof_sky_view[i];
        }
        const auto walls =
            facade_lit(dsm, std::span<const facade_patch>(res.facades), 1.0, d.azimuth_deg, d.elevation_deg);
        for (std::size_t i = 0; i < res.facades.size(); ++i) {
            const double cos_t =
                std::cos(d.elevation_deg * std::numbers::pi / 180.0) *
                std::cos((d.azimuth_deg - res.facades[i].facing_azimuth_deg) * std::numbers::pi / 180.0);
            facade[i] += (walls[i] == 1 ? dni * cos_t : 0.0) + dhi * res.facade_sky_view[i];
        }
    }
    REQUIRE(res.facades.size() > 100);
    double worst = 0.0;
    for (std::size_t i = 0; i < roof.size(); ++i)
        worst = std::max(worst, std::fabs(res.roof_energy[i].annual_kwh_m2 - roof[i]) / roof[i]);
    for (std::size_t i = 0; i < facade.size(); ++i)
        worst = std::max(worst, std::fabs(res.facade_energy[i].annual_kwh_m2 - facade[i]) / facade[i]);
    return worst;
}

}  // namespace

TEST_CASE("buildings/surface_energy: every patch's sum is its formula added sun by sun with the public kernels")
{
    // surface_energy sweeps its suns in batches, side by side, shallow ones along the rows of the transposed DSM,
    // adds a wall's beam once at its lowest lit sub-patch and the diffuse once per quarter; per patch the sums
    // must still be the formula's. The raster is not square, so a transposed layout mixed up would show.
    std::mt19937 rng(31);
    const auto s = reference::box_town_ids(rng, 48, 52, 10);
    const auto records = clear_sky_records(2021, 40.0, -75.0, {.interval = std::chrono::hours{6}});
    const solar_site site{40.0, -75.0};
    CHECK(worst_against_formula(s.dsm, s.ids, records, site, 1) < 1e-9);
    CHECK(worst_against_formula(s.dsm, s.ids, records, site, 2) < 1e-9);
    SUBCASE("overcast records (no beam, not swept) and no-data cells")
    {
        auto dull = records;
        for (std::size_t i = 0; i < dull.size(); i += 3) dull[i].dni_w_m2 = 0.0;
        auto holes = s.dsm;
        for (std::ptrdiff_t r = 0; r < holes.rows(); r += 7)
            for (std::ptrdiff_t c = 0; c < holes.cols(); c += 5)
                if (s.ids(r, c) == 0) holes(r, c) = std::numeric_limits<float>::quiet_NaN();
        CHECK(worst_against_formula(holes, s.ids, dull, site, 2) < 1e-9);
    }
}

TEST_CASE("buildings/surface_energy: a raster without rows or without columns gives an empty result")
{
    const auto records = clear_sky_records(2021, 40.0, -75.0, {.interval = std::chrono::hours{3}});
    for (const auto& [rows, cols] : {std::pair<std::ptrdiff_t, std::ptrdiff_t>{0, 5}, {5, 0}, {0, 0}}) {
        const auto res = surface_energy(raster<float>(rows, cols), raster<std::int32_t>(rows, cols), 1.0, {40.0, -75.0},
                                        records, {.run = {.threads = 2}});
        CHECK(res.roofs.empty());
        CHECK(res.facades.empty());
        CHECK(res.sun_up_records > 0);
    }
}

TEST_CASE("buildings/surface_energy: progress, cancellation and refusals")
{
    const auto s = reference::one_box(20, 20, 8, 8, 4, 4, 0.0f, 9.0f);
    const auto records = clear_sky_records(2021, 36.0, -80.0, {.interval = std::chrono::hours{6}});
    reference::progress_log log;
    surface_energy(s.dsm, s.ids, 1.0, {36.0, -80.0}, records,
                   {.sky = {.svf_directions = 8}, .run = {.progress = log.callback()}});
    CHECK(log.monotone_to_one());
    CHECK_THROWS_AS(surface_energy(s.dsm, s.ids, 1.0, {36.0, -80.0}, records,
                                   {.run = {.progress = [](double f) { return f < 0.5; }}}),
                    cancelled);
    const raster<std::int32_t> other(19, 20, 0);
    CHECK_THROWS_AS(surface_energy(s.dsm, other, 1.0, {36.0, -80.0}, records), invalid_input);
    CHECK_THROWS_AS(surface_energy(s.dsm, s.ids, 0.0, {36.0, -80.0}, records), invalid_input);
    CHECK_THROWS_AS(surface_energy(s.dsm, s.ids, 1.0, {95.0, -80.0}, records), invalid_input);
    CHECK_THROWS_AS(surface_energy(s.dsm, s.ids, 1.0, {36.0, -80.0}, records, {.sky = {.svf_directions = 2}}),
                    invalid_input);
    CHECK_THROWS_AS(surface_energy(s.dsm, s.ids, 1.0, {36.0, -80.0, 20.0}, records), invalid_input);
    auto bad = records;
    bad[3].dni_w_m2 = -1.0;
    CHECK_THROWS_AS(surface_energy(s.dsm, s.ids, 1.0, {36.0, -80.0}, bad), invalid_input);
}
