// SPDX-License-Identifier: Apache-2.0
// extract_buildings: buildings, their roof surfaces and outlines from a surface model (dissertation 3.2.1),
// with roof faces split by normal direction and trees rejected by returns and roughness. A composition of the
// steps in this folder, in order: ground_model (and replace_ground), building_candidates, local_planes and
// drop_rough_buildings, grow_roof_surfaces, dissolve_small_surfaces, assign_remaining_cells,
// merge_roof_surfaces, split_party_walls, number_roof_surfaces, building_heights, building_outlines.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/grid.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/kernels/vector/polygonize.hpp"
#include "lidarfx/pipelines/buildings/building_candidates.hpp"
#include "lidarfx/pipelines/buildings/building_heights.hpp"
#include "lidarfx/pipelines/buildings/building_outlines.hpp"
#include "lidarfx/pipelines/buildings/building_rim.hpp"
#include "lidarfx/pipelines/buildings/ground_model.hpp"
#include "lidarfx/pipelines/buildings/grow_roof_surfaces.hpp"
#include "lidarfx/pipelines/buildings/local_planes.hpp"
#include "lidarfx/pipelines/buildings/merge_roof_surfaces.hpp"
#include "lidarfx/pipelines/buildings/number_roof_surfaces.hpp"
#include "lidarfx/pipelines/buildings/party_walls.hpp"
#include "lidarfx/pipelines/buildings/roof_under_crowns.hpp"
#include "lidarfx/pipelines/buildings/vegetation_by_returns.hpp"

