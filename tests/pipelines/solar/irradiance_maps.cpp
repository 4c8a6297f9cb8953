// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/kernels/filter/slope_aspect.hpp>
#include <lidarfx/kernels/solar/clear_sky.hpp>
#include <lidarfx/kernels/solar/incidence.hpp>
#include <lidarfx/kernels/solar/perez_diffuse.hpp>
#include <lidarfx/kernels/solar/raylines_shadow.hpp>
#include <lidarfx/kernels/solar/sky_view_factor.hpp>
#include <lidarfx/kernels/solar/sun_position.hpp>
#include <lidarfx/pipelines/solar/irradiance_maps.hpp>

#include "reference/progress.hpp"
#include "reference/solar.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

using namespace lidarfx;

namespace {

// Golden, Colorado (SPA's example site) and Cape Town.
constexpr double golden_lat = 39.742476, golden_lon = -105.1786;
constexpr double cape_lat = -33.92, cape_lon = 18.42;

// Every `step`-th day of a clear-sky year (the test stays fast; closure holds record by record).
std::vector<irradiance_record> clear_days(double lat, double lon, int step)
{
    const auto all = clear_sky_records(2021, lat, lon);
    std::vector<irradiance_record> out;
    for (std::size_t i = 0; i < all.size(); ++i) {
        if ((i / 24) % static_cast<std::size_t>(step) == 0) out.push_back(all[i]);
    }
    return out;
}

bool same_bits(const raster<float>& a, const raster<float>& b)
{
    if (a.rows() != b.rows() || a.cols() != b.cols()) return false;
    for (std::ptrdiff_t r = 0; r < a.rows(); ++r) {
        if (std::memcmp(a.view().row(r), b.view().row(r), sizeof(float) * static_cast<std::size_t>(a.cols())) != 0) {
            return false;
        }
    }
    return true;
}

// A 10 m high block on flat ground: rows 20..22, columns 15..25 of a 40 x 40 raster with 1 m cells.
raster<float> block_scene()
{
    raster<float> z(40, 40, 0.0f);
    for (std::ptrdiff_t r = 20; r <= 22; ++r)
        for (std::ptrdiff_t c = 15; c <= 25; ++c) z(r, c) = 10.0f;
    return z;
}

// The annual map by its definition, record by record in double: each daylight sun's own raylines_shadow pass,
// then beam + diffuse (+ reflected) per cell, as irradiance_maps documents (isotropic or Perez sky, clamped or not).
raster<double> annual_by_definition(const raster<float>& z, double cell_m, const solar_site& site,
                                    const std::vector<irradiance_record>& records, const raster<float>* tilt,
                                    const raster<float>* aspect, const irradiance_maps_options& opt)
{
    raster<double> sum(z.rows(), z.cols(), 0.0);
    const raster<float> svf =
        sky_view_factor(z, cell_m, {.method = opt.sky.svf_method, .directions = opt.sky.svf_directions});
    const bool perez = opt.sky.diffuse == diffuse_model::perez;
    for (const daylight_sun& d : daylight_suns(records, site)) {
        const auto lit = raylines_shadow(z, cell_m, d.azimuth_deg, d.elevation_deg,
                                         {.nan_cell = 0, .line_phases = opt.shadow_line_phases});
        const double k = d.kwh_per_w_m2;
        const perez_sky p =
            perez ? perez_sky_coefficients(d.dhi_w_m2, d.dni_w_m2, d.elevation_deg, d.day_of_year, opt.sky.perez)
                  : perez_sky{};
        for (std::ptrdiff_t r = 0; r < z.rows(); ++r) {
            for (std::ptrdiff_t c = 0; c < z.cols(); ++c) {
                const double b = tilt ? (*tilt)(r, c) : 0.0, a = aspect ? (*aspect)(r, c) : 0.0;
                const double cos_t = tilt ? enu_dot(d.sun, surface_normal(b, a == a ? a : 0.0)) : d.sun.up;
                const bool sunny = lit(r, c) == 1 && cos_t > 0.0;
                const double cb = std::cos(b * std::numbers::pi / 180.0), sb = std::sin(b * std::numbers::pi / 180.0);
                const double circumsolar =
                    d.dhi_w_m2 * p.f1 / std::max(std::cos(85.0 * std::numbers::pi / 180.0), d.sun.up);
                double diffuse = d.dhi_w_m2 * ((1.0 - p.f1) * (1.0 + cb) / 2.0 + p.f2 * sb) * svf(r, c) +
                                 (sunny ? circumsolar * cos_t : 0.0);
                if (!opt.sky.perez.nonnegative) diffuse = std::max(0.0, diffuse);
                const double reflected = tilt ? d.ghi_w_m2 * opt.sky.albedo * (1.0 - cb) / 2.0 : 0.0;
                sum(r, c) += ((sunny ? d.dni_w_m2 * cos_t : 0.0) + diffuse + reflected) * k;
            }
        }
    }
    return sum;
}

}  // namespace

