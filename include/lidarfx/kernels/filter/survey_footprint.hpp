// SPDX-License-Identifier: Apache-2.0
// survey_footprint: the area a survey covered, as the cells a disc rolled in from outside cannot reach.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/kernels/filter/distance_transform.hpp"

namespace lidarfx {

/// Settings of survey_footprint.
struct survey_footprint_options {
    /// Radius of the disc rolled in from outside the grid, metres; > 0. Gaps in the coverage narrower than
    /// twice this (lakes, rivers and dropouts enclosed by returns or crossed by scan lines) stay inside;
    /// empty space wider than it that opens to the outside (unflown corners, a tile clipped to a circle)
    /// is outside. 50 m keeps rivers up to 100 m wide inside even where no scan line crosses them.
    double hull_radius_m = 50.0;
    execution run = {};  ///< threads, progress, cancellation (core/parallel.hpp); never changes the result
};

/// The footprint of a survey: 1 for cells inside the area the scanner covered, 0 outside. `covered` marks
/// cells known to be covered (1 = a return fell in the cell, or a scan line crossed it: see
/// scan_coverage); everything beyond the grid is open space, entered only through stretches of the
/// grid's edge without coverage longer than 2 R (shorter gaps between covered edge cells, such as a river
/// leaving the tile, count as covered). A disc of radius R = hull_radius_m / cell_m
/// cells rolls in from beyond the grid through cells not covered, never holding a covered cell centre
/// (its centre keeps a squared distance > R^2 to every covered cell); the cells the disc can sweep are
/// outside, every other cell (and every covered one) is inside: an alpha shape of the coverage with
/// alpha = R, computed on the raster with two exact distance transforms and a flood fill. No-return cells
/// outside the footprint are "nothing was flown here", not dropouts. O(cells + padding); the same result
/// for any thread count.
/// @throws invalid_input if cell_m or hull_radius_m is not finite and > 0, the padded grid would exceed
/// max_raster_cells, or run.threads < 0; cancelled if run.progress returns false.
inline raster<std::uint8_t> survey_footprint(raster_view<const std::uint8_t> covered, double cell_m,
                                             const survey_footprint_options& opt = {});

}  // namespace lidarfx

#include "lidarfx/kernels/filter/detail/survey_footprint_impl.hpp"
