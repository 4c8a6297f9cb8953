// SPDX-License-Identifier: Apache-2.0
// slope_aspect: terrain slope and aspect (down-slope azimuth) from Horn's 3x3 gradient, in degrees.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// Settings of slope_aspect.
struct slope_aspect_options {
    double flat_slope_deg = 0.0;  ///< cells with slope <= this (degrees, [0, 90)) are flat: aspect NaN, flat = 1
    execution run = {};           ///< threads, progress and cancellation (core/parallel.hpp); never changes the result
};

/// Slope, aspect and flat mask of a surface, each with the input's shape.
struct slope_aspect_result {
    raster<float> slope_deg;    ///< slope, degrees in [0, 90]; NaN where the gradient is unknown
    raster<float> aspect_deg;   ///< down-slope azimuth, degrees clockwise from north in [0, 360); NaN if flat
    raster<std::uint8_t> flat;  ///< 1 where slope <= flat_slope_deg, else 0 (0 where slope is NaN)
};

/// Slope and aspect (into form) by Horn's (1981) 3x3 weighted differences: dz/dx = ((c + 2f + i) - (a + 2d + g))
/// / (8 cell_m), dz/dy likewise across rows (row 0 is north). Slope = atan(|grad z|) in degrees [0, 90];
/// aspect = azimuth of the down-slope direction, degrees clockwise from north (0 N, 90 E, 180 S, 270 W) in
/// [0, 360), NaN on flat cells (slope <= flat_slope_deg, flat = 1). At borders and next to NaN cells no cell is
/// invented: each row (column) pair of the window uses its centred difference, else a one-sided one, else drops
/// out of the 1-2-1 mean, so planes come out exact everywhere. A NaN centre, or an axis with no difference at all
/// (a 1-row raster), gives NaN slope and aspect and flat = 0. O(rows * cols); progress between blocks of 64 rows.
/// @throws invalid_input if shapes differ, cell_m is not finite and > 0, flat_slope_deg is outside [0, 90),
/// run.threads < 0, or an output overlaps z or another output; cancelled if run.progress returns false.
template <raster_input In, class SlopeOut, class AspectOut, class FlatOut>
requires raster_output_of<SlopeOut, float> && raster_output_of<AspectOut, float> &&
    raster_output_of<FlatOut, std::uint8_t>
void slope_aspect(const In& z, SlopeOut&& slope_deg, AspectOut&& aspect_deg, FlatOut&& flat, double cell_m,
                  const slope_aspect_options& opt = {});

/// Slope and aspect (returning form); see the into form for the definition. z in metres, cell_m in metres.
template <raster_input In>
slope_aspect_result slope_aspect(const In& z, double cell_m, const slope_aspect_options& opt = {});

}  // namespace lidarfx

#include "lidarfx/kernels/filter/detail/slope_aspect_impl.hpp"
