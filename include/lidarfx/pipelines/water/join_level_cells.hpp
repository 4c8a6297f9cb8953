// SPDX-License-Identifier: Apache-2.0
// join_level_cells: the narrow-water refinement; cells at a grown region's water level join it.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// Options of join_level_cells.
struct join_level_cells_options {
    double tolerance_m = 0.15;  ///< a cell's min z lies within this of the level it is reached from,
                                ///< |min z - level| <= tolerance_m, metres; >= 0, 0 disables. Default 0.15 m.
    double max_rise_m = 0.5;    ///< and its max z at most this above that level, max z - level <= max_rise_m
                                ///< (a cell mostly on the bank is not water), metres; >= 0. Default 0.5 m.
    int depth_cells = 2;        ///< steps (8-neighbourhood) from the region the refinement reaches, cells;
                                ///< >= 0, 0 disables. Default 2.
};

/// Narrow-water refinement (docs/waterbodies.md): a breadth-first walk from the region's edge cells with a return
/// adds every eligible cell within depth_cells steps (8-neighbourhood) whose returns all lie at the water
/// level, that is |min z − L| <= tolerance_m and max z − L <= max_rise_m, where L is the min z of the region
/// edge cell the walk started from (kept along the walk). Cells without a return (NaN min z) never join.
/// Joined cells are appended to `region` (linear indices r * cols + c) in the order they join. Elevations in
/// metres. O(region + cells joined), plus a mark raster of the rasters' shape allocated per call
/// (grow_waterbodies refines each body in its label raster instead).
/// @throws invalid_input on rasters of different shapes, region cells outside them, options out of range.
inline void join_level_cells(std::vector<std::ptrdiff_t>& region, raster_view<const float> min_z,
                             raster_view<const float> max_z, const raster<std::uint8_t>& eligible,
                             const join_level_cells_options& opt = {});

}  // namespace lidarfx

#include "lidarfx/pipelines/water/detail/join_level_cells_impl.hpp"
