// SPDX-License-Identifier: Apache-2.0
// channel_water_seeds: seeds in narrow rivers that return as many pulses as the land, read from their shape: a
// strip of level, dark cells lower than a bank on either side.
#pragma once

#include <cstddef>
#include <cstdint>

#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// Options of channel_water_seeds.
struct channel_water_seeds_options {
    double level_tolerance_m = 0.05;   ///< along the channel and across its water, a cell's min z lies within this
                                       ///< of the cell tested, metres, >= 0. Default 0.05 (range noise and
                                       ///< waves on the lowest of a few returns)
    int along_cells = 3;               ///< cells read each way along the channel; each way holds at least one
                                       ///< with a return, >= 1. Default 3 (2 let dark hollows of land through)
    double bank_rise_m = 0.1;          ///< a bank is the first cell across the channel at least this above the
                                       ///< cell tested, metres, > level_tolerance_m. Default 0.1 (a beach rising 3 %
                                       ///< over 3 m)
    double max_width_m = 18.0;         ///< the strip between the banks (the cell tested and the cells passed on
                                       ///< either side, banks not counted) is at most this wide, metres, > 0.
                                       ///< Default 18 (rivers up to 15 m wide and their shore cells)
    double max_intensity_ratio = 0.6;  ///< the cell's mean intensity is at most this times the survey's land
                                       ///< intensity, > 0. Default 0.6 (water is darker than land in the
                                       ///< near infrared; a level trough of land is not)
    std::size_t min_cells = 6;         ///< 8-connected groups of channel cells smaller than this are dropped,
                                       ///< >= 1. Default 6
    double max_lower_share = 0.05;     ///< of the cells with a return within max_width_m (Chebyshev distance, in
                                       ///< cells rounded up), at most this share lie more than bank_rise_m below
                                       ///< the cell, in [0, 1]. Default 0.05 (water lies at the bottom of its
                                       ///< surroundings; a dark flat roof between higher ones does not)
    int clear_cells = 4;               ///< a channel cell with a body (taken > 0) within this Chebyshev distance
                                       ///< is left out, >= 0. Default 4 (beside water already found a level, dark
                                       ///< strip is its shore: wet ground above the water)
};

/// Seed cells of narrow rivers (1 = seed). A cell with a return, not `excluded` (vegetation; empty: none), in no
/// body (`taken` > 0; empty: none) and with a mean intensity of at most max_intensity_ratio · land_intensity is a
/// channel cell when, along one of the 4 axes (the row, the column, the two diagonals):
///  - along the axis, the along_cells cells each way that have a return lie within level_tolerance_m of it
///    (each way holds one at least): the water is level along its channel;
///  - across the axis, walking out on each side, cells without return, or less than bank_rise_m above the cell
///    and not more than level_tolerance_m below it (the water, a gently rising shore), are passed until a bank
///    (at least bank_rise_m above the cell) is met; a cell more than level_tolerance_m below it fails the axis:
///    the cell is the lowest of its strip (within the tolerance), and the strip ends in a bank on both sides;
///  - the strip (the cell and the cells passed, banks not counted) is at most max_width_m wide, in steps of
///    cell_m, or cell_m·√2 on the diagonals; a walk that leaves the raster fails the axis.
/// A channel cell also lies at the bottom of its surroundings: of the cells with a return within max_width_m
/// (Chebyshev distance, cells rounded up), at most max_lower_share lie more than bank_rise_m below it (a flat
/// roof between higher roof parts is a level strip between banks too, but the ground around the building lies
/// below it). Channel cells with a body within clear_cells (Chebyshev distance) are left out, then groups of
/// channel cells smaller than min_cells (8-connected) are dropped. A river 2 cells wide that returns as many
/// pulses as the land has no level 3×3 window and no run of dropouts, so neither the flat seeds nor the dropout
/// seeds start it; its level strip between two banks does. A level field ends in no bank within the width, a
/// level terrace beside the water has the water lower than it, and a trough of land is as bright as the land.
/// A NaN land_intensity (no land measured) gives no seed, and so does a NaN intensity.
/// O(cells · 4 · (along_cells + max_width_m / cell_m) + channel cells · ((2 · clear_cells + 1)² + (2 ·
/// max_width_m / cell_m + 1)²)); reaches and widths beyond the raster's rows + columns count as that. min z
/// and cell_m in metres; intensity in the survey's units. `run`: threads (rows are independent; its progress
/// is not called); never changes the result.
/// @throws invalid_input on shapes that differ, cell_m <= 0 or options out of range.
inline raster<std::uint8_t> channel_water_seeds(raster_view<const float> min_z, raster_view<const float> intensity,
                                                raster_view<const std::uint8_t> excluded,
                                                raster_view<const std::int32_t> taken, double cell_m,
                                                double land_intensity, const channel_water_seeds_options& opt = {},
                                                const execution& run = {});

}  // namespace lidarfx

#include "lidarfx/pipelines/water/detail/channel_water_seeds_impl.hpp"