namespace lidarfx {

/// Settings of extract_buildings: one member per step. Defaults are for 0.25-1 m cells of a first-return DSM.
struct extract_buildings_options {
    ground_model_options ground = {};             ///< edges (>= 45 deg), edge objects (>= 10 cells), hulls, IDW
    building_candidates_options candidates = {};  ///< min_height_m (2.5 m), min_area_m2 (15 m^2)
    local_planes_options local_planes = {};       ///< plane window (1.5 m), planar tolerance, min_planar_share (0.25)
    grow_roof_surfaces_options surfaces = {};     ///< plane_angle_deg (6), step_m (0.3 m), min_surface_m2 (4 m^2)
    merge_roof_surfaces_options merge = {};       ///< merge_rms_m (0.1 m)
    vegetation_by_returns_options returns = {};   ///< cell_share (0.5), part_share (0.2), min_seen_density (0.25)
    building_rim_options rim = {};                ///< min_raised_share (0.5), join_height_m (0.5 m)
    roof_under_crowns_options under_crowns = {};  ///< plane_tolerance_m (0.3 m), max_reach_m (6 m), 90 % raised
    party_walls_options party_walls = {};         ///< min_step_m (1 m), min_wall_share (0.5), min_part_m2 (30 m^2)
    execution run = {};  ///< drives every step: threads, progress, cancellation (core/parallel.hpp); never changes
                         ///< the result
};

/// One building.
struct building_record {
    std::int32_t id = 0;                 ///< 1-based, by decreasing footprint area (as in building_id)
    std::vector<polygon> outline;        ///< building cells outlined on the grid (building_outlines)
    double ground_z = 0;                 ///< mean terrain elevation under the footprint, metres
    double eave_z = 0;                   ///< 5th percentile of the roof elevation, metres
    double ridge_z = 0;                  ///< 99th percentile of the roof elevation, metres
    double roof_area_horizontal_m2 = 0;  ///< footprint area (cells x cell_m^2)
    double roof_area_sloped_m2 = 0;      ///< sum of its surfaces' sloped areas
    std::vector<std::int32_t> surfaces;  ///< ids of its roof surfaces, largest first
    /// The building may go on beyond the raster: some cell of it lies on the raster's border (a survey's or a
    /// tile's edge). Its footprint and areas are those of the part seen.
    bool clipped = false;
};

/// Buildings of a surface model.
struct extract_buildings_result {
    raster<std::int32_t> building_id;  ///< building of each cell, 0 = none
    raster<std::int32_t> surface_id;   ///< roof surface of each building cell, 0 = none
    raster<float> ground;              ///< terrain elevation used (DTM), metres
    raster<std::uint8_t> edges;        ///< angular value >= edge angle (ground_model)
    raster<std::uint8_t> vegetation;   ///< vegetation cells as used (input mask, grown into empty cells)
    /// 1 = a building cell whose roof was found under an overhanging crown (join_roof_under_crowns): the DSM there
    /// holds the crown, not the roof. All 0 without returns.lowest.
    raster<std::uint8_t> under_crowns;
    std::vector<building_record> buildings;  ///< buildings[i].id == i + 1
    std::vector<roof_surface> surfaces;      ///< surfaces[i].id == i + 1
    std::size_t rejected_rough = 0;          ///< candidates dropped as trees: too rough, or by their returns
};

/// Buildings of a surface model (dissertation 3.2.1): `dsm` in metres (first-return max_z; NaN = no return) on
/// grid g (cells of g.cell metres; outlines in g's world coordinates); `ground` an optional terrain model of
/// the same shape (e.g. min_z of class 2; NaN cells filled by IDW; empty = found by ground_model); `vegetation`
/// an optional mask of the same shape (1 = vegetation, e.g. rasterize_result::multiple_returns of first returns
/// or vegetation_mask; never a building; empty = no return information). The steps, in order:
///  1. ground_model: DSM holes filled by IDW, edges, edge objects, one convex hull each, ground outside the
///     hulls and IDW inside (replace_ground when `ground` is given);
///  2. building_candidates: inside a hull, high above the ground, not vegetation; parts of min_area_m2;
///  3. local_planes (edge-preserving local plane fits) and drop_rough_buildings (canopy dropped); with counted
///     pulses, drop_vegetation_parts instead and refine_building_rim when raised points are counted;
///  4. grow_roof_surfaces: regions of planar cells grown by normal and height step;
///  5. dissolve_small_surfaces, assign_remaining_cells (eaves, ridges, wall tops to the nearest plane in
///     height), merge_roof_surfaces (adjacent surfaces that one plane fits), split_party_walls (a block split
///     where two roofs do not meet along most of their boundary: terraced houses of different heights);
///  6. number_roof_surfaces (by area, with tilt and azimuth), building_heights, building_outlines.
/// Buildings and surfaces are numbered by area, largest first. O(cells * ((2 w + 1)^2 + radius^2 + idw_k)), w
/// the local plane window in cells. Same result for any thread count.
/// @throws invalid_input on bad options, an invalid grid, shapes that differ from g's, or a DSM (or given
/// ground) without a finite cell; cancelled if run.progress returns false.
template <raster_input In>
extract_buildings_result extract_buildings(const In& dsm, const grid& g, raster_view<const float> ground = {},
                                           raster_view<const std::uint8_t> vegetation = {},
                                           const extract_buildings_options& opt = {});

/// extract_buildings on a survey whose pulses are counted (`returns`, e.g. rasterize_result::count and
/// multiple_return_count of the DSM's points): trees are told from roofs by their split pulses. The vegetation
/// mask is vegetation_by_returns (cells where at least returns.cell_share of the points came from pulses with
/// several returns), and step 3 drops the candidates drop_vegetation_parts finds unseen (few returns: a surface
/// interpolated over water between crowns) or vegetation (at least returns.part_share of split pulses) instead
/// of every rough part: dense old roofs at 1 m cells (dormers, chimneys, narrow gables) are rough, yet their
/// pulses are whole. When returns.raised is given (the points standing candidates.min_height_m above `ground`,
/// which must then have no NaN where a cell holds points: e.g. fill_ground's), each building's one-cell rim is
/// then decided by its points (refine_building_rim): a wall's cell whose points lie mostly on the ground leaves
/// the building, an eave cell whose pulses split on the roof's edge joins it; buildings are numbered by area
/// again. When returns.lowest is given too, the roof hidden under an overhanging crown joins its building
/// (join_roof_under_crowns: 90 % of a cell's points raised, the lowest on the roof's plane), and the steps after it
/// read the roof there, not the crown. A survey without any split pulse (single-return sensors, or number_of_returns
/// left at 1) says nothing of trees: it takes the mask route with an empty mask, rough parts dropped (its rim is still
/// decided by returns.raised when given). Otherwise as extract_buildings above; rejected_rough counts the parts dropped
/// as vegetation or unseen.
/// @throws invalid_input as extract_buildings, and if returns.points, returns.multiple or returns.raised (when
/// given) differ from the DSM's shape or some cell counts more split pulses (or raised points) than points, or
/// returns.lowest is given without returns.raised or differs from the DSM's shape.
template <raster_input In>
extract_buildings_result extract_buildings(const In& dsm, const grid& g, raster_view<const float> ground,
                                           const pulse_returns& returns, const extract_buildings_options& opt = {});

/// extract_buildings on a survey whose buildings are classified: `building_cells` (1 = building, the DSM's
/// shape; e.g. the cells where at least half of the points are of the vendor's building class, ASPRS 6) are
/// the candidates (classified_building_parts: parts and holes under candidates.min_area_m2 dropped or filled),
/// with no test of height, trees or rim; the terrain is given (`ground`, NaN cells filled by IDW) or found, and
/// the roof surfaces, numbers, heights and outlines are steps 4-6 of extract_buildings. rejected_rough is 0 and
/// vegetation all 0. @throws invalid_input as extract_buildings, and if building_cells differs from the DSM's
/// shape.
template <raster_input In>
extract_buildings_result extract_classified_buildings(const In& dsm, const grid& g, raster_view<const float> ground,
                                                      raster_view<const std::uint8_t> building_cells,
                                                      const extract_buildings_options& opt = {});

/// extract_buildings without a given terrain or vegetation mask.
template <raster_input In>
extract_buildings_result extract_buildings(const In& dsm, const grid& g, const extract_buildings_options& opt)
{
    return extract_buildings(dsm, g, raster_view<const float>{}, raster_view<const std::uint8_t>{}, opt);
}

namespace detail {

inline void check_extract_buildings(const grid& g, const extract_buildings_options& opt, const char* function)
{
    g.validate(function);
    check_ground_model(g.cell, opt.ground, function);
    check_building_candidates(opt.candidates, function);
    check_local_planes(opt.local_planes, function);
    check_grow_roof_surfaces(opt.surfaces, function);
    check_roof_under_crowns(opt.under_crowns, function);
    require(opt.merge.merge_rms_m >= 0 && opt.merge.merge_rms_m < 1e300, function, "merge_rms_m", "finite and >= 0",
            opt.merge.merge_rms_m);
    require(opt.returns.cell_share > 0 && opt.returns.cell_share <= 1, function, "returns.cell_share", "in (0, 1]",
            opt.returns.cell_share);
    require(opt.returns.part_share > 0 && opt.returns.part_share <= 1, function, "returns.part_share", "in (0, 1]",
            opt.returns.part_share);
    require(opt.returns.min_seen_density >= 0 && opt.returns.min_seen_density <= 1, function,
            "returns.min_seen_density", "in [0, 1]", opt.returns.min_seen_density);
    check_building_rim(opt.rim, function);
    check_party_walls(opt.party_walls, function);
    check_execution(opt.run, function);
}

/// clipped[b - 1] for buildings 1..count of `ids`: some cell of b lies on the raster's border
/// (building_record::clipped). O(rows + cols).
inline std::vector<bool> clipped_buildings(raster_view<const std::int32_t> ids, std::size_t count)
{
    std::vector<bool> clipped(count, false);
    const std::ptrdiff_t rows = ids.rows(), cols = ids.cols();
    const auto mark = [&](std::ptrdiff_t r, std::ptrdiff_t c) {
        const std::int32_t b = ids(r, c);
        if (b > 0 && static_cast<std::size_t>(b) <= count) clipped[static_cast<std::size_t>(b - 1)] = true;
    };
    for (std::ptrdiff_t c = 0; c < cols && rows > 0; ++c) {
        mark(0, c);
        mark(rows - 1, c);
    }
    for (std::ptrdiff_t r = 0; r < rows && cols > 0; ++r) {
        mark(r, 0);
        mark(r, cols - 1);
    }
    return clipped;
}

}  // namespace detail

// ---- implementation ----

namespace detail {

/// The steps of every extract_buildings: candidates are judged by their returns when `split_seen` (the survey
/// split some pulse), else by roughness alone; the rim is decided by returns->raised when given. With
/// `classified` given its cells are the candidates as they are (extract_classified_buildings).
template <raster_input In>
extract_buildings_result extract_buildings_steps(const In& dsm, const grid& g, raster_view<const float> ground,
                                                 raster_view<const std::uint8_t> vegetation,
                                                 const pulse_returns* returns, bool split_seen,
                                                 const extract_buildings_options& opt,
                                                 const raster_view<const std::uint8_t>* classified = nullptr)
{
    constexpr const char* function = "extract_buildings";
    check_extract_buildings(g, opt, function);
    require(dsm.rows() == g.rows && dsm.cols() == g.cols, function, "dsm must have the grid's shape");
    if (!ground.empty()) require_same_shape(dsm, ground, function, "dsm", "ground");
    if (!vegetation.empty()) require_same_shape(dsm, vegetation, function, "dsm", "vegetation");
    const std::ptrdiff_t rows = dsm.rows(), cols = dsm.cols();
    const double cell_m = g.cell;
    extract_buildings_result out;
    out.building_id = raster<std::int32_t>(rows, cols);
    out.surface_id = raster<std::int32_t>(rows, cols);
    out.vegetation = raster<std::uint8_t>(rows, cols);
    out.under_crowns = raster<std::uint8_t>(rows, cols, 0);
    if (rows == 0 || cols == 0) return out;
    const execution inner{opt.run.threads, {}};  // steps report no progress of their own

    ground_model_result terrain = ground_model(dsm, cell_m, opt.ground, inner);
    detail::report(opt.run.progress, 0.3, function);
    if (!ground.empty()) replace_ground(terrain, ground, cell_m, opt.ground, inner);
    building_candidates_result candidates =
        classified ? classified_building_parts(*classified, cell_m, opt.candidates, inner)
                   : building_candidates(dsm, terrain, cell_m, vegetation, opt.candidates, inner);
    out.building_id = std::move(candidates.building_id);
    out.vegetation = std::move(candidates.vegetation);
    detail::report(opt.run.progress, 0.45, function);

    const raster_view<const float> z = terrain.surface;
    local_planes_result lp = local_planes(z, out.building_id, cell_m, opt.local_planes, inner);
    auto [kept, rough] = classified ? std::array<std::size_t, 2>{candidates.count, 0}
                         : split_seen
                             ? drop_vegetation_parts(out.building_id, candidates.count, *returns, opt.returns)
                             : drop_rough_buildings(out.building_id, candidates.count, lp, cell_m, opt.local_planes);
    out.rejected_rough = rough;
    if (!classified && returns && !returns->raised.empty() && kept > 0) {
        const building_rim_result rim =
            refine_building_rim(out.building_id, kept, z, returns->points, returns->raised, opt.rim);
        if (rim.joined + rim.left > 0) {
            kept = detail::drop_small_pieces(out.building_id, kept, detail::min_part_cells(opt.candidates, cell_m));
            // Eaves that joined are roof, not vegetation; the local planes are fitted again on the new cells.
            for (std::ptrdiff_t i = 0; i < out.building_id.size(); ++i)
                if (out.building_id.data()[i] > 0) out.vegetation.data()[i] = 0;
            lp = local_planes(z, out.building_id, cell_m, opt.local_planes, inner);
        }
        const roof_under_crowns_result crowns =
            !returns->lowest.empty() && kept > 0
                ? join_roof_under_crowns(out.building_id, kept, terrain.surface.view(), lp, returns->lowest,
                                         returns->points, returns->raised, cell_m, opt.under_crowns)
                : roof_under_crowns_result{};
        if (!crowns.cells.empty()) {
            // The roof under a crown is not vegetation (the other building cells are not: candidates never are,
            // the rim's joins were cleared above); the surface now holds the roof there (z views it). The later
            // steps keep every building cell, so the joined cells stay building cells.
            for (const std::ptrdiff_t i : crowns.cells) {
                out.under_crowns.data()[i] = 1;
                out.vegetation.data()[i] = 0;
            }
            lp = local_planes(z, out.building_id, cell_m, opt.local_planes, inner);
        }
    }
    detail::report(opt.run.progress, 0.6, function);

    roof_regions regions = grow_roof_surfaces(z, out.building_id, lp, cell_m, opt.local_planes, opt.surfaces);
    dissolve_small_surfaces(regions, z, out.building_id, kept, cell_m, opt.surfaces);
    assign_remaining_cells(regions, z, out.building_id, cell_m);
    merge_roof_surfaces(regions, z, cell_m, opt.local_planes, opt.merge);
    kept = split_party_walls(out.building_id, kept, regions, z, cell_m, opt.party_walls).count;
    detail::report(opt.run.progress, 0.85, function);

    number_roof_surfaces_result numbered = number_roof_surfaces(regions, z, out.building_id, cell_m);
    out.surface_id = std::move(numbered.surface_id);
    out.surfaces = std::move(numbered.surfaces);
    const std::vector<building_height> heights = building_heights(z, terrain.ground, out.building_id, kept, cell_m);
    std::vector<std::vector<polygon>> outlines = building_outlines(out.building_id, kept, g);
    out.buildings.resize(kept);
    const std::vector<bool> clipped = detail::clipped_buildings(out.building_id.view(), kept);
    for (std::size_t b = 0; b < kept; ++b) {
        building_record& rec = out.buildings[b];
        rec.id = static_cast<std::int32_t>(b + 1);
        rec.outline = std::move(outlines[b]);
        rec.ground_z = heights[b].ground_z;
        rec.eave_z = heights[b].eave_z;
        rec.ridge_z = heights[b].ridge_z;
        rec.roof_area_horizontal_m2 = heights[b].footprint_m2;
        rec.clipped = clipped[b];
    }
    for (const roof_surface& s : out.surfaces) {
        building_record& rec = out.buildings[static_cast<std::size_t>(s.building - 1)];
        rec.surfaces.push_back(s.id);
        rec.roof_area_sloped_m2 += s.area_m2;
    }
    out.ground = std::move(terrain.ground);
    out.edges = std::move(terrain.edges);
    detail::report(opt.run.progress, 1.0, function);
    return out;
}

}  // namespace detail

template <raster_input In>
extract_buildings_result extract_buildings(const In& dsm, const grid& g, raster_view<const float> ground,
                                           raster_view<const std::uint8_t> vegetation,
                                           const extract_buildings_options& opt)
{
    return detail::extract_buildings_steps(dsm, g, ground, vegetation, nullptr, false, opt);
}

template <raster_input In>
extract_buildings_result extract_buildings(const In& dsm, const grid& g, raster_view<const float> ground,
                                           const pulse_returns& returns, const extract_buildings_options& opt)
{
    constexpr const char* function = "extract_buildings";
    detail::require_same_shape(dsm, returns.points, function, "dsm", "returns.points");
    detail::require_same_shape(returns.points, returns.multiple, function, "returns.points", "returns.multiple");
    if (!returns.raised.empty())
        detail::require_same_shape(returns.points, returns.raised, function, "returns.points", "returns.raised");
    if (!returns.lowest.empty()) {
        detail::require(!returns.raised.empty(), function, "returns.lowest needs returns.raised");
        detail::require_same_shape(returns.points, returns.lowest, function, "returns.points", "returns.lowest");
    }
    bool any_split = false;
    for (std::ptrdiff_t r = 0; r < returns.multiple.rows() && !any_split; ++r)
        for (std::ptrdiff_t c = 0; c < returns.multiple.cols() && !any_split; ++c)
            any_split = returns.multiple(r, c) > 0;
    detail::require_counts_within(returns.raised, returns.points, function,
                                  "returns.raised must not exceed returns.points in any cell");
    if (!any_split) return detail::extract_buildings_steps(dsm, g, ground, {}, &returns, false, opt);
    const raster<std::uint8_t> vegetation = vegetation_by_returns(returns, opt.returns);
    return detail::extract_buildings_steps(dsm, g, ground, vegetation.view(), &returns, true, opt);
}

template <raster_input In>
extract_buildings_result extract_classified_buildings(const In& dsm, const grid& g, raster_view<const float> ground,
                                                      raster_view<const std::uint8_t> building_cells,
                                                      const extract_buildings_options& opt)
{
    detail::require_same_shape(dsm, building_cells, "extract_classified_buildings", "dsm", "building_cells");
    return detail::extract_buildings_steps(dsm, g, ground, {}, nullptr, false, opt, &building_cells);
}

}  // namespace lidarfx
