// SPDX-License-Identifier: Apache-2.0
// measure_waterbodies: number the bodies of a label raster by decreasing area and describe each one.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/grid.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/pipelines/water/water_rasters.hpp"

namespace lidarfx {

/// One extracted waterbody.
struct waterbody {
    std::int32_t label = 0;  ///< 1..n by decreasing area
    std::size_t cells = 0;
    double area_m2 = 0;
    cell_box box;                 ///< bounding box, cells (inclusive)
    std::int32_t seed = 0;        ///< rank of the seed it grew from (1 = largest seed)
    double theta_deg = NAN;       ///< angular threshold reached when growth stopped
    bool stopped_by_ks = false;   ///< false: θ_max reached without a KS rejection
    double mean_intensity = NAN;  ///< mean intensity of its cells with returns (NaN if none)
    double water_level_m = NAN;   ///< median min z of its cells with returns, metres (NaN if none)
    double dropout_fraction = 0;  ///< share of its cells without returns
};

/// Numbers the bodies of `labels` by decreasing area and measures them. On entry, label l > 0 marks body l
/// and bodies[l - 1] holds what is known of it (seed, theta_deg, stopped_by_ks; bodies grows with default
/// entries up to the largest label). On return, labels are 1..n by decreasing cell count (equal counts keep
/// the order of the old labels), labels without cells are gone, and bodies[i] describes label i + 1:
/// cells, area_m2 = cells · cell_m², bounding box, and over its cells with returns (dropout == 0) the mean
/// intensity, the water level (median of the finite min z, metres: the element at position n / 2 of the n
/// sorted values) and the dropout share. O(cells + n log n); bands of rows, then the bodies' medians, run on
/// `run.threads` threads (the same result for any count: a body's intensity is summed run by run, in raster order).
/// @throws invalid_input on rasters of different shapes, cell_m <= 0, negative labels or run.threads < 0.
inline void measure_waterbodies(raster_view<std::int32_t> labels, std::vector<waterbody>& bodies,
                                const water_rasters& in, double cell_m, const execution& run = {});

}  // namespace lidarfx

#include "lidarfx/pipelines/water/detail/measure_waterbodies_impl.hpp"
