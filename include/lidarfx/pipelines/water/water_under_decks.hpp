// SPDX-License-Identifier: Apache-2.0
// water_under_decks: a flattened river continues under its bridge decks, bank to bank.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// Options of water_under_decks.
struct water_under_decks_options {
    double deck_clearance_m = 2.0;    ///< a cell whose lowest return stands at least this far above the river beside
                                      ///< it is a deck, metres, > 0. Default 2 m (river_profile_options'
                                      ///< deck_clearance_m, join_across_bridges' min_clearance_m)
    double level_tolerance_m = 0.15;  ///< a cell whose lowest return lies within this of the river beside it is
                                      ///< water seen past a deck's edge, metres, >= 0. Default 0.15 m
                                      ///< (join_across_bridges' water_tolerance_m)
    double reach_m = 8.0;             ///< such cells join only this close to a deck cell, not along the whole bank,
                                      ///< metres, >= 0. Default 8 m
    double max_span_m = 30.0;         ///< longest run of deck cells crossed between two cells of one river (n cells
                                      ///< with n · cell_m <= max_span_m), metres, >= 0. Default 30 m
                                      ///< (join_across_bridges' max_span_m)
};

/// What water_under_decks added.
struct water_under_decks_result {
    std::size_t level_cells = 0;  ///< cells at the river's level beside a deck that joined it
    std::size_t deck_cells = 0;   ///< cells under a deck that joined it
};

/// Extends the rivers `rivers` (ids) of `body` (body ids per cell, 0 land) and `water_surface` (their water
/// level, metres, NaN off the water) under the bridge decks that cross them, from the survey's lowest returns
/// `min_z` (metres, NaN where none) on cells of cell_m metres. Next to a deck the waterbodies lose the water
/// whose cells also hold returns of the deck's edge or railing, and with them the runs that would cross the deck
/// from water to water; the river is then flattened with a notch under the deck that keeps the deck as terrain.
///  1. Deck cells are the land cells 8-adjacent to a river cell whose lowest return stands at least
///     deck_clearance_m above that cell's water. Within reach_m of one (centre to centre), a land cell whose
///     lowest return lies within level_tolerance_m of the water of an 8-adjacent river cell (the first in
///     row-major order of the 3 x 3 window) joins that river at that cell's level; repeated, each round reading
///     the last, until no cell joins.
///  2. A straight run (row, column, diagonal, anti-diagonal) of land cells between two cells of the same river,
///     on land that reaches the raster's edge (a deck reaches a bank; an island is land the water encloses,
///     4-connected), each a deck cell relative to the run's first end (lowest return at least deck_clearance_m above
///     its water) or without a return, at least one with a return, and n · cell_m <= max_span_m, joins that river, each
///     cell at the level interpolated linearly between the run's two ends. Runs are found on the cells as step 1 left
///     them; a cell on several runs takes the first (directions in the order above, then raster order of the
///     run's first end).
/// Only the lowest returns tell a deck from ground: a neck of high ground narrower than max_span_m between two
/// loops of one river would be crossed too. Bodies not in `rivers` and their cells are left alone. O(cells + river
/// cells · the longest run).
/// @throws invalid_input on rasters of different shapes, cell_m not finite and > 0, options out of range, or a
/// negative id in `body` or `rivers`.
inline water_under_decks_result water_under_decks(raster_view<std::int32_t> body, raster_view<float> water_surface,
                                                  raster_view<const float> min_z, std::span<const std::int32_t> rivers,
                                                  double cell_m, const water_under_decks_options& opt = {});

}  // namespace lidarfx

#include "lidarfx/pipelines/water/detail/water_under_decks_impl.hpp"
