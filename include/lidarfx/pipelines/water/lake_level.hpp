// SPDX-License-Identifier: Apache-2.0
// lake_level: one water level for a lake or pond, from its own returns and its shore.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "lidarfx/core/grid.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// Options of lake_level.
struct lake_level_options {
    double mode_window_m = 0.1;    ///< the level is the median of the water heights inside the densest window of
                                   ///< this height, metres, > 0. Default 0.1 m: water is flat, so its heights
                                   ///< crowd into a few cm; a bank or a reed belt the body took in spreads over
                                   ///< metres and does not move the level. Infinite: the median of all heights
    bool cap_at_shore = false;     ///< lower the level to the shore's low ground when that is lower. Off by default:
                                   ///< cells on the waterline hold water returns, whose lowest lies below the surface,
                                   ///< so the cap sets the level a few cm low; enforce_shorelines raises such shore
                                   ///< ground to the level instead
    double shore_quantile = 0.05;  ///< the shore's low ground is this quantile of its cells' ground, in [0, 1]:
                                   ///< 0.05 ignores a few cells of noise or pits. Default 0.05
    double below_shore_m = 0.0;    ///< the level stays at least this far below the shore's low ground, metres,
                                   ///< >= 0. Default 0 (at the lowest shoreline ground)
};

/// A lake's level and what it was made from.
struct lake_level_result {
    double level_m = NAN;          ///< returns_level_m (with cap_at_shore: at most shore_low_m − below_shore_m);
                                   ///< shore_low_m − below_shore_m without returns; NaN when neither is known
    double returns_level_m = NAN;  ///< the level of the body's own returns (its finite water_z), metres
    double shore_low_m = NAN;      ///< shore_quantile of the ground of the shore cells, metres
    std::size_t returns = 0;       ///< body cells with a return
    std::size_t shore_cells = 0;   ///< land cells (label 0) 8-adjacent to the body with a finite ground
};

/// The level of lake `label` (cells inside `box`) from its cells' water heights (`water_z`, metres, NaN where no
/// return: e.g. water_heights(labels, min_z, max_z)): of the windows [z, z + mode_window_m] starting at one of the
/// sorted finite heights, the one holding the most (the lowest on ties); the level is the median of the heights in
/// it (the element at position m / 2 of its m sorted values). With cap_at_shore it is lowered to the shore's low ground
/// minus below_shore_m when that is lower; a lake without returns takes that value. The shore is every land cell (label
/// 0) 8-adjacent to the body whose `ground` is finite; its low ground is the value at position ⌊shore_quantile · (n −
/// 1)⌋ of the n sorted values. O(box cells + n log n).
/// @throws invalid_input on rasters of different shapes, options out of range or a box outside the raster.
inline lake_level_result lake_level(raster_view<const std::int32_t> labels, std::int32_t label, const cell_box& box,
                                    raster_view<const float> water_z, raster_view<const float> ground,
                                    const lake_level_options& opt = {});

}  // namespace lidarfx

#include "lidarfx/pipelines/water/detail/lake_level_impl.hpp"
