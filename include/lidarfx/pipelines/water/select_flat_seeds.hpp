// SPDX-License-Identifier: Apache-2.0
// select_flat_seeds: which components of level cells are flat water seeds, and their seed cells.
#pragma once

#include <cstdint>
#include <vector>

#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/pipelines/water/flat_seed_components.hpp"
#include "lidarfx/pipelines/water/flat_seed_rings.hpp"
#include "lidarfx/pipelines/water/flat_water_seeds_options.hpp"
#include "lidarfx/pipelines/water/water_surface_slope.hpp"

namespace lidarfx {

/// Fourth step of flat_water_seeds: keep[l] = 1 for each component l of `comps` that is a seed, else 0
/// (count() + 1 entries, keep[0] = 0). A component with free cells and a ring is a seed when it is lowest
/// (rings.lower <= opt.max_lower_share · ring cells) and sparse: its mean in.count over its ring's (the
/// density ratio) is <= opt.bright_density_ratio whatever the intensity; or, when it is not land-like (mean
/// intensity below rings.land_intensity, the survey's land quantile; NaN: never land-like), dark against
/// the survey (mean intensity <= opt.max_land_intensity_ratio · rings.land_intensity) and sunken
/// (rings.raised >= opt.min_raised_share · ring cells) whatever its density, or <=
/// opt.max_density_ratio while its intensity ratio is <= 1, or <= opt.dark_density_ratio and dark (intensity
/// ratio <= opt.max_intensity_ratio, or mean intensity <= opt.max_land_intensity_ratio ·
/// rings.land_intensity), smooth (mean max z − min z <= opt.max_roughness_ratio · the median of
/// comps.level_roughness) or, on >= opt.joint_min_cells cells, density · intensity · roughness ratios <=
/// opt.max_joint_ratio. With `surface_slope` (optional, same shape, m/m) and opt.max_surface_slope >= 0, a
/// seed whose median slope over its cells (NaN counted as 0, level) exceeds it is dropped.
/// O(components), plus O(cells) with a slope; the median of the level roughness only when needed.
/// @throws invalid_input on options out of range or sizes that do not match.
inline std::vector<std::uint8_t> select_flat_seeds(const flat_seed_components& comps, const flat_seed_rings& rings,
                                                   const flat_water_seeds_options& opt = {},
                                                   surface_slope_source surface_slope = {});

/// Last step of flat_water_seeds: the seed mask into `mask` (same shape as comps.labels): 1 on the cells
/// of the components l with keep[l] that are not `taken` (optional, same shape; > 0 = a cell of a body
/// grown before) and, with `surface_slope` (optional) and opt.max_surface_slope >= 0, where the slope does
/// not exceed opt.max_surface_slope (a beach joined to the water); 0 elsewhere. Every cell of `mask` is
/// written; it may be the level mask comps was labelled from. O(cells).
/// @throws invalid_input on shapes that differ or keep of the wrong size.
inline void write_flat_seed_mask(const flat_seed_components& comps, const std::vector<std::uint8_t>& keep,
                                 raster_view<std::uint8_t> mask, raster_view<const std::int32_t> taken = {},
                                 surface_slope_source surface_slope = {}, const flat_water_seeds_options& opt = {});

}  // namespace lidarfx

#include "lidarfx/pipelines/water/detail/select_flat_seeds_impl.hpp"