TEST_CASE("solar/irradiance_maps: equal to the sum of its formula record by record, for every sky and surface")
{
    // irradiance_maps sums the shadow-free terms per month before they meet the cells; the definition sums every
    // term per record. They differ only in rounding.
    std::mt19937 rng(606);
    const raster<float> z = reference::box_town(rng, 36, 44, 9, 0.3, 3, 9);
    const auto sa = slope_aspect(z, 1.0);
    const solar_site site{golden_lat, golden_lon};
    const auto records = clear_days(golden_lat, golden_lon, 23);
    // Modes: 0 flat isotropic; 1 tilted isotropic with albedo; 2 tilted Perez; 3 flat Perez; 4 tilted Perez
    // clamped at 0; 5 tilted isotropic with the Perez clamp asked for (the isotropic sky ignores it).
    for (int mode = 0; mode < 6; ++mode) {
        irradiance_maps_options opt;
        if (mode >= 2 && mode <= 4) opt.sky.diffuse = diffuse_model::perez;
        if (mode >= 1) opt.sky.albedo = 0.25;
        if (mode >= 4) opt.sky.perez.nonnegative = false;
        const bool tilted = mode != 3;
        const auto got =
            irradiance_maps(z, 1.0, site, records, tilted ? sa.slope_deg.view() : raster_view<const float>{},
                            tilted ? sa.aspect_deg.view() : raster_view<const float>{}, opt);
        const auto want = annual_by_definition(z, 1.0, site, records, tilted ? &sa.slope_deg : nullptr,
                                               tilted ? &sa.aspect_deg : nullptr, opt);
        double worst = 0.0, total = 0.0;
        for (std::ptrdiff_t r = 0; r < z.rows(); ++r) {
            for (std::ptrdiff_t c = 0; c < z.cols(); ++c) {
                worst = std::max(worst, std::fabs(got.annual_kwh_m2(r, c) - want(r, c)) / std::max(1e-9, want(r, c)));
                total += want(r, c);
            }
        }
        CAPTURE(mode);
        CHECK(total > 0.0);
        CHECK(worst < 2e-5);  // float maps and float normals; a missing or doubled term is >= 1e-3
    }
}

TEST_CASE("solar/irradiance_maps: on open flat ground the annual sum equals the year's GHI (energy closure)")
{
    // Clear-sky records have DNI sin e + DHI = GHI, with the sun at each interval's middle (as the maps take it).
    const auto records = clear_sky_records(2021, golden_lat, golden_lon);
    REQUIRE(records.size() == 8760);
    const raster<float> flat(12, 9, 1600.0f);
    const auto res = irradiance_maps(flat, 2.0, solar_site{golden_lat, golden_lon}, records);
    // Haurwitz's cloudless year at 40 N: about 2,000 kWh/m^2 (TMY3 sites in the US get 1,200..2,300 with clouds).
    CHECK(res.ghi_kwh_m2 > 1800.0);
    CHECK(res.ghi_kwh_m2 < 2400.0);
    CHECK(res.sun_up_records > 4300);
    CHECK(res.sun_up_records < 4500);
    for (std::ptrdiff_t r = 0; r < flat.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < flat.cols(); ++c) {
            INFO("cell ", r, ", ", c);
            CHECK(res.sky_view_factor(r, c) == 1.0f);
            CHECK(std::fabs(res.annual_kwh_m2(r, c) / res.ghi_kwh_m2 - 1.0) < 0.01);
            CHECK(std::fabs(res.annual_kwh_m2(r, c) / res.ghi_kwh_m2 - 1.0) < 1e-5);  // consistent records: exact
        }
    }
    MESSAGE("clear-sky year at Golden: GHI ", res.ghi_kwh_m2, " kWh/m^2, flat open cell ", res.annual_kwh_m2(5, 5),
            " kWh/m^2");
}

