// SPDX-License-Identifier: Apache-2.0
// water_rasters: the survey rasters every waterbody step reads, and their validation.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/kernels/points/rasterize.hpp"
#include "lidarfx/kernels/stats/ks_one_sided.hpp"

namespace lidarfx {

/// The rasters of a survey that the waterbody steps read, all of one shape on one grid (see rasterize()).
/// Views: the caller keeps the rasters alive while a step runs.
struct water_rasters {
    raster_view<const float> min_z;                         ///< lowest return, metres; NaN = no return
    raster_view<const float> max_z;                         ///< highest return, metres; NaN = no return
    raster_view<const float> mean_intensity;                ///< mean return intensity; ignored where dropout
    raster_view<const std::uint8_t> dropout;                ///< 1 = no return in the cell
    raster_view<const std::uint8_t> multiple_returns = {};  ///< optional: 1 = a pulse with several returns
    raster_view<const std::uint32_t> count = {};            ///< optional: points per cell (density checks)
    raster_view<const std::uint8_t> footprint = {};         ///< optional: 1 = inside the surveyed area (see
                                                            ///< survey_footprint); cells outside are no
                                                            ///< data, never dropouts. Empty = all inside
};

/// Views of the output of rasterize() (all six rasters); `pr` must outlive the result.
inline water_rasters to_water_rasters(const rasterize_result& pr) noexcept
{
    return water_rasters{pr.min_z, pr.max_z, pr.mean_intensity, pr.dropout, pr.multiple_returns, pr.count};
}

namespace detail {

/// Refuses rasters of different shapes (the optional ones only when given) and empty rasters.
inline void validate(const water_rasters& in, const char* fn)
{
    require_same_shape(in.min_z, in.max_z, fn, "min_z", "max_z");
    require_same_shape(in.min_z, in.mean_intensity, fn, "min_z", "mean_intensity");
    require_same_shape(in.min_z, in.dropout, fn, "min_z", "dropout");
    if (!in.multiple_returns.empty())
        require_same_shape(in.min_z, in.multiple_returns, fn, "min_z", "multiple_returns");
    if (!in.count.empty()) require_same_shape(in.min_z, in.count, fn, "min_z", "count");
    if (!in.footprint.empty()) require_same_shape(in.min_z, in.footprint, fn, "min_z", "footprint");
    require(!in.min_z.empty(), fn, "the rasters are empty (0 cells)");
}

/// True when cell (r, c) lies inside the survey's footprint (always when no footprint is given).
inline bool inside_footprint(const water_rasters& in, std::ptrdiff_t r, std::ptrdiff_t c) noexcept
{
    return in.footprint.empty() || in.footprint(r, c) != 0;
}

/// min(0, smallest label) and max(0, largest label) of a label raster. O(cells).
inline std::pair<std::int32_t, std::int32_t> label_range(raster_view<const std::int32_t> labels) noexcept
{
    std::int32_t lo = 0, hi = 0;
    for (std::ptrdiff_t r = 0; r < labels.rows(); ++r) {
        const auto [row_lo, row_hi] = row_label_range(labels.row(r), labels.cols());
        lo = std::min(lo, row_lo);
        hi = std::max(hi, row_hi);
    }
    return {lo, hi};
}

/// Median of `values` (no NaN; may be reordered; NaN when empty): the element at position size / 2 of the
/// sorted values (-0 and +0 count as one value, +0). Small sets: nth_element. From 2^16 values on (a large
/// waterbody's heights): radix selection on the 32-bit keys that order floats as numbers (ks_key), offset by
/// the smallest key: the high bits of the offsets that span their range, at most 16, in one counting pass,
/// then the remaining low bits among the values of the bucket holding the median. Heights of one level share
/// their top bits, so counting on fixed top bits would send nearly every value to one counter (each increment
/// waiting on the last); the offsets spread them. Two or three passes that read the values in order (smallest
/// key, high bits, low bits when the span exceeds 2^16), instead of nth_element's scattered partitioning.
/// O(size), plus O(2^16).
inline double median(std::span<float> values)
{
    if (values.empty()) return NAN;
    std::size_t rank = values.size() / 2;
    if (values.size() < (std::size_t{1} << 16) || values.size() > std::numeric_limits<std::uint32_t>::max()) {
        const auto mid = values.begin() + static_cast<std::ptrdiff_t>(rank);
        std::nth_element(values.begin(), mid, values.end());
        return *mid == 0 ? 0.0 : *mid;
    }
    std::uint32_t lowest = std::numeric_limits<std::uint32_t>::max(), highest = 0;
    for (const float x : values) {
        lowest = std::min(lowest, sortable_key(x));
        highest = std::max(highest, sortable_key(x));
    }
    // Offsets k − lowest in [0, highest − lowest]: `shift` low bits below the (at most 16) counted ones.
    const int span_bits = static_cast<int>(std::bit_width(highest - lowest));
    const int shift = std::max(0, span_bits - 16);
    std::vector<std::uint32_t> histogram((std::size_t{1} << 16), 0);
    for (const float x : values) ++histogram[(sortable_key(x) - lowest) >> shift];
    std::uint32_t high = 0;
    while (rank >= histogram[high]) rank -= histogram[high++];
    std::uint32_t low = 0;
    if (shift > 0) {
        std::fill(histogram.begin(), histogram.end(), 0);
        const std::uint32_t mask = (std::uint32_t{1} << shift) - 1;
        for (const float x : values) {
            const std::uint32_t k = sortable_key(x) - lowest;
            if ((k >> shift) == high) ++histogram[k & mask];
        }
        while (rank >= histogram[low]) rank -= histogram[low++];
    }
    const float m = from_sortable_key<float>(lowest + (high << shift | low));
    return m == 0 ? 0.0 : m;
}

}  // namespace detail

}  // namespace lidarfx
