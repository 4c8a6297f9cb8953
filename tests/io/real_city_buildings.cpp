// SPDX-License-Identifier: Apache-2.0
// Buildings of a real city survey against the vendor's own building class: a 50 m tile of IGN's LiDAR HD over
// Montpellier (committed fixture, tests/data/README.md), 29 points/m², apartment blocks, trees and gardens,
// classified by IGN (2 ground, 3-5 vegetation, 6 building).
#include <doctest/doctest.h>

#include "io/las.hpp"

#include <lidarfx/kernels/filter/surface_outliers.hpp>
#include <lidarfx/kernels/interpolate/idw_fill.hpp>
#include <lidarfx/kernels/points/count_points_above.hpp>
#include <lidarfx/kernels/points/rasterize.hpp>
#include <lidarfx/pipelines/buildings/extract_buildings.hpp>
#include <lidarfx/pipelines/buildings/morphological_ground.hpp>

#include <cmath>
#include <cstdint>
#include <string>

using namespace lidarfx;

namespace {

/// Recall and precision by area of found building cells against the cells where at least half of the points
/// are class 6, over the cells with points.
struct area_scores {
    double recall = 0, precision = 0, iou = 0;
};

area_scores score_against_class_6(raster_view<const std::int32_t> found, const rasterize_result& all,
                                  const rasterize_result& class_6)
{
    double hit = 0, truth = 0, claimed = 0;
    for (std::ptrdiff_t r = 0; r < found.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < found.cols(); ++c) {
            if (all.count(r, c) == 0) continue;
            const bool is_building = 2 * class_6.count(r, c) >= all.count(r, c);
            const bool was_found = found(r, c) > 0;
            truth += is_building;
            claimed += was_found;
            hit += is_building && was_found;
        }
    }
    return {hit / truth, hit / claimed, hit / (truth + claimed - hit)};
}

}  // namespace

TEST_CASE("io/real city: extract_buildings with the survey's pulse counts and ground finds IGN's class-6 blocks")
{
    const io::las_points pts =
        io::read_las(std::string(LIDARFX_TEST_DATA_DIR) + "/lidarhd_montpellier_77055_627755.laz");
    REQUIRE(pts.size() == 72770);
    // 1 m cells over the tile (x 770550-770600, y 6277500-6277550), as lidarfx solar --facades builds them.
    const grid g{770550.0, 6277550.0, 1.0, 50, 50};
    const rasterize_result all = rasterize(pts.cloud(), g);
    const rasterize_result class_6 = rasterize(pts.cloud(), g, {.classes = {.include = {6}}});
    const rasterize_result class_2 = rasterize(pts.cloud(), g, {.classes = {.include = {2}}});
    REQUIRE(all.points_outside == 0);
    const raster<float> dsm = remove_surface_outliers(idw_fill(all.max_z, g.cell).filled).surface;

    // Trees by their split pulses, the terrain from class 2: both blocks, and little else.
    const extract_buildings_result b =
        extract_buildings(dsm, g, class_2.min_z, pulse_returns{all.count, all.multiple_return_count});
    const area_scores s = score_against_class_6(b.building_id, all, class_6);
    CAPTURE(s.recall);
    CAPTURE(s.precision);
    CHECK(s.recall >= 0.90);
    CHECK(s.precision >= 0.90);

    // Each building's rim decided by the share of its points raised above the filled class-2 terrain (as lidarfx
    // solar --facades does on LAS input): walls' cells of ground points leave, eaves of split pulses join.
    const raster<float> terrain = fill_ground(class_2.min_z, g.cell);
    const raster<std::uint32_t> raised =
        count_points_above(pts.cloud(), g, terrain.view(), building_candidates_options{}.min_height_m);
    const extract_buildings_result rim =
        extract_buildings(dsm, g, terrain, pulse_returns{all.count, all.multiple_return_count, raised});
    const area_scores with_rim = score_against_class_6(rim.building_id, all, class_6);
    CAPTURE(with_rim.recall);
    CAPTURE(with_rim.precision);
    CHECK(with_rim.recall >= 0.90);
    CHECK(with_rim.precision >= 0.90);
    CHECK(with_rim.iou > s.iou + 0.01);

    // The vendor's buildings taken as they are (--buildings class6): the cells of a class-6 majority, parts
    // under 15 m^2 dropped and holes under it filled, roof surfaces found on them.
    raster<std::uint8_t> class_6_cells(g.rows, g.cols);
    for (std::ptrdiff_t r = 0; r < g.rows; ++r)
        for (std::ptrdiff_t c = 0; c < g.cols; ++c)
            class_6_cells(r, c) = all.count(r, c) > 0 && 2 * class_6.count(r, c) >= all.count(r, c) ? 1 : 0;
    const extract_buildings_result vendor = extract_classified_buildings(dsm, g, terrain, class_6_cells);
    const area_scores v = score_against_class_6(vendor.building_id, all, class_6);
    CAPTURE(v.recall);
    CAPTURE(v.precision);
    CHECK(v.recall >= 0.98);
    CHECK(v.precision >= 0.98);
    CHECK(vendor.buildings.size() >= 2);
    CHECK(!vendor.surfaces.empty());
    CHECK(vendor.rejected_rough == 0);
    // An empty mask is a mask of the wrong shape, not a request for the points' route.
    CHECK_THROWS_AS(extract_classified_buildings(dsm, g, terrain, raster_view<const std::uint8_t>{}), invalid_input);

    // For the record (bench/buildings_real_surveys.sh): every cell holding a split pulse taken as a tree loses
    // most of the blocks, whose edges and ridges split pulses.
    const extract_buildings_result any_split = extract_buildings(dsm, g, class_2.min_z, all.multiple_returns);
    MESSAGE("any split pulse a tree: recall " << score_against_class_6(any_split.building_id, all, class_6).recall);

    // Without the classes: the ground of a morphological filter on the lowest points does as well.
    const extract_buildings_result filtered = extract_buildings(dsm, g, morphological_ground(all.min_z, g.cell).ground,
                                                                pulse_returns{all.count, all.multiple_return_count});
    const area_scores f = score_against_class_6(filtered.building_id, all, class_6);
    CAPTURE(f.recall);
    CAPTURE(f.precision);
    CHECK(f.recall >= 0.90);
    CHECK(f.precision >= 0.90);

    // And the terrain found from the surface alone (edges and their hulls) misses most of a block that fills the
    // tile.
    const extract_buildings_result model =
        extract_buildings(dsm, g, {}, pulse_returns{all.count, all.multiple_return_count});
    MESSAGE("terrain from the DSM's edge hulls: recall "
            << score_against_class_6(model.building_id, all, class_6).recall);
}
