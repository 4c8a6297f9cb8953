// SPDX-License-Identifier: Apache-2.0
// enforce_shorelines: no ground next to the water lies below the water surface.
#pragma once

#include <cstddef>

#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// What enforce_shorelines does with shore ground below the water.
enum class shoreline_rule {
    lift,  ///< the ground is raised to the water surface beside it
    flag,  ///< the ground stays; the cells are only counted
};

/// Shore ground found below the water.
struct shoreline_check {
    std::size_t below = 0;                          ///< shore cells whose ground lay below the water beside them
    double worst_m = 0;                             ///< the largest depth below the water, metres (0 when none)
    std::ptrdiff_t worst_row = -1, worst_col = -1;  ///< where it is, raster cells (-1 when none)
};

/// The shore cells are the land cells (`water_surface` NaN, `ground` finite) 8-adjacent to a water cell
/// (`water_surface` finite); each is compared with the highest water surface among those neighbours, h. A
/// cell whose ground lies below h is counted, and with shoreline_rule::lift its ground becomes h (so
/// the flattened water never stands above its shore). Elevations in metres. One pass, O(cells).
/// @throws invalid_input on rasters of different shapes.
inline shoreline_check enforce_shorelines(raster_view<float> ground, raster_view<const float> water_surface,
                                          shoreline_rule rule = shoreline_rule::lift);

}  // namespace lidarfx

#include "lidarfx/pipelines/water/detail/enforce_shorelines_impl.hpp"
