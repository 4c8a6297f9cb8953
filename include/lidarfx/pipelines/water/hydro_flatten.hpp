// SPDX-License-Identifier: Apache-2.0
// hydro_flatten: a hydro-flattened bare-earth DEM from a DEM and the waterbodies of the same survey.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/pipelines/water/enforce_shorelines.hpp"
#include "lidarfx/pipelines/water/hydro_body_shape.hpp"
#include "lidarfx/pipelines/water/hydro_qa.hpp"
#include "lidarfx/pipelines/water/join_channel_parts.hpp"
#include "lidarfx/pipelines/water/lake_level.hpp"
#include "lidarfx/pipelines/water/lower_to_banks.hpp"
#include "lidarfx/pipelines/water/river_profile.hpp"
#include "lidarfx/pipelines/water/water_heights.hpp"
#include "lidarfx/pipelines/water/water_under_decks.hpp"

namespace lidarfx {

/// Options of hydro_flatten. The minimum sizes are those of the USGS Lidar Base Specification, in metres.
struct hydro_flatten_options {
    double min_lake_area_m2 = 8093.71;    ///< lakes and ponds at least this large are flattened (2 acres), m², >= 0
    double min_river_width_m = 30.48;     ///< rivers at least this wide (nominal width, area / length) are
                                          ///< flattened (100 ft), metres, >= 0
    double min_island_area_m2 = 4046.86;  ///< holes in a body at least this large stay land (1 acre); smaller
                                          ///< ones are flattened with the water, m², >= 0
    double min_river_elongation = 6.0;    ///< a body at least this many widths long (hydro_body_shape::elongation)
                                          ///< is a river, else a lake, >= 1. Default 6 (a round lake is about 1.6, a
                                          ///< pond with a narrow tail 4-5)
    bool join_channels = true;          ///< join_channel_parts: one body for the pieces of a river cut apart at a weir
                                        ///< or a bridge deck, with the land under the deck
    channel_join_options join = {};     ///< join_channel_parts: when two pieces are one channel
    lake_level_options lake = {};       ///< lake_level: whether the shore caps the level, and how
    river_profile_options river = {};   ///< trace_river_profile: section spacing, deck clearance, weirs
    bool to_banks = true;               ///< lower_to_banks: a river's sections without measured water no higher than
                                        ///< their banks
    lower_to_banks_options banks = {};  ///< lower_to_banks: the bank's quantile
    bool under_decks = true;            ///< water_under_decks: the rivers continue under their bridge decks
    water_under_decks_options decks = {};             ///< water_under_decks: deck clearance, reach, longest span
    shoreline_rule shoreline = shoreline_rule::lift;  ///< enforce_shorelines: lift the shore or only count it
    double flat_tolerance_m = 0.001;  ///< hydro_qa: largest max − min of a lake or a section, metres. 1 mm
    execution run = {};               ///< threads of the island fill; progress per body, false cancels
};

/// The two kinds of hydro-flattened water.
enum class hydro_body_type {
    lake,   ///< one level for the whole body
    river,  ///< flat cross-sections whose levels fall downstream
};

/// One waterbody as hydro_flatten saw it.
struct hydro_body {
    std::int32_t id = 0;  ///< its label in the input labels
    hydro_body_type type = hydro_body_type::lake;
    bool flattened = false;                       ///< false: under the minimum size of its type, left to the terrain
    hydro_body_shape shape;                       ///< area, length, nominal width
    cell_box box;                                 ///< its cells, raster cells
    std::size_t shore_cells_lifted = 0;           ///< land cells beside it raised to its water (shoreline_rule::lift)
    double level_min_m = NAN, level_max_m = NAN;  ///< its lowest and highest water level, metres (a lake: equal)
    lake_level_result lake;                       ///< lakes: the level and what it came from
    river_profile river;                          ///< rivers: sections and levels, upstream first
    lower_to_banks_result banks;                  ///< rivers: the unmeasured sections lowered to their banks
    /// The fall from its highest to its lowest level, metres (0 for a lake).
    double drop_m() const noexcept { return level_max_m - level_min_m; }
};

/// A hydro-flattened DEM and its water.
struct hydro_flatten_result {
    raster<float> dem;                       ///< the input DEM with flattened water and lifted shores, metres
    raster<float> water_surface;             ///< the water level on flattened water, NaN elsewhere, metres
    raster<std::int32_t> body;               ///< the id of the flattened body per cell, 0 elsewhere
    std::vector<hydro_body> bodies;          ///< every body with cells (after the split into connected parts), in
                                             ///< increasing id (ids of pieces joined to a smaller one are absent)
    std::vector<hydro_check> qa;             ///< hydro_qa of the flattened bodies
    std::size_t island_cells_flattened = 0;  ///< cells of islands under min_island_area_m2 flattened with the water
    std::vector<channel_join> joins;  ///< pairs of pieces of one channel joined (join_channels), by (kept, part_a,
                                      ///< part_b)
    water_under_decks_result decks;   ///< cells the rivers took under and beside bridge decks (under_decks)
    shoreline_check shorelines;       ///< shore cells found below the water (and lifted, with shoreline_rule::lift)
};

/// Hydro-flattens `dem` (a bare-earth DEM, metres, NaN where unknown) with the waterbodies `labels` (0 land,
/// 1..n bodies, as extract_waterbodies numbers them) and the survey's lowest and highest returns `min_z`,
/// `max_z` (metres, NaN where none) on cells of cell_m metres, as a composition of public steps:
///  1. fill_small_islands: holes under min_island_area_m2 join their body; a body in several 8-connected parts
///     is split: its largest part keeps its id, the others take ids after the largest label (by decreasing
///     size, then raster order), each then a body of its own; with join_channels, join_channel_parts makes the
///     pieces of one river cut apart at a weir or a deck one body again (the smallest label), with the land under
///     the deck;
///  2. measure_hydro_body_shape per body: elongation >= min_river_elongation makes a river, else a lake; a lake
///     under min_lake_area_m2 or a river narrower than min_river_width_m is left to the terrain;
///  3. water_heights(labels, min_z, max_z); lakes: lake_level, one level over the body; rivers:
///     trace_river_profile, each cross-section at its level, non-increasing downstream, decks and unflown
///     stretches at the interpolated level, the sections beside a weir cut along it; with to_banks,
///     lower_to_banks: the sections without measured water no higher than their banks in `dem`;
///  4. the DEM takes the water level on the flattened water (also where it was NaN inside a body; a river's cell
///     without a section, which its profile could not reach, stays as it was); with under_decks, water_under_decks
///     on the flattened rivers: the water continues under their decks, at the level beside them and interpolated
///     across them, and the DEM takes it there too (a body's box grows with its new cells; its shape and sections
///     stay as measured);
///  5. enforce_shorelines with `shoreline`: no shore ground below the water beside it;
///  6. hydro_qa of every flattened body.
/// O(cells + sum over bodies of n log n). Same result for any thread count. Progress: 0, per body, 1.
/// @throws invalid_input on rasters of different shapes, cell_m not finite and > 0, options out of range or a
/// negative label; cancelled.
inline hydro_flatten_result hydro_flatten(raster_view<const float> dem, raster_view<const std::int32_t> labels,
                                          raster_view<const float> min_z, raster_view<const float> max_z, double cell_m,
                                          const hydro_flatten_options& opt = {});

}  // namespace lidarfx

#include "lidarfx/pipelines/water/detail/hydro_flatten_impl.hpp"
