// SPDX-License-Identifier: Apache-2.0
// river_profile: a river's cross-sections and their water levels, falling monotonically downstream.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "lidarfx/core/grid.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/pipelines/water/hydro_body_shape.hpp"

namespace lidarfx {

/// Options of river_profile.
struct river_profile_options {
    double section_spacing_m = 5.0;   ///< length of a cross-section along the channel, metres, > 0; sections are
                                      ///< never shorter than one cell. Default 5 m
    double deck_clearance_m = 2.0;    ///< a cell at least this far above the low water nearby is a deck, not water:
                                      ///< join_across_bridges' min_clearance_m, metres, > 0; weirs and dams must
                                      ///< drop less. Default 2 m
    double floor_window_m = 200.0;    ///< the low water nearby is the 10 % quantile of the section quartiles within
                                      ///< half this distance along the channel, metres, > 0. Default 200 m
    double level_window_m = 50.0;     ///< the local level of a section is the median of the section medians within
                                      ///< half this distance along the channel, metres, > 0. Default 50 m: a
                                      ///< stretch between weirs shorter than half of it takes its neighbours' level
    double return_tolerance_m = 0.3;  ///< a cell whose water height lies further than this from its section's
                                      ///< local level is not water (a pier, a bank), metres, > 0. Default 0.3 m
    double level_tolerance_m = 0.15;  ///< a section's reading further than this from its local level is not
                                      ///< measured (interpolated instead), metres, > 0. Default 0.15 m
    double mode_window_m = 0.1;       ///< a section's level is the median of its water returns inside a window of this
                                      ///< height (step 2), metres, > 0. Default 0.1 m
    double lowest_mode_share = 0.25;  ///< a section's heights are read at their lowest window of mode_window_m that
                                      ///< holds at least this share of their densest window's: water is the lowest
                                      ///< surface across a channel, and a level field taken into the body stands
                                      ///< above it. In (0, 1]; 1 reads the densest window. Default 0.25
    double min_return_share = 0.1;    ///< a section whose water returns number fewer than this share of its cells
                                      ///< is not measured (beside a deck, at a ragged end), in [0, 1]. Default 0.1:
                                      ///< water loses most pulses in dropout patches, and such stretches still
                                      ///< hold their level
    double weir_min_drop_m = 0.3;     ///< a fall of at least this between two neighbouring sections is counted as
                                      ///< a weir or dam, metres, > 0. Default 0.3 m
    bool cut_sections_at_weirs = true;  ///< the sections around a weir follow the weir, cell by cell, rather than
                                        ///< straddle it (step 5)
};

/// A river's sections from upstream to downstream.
struct river_profile {
    cell_box box;                      ///< the body's cells, raster cells
    raster<std::int32_t> section;      ///< box-sized: section of each body cell (0 = upstream), -1 off the body
    std::vector<double> level_m;       ///< water level per section, metres: non-increasing downstream
    std::vector<double> measured_m;    ///< median of the section's water returns, metres; NaN where none
    std::vector<std::size_t> returns;  ///< water returns per section (cells within return_tolerance_m of the local
                                       ///< level); 0 for a section that is not measured
    std::vector<std::size_t> cells;    ///< cells per section
    std::vector<std::array<double, 2>> centre;  ///< mean (row, col) of each section's cells, raster cells;
                                                ///< (0, 0) for a section without cells (cells[k] == 0)
    std::size_t weirs = 0;                      ///< falls of at least weir_min_drop_m between neighbouring sections
    double largest_step_m = 0;                  ///< the largest fall between neighbouring sections, metres
};

/// The cross-sections of river `label` (cells inside `box`, with `shape` from measure_hydro_body_shape) and their
/// levels. Sections are cut from the geodesic distance to the shape's end_a: section k holds the body cells at
/// distance [k·s, (k+1)·s), s = max(section_spacing_m, cell_m), so each lies across the channel. Levels, metres:
///  1. decks: each section's lower quartile of its cells' finite `water_z` (the height of their returns, metres,
///     e.g. water_heights(labels, min_z, max_z); the value at position ⌊(n − 1) / 4⌋ of the n sorted values); the
///     low water nearby is the 10 % quantile (position ⌊(n − 1) / 10⌋) of these quartiles over the sections within
///     floor_window_m / 2; cells at least deck_clearance_m above it are a deck. A weir's upper pool stands less
///     than deck_clearance_m above its lower one, so it is not taken for a deck;
///  2. each section is read at its water: the median of its other cells' heights in their lowest window of
///     mode_window_m that holds at least lowest_mode_share of their densest window's (and 3 heights; water is the
///     lowest surface across a channel, so a level field or a bank taken into the body does not lift it). The
///     local level of a section is the median of these readings over the sections within level_window_m / 2 (a
///     running median follows a steady fall exactly, but within half a window of the ends, and keeps the step of
///     a weir; sections without such cells are skipped). A section's water returns are its cells with water_z
///     within return_tolerance_m of its local level, read the same way as measured_m (NaN when none). A section
///     is measured when it has such returns and measured_m lies within level_tolerance_m of its local level and
///     its returns are at least min_return_share of its cells (a few returns off a bank, a ramp or beside a deck
///     do not set a level);
///  3. the river flows towards the end where a least-squares line through the measured levels (weighted by
///     returns) is lower; sections are numbered from upstream (end_b is upstream when the line rises from
///     end_a);
///  4. the measured levels are fitted by isotonic_regression (non-increasing, weighted by returns); sections
///     further than level_tolerance_m from the fit are no longer measured and the rest is fitted again (up to
///     three rounds: a few returns of something in the channel do not hold up a stretch of the profile); a section
///     without returns (under a deck, or unflown) takes the level interpolated linearly between the nearest
///     fitted sections on either side, or the nearest one's at the ends. So the profile only falls, and where
///     nothing was measured the water surface continues at the interpolated level;
///  5. with cut_sections_at_weirs, a weir is followed cell by cell. A weir is a run of at most (width / spacing
///     + 3) neighbouring sections whose levels fall, beyond the river's own fall (the median fall over
///     level_window_m / 2 plus such a run either side), by more than a quarter of weir_min_drop_m at every step and by
///     at least weir_min_drop_m in all: a steep river is not a weir. Within half the river's width plus one section of
///     it (not into the next weir's reach), each cell takes the upper or the lower level, whichever its water_z is
///     nearer. A cell the crest crosses reads the lower pool (its lowest return), so the line that best separates
///     the two pools' cells (the fewest on the wrong side, its direction from every cell of both) lies half a
///     cell's projection before the crest; when it leaves at most 5 % of them on the wrong side the crest is
///     straight. Cells without a height near either pool then take the side of that line within half the river's
///     width plus one section of it (a dropout patch over the crest does not follow the nearer pool's returns),
///     the others the side of the nearest cell that has one; a cell of one side not connected through its side
///     to its own pool takes the other (a stray return does not cross the weir); the cells within one cell of a
///     straight crest take the side their centre lies on. The upper cells join the
///     weir's last upper section, the lower cells its first lower section, and the sections between are left
///     without cells (at the lower level, no longer measured). An oblique weir then leaves no section straddling
///     it; every section stays flat and the profile still only falls.
/// O(n log n) in the body's n cells, plus O(cells of the box + 145 m log m) per weir with m cells around it.
/// @throws invalid_input on rasters of different shapes, options out of range, a box outside the raster or a
/// label without a cell there.
inline river_profile trace_river_profile(raster_view<const std::int32_t> labels, std::int32_t label,
                                         const cell_box& box, const hydro_body_shape& shape,
                                         raster_view<const float> water_z, double cell_m,
                                         const river_profile_options& opt = {});

}  // namespace lidarfx

#include "lidarfx/pipelines/water/detail/river_profile_impl.hpp"
