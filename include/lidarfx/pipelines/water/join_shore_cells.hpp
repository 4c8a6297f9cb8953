// SPDX-License-Identifier: Apache-2.0
// join_shore_cells: land cells on a waterbody's edge that their count says are mostly water join it.
#pragma once

#include <cstddef>
#include <cstdint>

#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// Options of join_shore_cells.
struct join_shore_cells_options {
    int window_cells = 3;          ///< the water and land a shore cell is compared with lie within this Chebyshev
                                   ///< distance of it, cells, >= 1. Default 3 (a 7 × 7 window)
    double min_contrast = 0.3;     ///< the land's mean returns per cell exceed the water's by at least this share
                                   ///< of the land's, (n_land − n_water) / n_land (without that contrast the
                                   ///< count says nothing of the mix), in (0, 1]. Default 0.3
    double min_water_share = 0.5;  ///< the cell's estimated water share f = (n_land − count) / (n_land −
                                   ///< n_water) is at least this (a cell is water when its centre is: half its
                                   ///< area), in (0, 1]. Default 0.5
    int min_body_neighbours = 3;   ///< the cell has at least this many body cells among its 8 neighbours (a
                                   ///< whole side on the water, not a corner touching it), in [1, 8]. Default 3
};

/// Shore refinement: a cell on a body's edge whose centre lies on the water holds more water than land, and
/// water loses pulses (specular reflection, absorption) that land returns. So where the water around it
/// returns clearly fewer points than the land around it, the cell's count tells its water share. For every
/// land cell (label <= 0, inside the footprint; excluded or not) with at least min_body_neighbours body cells
/// among its 8 neighbours ("shore cell"): n_water = mean count over the body cells of its (2 window_cells +
/// 1)² window (dropouts count 0), n_land = mean count over the window's land cells with a return that are
/// neither next to a body (a body cell among their 8 neighbours) nor excluded; the cell joins when n_land
/// > 0, (n_land − n_water) / n_land >= min_contrast and (n_land − count) / (n_land − n_water) >=
/// min_water_share. It takes the label most frequent among its body neighbours (ties: the smallest). All
/// decisions read the labels as given (one pass; joined cells do not feed each other). `excluded` (optional;
/// e.g. vegetation, whose several returns per pulse would lift n_land) only keeps cells out of n_land; a
/// shore cell may be excluded itself (a bank's edge reads as vegetation). `footprint` is optional (empty =
/// all inside). Returns the number of cells joined.
/// O(cells + shore cells · (2 window_cells + 1)²); bands of rows run on `run.threads` threads (the same result
/// for any count).
/// @throws invalid_input on rasters of different shapes, options out of range or run.threads < 0.
inline std::size_t join_shore_cells(raster_view<std::int32_t> labels, raster_view<const std::uint32_t> count,
                                    raster_view<const std::uint8_t> excluded = {},
                                    raster_view<const std::uint8_t> footprint = {},
                                    const join_shore_cells_options& opt = {}, const execution& run = {});

}  // namespace lidarfx

#include "lidarfx/pipelines/water/detail/join_shore_cells_impl.hpp"
