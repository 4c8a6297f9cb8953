// SPDX-License-Identifier: Apache-2.0
// Internals shared by seeds_beyond_bridges and channel_water_seeds: whether a body lies near a cell (a seed cell
// beside water already found is its bank or shore, not water of its own).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "lidarfx/core/raster_view.hpp"

namespace lidarfx::detail {

/// Whether a body (label > 0) lies within `reach` cells (Chebyshev distance) of cell (r, c); empty labels: none.
inline bool body_within(raster_view<const std::int32_t> labels, std::ptrdiff_t r, std::ptrdiff_t c,
                        std::ptrdiff_t reach)
{
    if (labels.empty()) return false;
    for (std::ptrdiff_t y = std::max<std::ptrdiff_t>(0, r - reach); y <= std::min(labels.rows() - 1, r + reach); ++y)
        for (std::ptrdiff_t x = std::max<std::ptrdiff_t>(0, c - reach); x <= std::min(labels.cols() - 1, c + reach);
             ++x)
            if (labels(y, x) > 0) return true;
    return false;
}

}  // namespace lidarfx::detail
