// SPDX-License-Identifier: Apache-2.0
// lower_to_banks: a river's sections without measured water no higher than the ground of their banks.
#pragma once

#include <cstddef>
#include <cstdint>

#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/pipelines/water/river_profile.hpp"

namespace lidarfx {

/// Options of lower_to_banks.
struct lower_to_banks_options {
    double bank_quantile = 0.1;  ///< a section's bank stands at this quantile of the ground of the land cells
                                 ///< 8-adjacent to its cells, in [0, 1]. Default 0.1: cells on the waterline
                                 ///< hold water returns, so the bank's low ground lies at the water; a few pits
                                 ///< or noisy cells below it are ignored
};

/// What lower_to_banks changed.
struct lower_to_banks_result {
    std::size_t sections_lowered = 0;  ///< sections whose level was lowered
    double largest_drop_m = 0;         ///< the most a section was lowered, metres
};

/// Lowers the sections of river `label`'s profile `p` (from trace_river_profile on the same labels) that were not
/// measured (p.returns[k] == 0: under a deck, in a stretch without returns) to their banks, where the level
/// interpolated across them stands above their banks: water never stands above the ground beside it, and a weir
/// hidden in a stretch without returns, or a stretch without returns below the last weir, would otherwise keep
/// the upper pool's level. A section's bank is the bank_quantile of `ground` (a bare-earth DEM, metres, NaN where
/// unknown) over the land cells 8-adjacent to its cells (cells not labelled `label`); a section without such
/// cells keeps its level. A section is never lowered below the next measured section downstream, and the
/// sections of each unmeasured stretch then take the running minimum from upstream: the profile still only
/// falls, and measured sections keep their levels. p.weirs and p.largest_step_m are counted again.
/// O(cells of the box).
/// @throws invalid_input on rasters of different shapes, a box outside the raster, a profile whose section raster
/// is not box-sized or options out of range.
inline lower_to_banks_result lower_to_banks(river_profile& p, raster_view<const std::int32_t> labels,
                                            std::int32_t label, raster_view<const float> ground,
                                            const river_profile_options& river = {},
                                            const lower_to_banks_options& opt = {});

}  // namespace lidarfx

#include "lidarfx/pipelines/water/detail/lower_to_banks_impl.hpp"
