// SPDX-License-Identifier: Apache-2.0
// roof_yield: a patch's irradiation is what irradiance_maps gives its cells with the patch's plane as their
// surface, averaged; shading by a neighbour lowers it; the energy follows the system size.
#include <doctest/doctest.h>

#include <lidarfx/kernels/solar/clear_sky.hpp>
#include <lidarfx/pipelines/pv/roof_suitability.hpp>
#include <lidarfx/pipelines/pv/roof_yield.hpp>
#include <lidarfx/pipelines/solar/irradiance_maps.hpp>

#include <cmath>
#include <cstdint>
#include <vector>

using namespace lidarfx;

namespace {

// 48 x 48 cells of 1 m on flat ground at 100 m: a shed roof facing south (rises 0.5 m per row to the north,
// tilt 26.57 deg) on rows 10..21, columns 10..29 (building 1), a flat roof at 108 m on rows 30..41, columns
// 10..24 (building 2) and, when `tower`, a 40 m tower just south-east of the shed that shades it.
struct scene {
    raster<float> dsm{48, 48, 100.0f}, dtm{48, 48, 100.0f};
    raster<std::int32_t> ids{48, 48, 0};
    grid g{0.0, 48.0, 1.0, 48, 48};
};

scene make_scene(bool tower)
{
    scene s;
    for (std::ptrdiff_t r = 10; r < 22; ++r)
        for (std::ptrdiff_t c = 10; c < 30; ++c) {
            s.dsm(r, c) = static_cast<float>(106.0 + 0.5 * static_cast<double>(21 - r));
            s.ids(r, c) = 1;
        }
    for (std::ptrdiff_t r = 30; r < 42; ++r)
        for (std::ptrdiff_t c = 10; c < 25; ++c) {
            s.dsm(r, c) = 108.0f;
            s.ids(r, c) = 2;
        }
    if (tower) {
        for (std::ptrdiff_t r = 23; r < 27; ++r)
            for (std::ptrdiff_t c = 30; c < 34; ++c) s.dsm(r, c) = 140.0f;
    }
    return s;
}

}  // namespace

TEST_CASE(
    "pv/roof_yield: each patch gets the mean of irradiance_maps over its cells on the patch's plane, with "
    "and without a meridian convergence")
{
    const scene s = make_scene(true);
    const auto roofs = roof_suitability(s.dsm, s.dtm, s.ids, s.g);
    REQUIRE(roofs.patches.size() >= 2);
    const auto records = clear_sky_records(2023, 40.0, -105.0);
    // The same physics through irradiance_maps: every cell of a patch tilted as its patch.
    raster<float> tilt(48, 48, 0.0f), azimuth(48, 48, 0.0f);
    for (const roof_patch& p : roofs.patches)
        for (std::ptrdiff_t r = 0; r < 48; ++r)
            for (std::ptrdiff_t c = 0; c < 48; ++c)
                if (roofs.patch_id(r, c) == p.patch_id) {
                    tilt(r, c) = static_cast<float>(p.tilt_deg);
                    azimuth(r, c) = static_cast<float>(p.azimuth_deg);
                }
    std::vector<double> shed(2, 0.0);
    for (const double convergence : {0.0, -2.4}) {
        INFO("meridian convergence ", convergence);
        const solar_site site{.latitude_deg = 40.0,
                              .longitude_deg = -105.0,
                              .utc_offset_h = -7.0,
                              .meridian_convergence_deg = convergence};
        const auto yield = roof_yield(s.dsm, 1.0, roofs, site, records);
        REQUIRE(yield.size() == roofs.patches.size());
        const auto maps = irradiance_maps(s.dsm, 1.0, site, records, tilt.view(), azimuth.view());
        for (std::size_t i = 0; i < roofs.patches.size(); ++i) {
            const roof_patch& p = roofs.patches[i];
            double sum = 0, n = 0;
            for (std::ptrdiff_t r = 0; r < 48; ++r)
                for (std::ptrdiff_t c = 0; c < 48; ++c)
                    if (roofs.patch_id(r, c) == p.patch_id) {
                        sum += maps.annual_kwh_m2(r, c);
                        n += 1;
                    }
            INFO("patch ", p.patch_id, " tilt ", p.tilt_deg, " azimuth ", p.azimuth_deg);
            CHECK(yield[i].patch_id == p.patch_id);
            CHECK(yield[i].annual_kwh_m2 == doctest::Approx(sum / n).epsilon(1e-5));
            CHECK(yield[i].annual_kwh == doctest::Approx(yield[i].annual_kwh_m2 * p.kwp * 0.8));
            if (p.building_id == 1 && p.tilt_deg > 20) shed[convergence == 0.0 ? 0 : 1] = yield[i].annual_kwh_m2;
        }
    }
    // The convergence turns the sun against the shed and its tower: the yield moves.
    CHECK(shed[0] > 0.0);
    CHECK(shed[1] != shed[0]);
}

TEST_CASE("pv/roof_yield: a south-facing patch beats a flat one at 40 N, a tower's shadow costs energy")
{
    const auto records = clear_sky_records(2023, 40.0, -105.0);
    double open_shed = 0, shaded_shed = 0, flat = 0;
    for (const bool tower : {false, true}) {
        const scene s = make_scene(tower);
        const auto roofs = roof_suitability(s.dsm, s.dtm, s.ids, s.g);
        const auto yield = roof_yield(s.dsm, 1.0, roofs, {40.0, -105.0}, records, {.run = {.threads = tower ? 2 : 1}});
        for (std::size_t i = 0; i < roofs.patches.size(); ++i) {
            if (roofs.patches[i].building_id == 1 && roofs.patches[i].tilt_deg > 20) {
                (tower ? shaded_shed : open_shed) = yield[i].annual_kwh_m2;
            }
            if (roofs.patches[i].building_id == 2 && !tower) flat = yield[i].annual_kwh_m2;
        }
    }
    MESSAGE("south shed open ", open_shed, ", shaded ", shaded_shed, ", flat ", flat, " kWh/m2");
    CHECK(open_shed > 1.05 * flat);
    CHECK(shaded_shed < open_shed);
    CHECK(shaded_shed > 0.5 * open_shed);
}

TEST_CASE("pv/roof_yield: no patches, bad inputs")
{
    const scene s = make_scene(false);
    roof_suitability_result none{raster<std::int32_t>(48, 48, 0), {}, {}};
    const auto records = clear_sky_records(2023, 40.0, -105.0);
    CHECK(roof_yield(s.dsm, 1.0, none, {40.0, -105.0}, records).empty());
    CHECK_THROWS_AS(roof_yield(s.dsm, 0.0, none, {40.0, -105.0}, records), invalid_input);
    CHECK_THROWS_AS(roof_yield(s.dsm, 1.0, none, {40.0, -105.0}, records, {.performance_ratio = 0}), invalid_input);
    CHECK_THROWS_AS(roof_yield(s.dsm, 1.0, none, {40.0, -105.0}, records, {.sky = {.diffuse = diffuse_model::perez}}),
                    invalid_input);
    CHECK_THROWS_AS(roof_yield(s.dsm, 1.0, none, {40.0, -105.0, 0.0, 95.0}, records), invalid_input);
    roof_suitability_result wrong{raster<std::int32_t>(4, 4, 0), {}, {}};
    CHECK_THROWS_AS(roof_yield(s.dsm, 1.0, wrong, {40.0, -105.0}, records), invalid_input);
}
