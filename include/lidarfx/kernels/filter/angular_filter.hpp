// SPDX-License-Identifier: Apache-2.0
// angular_filter: per cell, the steepest angle to any neighbour within a square window (edge strength, degrees).
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <type_traits>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// Settings of angular_filter.
struct angular_filter_options {
    int radius_cells = 2;  ///< window half-size, cells: the window is (2*radius_cells+1)^2; >= 1 (2 = "two tiers")
    execution run = {};    ///< threads, progress and cancellation (core/parallel.hpp); never changes the result
};

/// Angular filter (into form): out(p) = max over neighbours q of atan(|z(q) - z(p)| / (cell_m * |p - q|)),
/// q ranging over the (2*radius_cells+1)^2 window around p clipped at the raster border (Acharjee et al.
/// 2015, the dissertation's "two tiers" for radius 2). Degrees in [0, 90]: 0 on flat ground, near 90 at
/// walls. NaN neighbours are skipped, a NaN centre gives NaN, a cell with no valid neighbour gives 0. z in
/// metres. O(rows * cols * radius_cells^2), one atan per cell; progress between blocks of 64 rows.
/// @throws invalid_input if the shapes differ, cell_m is not finite and > 0, radius_cells < 1,
/// run.threads < 0, or out overlaps z; cancelled if run.progress returns false.
template <raster_input In, class Out>
requires raster_output_of<Out, float>
void angular_filter(const In& z, Out&& out, double cell_m, const angular_filter_options& opt = {});

/// Angular filter (returning form) with options; see the into form for the definition.
template <raster_input In>
raster<float> angular_filter(const In& z, double cell_m, const angular_filter_options& opt);

/// Angular filter (returning form) over a (2*radius_cells+1)^2 window, on the caller's thread.
/// Degrees in [0, 90]; NaN centre gives NaN. @throws invalid_input for cell_m <= 0 or radius_cells < 1.
template <raster_input In>
raster<float> angular_filter(const In& z, double cell_m, int radius_cells = 2);

}  // namespace lidarfx

#include "lidarfx/kernels/filter/detail/angular_filter_impl.hpp"
