// SPDX-License-Identifier: Apache-2.0
// vegetation_mask: cells whose points spread over more than a height (trees, shrubs), closed by a square.
#pragma once

#include <cmath>
#include <cstdint>
#include <type_traits>
#include <utility>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/kernels/filter/morphology.hpp"

namespace lidarfx {

/// Settings of vegetation_mask.
struct vegetation_mask_options {
    double height_m = 2.0;       ///< vegetation where max_z - min_z > height_m (strictly), metres; finite, >= 0
    int closing_size_cells = 5;  ///< side of the square closing the mask, cells; odd, >= 1 (1 = no closing)
    execution run = {};          ///< threads, progress, cancellation (core/parallel.hpp); never changes the result
};

/// Vegetation mask of a survey (dissertation 2.3.1): 1 where the vertical spread of a cell's points,
/// max_z - min_z, exceeds height_m (canopy above ground), 0 elsewhere and where either raster is NaN
/// (no return); then a morphological closing by a closing_size_cells square (morph_close, clipped at the
/// border) joins the scattered cells of one canopy. Heights in metres. O(cells); progress is reported
/// between blocks of rows of the threshold (first 20 %) and of the closing.
/// @throws invalid_input if the shapes of min_z, max_z and out differ, height_m is negative or not
/// finite, closing_size_cells is even or < 1, or run.threads < 0; cancelled if run.progress returns false.
template <raster_input MinZ, raster_input MaxZ, class Out>
requires raster_output_of<Out, std::uint8_t> && std::is_arithmetic_v<typename MinZ::value_type> &&
    std::is_arithmetic_v<typename MaxZ::value_type>
void vegetation_mask(const MinZ& min_z, const MaxZ& max_z, Out&& out, const vegetation_mask_options& opt = {});

/// Returning form of vegetation_mask: a new 0/1 raster of min_z's shape.
template <raster_input MinZ, raster_input MaxZ>
requires std::is_arithmetic_v<typename MinZ::value_type> && std::is_arithmetic_v<typename MaxZ::value_type>
    raster<std::uint8_t> vegetation_mask(const MinZ& min_z, const MaxZ& max_z, const vegetation_mask_options& opt = {});

}  // namespace lidarfx

#include "lidarfx/kernels/filter/detail/vegetation_mask_impl.hpp"
