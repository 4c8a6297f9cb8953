// SPDX-License-Identifier: Apache-2.0
// zonal_statistics: per-label statistics of a value raster (count, mean, standard deviation, min, max,
// median) and of an angle raster (circular mean, resultant length, mode and histogram), for buildings,
// waterbodies or any labelling.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// Statistics of the finite values of one label.
struct zone_statistics {
    std::size_t count = 0;  ///< finite values (NaN cells of the label are not counted)
    double mean = NAN;      ///< NaN when count = 0
    double std = NAN;       ///< population standard deviation sqrt(sum (v - mean)^2 / count); NaN when count = 0
    double min = NAN, max = NAN;
    double median = NAN;  ///< middle value; the mean of the two middle values for an even count
};

/// Per-label statistics of `values` over `labels` (same shape): result[k] describes label k for k in
/// 0 .. max label (index 0 = the background, label 0, included for completeness). Non-finite values are left
/// out of every statistic. Sums in double, two passes (mean, then squared deviations): exact order-free
/// results. O(cells + sum of per-label sorts for the medians).
/// @throws invalid_input if the shapes differ or a label is negative.
template <raster_input Labels, raster_input Values>
std::vector<zone_statistics> zonal_statistics(const Labels& labels, const Values& values);

/// Settings of zonal_circular_statistics.
struct zonal_circular_statistics_options {
    double bin_width_deg = 1.0;   ///< histogram bin width, degrees; 360 / bin_width_deg must be a whole number
    bool keep_histograms = true;  ///< fill circular_zone_statistics::histogram (360 / bin_width_deg counts per label)
};

/// Circular statistics of the finite angles (degrees, any range: taken modulo 360) of one label.
struct circular_zone_statistics {
    std::size_t count = 0;
    double mean_deg = NAN;          ///< atan2(sum sin, sum cos) in [0, 360); NaN when count = 0 or the resultant is 0
    double resultant_length = NAN;  ///< |sum of unit vectors| / count in [0, 1]: 1 = all equal, 0 = spread evenly
    double mode_deg = NAN;          ///< centre k * w of the fullest bin [k w - w/2, k w + w/2); ties: smallest k
    std::size_t mode_count = 0;     ///< angles in that bin
    std::vector<std::uint32_t> histogram;  ///< bin k = [k w - w/2, k w + w/2) modulo 360; empty unless kept
};

/// Per-label circular statistics of `angles_deg` over `labels` (same shape), result[k] for label k as in
/// zonal_statistics (aspect modes, mean facing of roof cells, flow directions). Bins are centred on multiples
/// of the bin width, so integer aspects fall in the middle of 1-degree bins. O(cells + labels * bins).
/// @throws invalid_input if the shapes differ, a label is negative or 360 / bin_width_deg is not a whole
/// number in [1, 36000].
template <raster_input Labels, raster_input Angles>
std::vector<circular_zone_statistics> zonal_circular_statistics(const Labels& labels, const Angles& angles_deg,
                                                                const zonal_circular_statistics_options& opt = {});

}  // namespace lidarfx

#include "lidarfx/kernels/stats/detail/zonal_statistics_impl.hpp"