TEST_CASE("solar/irradiance_maps: the monthly maps sum to the annual map, and the monthly GHI to the year's")
{
    const auto records = clear_days(golden_lat, golden_lon, 5);
    const auto z = block_scene();
    const auto res = irradiance_maps(z, 1.0, solar_site{golden_lat, golden_lon}, records);
    double ghi = 0.0;
    for (int m = 0; m < 12; ++m) {
        ghi += res.month_ghi_kwh_m2[static_cast<std::size_t>(m)];
        CHECK(res.month_ghi_kwh_m2[static_cast<std::size_t>(m)] > 0.0);
    }
    CHECK(ghi == doctest::Approx(res.ghi_kwh_m2).epsilon(1e-12));
    // June gets more than December in the north.
    CHECK(res.month_kwh_m2[5](0, 0) > 2.0 * res.month_kwh_m2[11](0, 0));
    for (std::ptrdiff_t r = 0; r < z.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < z.cols(); ++c) {
            double sum = 0.0;
            for (const auto& m : res.month_kwh_m2) sum += m(r, c);
            INFO("cell ", r, ", ", c);
            CHECK(sum == doctest::Approx(res.annual_kwh_m2(r, c)).epsilon(1e-5));
        }
    }
}

TEST_CASE("solar/irradiance_maps: a cell in a block's shadow gets less than open ground, and less beam in winter")
{
    const auto records = clear_days(golden_lat, golden_lon, 3);
    const auto res = irradiance_maps(block_scene(), 1.0, solar_site{golden_lat, golden_lon}, records);
    const double open = res.annual_kwh_m2(0, 0), north_of_block = res.annual_kwh_m2(18, 20);
    const double south_of_block = res.annual_kwh_m2(24, 20);
    MESSAGE("open ", open, ", just north of the block ", north_of_block, ", just south ", south_of_block, " kWh/m^2");
    CHECK(north_of_block < 0.7 * open);
    CHECK(south_of_block < open);            // it sees less sky
    CHECK(south_of_block > north_of_block);  // but keeps the midday sun
    CHECK(res.month_kwh_m2[11](18, 20) < 0.5 * res.month_kwh_m2[11](0, 0));
    // Open ground far from the block keeps (nearly) the whole sky and (nearly) all its sun.
    CHECK(open > 0.95 * res.ghi_kwh_m2);
    CHECK(open <= res.ghi_kwh_m2 * (1.0 + 1e-6));
}

TEST_CASE(
    "solar/irradiance_maps: a vertical south wall gets more than a north wall in the north, and walls get "
    "half the sky")
{
    const auto records = clear_days(golden_lat, golden_lon, 5);
    const raster<float> z(4, 6, 0.0f);
    raster<float> tilt(4, 6, 90.0f), azimuth(4, 6, 180.0f);
    for (std::ptrdiff_t r = 0; r < 4; ++r)
        for (std::ptrdiff_t c = 3; c < 6; ++c) azimuth(r, c) = 0.0f;  // east half faces north
    const auto res = irradiance_maps(z, 1.0, solar_site{golden_lat, golden_lon}, records, tilt.view(), azimuth.view());
    const double south = res.annual_kwh_m2(1, 1), north = res.annual_kwh_m2(1, 4);
    MESSAGE("vertical walls at Golden: south ", south, ", north ", north, " kWh/m^2");
    CHECK(south > 2.0 * north);
    CHECK(north > 0.0);  // half the (open) sky, and the early and late summer sun
    const auto flat = irradiance_maps(z, 1.0, solar_site{golden_lat, golden_lon}, records);
    CHECK(south < flat.annual_kwh_m2(1, 1));
    // Ground reflection adds to walls and only to walls.
    const auto bright = irradiance_maps(z, 1.0, solar_site{golden_lat, golden_lon}, records, tilt.view(),
                                        azimuth.view(), {.sky = {.albedo = 0.2}});
    CHECK(bright.annual_kwh_m2(1, 4) == doctest::Approx(north + 0.2 * 0.5 * res.ghi_kwh_m2).epsilon(1e-5));
}

