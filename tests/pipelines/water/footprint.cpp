// SPDX-License-Identifier: Apache-2.0
// Waterbodies inside a survey's footprint: empty space that was never flown is no data, never water.
#include <doctest/doctest.h>

#include <lidarfx/kernels/filter/survey_footprint.hpp>
#include <lidarfx/kernels/points/rasterize.hpp>
#include <lidarfx/kernels/points/scan_coverage.hpp>
#include <lidarfx/pipelines/water/extract_waterbodies.hpp>
#include <lidarfx/synth/scenes.hpp>

#include <cmath>
#include <cstdint>

using namespace lidarfx;

namespace {

/// The points of `sc` within `radius_m` of the scene's centre (a tile clipped to a circle), in scan order.
synth::point_set clip_to_circle(const synth::scene& sc, double radius_m)
{
    const auto& p = sc.points;
    const auto ext = sc.truth.g.extent();
    const double cx = 0.5 * (ext.xmin + ext.xmax), cy = 0.5 * (ext.ymin + ext.ymax);
    synth::point_set out;
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (std::hypot(p.x[i] - cx, p.y[i] - cy) > radius_m) continue;
        out.pulse_time_s = p.gps_time[i];
        out.push(p.x[i], p.y[i], p.z[i], p.intensity[i], p.return_number[i], p.number_of_returns[i],
                 p.classification[i]);
    }
    return out;
}

struct clipped_run {
    synth::scene scene;
    rasterize_result rasters;
    raster<std::uint8_t> footprint;
    double radius_m = 0;

    /// Water cells whose centre lies more than a cell beyond the circle.
    std::size_t water_outside(const raster<std::uint8_t>& water) const
    {
        const auto& g = rasters.g;
        const auto ext = g.extent();
        const double cx = 0.5 * (ext.xmin + ext.xmax), cy = 0.5 * (ext.ymin + ext.ymax);
        std::size_t n = 0;
        for (std::ptrdiff_t r = 0; r < g.rows; ++r)
            for (std::ptrdiff_t c = 0; c < g.cols; ++c) {
                const auto [x, y] = g.center(r, c);
                n += water(r, c) && std::hypot(x - cx, y - cy) > radius_m + g.cell;
            }
        return n;
    }
};

clipped_run lake_in_circle()
{
    clipped_run run{synth::lake_scene(), {}, {}, 0.45 * synth::scene_options{}.size_m};
    const auto points = clip_to_circle(run.scene, run.radius_m);
    const grid& g = run.scene.truth.g;
    run.rasters = rasterize(points.cloud(), g);
    scan_coverage scans(g);
    scans.add(points.x, points.y, points.gps_time);
    raster<std::uint8_t> covered(g.rows, g.cols);
    for (std::ptrdiff_t i = 0; i < covered.size(); ++i)
        covered.data()[i] = !run.rasters.dropout.data()[i] || scans.covered().data()[i];
    run.footprint = survey_footprint(covered, g.cell);
    return run;
}

}  // namespace

TEST_CASE("water/footprint: on a tile clipped to a circle the empty corners are no data, not a lake")
{
    const auto run = lake_in_circle();
    const double cell_m = run.rasters.g.cell;
    // Without a footprint the corners' empty cells are dropouts, and become water (the failure this fixes).
    const auto blind = extract_waterbodies(run.rasters, {.check_inputs = false});
    CHECK(run.water_outside(blind.water) > 1000);

    auto inputs = to_water_rasters(run.rasters);
    inputs.footprint = run.footprint;
    const auto seen = extract_waterbodies(inputs, cell_m);
    REQUIRE(seen.ran);
    CHECK(run.water_outside(seen.water) == 0);
    // More than the disc's radius inside the circle the lake is found as on the whole tile (nearer the cut,
    // where the lake meets the unflown space, nothing tells water from "not flown").
    const auto& truth = run.scene.truth.water_filled;
    const auto& g = run.rasters.g;
    const double inner_m = run.radius_m - survey_footprint_options{}.hull_radius_m - g.cell;
    std::size_t true_inside = 0, found_inside = 0;
    for (std::ptrdiff_t r = 0; r < g.rows; ++r)
        for (std::ptrdiff_t c = 0; c < g.cols; ++c) {
            const auto [x, y] = g.center(r, c);
            const auto ext = g.extent();
            if (std::hypot(x - 0.5 * (ext.xmin + ext.xmax), y - 0.5 * (ext.ymin + ext.ymax)) > inner_m) continue;
            true_inside += truth(r, c) != 0;
            found_inside += truth(r, c) && seen.water(r, c);
        }
    REQUIRE(true_inside > 1000);
    CHECK(static_cast<double>(found_inside) >= 0.97 * static_cast<double>(true_inside));
}

TEST_CASE("water/footprint: a footprint covering every cell changes nothing; outside cells never seed")
{
    const auto sc = synth::river_scene();
    const auto rasters = rasterize(sc.points.cloud(), sc.truth.g);
    const auto plain = extract_waterbodies(rasters);
    raster<std::uint8_t> everywhere(sc.truth.g.rows, sc.truth.g.cols, 1);
    auto inputs = to_water_rasters(rasters);
    inputs.footprint = everywhere;
    const auto same = extract_waterbodies(inputs, sc.truth.g.cell);
    CHECK(same.labels == plain.labels);
    CHECK(same.bodies.size() == plain.bodies.size());
    // Nothing flown: every cell is outside, so nothing is water.
    raster<std::uint8_t> nowhere(sc.truth.g.rows, sc.truth.g.cols, 0);
    inputs.footprint = nowhere;
    const auto none = extract_waterbodies(inputs, sc.truth.g.cell, {.check_inputs = false});
    CHECK(none.bodies.empty());
    raster<std::uint8_t> wrong_shape(3, 3, 1);
    inputs.footprint = wrong_shape;
    CHECK_THROWS_AS(extract_waterbodies(inputs, sc.truth.g.cell), invalid_input);
}
