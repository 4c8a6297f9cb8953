// SPDX-License-Identifier: Apache-2.0
// seed_water_level: the water level a seed of dropouts lies at, from the returns around it.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// Options of seed_water_level.
struct seed_water_level_options {
    int ring_cells = 2;      ///< cells within this Chebyshev distance of the seed are read, >= 1. Default 2.
    double quantile = 0.1;   ///< the level is this quantile of their min z, in [0, 1]. Default 0.1: a seed's
                             ///< surroundings are water and bank; the water's returns are the lowest.
};

/// Water level of a seed (a component of dropout cells, as linear indices r * cols + c): the `quantile`
/// of the finite min z of the cells within ring_cells of a seed cell that are not seed cells (each cell
/// once; the element at position ⌊quantile · (n − 1)⌋ of the n sorted values), metres; NaN when no such
/// cell has a return. A seed lies on water, so its ring holds the water's returns at the level and, where
/// the seed reaches the shore, the bank's returns above it: a low quantile is the water's level even
/// when most of the ring is bank. O(seed boundary cells · (2 ring + 1)²).
/// @throws invalid_input on options out of range or a seed index outside min_z.
inline double seed_water_level(std::span<const std::ptrdiff_t> seed, raster_view<const float> min_z,
                               const seed_water_level_options& opt = {})
{
    constexpr const char* fn = "seed_water_level";
    detail::require(opt.ring_cells >= 1, fn, "ring_cells", ">= 1", opt.ring_cells);
    detail::require(opt.quantile >= 0 && opt.quantile <= 1, fn, "quantile", "in [0, 1]", opt.quantile);
    const std::ptrdiff_t rows = min_z.rows(), cols = min_z.cols(), n = rows * cols;
    const std::ptrdiff_t k = opt.ring_cells;
    std::vector<std::ptrdiff_t> ring;
    const detail::cell_splitter split(cols);
    for (const auto i : seed) {
        if (i < 0 || i >= n) [[unlikely]]
            detail::require(false, fn, "seed cell index", "inside min_z", i);
        const auto [r, c] = split(i);
        for (std::ptrdiff_t rr = std::max<std::ptrdiff_t>(0, r - k); rr <= std::min(rows - 1, r + k); ++rr)
            for (std::ptrdiff_t cc = std::max<std::ptrdiff_t>(0, c - k); cc <= std::min(cols - 1, c + k); ++cc)
                if (std::isfinite(min_z(rr, cc))) ring.push_back(rr * cols + cc);
    }
    // Seed cells are dropouts (no return), so finite cells are never seed cells; count each once.
    std::sort(ring.begin(), ring.end());
    ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
    if (ring.empty()) return NAN;
    std::vector<float> z;
    z.reserve(ring.size());
    for (const auto i : ring) {
        const auto [r, c] = split(i);
        z.push_back(min_z(r, c));
    }
    const auto at = z.begin() + static_cast<std::ptrdiff_t>(std::floor(opt.quantile * static_cast<double>(z.size() - 1)));
    std::nth_element(z.begin(), at, z.end());
    return *at;
}

}  // namespace lidarfx
