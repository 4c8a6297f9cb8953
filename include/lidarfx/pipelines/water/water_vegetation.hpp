// SPDX-License-Identifier: Apache-2.0
// water_vegetation: the cells that never join a waterbody (canopy by height spread, multiple returns).
#pragma once

#include <cstddef>
#include <cstdint>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/kernels/filter/vegetation_mask.hpp"
#include "lidarfx/pipelines/water/water_rasters.hpp"

namespace lidarfx {

/// Options of water_vegetation.
struct water_vegetation_options {
    double height_m = 2.0;              ///< h: max z − min z > h is vegetation, metres; > 0. Default 2 m.
    int closing_size_cells = 5;         ///< side of the square closing the height mask, cells; odd, >= 1
                                        ///< (1 = no closing). Default 5.
    bool from_multiple_returns = true;  ///< cells with returns and a multiple-return pulse are vegetation too
                                        ///< (needs the multiple_returns raster). Default true.
};

/// Vegetation mask of the waterbody method (dissertation 2.3.1): vegetation_mask (1 where max z − min z >
/// height_m, closed by a closing_size_cells square), then OR cells with a return (dropout == 0) whose
/// multiple_returns is set, when from_multiple_returns and that raster is given. 1 = vegetation.
/// O(cells). `run`: threads of the kernels, progress (0 on entry, 1 when done) and cancellation; never changes
/// the result.
/// @throws invalid_input on rasters of different shapes or empty, options or run out of range; cancelled.
inline raster<std::uint8_t> water_vegetation(const water_rasters& in, const water_vegetation_options& opt = {},
                                             const execution& run = {});

}  // namespace lidarfx

#include "lidarfx/pipelines/water/detail/water_vegetation_impl.hpp"