TEST_CASE(
    "solar/irradiance_maps: in the southern hemisphere a north-facing slope gets more than a south-facing "
    "one")
{
    // An east-west ridge with 1:2 slopes: rows above row 20 face north, rows below face south.
    raster<float> z(41, 21);
    for (std::ptrdiff_t r = 0; r < z.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < z.cols(); ++c) {
            z(r, c) = static_cast<float>(30.0 - 0.5 * static_cast<double>(std::abs(r - 20)));
        }
    const auto sa = slope_aspect(z, 1.0);
    REQUIRE(sa.aspect_deg(10, 10) == doctest::Approx(0.0).epsilon(1e-6));
    REQUIRE(sa.aspect_deg(30, 10) == doctest::Approx(180.0));
    const auto cape = irradiance_maps(z, 1.0, solar_site{cape_lat, cape_lon}, clear_days(cape_lat, cape_lon, 5),
                                      sa.slope_deg.view(), sa.aspect_deg.view());
    MESSAGE("Cape Town: north-facing slope ", cape.annual_kwh_m2(10, 10), ", south-facing ", cape.annual_kwh_m2(30, 10),
            " kWh/m^2");
    CHECK(cape.annual_kwh_m2(10, 10) > 1.1 * cape.annual_kwh_m2(30, 10));
    // The same ridge in the north: the other way round.
    const auto golden =
        irradiance_maps(z, 1.0, solar_site{golden_lat, golden_lon}, clear_days(golden_lat, golden_lon, 5),
                        sa.slope_deg.view(), sa.aspect_deg.view());
    CHECK(golden.annual_kwh_m2(30, 10) > 1.1 * golden.annual_kwh_m2(10, 10));
}

TEST_CASE("solar/irradiance_maps: the Perez sky keeps flat open ground near GHI and favours a slope facing the sun")
{
    const auto records = clear_days(golden_lat, golden_lon, 5);
    const raster<float> z(4, 6, 0.0f);
    const auto iso_flat = irradiance_maps(z, 1.0, solar_site{golden_lat, golden_lon}, records);
    const auto perez_flat = irradiance_maps(z, 1.0, solar_site{golden_lat, golden_lon}, records, {}, {},
                                            {.sky = {.diffuse = diffuse_model::perez}});
    // Flat and open: the circumsolar share lands whole on the cell while the sun is >= 5 deg high, and a little
    // less below (a / c = sin e / cos 85 < 1), so Perez gives slightly less than GHI, never more.
    const double ratio_flat = perez_flat.annual_kwh_m2(1, 1) / iso_flat.annual_kwh_m2(1, 1);
    MESSAGE("flat open ground at Golden, clear sky: Perez / isotropic = ", ratio_flat);
    CHECK(ratio_flat <= 1.0);
    CHECK(ratio_flat > 0.97);
    CHECK(perez_flat.annual_kwh_m2(1, 1) == doctest::Approx(perez_flat.ghi_kwh_m2).epsilon(0.03));

    // A 35 deg slope facing south: the bright sky around the sun is in front of it.
    const raster<float> tilt(4, 6, 35.0f), azimuth(4, 6, 180.0f);
    irradiance_maps_options south_perez;
    south_perez.sky.diffuse = diffuse_model::perez;
    const auto iso = irradiance_maps(z, 1.0, solar_site{golden_lat, golden_lon}, records, tilt.view(), azimuth.view());
    const auto per =
        irradiance_maps(z, 1.0, solar_site{golden_lat, golden_lon}, records, tilt.view(), azimuth.view(), south_perez);
    const double ratio = per.annual_kwh_m2(1, 1) / iso.annual_kwh_m2(1, 1);
    MESSAGE("35 deg south slope at Golden, clear sky: isotropic ", iso.annual_kwh_m2(1, 1), ", Perez ",
            per.annual_kwh_m2(1, 1), " kWh/m^2 (ratio ", ratio, ")");
    CHECK(ratio > 1.02);
    CHECK(ratio < 1.15);
}

