// SPDX-License-Identifier: Apache-2.0
// Plain reference for joining waterbodies across bridges: for every land cell, walk both ways along each
// of the 4 directions until water, as the rule is stated.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <vector>

#include <lidarfx/core/raster.hpp>

namespace reference {

inline void join_across_bridges(lidarfx::raster<std::int32_t>& labels, lidarfx::raster_view<const float> min_z,
                                const std::vector<double>& level, int span, double level_tolerance, double clearance,
                                double water_tolerance)
{
    const std::ptrdiff_t rows = labels.rows(), cols = labels.cols();
    std::vector<std::int32_t> parent(level.size());
    std::iota(parent.begin(), parent.end(), 0);
    const auto find = [&](std::int32_t x) {
        while (parent[x] != x) x = parent[x];
        return x;
    };
    const lidarfx::raster<std::int32_t> original = labels;
    const int dirs[4][2] = {{0, 1}, {1, 0}, {1, 1}, {1, -1}};
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            if (original(r, c) != 0) continue;
            for (const auto& d : dirs) {
                std::int32_t end[2] = {0, 0};
                int steps[2] = {0, 0};
                for (int side = 0; side < 2; ++side) {
                    const int sign = side == 0 ? 1 : -1;
                    for (int k = 1; k <= span; ++k) {
                        const std::ptrdiff_t rr = r + sign * k * d[0], cc = c + sign * k * d[1];
                        if (rr < 0 || cc < 0 || rr >= rows || cc >= cols) break;
                        if (original(rr, cc) != 0) {
                            end[side] = original(rr, cc);
                            steps[side] = k;
                            break;
                        }
                    }
                }
                const auto a = end[0], b = end[1];
                if (a == 0 || b == 0 || a == b || steps[0] + steps[1] - 1 > span) continue;
                const double la = level[a], lb = level[b];
                if (!(std::abs(la - lb) <= level_tolerance)) continue;
                const float z = min_z(r, c);
                if (std::isfinite(z)) {
                    const double above = z - std::max(la, lb), below = std::min(la, lb) - z;
                    if (!(above >= clearance) && !(above <= water_tolerance && below <= water_tolerance)) continue;
                }
                labels(r, c) = std::min(a, b);
                const auto ra = find(a), rb = find(b);
                if (ra != rb) parent[std::max(ra, rb)] = std::min(ra, rb);
                break;
            }
        }
    for (auto& l : labels)
        if (l > 0) l = find(l);
}

}  // namespace reference
