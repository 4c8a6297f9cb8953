// SPDX-License-Identifier: Apache-2.0
// convex_hull: the exact convex hull of integer cell positions, and burn_convex, which marks the cells whose
// centres lie inside (or on) such a hull (ground_model's hull of each edge object; join_channel_parts takes the
// hull of a deck's two water edges).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// A cell position (col, row) with integer coordinates.
using cell_point = std::array<std::int64_t, 2>;

/// Convex hull of integer points (col, row) by Andrew's monotone chain: the hull's vertices counter-clockwise in
/// (col, row) axes, starting at the smallest point; duplicates and collinear points dropped; fewer than three
/// distinct points come back sorted and unique. Exact: 64-bit cross products (coordinates in [0, 2^31)).
/// O(n log n). Never throws except std::bad_alloc.
inline std::vector<cell_point> convex_hull(std::vector<cell_point> points);

/// Sets mask(r, c) = 1 for every cell whose centre (c, r) lies inside or on the convex polygon `hull` (counter-
/// clockwise in (col, row) axes, as convex_hull returns it); one point marks that cell, two points the cells on
/// that segment. Other cells are left as they are. The hull must lie inside the mask (an internal invariant:
/// not checked). O(cells of the hull's bounding box x hull vertices).
inline void burn_convex(const std::vector<cell_point>& hull, raster_view<std::uint8_t> mask);

// ---- implementation ----

inline std::vector<cell_point> convex_hull(std::vector<cell_point> p)
{
    std::sort(p.begin(), p.end());
    p.erase(std::unique(p.begin(), p.end()), p.end());
    if (p.size() < 3) return p;
    const auto cross = [](const auto& o, const auto& a, const auto& b) {
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
    };
    std::vector<cell_point> h(2 * p.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
        h[k++] = p[i];
    }
    for (std::size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
        while (k >= t && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
        h[k++] = p[i];
    }
    h.resize(k - 1);
    return h;
}

inline void burn_convex(const std::vector<cell_point>& hull, raster_view<std::uint8_t> mask)
{
    if (hull.empty()) return;
    std::int64_t r0 = hull[0][1], r1 = r0, c0 = hull[0][0], c1 = c0;
    for (const auto& v : hull) {
        r0 = std::min(r0, v[1]);
        r1 = std::max(r1, v[1]);
        c0 = std::min(c0, v[0]);
        c1 = std::max(c1, v[0]);
    }
    const std::size_t n = hull.size();
    for (std::int64_t r = r0; r <= r1; ++r) {
        for (std::int64_t c = c0; c <= c1; ++c) {
            bool inside = true;
            for (std::size_t i = 0; i < n && inside; ++i) {
                const auto& a = hull[i];
                const auto& b = hull[(i + 1) % n];
                const std::int64_t cr = (b[0] - a[0]) * (r - a[1]) - (b[1] - a[1]) * (c - a[0]);
                if (n >= 3)
                    inside = cr >= 0;
                else if (n == 2)
                    inside = cr == 0 && std::min(a[0], b[0]) <= c && c <= std::max(a[0], b[0]) &&
                             std::min(a[1], b[1]) <= r && r <= std::max(a[1], b[1]);
            }
            if (n == 1) inside = r == hull[0][1] && c == hull[0][0];
            if (inside) mask(static_cast<std::ptrdiff_t>(r), static_cast<std::ptrdiff_t>(c)) = 1;
        }
    }
}

}  // namespace lidarfx