TEST_CASE("solar/irradiance_maps: with the Perez sky an open cell gets beam + perez_diffuse's total for its record")
{
    // One hour, 21 June 2021 18:00-19:00 UTC at Golden (sun high in the south), on an open 30 deg slope facing
    // 160 deg: kWh/m^2 = (DNI cos theta + isotropic + circumsolar + horizon) W/m^2 * 1 h / 1000.
    std::vector<irradiance_record> records(1);
    records[0].start_utc = std::chrono::sys_days{std::chrono::year{2021} / 6 / 21} + std::chrono::hours{18};
    records[0].dni_w_m2 = 800.0;
    records[0].dhi_w_m2 = 120.0;
    records[0].ghi_w_m2 = 850.0;
    const raster<float> z(3, 4, 0.0f), tilt(3, 4, 30.0f), azimuth(3, 4, 160.0f);
    const auto res = irradiance_maps(z, 1.0, solar_site{golden_lat, golden_lon}, records, tilt.view(), azimuth.view(),
                                     {.sky = {.diffuse = diffuse_model::perez}});
    const sun_position_result sun = sun_position(records[0].middle_utc(), golden_lat, golden_lon);
    const double cos_theta = cos_incidence(sun.azimuth_deg, sun.elevation_deg, 30.0, 160.0);
    const perez_diffuse_result sky = perez_diffuse(120.0, 800.0, sun.elevation_deg, cos_theta, 30.0, 172);
    REQUIRE(sky.circumsolar_w_m2 > 0.0);
    REQUIRE(sky.horizon_w_m2 > 0.0);
    CHECK(res.sky_view_factor(1, 1) == 1.0f);
    CHECK(res.annual_kwh_m2(1, 1) == doctest::Approx((800.0 * cos_theta + sky.total_w_m2()) / 1000.0).epsilon(1e-6));
}

TEST_CASE("solar/irradiance_maps: with the Perez sky a cast shadow hides the circumsolar diffuse with the beam")
{
    const auto records = clear_days(golden_lat, golden_lon, 7);
    const raster<float> z = block_scene();
    const auto iso = irradiance_maps(z, 1.0, solar_site{golden_lat, golden_lon}, records);
    const auto per = irradiance_maps(z, 1.0, solar_site{golden_lat, golden_lon}, records, {}, {},
                                     {.sky = {.diffuse = diffuse_model::perez}});
    // North of the block (row 18: 2 m away, in its shadow for most of the year) against open ground south of it.
    const double shaded = per.annual_kwh_m2(18, 20) / iso.annual_kwh_m2(18, 20);
    const double open = per.annual_kwh_m2(35, 20) / iso.annual_kwh_m2(35, 20);
    MESSAGE("Perez / isotropic: shaded cell ", shaded, ", open cell ", open);
    CHECK(shaded < open - 0.02);
    CHECK(per.sky_view_factor(18, 20) == iso.sky_view_factor(18, 20));

    // The same for any thread count, on per-cell surfaces too, and with the published (signed) coefficients.
    raster<float> tilt(40, 40, 20.0f), azimuth(40, 40, 135.0f);
    tilt(7, 7) = std::numeric_limits<float>::quiet_NaN();
    for (bool nonnegative : {true, false}) {
        const irradiance_maps_options o{
            .sky = {.diffuse = diffuse_model::perez, .perez = {.nonnegative = nonnegative}, .albedo = 0.2},
            .run = {.threads = 1}};
        irradiance_maps_options o3 = o;
        o3.run.threads = 3;
        const auto one =
            irradiance_maps(z, 1.0, solar_site{golden_lat, golden_lon}, records, tilt.view(), azimuth.view(), o);
        const auto three =
            irradiance_maps(z, 1.0, solar_site{golden_lat, golden_lon}, records, tilt.view(), azimuth.view(), o3);
        CHECK(same_bits(one.annual_kwh_m2, three.annual_kwh_m2));
        CHECK(std::isnan(one.annual_kwh_m2(7, 7)));
        CHECK(one.annual_kwh_m2(18, 20) > 0.0);
    }
}

TEST_CASE("solar/irradiance_maps: identical results for any thread count; NaN cells; progress and cancellation")
{
    const auto records = clear_days(golden_lat, golden_lon, 11);
    raster<float> z = block_scene();
    for (std::ptrdiff_t r = 0; r < z.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < z.cols(); ++c) z(r, c) += static_cast<float>((r * 7 + c * 13) % 5) * 0.3f;
    z(3, 4) = std::numeric_limits<float>::quiet_NaN();
    const auto one =
        irradiance_maps(z, 0.5, solar_site{golden_lat, golden_lon}, records, {}, {}, {.run = {.threads = 1}});
    for (int threads : {2, 3, 0}) {
        INFO("threads ", threads);
        const auto many =
            irradiance_maps(z, 0.5, solar_site{golden_lat, golden_lon}, records, {}, {}, {.run = {.threads = threads}});
        CHECK(same_bits(one.annual_kwh_m2, many.annual_kwh_m2));
        for (std::size_t m = 0; m < 12; ++m) CHECK(same_bits(one.month_kwh_m2[m], many.month_kwh_m2[m]));
    }
    CHECK(std::isnan(one.annual_kwh_m2(3, 4)));
    CHECK(std::isnan(one.month_kwh_m2[6](3, 4)));
    CHECK(std::isfinite(one.annual_kwh_m2(3, 5)));

    reference::progress_log log;
    irradiance_maps(z, 0.5, solar_site{golden_lat, golden_lon}, records, {}, {}, {.run = {.progress = log.callback()}});
    CHECK(log.monotone_to_one(10));
    CHECK_THROWS_AS(irradiance_maps(z, 0.5, solar_site{golden_lat, golden_lon}, records, {}, {},
                                    {.run = {.progress = reference::cancel_at_once()}}),
                    cancelled);
}

