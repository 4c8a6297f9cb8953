// SPDX-License-Identifier: Apache-2.0
// intensity_bins: intensities as ranks of their distinct rounded values, the samples of the KS stop.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// Options of intensity_bins.
struct intensity_bins_options {
    double resolution = 1.0;  ///< intensity quantum: values are rounded to multiples of it (nearest, ties to
                              ///< even), in intensity units; finite, > 0. Default 1 (LAS integer intensities).
};

/// Intensity bins of a survey, the form grow_waterbody reads (water_field::intensity_bin and bins).
struct intensity_bins_result {
    raster<std::int32_t> bin;  ///< rank of the cell's rounded intensity among the distinct values, 0-based;
                               ///< -1 for dropouts and non-finite intensities
    int bins = 1;              ///< number of distinct rounded values (ranks 0 .. bins - 1), >= 1
};

namespace detail {

inline void validate(const intensity_bins_options& o, const char* fn)
{
    require_positive(o.resolution, fn, "resolution");
}

}  // namespace detail

/// Rounds the mean intensity of every cell with returns to q = nearbyint(intensity / resolution) and
/// replaces q by its rank among the distinct q of the raster, so that a KS histogram has one bin per
/// distinct value: the one-sided KS statistic depends only on the order of the values, so ranks give the
/// same test as the values. Cells with dropout != 0 or a non-finite intensity get -1.
/// O(cells + range of q) when that range is below 2^24 (LAS intensities), else O(cells log cells).
/// @throws invalid_input if the shapes differ or resolution is not finite and > 0.
inline intensity_bins_result intensity_bins(raster_view<const float> mean_intensity,
                                            raster_view<const std::uint8_t> dropout,
                                            const intensity_bins_options& opt = {})
{
    constexpr const char* fn = "intensity_bins";
    detail::require_same_shape(mean_intensity, dropout, fn, "mean_intensity", "dropout");
    detail::validate(opt, fn);
    const std::ptrdiff_t rows = mean_intensity.rows(), cols = mean_intensity.cols();
    constexpr std::int32_t none = std::numeric_limits<std::int32_t>::min();
    intensity_bins_result result{raster<std::int32_t>(rows, cols, uninitialized), 1};  // pass 1 writes every cell
    raster<std::int32_t>& out = result.bin;
    // Pass 1: rounded values as integers (none = no sample), while they fit in +-1e9 (LAS intensities do).
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    const double inverse = 1.0 / opt.resolution;
    // Presence of the values 0..65535 (16-bit LAS intensities), marked on the way.
    constexpr std::int32_t small = 65536;
    std::vector<std::uint8_t> seen_small(small, 0);
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        std::int32_t* o = out.row(r);
        const std::uint8_t* d = dropout.row(r);
        const float* mean = mean_intensity.row(r);
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            if (d[c] || !std::isfinite(mean[c])) {
                o[c] = none;
                continue;
            }
            const double q = std::nearbyint(static_cast<double>(mean[c]) * inverse);
            lo = std::min(lo, q);
            hi = std::max(hi, q);
            o[c] = static_cast<std::int32_t>(std::clamp(q, -1.0e9, 1.0e9));
            if (o[c] >= 0 && o[c] < small) seen_small[static_cast<std::size_t>(o[c])] = 1;
        }
    }
    if (lo > hi) {
        out.fill(-1);
        return result;
    }
    std::int32_t* cell = out.data();
    const std::ptrdiff_t n = out.size();
    if (hi - lo < double(1 << 24) && lo >= -1.0e9 && hi <= 1.0e9) {
        // Ranks from a presence table over the range of values.
        const auto base = static_cast<std::int64_t>(lo);
        std::vector<std::int32_t> rank(static_cast<std::size_t>(hi - lo) + 1, 0);
        if (lo >= 0 && hi < small) {
            for (std::size_t k = 0; k < rank.size(); ++k) rank[k] = seen_small[k + static_cast<std::size_t>(base)];
        } else {
            for (std::ptrdiff_t i = 0; i < n; ++i)
                if (cell[i] != none) rank[static_cast<std::size_t>(cell[i] - base)] = 1;
        }
        std::int32_t next = 0;
        for (auto& k : rank) k = k ? next++ : -1;
        result.bins = std::max(1, static_cast<int>(next));
        for (std::ptrdiff_t i = 0; i < n; ++i) cell[i] = cell[i] == none ? -1 : rank[static_cast<std::size_t>(cell[i] - base)];
        return result;
    }
    // Wide ranges: ranks from the sorted distinct values, recomputed exactly.
    std::vector<double> distinct;
    const auto value = [&](std::ptrdiff_t i) {
        return std::nearbyint(static_cast<double>(mean_intensity(i / cols, i % cols)) * inverse);
    };
    for (std::ptrdiff_t i = 0; i < n; ++i)
        if (cell[i] != none) distinct.push_back(value(i));
    std::sort(distinct.begin(), distinct.end());
    distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
    result.bins = std::max(1, static_cast<int>(distinct.size()));
    for (std::ptrdiff_t i = 0; i < n; ++i)
        cell[i] = cell[i] == none ? -1
                                  : static_cast<std::int32_t>(std::lower_bound(distinct.begin(), distinct.end(), value(i)) -
                                                              distinct.begin());
    return result;
}

}  // namespace lidarfx
