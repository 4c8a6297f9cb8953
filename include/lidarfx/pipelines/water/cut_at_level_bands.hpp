// SPDX-License-Identifier: Apache-2.0
// cut_at_level_bands: a seed mask cut where its min z crosses a level band, one water level per seed.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// Cuts a seed mask where its min z crosses a level band, so that each seed holds one water level (a seed
/// along a falling river would otherwise take the level of its low end and gate out its high end; the bands
/// are centred on each part's mean, so a lake whose level lies on a multiple of the band stays whole).
/// `parts` labels the 8-connected parts of
/// `mask` (1..count, 0 off the mask; as connected_components gives them). A mask cell with a return has the
/// band index floor((min z − mean) / band + 0.5) in double, mean = its part's mean min z over the cells with
/// a return (0 when none); one without a return has none. A mask cell (r, c) with c + 1 < cols and r + 1 <
/// rows becomes 0 when its right or lower neighbour is on the mask and both have a band index and they
/// differ (uncut neighbours: each cell reads the mask as it was); the other cells keep their value. band in
/// metres, > 0 (extract_waterbodies cuts at 2 level gates). Only the runs of the mask are visited (stretches of 64
/// cells off it are passed over at once): O(cells / 64 + mask cells).
/// @throws invalid_input on rasters of different shapes, band <= 0 or a part label outside [0, count].
inline void cut_at_level_bands(raster_view<std::uint8_t> mask, raster_view<const std::int32_t> parts, std::size_t count,
                               raster_view<const float> min_z, double band);

// ---- implementation ----

inline void cut_at_level_bands(raster_view<std::uint8_t> mask, raster_view<const std::int32_t> parts, std::size_t count,
                               raster_view<const float> min_z, double band)
{
    constexpr const char* fn = "cut_at_level_bands";
    detail::require_same_shape(mask, parts, fn, "mask", "parts");
    detail::require_same_shape(mask, min_z, fn, "mask", "min_z");
    detail::require_positive(band, fn, "band");
    const std::ptrdiff_t rows = mask.rows(), cols = mask.cols();
    std::vector<double> mean(count + 1, 0.0), finite(count + 1, 0.0);  // over returns
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        const std::int32_t* part = parts.row(r);
        const float* z = min_z.row(r);
        detail::for_each_run(part, cols, [&](std::int32_t label, std::ptrdiff_t from, std::ptrdiff_t to) {
            const auto l = static_cast<std::size_t>(label);
            if (l > count) [[unlikely]]
                detail::require(false, fn, "parts", "labels in [0, count]", label);
            double sum = mean[l], n = finite[l];  // along the run in registers, the same additions in order
            for (std::ptrdiff_t c = from; c < to; ++c) {
                if (std::isfinite(z[c])) {
                    sum += z[c];
                    n += 1;
                }
            }
            mean[l] = sum;
            finite[l] = n;
        });
    }
    for (std::size_t l = 1; l < mean.size(); ++l) mean[l] = finite[l] > 0 ? mean[l] / finite[l] : 0.0;
    // Row by row, with the band index of each mask cell of this row and the next (NaN without a return; cells
    // off the mask are not written and not read); a cell's cut reads the uncut mask to its right and below,
    // which `parts` still shows, so row r is cut in place.
    std::vector<double> here(static_cast<std::size_t>(cols)), below(here.size());
    const auto band_row = [&](std::ptrdiff_t r, double* out) {
        const std::int32_t* part = parts.row(r);
        const float* z = min_z.row(r);
        detail::for_each_run(part, cols, [&](std::int32_t l, std::ptrdiff_t from, std::ptrdiff_t to) {
            const double m = mean[static_cast<std::size_t>(l)];
            for (std::ptrdiff_t c = from; c < to; ++c) out[c] = std::floor((z[c] - m) / band + 0.5);
        });
    };
    if (rows > 1) band_row(0, here.data());
    for (std::ptrdiff_t r = 0; r + 1 < rows; ++r) {
        band_row(r + 1, below.data());
        const std::int32_t* part = parts.row(r);
        const std::int32_t* part_below = parts.row(r + 1);
        std::uint8_t* m = mask.row(r);
        for (std::ptrdiff_t c = detail::next_positive(part, 0, cols - 1); c < cols - 1;
             c = detail::next_positive(part, c, cols - 1)) {
            for (; c < cols - 1 && part[c] > 0; ++c) {
                // A dropout in the mask has no band (NaN): nothing is cut next to it.
                const double h = here[static_cast<std::size_t>(c)];
                if (std::isnan(h)) continue;
                const double right = here[static_cast<std::size_t>(c + 1)], down = below[static_cast<std::size_t>(c)];
                const bool cut_right = part[c + 1] > 0 && !std::isnan(right) && right != h;
                const bool cut_down = part_below[c] > 0 && !std::isnan(down) && down != h;
                if (cut_right || cut_down) m[c] = 0;
            }
        }
        here.swap(below);
    }
}

}  // namespace lidarfx
