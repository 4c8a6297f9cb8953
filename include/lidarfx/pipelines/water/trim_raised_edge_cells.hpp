// SPDX-License-Identifier: Apache-2.0
// trim_raised_edge_cells: waterbody edge cells standing above the local water level become land.
#pragma once

#include <cstddef>
#include <cstdint>

#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// Options of trim_raised_edge_cells.
struct trim_raised_edge_cells_options {
    int window_cells = 3;             ///< the local water level is read within this Chebyshev distance, cells, >= 1.
                                      ///< Default 3 (a 7 × 7 window)
    double min_rise_m = 0.05;         ///< an edge cell whose min z stands more than this above the local level is
                                      ///< dry ground (2 σ of the 2-3 cm range noise of the lowest return), metres,
                                      ///< >= 0. Default 0.05
    double max_rise_m = 0.5;          ///< ... up to this; higher cells are bridge decks or bank cells whose water
                                      ///< returns were lost, left as they are (join_shore_cells, which runs after
                                      ///< this step in extract_waterbodies, judges bank cells by their count),
                                      ///< metres, > min_rise_m. Default 0.5
    std::size_t min_level_cells = 3;  ///< the local level needs at least this many interior body cells with a
                                      ///< return in the window, >= 1. Default 3
};

/// Edge refinement: the level gate and join_level_cells let a body take ground up to their tolerance (0.15 m)
/// above its level, a metre or two of a beach or a field; the water surface next to an edge cell is known far
/// better than that. For every edge cell (a body cell with a land cell among its 8 neighbours) with a return,
/// the local level is the median min z (the upper median of an even count) over the interior cells (no
/// land neighbour) of the same body with a finite min z in its (2 window_cells + 1)² window, given at least
/// min_level_cells of them (a body next to another at a different level reads its own); the cell becomes land (label 0)
/// when min_rise_m < min z − level <= max_rise_m. One pass over the labels as given. Returns the number of cells
/// trimmed. Elevations in metres. O(cells + edge cells · (2 window_cells + 1)²); bands of rows run on
/// `run.threads` threads (the same result for any count).
/// @throws invalid_input on rasters of different shapes, options out of range or run.threads < 0.
inline std::size_t trim_raised_edge_cells(raster_view<std::int32_t> labels, raster_view<const float> min_z,
                                          const trim_raised_edge_cells_options& opt = {}, const execution& run = {});

}  // namespace lidarfx

#include "lidarfx/pipelines/water/detail/trim_raised_edge_cells_impl.hpp"
