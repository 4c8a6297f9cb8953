// SPDX-License-Identifier: Apache-2.0
// seed_water_level: the water level a seed of dropouts lies at, from the returns around it.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// Options of seed_water_level.
struct seed_water_level_options {
    int ring_cells = 2;     ///< cells within this Chebyshev distance of the seed are read, >= 1. Default 2.
    double quantile = 0.1;  ///< the level is this quantile of their min z, in [0, 1]. Default 0.1: a seed's
                            ///< surroundings are water and bank; the water's returns are the lowest.
};

/// Water level of a seed (a component of cells, as linear indices r * cols + c): the `quantile` of the
/// finite min z of the cells within ring_cells of a seed cell (each cell once; the element at position
/// ⌊quantile · (n − 1)⌋ of the n sorted values), metres; NaN when no such cell has a return. A dropout
/// seed's own cells have none, so its level comes from the ring around it; a seed with returns (flat seeds)
/// counts its own cells too. A seed lies on water, so its ring holds the water's returns at the level and,
/// where the seed reaches the shore, the bank's returns above it: a low quantile is the water's level even
/// when most of the ring is bank. O(seed cells · (2 ring + 1)² + box / 64) time, O(box / 64) words of
/// memory, box = the cells of the seed's bounding box grown by ring_cells.
/// @throws invalid_input on options out of range or a seed index outside min_z.
inline double seed_water_level(std::span<const std::ptrdiff_t> seed, raster_view<const float> min_z,
                               const seed_water_level_options& opt = {})
{
    constexpr const char* fn = "seed_water_level";
    detail::require(opt.ring_cells >= 1, fn, "ring_cells", ">= 1", opt.ring_cells);
    detail::require(opt.quantile >= 0 && opt.quantile <= 1, fn, "quantile", "in [0, 1]", opt.quantile);
    const std::ptrdiff_t rows = min_z.rows(), cols = min_z.cols(), n = rows * cols;
    const std::ptrdiff_t k = opt.ring_cells;
    if (seed.empty()) return NAN;
    const detail::cell_splitter split(cols);
    // The ring's cells, each once, marked in a bit raster over the seed's bounding box grown by k (in row
    // order, as sorting their indices would list them).
    std::ptrdiff_t r_lo = rows, r_hi = -1, c_lo = cols, c_hi = -1;
    for (const auto i : seed) {
        if (i < 0 || i >= n) [[unlikely]]
            detail::require(false, fn, "seed cell index", "inside min_z", i);
        const auto [r, c] = split(i);
        r_lo = std::min(r_lo, r);
        r_hi = std::max(r_hi, r);
        c_lo = std::min(c_lo, c);
        c_hi = std::max(c_hi, c);
    }
    r_lo = std::max<std::ptrdiff_t>(0, r_lo - k);
    r_hi = std::min(rows - 1, r_hi + k);
    c_lo = std::max<std::ptrdiff_t>(0, c_lo - k);
    c_hi = std::min(cols - 1, c_hi + k);
    const std::ptrdiff_t box_cols = c_hi - c_lo + 1, words_per_row = (box_cols + 63) / 64;
    std::vector<std::uint64_t> in_ring(static_cast<std::size_t>((r_hi - r_lo + 1) * words_per_row), 0);
    for (const auto i : seed) {
        const auto [r, c] = split(i);
        for (std::ptrdiff_t rr = std::max<std::ptrdiff_t>(0, r - k); rr <= std::min(rows - 1, r + k); ++rr) {
            std::uint64_t* bits = in_ring.data() + (rr - r_lo) * words_per_row;
            for (std::ptrdiff_t cc = std::max<std::ptrdiff_t>(0, c - k); cc <= std::min(cols - 1, c + k); ++cc)
                if (std::isfinite(min_z(rr, cc))) bits[(cc - c_lo) / 64] |= std::uint64_t{1} << ((cc - c_lo) % 64);
        }
    }
    std::vector<float> z;
    for (std::ptrdiff_t rr = r_lo; rr <= r_hi; ++rr) {
        const std::uint64_t* bits = in_ring.data() + (rr - r_lo) * words_per_row;
        for (std::ptrdiff_t w = 0; w < words_per_row; ++w)
            for (std::uint64_t word = bits[w]; word != 0; word &= word - 1)
                z.push_back(min_z(rr, c_lo + w * 64 + std::countr_zero(word)));
    }
    if (z.empty()) return NAN;
    const auto at =
        z.begin() + static_cast<std::ptrdiff_t>(std::floor(opt.quantile * static_cast<double>(z.size() - 1)));
    std::nth_element(z.begin(), at, z.end());
    return *at;
}

}  // namespace lidarfx
