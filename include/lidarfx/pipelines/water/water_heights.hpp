// SPDX-License-Identifier: Apache-2.0
// water_heights: the height of the water surface in each water cell, unbiased by the spread of the waves.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// The water surface's height in each cell of a body of `labels` (1..n, 0 land), metres: the cell's lowest
/// return plus its body's half spread, the median of (max_z − min_z) / 2 over the body's inner cells with returns
/// (all 8 neighbours in the body: no bank, reed or deck edge in them; over all its cells with returns when it
/// has no inner one; the element at position n / 2 of the n sorted values); NaN on land and where the cell has
/// no return.
/// On water the returns scatter about the surface (waves, noise): a cell's lowest return lies below it by
/// more the more returns the cell has (about 4 cm at 7 pulses/m² on 2 m cells). The midpoint of the lowest
/// and highest return would not be, but a deck's edge, a branch or a bank in the cell raises it; the lowest
/// return is not raised by them, and the half spread of the body, a median, is that of its open water.
/// O(cells + n log n).
/// @throws invalid_input on rasters of different shapes or a negative label.
inline raster<float> water_heights(raster_view<const std::int32_t> labels, raster_view<const float> min_z,
                                   raster_view<const float> max_z)
{
    constexpr const char* fn = "water_heights";
    detail::require_same_shape(labels, min_z, fn, "labels", "min_z");
    detail::require_same_shape(labels, max_z, fn, "labels", "max_z");
    std::vector<std::vector<float>> spread, edge_spread;
    const std::ptrdiff_t rows = labels.rows(), cols = labels.cols();
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const std::int32_t l = labels(r, c);
            detail::require(l >= 0, fn, "labels", ">= 0", l);
            if (l == 0 || !std::isfinite(min_z(r, c)) || !std::isfinite(max_z(r, c))) continue;
            const auto k = static_cast<std::size_t>(l);
            if (spread.size() <= k) {
                spread.resize(k + 1);
                edge_spread.resize(k + 1);
            }
            bool inner = r > 0 && c > 0 && r + 1 < rows && c + 1 < cols;
            for (std::ptrdiff_t rr = r - 1; rr <= r + 1 && inner; ++rr)
                for (std::ptrdiff_t cc = c - 1; cc <= c + 1; ++cc) inner = inner && labels(rr, cc) == l;
            (inner ? spread : edge_spread)[k].push_back(0.5f * (max_z(r, c) - min_z(r, c)));
        }
    std::vector<float> half(spread.size(), 0.0f);
    for (std::size_t l = 0; l < spread.size(); ++l) {
        auto& s = spread[l].empty() ? edge_spread[l] : spread[l];
        if (s.empty()) continue;
        std::nth_element(s.begin(), s.begin() + static_cast<std::ptrdiff_t>(s.size() / 2), s.end());
        half[l] = s[s.size() / 2];
    }
    raster<float> out(labels.rows(), labels.cols(), NAN);
    for (std::ptrdiff_t r = 0; r < labels.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < labels.cols(); ++c)
            if (const std::int32_t l = labels(r, c); l > 0 && static_cast<std::size_t>(l) < half.size())
                out(r, c) = min_z(r, c) + half[static_cast<std::size_t>(l)];
    return out;
}

}  // namespace lidarfx
