// SPDX-License-Identifier: Apache-2.0
// distance_transform: exact squared Euclidean distance from every cell to the nearest feature cell.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// Settings of squared_distance_transform.
struct distance_transform_options {
    execution run = {};  ///< threads, progress, cancellation (core/parallel.hpp); never changes the result
};

/// The value squared_distance_transform gives every cell of a raster without features.
inline constexpr float no_feature_distance = std::numeric_limits<float>::infinity();

/// Squared Euclidean distance, in cells², from the centre of every cell to the centre of the nearest cell
/// where `features` is nonzero: 0 on features, no_feature_distance (+infinity) everywhere when there is
/// none. Exact (a pass down the columns, then Felzenszwalb and Huttenlocher's lower envelope of parabolas
/// along the rows); the values are integers, exact in float up to 2^24 (distances below 4,096 cells) and
/// rounded to float beyond. Multiply by cell_m² for square metres. O(cells); the same result for any
/// thread count; progress over blocks of the row pass.
/// @throws invalid_input if run.threads < 0; cancelled if run.progress returns false.
inline raster<float> squared_distance_transform(raster_view<const std::uint8_t> features,
                                                const distance_transform_options& opt = {});

}  // namespace lidarfx

#include "lidarfx/kernels/filter/detail/distance_transform_impl.hpp"