TEST_CASE(
    "solar/irradiance_maps: meridian_convergence_deg turns the sun from true to grid north (a_grid = a_true - "
    "convergence)")
{
    // One hour of beam only (DHI 0): a cell's sum is DNI sin e where it is lit and 0 in shadow.
    std::vector<irradiance_record> records(1);
    records[0].start_utc = std::chrono::sys_days{std::chrono::year{2021} / 3 / 20} + std::chrono::hours{16};
    records[0].dni_w_m2 = 800.0;
    records[0].ghi_w_m2 = 500.0;
    const auto sun = sun_position(records[0].middle_utc(), golden_lat, golden_lon);
    REQUIRE(sun.elevation_deg > 10.0);
    const raster<float> z = block_scene();
    const double convergence = 25.0;  // grid north 25 degrees east of true north
    const auto turned = irradiance_maps(z, 1.0, solar_site{golden_lat, golden_lon, 0.0, convergence}, records);
    const auto lit_grid = raylines_shadow(z, 1.0, sun.azimuth_deg - convergence, sun.elevation_deg, {.nan_cell = 0});
    const auto lit_true = raylines_shadow(z, 1.0, sun.azimuth_deg, sun.elevation_deg, {.nan_cell = 0});
    std::ptrdiff_t differ = 0, shadow = 0;
    for (std::ptrdiff_t r = 0; r < z.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < z.cols(); ++c) {
            CHECK((turned.annual_kwh_m2(r, c) > 0.0f) == (lit_grid(r, c) == 1));
            differ += lit_grid(r, c) != lit_true(r, c);
            shadow += lit_grid(r, c) == 0;
        }
    }
    CHECK(shadow > 10);
    CHECK(differ > 5);  // the turn moves the shadow: the check above tells the two apart
    // 0 (the default) leaves the maps bit for bit as they were.
    CHECK(same_bits(irradiance_maps(z, 1.0, solar_site{golden_lat, golden_lon}, records).annual_kwh_m2,
                    irradiance_maps(z, 1.0, solar_site{golden_lat, golden_lon, 0.0, 0.0}, records).annual_kwh_m2));

    // A tilted cell facing grid azimuth A under convergence g gets what a cell facing A + g gets without it.
    const raster<float> flat(3, 3, 0.0f), tilt(3, 3, 40.0f), facing_grid(3, 3, 150.0f), facing_true(3, 3, 175.0f);
    const auto on_grid = irradiance_maps(flat, 1.0, solar_site{golden_lat, golden_lon, 0.0, convergence}, records,
                                         tilt.view(), facing_grid.view());
    const auto on_true =
        irradiance_maps(flat, 1.0, solar_site{golden_lat, golden_lon}, records, tilt.view(), facing_true.view());
    const auto unturned =
        irradiance_maps(flat, 1.0, solar_site{golden_lat, golden_lon}, records, tilt.view(), facing_grid.view());
    CHECK(on_grid.annual_kwh_m2(1, 1) == doctest::Approx(on_true.annual_kwh_m2(1, 1)).epsilon(1e-6));
    CHECK(std::abs(on_grid.annual_kwh_m2(1, 1) - unturned.annual_kwh_m2(1, 1)) > 0.01f);

    CHECK_THROWS_WITH_AS(irradiance_maps(z, 1.0, solar_site{golden_lat, golden_lon, 0.0, 91.0}, records),
                         doctest::Contains("meridian_convergence_deg"), invalid_input);
}

