// SPDX-License-Identifier: Apache-2.0
// seeds_beyond_bridges: where a waterbody ends at a bridge deck, the water at its level beyond the deck.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/pipelines/water/water_surface_slope.hpp"

namespace lidarfx {

/// Options of seeds_beyond_bridges.
struct seeds_beyond_bridges_options {
    double max_span_m = 30.0;          ///< longest deck crossed along a row, column or diagonal, metres, > 0.
                                       ///< Default 30 (join_across_bridges' max_span_m)
    double min_clearance_m = 2.0;      ///< every deck cell has no return or a min z at least this above the water
                                       ///< cell the walk starts from, metres, >= 0. Default 2 (a deck stands
                                       ///< clear of the water; join_across_bridges' min_clearance_m)
    double level_tolerance_m = 0.15;   ///< beyond the deck, a cell is water-like when its min z lies within this
                                       ///< of the start cell's, metres, >= 0. Default 0.15 (the level gate: a
                                       ///< river falls a few cm across a bridge)
    int beyond_cells = 4;              ///< a walk counts when this many consecutive water-like cells follow the
                                       ///< deck (eligible, in no body), and marks them, >= 1. Default 4
    int approach_cells = 2;            ///< land cells at the water's level (or without return) allowed between the
                                       ///< body and the deck (a body may stop a cell short of it), >= 0. Default 2
    double max_surface_slope = 0.008;  ///< given a surface slope (water_surface_slope or its lazy form), the cells
                                       ///< beyond the deck must be level: slope at most this (NaN: unknown,
                                       ///< accepted), m/m;
                                       ///< < 0 disables. Default 0.008 (flat_water_seeds' max_surface_slope)
    int clear_cells = 4;               ///< a marked cell with a body within this Chebyshev distance is left out
                                       ///< (it borders water already found: a walk over a deck's end lands on
                                       ///< the bank beyond), >= 0. Default 4
    int behind_cells = 3;              ///< the walk starts from a water cell with this many cells of its own body
                                       ///< behind it on the line (the end of a channel, not a stray cell), >= 0.
                                       ///< Default 3
};

/// Seed cells beyond bridge decks: from every cell of a body (label > 0, finite min z, behind_cells cells of
/// the same body behind it) a walk goes along each of the 8 directions of the rows, columns and diagonals over
/// a deck: after at most approach_cells land cells at the start cell's level (within level_tolerance_m) or
/// without return, land cells (label 0) that have no return or stand min_clearance_m above the start cell's
/// min z (at least one of them with a return), up to floor(max_span_m / step) cells from the start, step =
/// cell_m or cell_m·√2; when the beyond_cells cells after the deck are eligible (eligible != 0, label 0) with
/// min z within level_tolerance_m of the start cell's (and, given surface_slope, a slope of at most
/// max_surface_slope or NaN), they are marked 1; marks within clear_cells of a body are then dropped. A river's
/// stretch that no seed reached, cut off by a bridge from a stretch found, so gets seeds at the level the found
/// stretch has at the deck; they grow like any seed (the level gate and the intensity test decide what joins).
/// A walk sideways from a bank over a building only marks ground at the water's level behind it, which the same
/// tests then judge.
/// O(cells of bodies · 8 · (span + beyond_cells)); bands of rows run on `run.threads` threads (the same seeds for
/// any count). Elevations and cell_m in metres.
/// @throws invalid_input on shapes that differ, cell_m <= 0, options out of range or run.threads < 0.
inline raster<std::uint8_t> seeds_beyond_bridges(raster_view<const std::int32_t> labels, raster_view<const float> min_z,
                                                 raster_view<const std::uint8_t> eligible, double cell_m,
                                                 const seeds_beyond_bridges_options& opt = {},
                                                 surface_slope_source surface_slope = {}, const execution& run = {});

}  // namespace lidarfx

#include "lidarfx/pipelines/water/detail/seeds_beyond_bridges_impl.hpp"
