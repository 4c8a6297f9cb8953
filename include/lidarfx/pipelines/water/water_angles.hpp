// SPDX-License-Identifier: Apache-2.0
// water_angles: the angular filter of the minimum elevation as region growing reads it.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/kernels/filter/angular_filter.hpp"
#include "lidarfx/kernels/interpolate/idw_fill.hpp"
#include "lidarfx/pipelines/water/water_rasters.hpp"

namespace lidarfx {

/// Which elevation the angular filter reads.
enum class angular_input {
    returns_only,  ///< minimum elevation of cells with returns; dropouts are skipped as neighbours and
                   ///< join the region at any threshold (their height is unknown, not steep)
    idw_filled,    ///< minimum elevation with dropouts filled by IDW, as in the dissertation
};

/// Options of water_angles.
struct water_angles_options {
    int radius_cells = 2;                               ///< angular filter window radius, cells; >= 1. Default 2
                                                        ///< ("two tiers": a 5 x 5 window).
    angular_input input = angular_input::returns_only;  ///< elevation the filter reads. Default returns_only.
    bool dropouts_join_any_threshold = true;            ///< dropout cells get NaN (join at any θ: their angle is
                                                        ///< unknown); false = the dissertation's literal behaviour
                                                        ///< (a dropout the filter gave no angle gets 90°)
};

/// Angles for region growing: angular_filter of min z (per cell the largest
/// atan(|Δz| / distance) over the (2·radius_cells + 1)² window, degrees in [0, 90], NaN neighbours skipped,
/// NaN centre gives NaN), read on the returns only or on min z filled by idw_fill; then dropout cells get
/// NaN (dropouts_join_any_threshold: grow_waterbody lets NaN join at any θ) or, otherwise, 90° where the
/// filter left NaN. cell_m is the cell size, metres. O(cells · radius_cells) (plus IDW when idw_filled).
/// `run`: threads of the kernels, progress (0 on entry, 1 when done) and cancellation; never changes the result.
/// @throws invalid_input on rasters of different shapes or empty, cell_m <= 0, options or run out of range;
/// cancelled.
inline raster<float> water_angles(const water_rasters& in, double cell_m, const water_angles_options& opt = {},
                                  const execution& run = {});

}  // namespace lidarfx

#include "lidarfx/pipelines/water/detail/water_angles_impl.hpp"
