// SPDX-License-Identifier: Apache-2.0
// flat_level_cells: the level cells of flat_water_seeds: returns that are smooth and level with their window.
#pragma once

#include <cstdint>

#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/pipelines/water/flat_water_seeds_options.hpp"
#include "lidarfx/pipelines/water/water_rasters.hpp"

namespace lidarfx {

/// The level cells, first step of flat_water_seeds: level(r, c) = 1 where the cell has a return (no
/// dropout, finite min z, inside in.footprint), is not `excluded` (optional, same shape; nonzero = never a
/// seed), is smooth (max z − min z <= opt.max_roughness_m) and level (the finite min z over the
/// (2 opt.level_radius_cells + 1)² window around it, clipped at the border, span at most
/// opt.level_tolerance_m); else 0. Thresholds compare in float, rounded down (float_at_most).
/// Windows of radius 1 and 2 are read in place row by row; larger ones by running min/max filters over
/// strips of rows (min_filter_rows, max_filter_rows): O(cells · log level_radius_cells). `run`: threads
/// (its progress is not called), the same result for any count. Every cell of `level` is written.
/// @throws invalid_input on rasters of different shapes or options or run out of range.
inline void flat_level_cells(const water_rasters& in, raster_view<const std::uint8_t> excluded,
                             const flat_water_seeds_options& opt, raster_view<std::uint8_t> level,
                             const execution& run = {});

/// Returning form: a new mask of min z's shape (see the into form).
inline raster<std::uint8_t> flat_level_cells(const water_rasters& in, raster_view<const std::uint8_t> excluded = {},
                                             const flat_water_seeds_options& opt = {}, const execution& run = {});

}  // namespace lidarfx

#include "lidarfx/pipelines/water/detail/flat_level_cells_impl.hpp"
