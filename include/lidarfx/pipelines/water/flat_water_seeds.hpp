// SPDX-License-Identifier: Apache-2.0
// flat_water_seeds: seeds of waterbodies from cells with returns: level, smooth, low, and sparser than the land around.
#pragma once

#include <cmath>
#include <cstdint>
#include <utility>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/pipelines/water/flat_level_cells.hpp"
#include "lidarfx/pipelines/water/flat_seed_components.hpp"
#include "lidarfx/pipelines/water/flat_seed_rings.hpp"
#include "lidarfx/pipelines/water/flat_water_seeds_options.hpp"
#include "lidarfx/pipelines/water/select_flat_seeds.hpp"
#include "lidarfx/pipelines/water/water_rasters.hpp"
#include "lidarfx/pipelines/water/water_surface_slope.hpp"

namespace lidarfx {

/// Memory flat_water_seeds reuses from one call to the next (a new raster's pages cost their first touch).
/// Default-constructed empty; one per thread.
struct flat_water_seeds_workspace {
    raster<std::int32_t> labels;  ///< the level cells' component labels of the last call; contents unspecified
                                  ///< between calls (a caller may move the raster out to reuse its memory)
    double land_intensity = NAN;  ///< the survey's land intensity of the last call (survey_land_intensity), NaN
                                  ///< when not measured
};

/// Seed mask of waterbodies that need no dropouts: seed = components (8-connected, >= min_cells) of the
/// level cells {return, not excluded, max z − min z <= max_roughness_m, max − min of min z over the
/// (2 level_radius_cells + 1)² window <= level_tolerance_m} that are sparse at bright_density_ratio, or,
/// when not land-like (mean intensity below the land_intensity_quantile of the survey's land: the cells
/// with a return outside the lowest components), sparse in one of the following ways (mean
/// count <= max_density_ratio · their ring's and not brighter, or <= bright_density_ratio · whatever the intensity),
/// or, on >= joint_min_cells, <= dark_density_ratio · with count ratio × intensity ratio × roughness ratio
/// <= max_joint_ratio, or dark and sparse (<= dark_density_ratio · and mean intensity <=
/// max_intensity_ratio · their ring's or <= max_land_intensity_ratio · the land quantile), or smooth and sparse (<=
/// dark_density_ratio · and mean max z − min z <= max_roughness_ratio · median over level cells) and lowest (<=
/// max_lower_share of the ring more than level_tolerance_m below the component's lowest min z within ring_cells of the
/// ring cell); the ring: cells with returns within ring_cells of the component, not in a component. Steps, in order:
/// flat_level_cells, label_flat_seed_components, measure_flat_seed_rings, survey_land_intensity (into the rings),
/// select_flat_seeds, write_flat_seed_mask. With `surface_slope` (optional, same shape: water_surface_slope of min z,
/// m/m), a component whose median slope exceeds max_surface_slope is no seed, nor is any cell where the slope exceeds
/// it. Needs in.count (without it the mask is empty). `excluded` (optional, same shape; nonzero = never a seed, e.g.
/// vegetation) and in.footprint keep cells out. Returns 1 = seed cell. `taken` (optional, same shape; > 0 = a cell of a
/// body grown before) clears those cells from the mask and changes nothing else: they still count as level cells in the
/// components, the rings and the slope medians. A component entirely taken is not tested at all (its slope is not
/// read). The windows are running min/max filters (min_filter_rows / max_filter_rows over strips of rows; the level
/// window of radius 1 or 2 is read in place): O(cells · log(level_radius_cells · ring_cells)), plus
/// (2 ring_cells + 1)² per ring cell within reach of two components or more. `run`: threads of the window
/// filters and the labelling (its progress is not called); never changes the result.
/// @throws invalid_input on rasters of different shapes or options or run out of range.
inline raster<std::uint8_t> flat_water_seeds(const water_rasters& in, raster_view<const std::uint8_t> excluded = {},
                                             const flat_water_seeds_options& opt = {},
                                             surface_slope_source surface_slope = {},
                                             raster_view<const std::int32_t> taken = {}, const execution& run = {});

/// flat_water_seeds (see above) reusing the memory of `workspace` (a caller that seeds or labels again,
/// e.g. extract_waterbodies, saves the first touch of a new label raster). The same result.
inline raster<std::uint8_t> flat_water_seeds(const water_rasters& in, raster_view<const std::uint8_t> excluded,
                                             const flat_water_seeds_options& opt, surface_slope_source surface_slope,
                                             raster_view<const std::int32_t> taken,
                                             flat_water_seeds_workspace& workspace, const execution& run = {});

// ---- implementation ----

inline raster<std::uint8_t> flat_water_seeds(const water_rasters& in, raster_view<const std::uint8_t> excluded,
                                             const flat_water_seeds_options& opt, surface_slope_source surface_slope,
                                             raster_view<const std::int32_t> taken,
                                             flat_water_seeds_workspace& workspace, const execution& run)
{
    constexpr const char* fn = "flat_water_seeds";
    detail::validate(in, fn);
    detail::validate(opt, fn);
    detail::check_execution(run, fn);
    if (!excluded.empty()) detail::require_same_shape(in.min_z, excluded, fn, "min_z", "excluded");
    if (!surface_slope.empty()) detail::require_same_shape(in.min_z, surface_slope, fn, "min_z", "surface_slope");
    if (!taken.empty()) detail::require_same_shape(in.min_z, taken, fn, "min_z", "taken");
    if (in.count.empty()) return raster<std::uint8_t>(in.min_z.rows(), in.min_z.cols(), 0);
    // The level mask becomes the seed mask once labelled (the last step rewrites every cell).
    auto mask = flat_level_cells(in, excluded, opt, run);
    auto comps = label_flat_seed_components(in, mask, taken, opt, std::move(workspace.labels), run);
    auto rings = measure_flat_seed_rings(in, comps, opt, run);
    rings.land_intensity = survey_land_intensity(in, comps, rings, opt, run);
    workspace.land_intensity = rings.land_intensity;
    const auto keep = select_flat_seeds(comps, rings, opt, surface_slope);
    write_flat_seed_mask(comps, keep, mask, taken, surface_slope, opt);
    workspace.labels = std::move(comps.labels);
    return mask;
}

inline raster<std::uint8_t> flat_water_seeds(const water_rasters& in, raster_view<const std::uint8_t> excluded,
                                             const flat_water_seeds_options& opt, surface_slope_source surface_slope,
                                             raster_view<const std::int32_t> taken, const execution& run)
{
    flat_water_seeds_workspace workspace;
    return flat_water_seeds(in, excluded, opt, surface_slope, taken, workspace, run);
}

}  // namespace lidarfx
