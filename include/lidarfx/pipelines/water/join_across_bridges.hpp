// SPDX-License-Identifier: Apache-2.0
// join_across_bridges: waterbodies at one level on both sides of a bridge become one body.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <span>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/pipelines/water/water_rasters.hpp"

namespace lidarfx {

/// Options of join_across_bridges.
struct join_across_bridges_options {
    double max_span_m = 30.0;         ///< longest land run bridged: runs of n cells with n·cell_m <= max_span_m
                                      ///< (n <= floor(max_span_m / cell_m)), metres; >= 0, 0 disables. Default 30.
    double level_tolerance_m = 1.0;   ///< the water levels of the two bodies differ by at most this, metres;
                                      ///< >= 0. Default 1 m.
    double min_clearance_m = 2.0;     ///< a deck cell's min z stands at least this above both levels, metres;
                                      ///< >= 0. Default 2 m.
    double water_tolerance_m = 0.15;  ///< a cell whose min z lies between the lower level − this and the higher
                                      ///< level + this is water seen past the deck's edge, metres; >= 0. Default
                                      ///< 0.15 m (join_level_cells' tolerance_m).
    bool join_touching = true;        ///< bodies a != b that touch (8-adjacent cells, a run of 0 land cells) with
                                      ///< levels within level_tolerance_m merge too: one water surface grown
                                      ///< from several seeds (a river whose level gate let each seed cover only
                                      ///< part of its fall) is one body. Default true.
};

/// Water level of every body of a label raster: level[l] = median of the finite min z (metres) of the cells
/// labelled l (the element at position n / 2 of their n sorted values), for l = 1 .. the largest label;
/// NaN for a label without such cells and for level[0] (land). O(cells + largest label) time and memory; bands of
/// rows, then the labels' medians, run on `run.threads` threads (the same levels for any count).
/// @throws invalid_input if the shapes differ, a label is negative or run.threads < 0.
inline std::vector<double> water_levels(raster_view<const std::int32_t> labels, raster_view<const float> min_z,
                                        const execution& run = {});

/// Joins waterbodies across bridges: a straight run (row, column or diagonal) of n land cells (label 0),
/// n·cell_m <= max_span_m, whose two ends touch bodies a != b with |level[a] − level[b]| <= level_tolerance_m, is
/// a bridge when its water and deck cells lie in the order: water seen past the deck's edge (min z between the
/// lower level − water_tolerance_m and the higher level + water_tolerance_m), one stretch of deck (min z at least
/// min_clearance_m above both levels), water seen (any part may be empty), and the run holds a deck cell or a cell
/// without a return (NaN min z). Its cells without a return, deck and water cells become water; the others (banks,
/// abutments) stay land. Land at a water level between two bodies without a deck, or ground between two decks (a
/// street between roofs), is no bridge. A bridged cell takes label min(a, b); a cell bridged in several directions
/// takes the label of the first of row, column, diagonal, anti-diagonal. Bodies joined by a bridged cell merge (every
/// label of a merged group becomes its smallest), and with join_touching so do bodies with 8-adjacent cells and levels
/// within level_tolerance_m. Every decision reads the labels as given. Elevations in metres. One row-major pass keeps,
/// per line of the 4 directions, the last water cell seen; a run is examined when a water cell of another body closes
/// it. O(cells + cells of examined runs). Returns the number of bridged cells.
/// @throws invalid_input on shapes that differ, cell_m <= 0, options out of range, a negative label or a
/// label without an entry in `level`.
inline std::size_t join_across_bridges(raster_view<std::int32_t> labels, raster_view<const float> min_z,
                                       std::span<const double> level, double cell_m,
                                       const join_across_bridges_options& opt = {});

/// join_across_bridges with each body's level from water_levels(labels, min_z, run) (the levels on `run.threads`
/// threads; the sweep on the calling thread).
/// @throws invalid_input on shapes that differ, cell_m <= 0, options out of range, a negative label or
/// run.threads < 0.
inline std::size_t join_across_bridges(raster_view<std::int32_t> labels, raster_view<const float> min_z, double cell_m,
                                       const join_across_bridges_options& opt = {}, const execution& run = {});

}  // namespace lidarfx

#include "lidarfx/pipelines/water/detail/join_across_bridges_impl.hpp"