TEST_CASE("solar/irradiance_maps: bad input is refused with the argument's name")
{
    const raster<float> z(5, 5, 0.0f), tilt(5, 5, 30.0f), small(4, 5, 0.0f);
    std::vector<irradiance_record> records(1);
    records[0].start_utc = std::chrono::sys_days{std::chrono::year{2021} / 6 / 21} + std::chrono::hours{18};
    records[0].ghi_w_m2 = 500.0;
    CHECK_THROWS_WITH_AS(irradiance_maps(z, 0.0, solar_site{40.0, -105.0}, records), doctest::Contains("cell_m"),
                         invalid_input);
    CHECK_THROWS_WITH_AS(irradiance_maps(z, 1.0, solar_site{95.0, -105.0}, records), doctest::Contains("latitude_deg"),
                         invalid_input);
    CHECK_THROWS_WITH_AS(irradiance_maps(z, 1.0, solar_site{40.0, -105.0}, records, tilt.view()),
                         doctest::Contains("surface_azimuth_deg"), invalid_input);
    CHECK_THROWS_WITH_AS(irradiance_maps(z, 1.0, solar_site{40.0, -105.0}, records, small.view(), small.view()),
                         doctest::Contains("same shape"), invalid_input);
    CHECK_THROWS_WITH_AS(irradiance_maps(z, 1.0, solar_site{40.0, -105.0}, records, {}, {}, {.sky = {.albedo = 1.5}}),
                         doctest::Contains("albedo"), invalid_input);
    CHECK_THROWS_WITH_AS(
        irradiance_maps(z, 1.0, solar_site{40.0, -105.0}, records, {}, {}, {.sky = {.svf_directions = 2}}),
        doctest::Contains("irradiance_maps: sky.svf_directions"), invalid_input);
    CHECK_THROWS_WITH_AS(
        irradiance_maps(z, 1.0, solar_site{40.0, -105.0}, records, {}, {},
                        {.sky = {.diffuse = diffuse_model::perez, .perez = {.solar_constant_w_m2 = -1.0}}}),
        doctest::Contains("perez.solar_constant_w_m2"), invalid_input);
    records[0].dni_w_m2 = -3.0;
    CHECK_THROWS_WITH_AS(irradiance_maps(z, 1.0, solar_site{40.0, -105.0}, records), doctest::Contains("records[0]"),
                         invalid_input);
    records[0].dni_w_m2 = 0.0;
    records[0].interval = std::chrono::seconds{0};
    CHECK_THROWS_WITH_AS(irradiance_maps(z, 1.0, solar_site{40.0, -105.0}, records), doctest::Contains("interval"),
                         invalid_input);
}

TEST_CASE("solar/clear_sky: DNI sin e + DHI = GHI, zero at night, beam dominates a high sun")
{
    const irradiance_record high = clear_sky_irradiance(60.0, 172), low = clear_sky_irradiance(5.0, 172);
    const double s60 = std::sin(60.0 * std::numbers::pi / 180.0), s5 = std::sin(5.0 * std::numbers::pi / 180.0);
    CHECK(high.dni_w_m2 * s60 + high.dhi_w_m2 == doctest::Approx(high.ghi_w_m2).epsilon(1e-12));
    CHECK(low.dni_w_m2 * s5 + low.dhi_w_m2 == doctest::Approx(low.ghi_w_m2).epsilon(1e-12));
    CHECK(high.ghi_w_m2 == doctest::Approx(1098.0 * s60 * std::exp(-0.057 / s60)));
    CHECK(high.dni_w_m2 > 700.0);
    CHECK(high.dhi_w_m2 < 0.25 * high.ghi_w_m2);
    CHECK(low.dhi_w_m2 > 0.25 * low.ghi_w_m2);
    const irradiance_record night = clear_sky_irradiance(-3.0, 10);
    CHECK(night.ghi_w_m2 == 0.0);
    CHECK(night.dni_w_m2 == 0.0);
    CHECK(night.dhi_w_m2 == 0.0);
    const auto leap = clear_sky_records(2024, 0.0, 0.0);
    CHECK(leap.size() == 8784);
    CHECK(leap.front().start_utc == std::chrono::sys_days{std::chrono::year{2024} / 1 / 1});
    CHECK(leap[1].start_utc - leap[0].start_utc == std::chrono::hours{1});
    CHECK_THROWS_WITH_AS(clear_sky_records(2024, 0.0, 0.0, {.interval = std::chrono::seconds{7}}),
                         doctest::Contains("interval"), invalid_input);
}
