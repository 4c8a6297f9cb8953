// SPDX-License-Identifier: Apache-2.0
// Plain reference for joining waterbodies across bridges: for every land cell, walk both ways along each
// of the 4 directions until water, and test the run between the two bodies as the rule is stated: some split
// of its deck and water cells into water, deck, water, with a deck cell or a cell without a return in the run;
// the cell joins when it has no return or is deck or water.
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
                // The run from body b (the side walked with -d) to body a.
                std::vector<float> run;
                for (int k = steps[1] - 1; k >= 1; --k) run.push_back(min_z(r - k * d[0], c - k * d[1]));
                run.push_back(min_z(r, c));
                for (int k = 1; k < steps[0]; ++k) run.push_back(min_z(r + k * d[0], c + k * d[1]));
                // Water seen lies between the lower level − water_tolerance and the higher + water_tolerance, the
                // deck clearance above the higher; other cells with a return (banks) are left out of the order and
                // stay land.
                const auto deck = [&](float z) { return z - std::max(la, lb) >= clearance; };
                const auto water = [&](float z) {
                    return z >= std::min(la, lb) - water_tolerance && z <= std::max(la, lb) + water_tolerance;
                };
                std::vector<bool> kept_deck;
                bool has_deck = false;
                for (const float z : run) {
                    has_deck = has_deck || !std::isfinite(z) || deck(z);
                    if (std::isfinite(z) && (deck(z) || water(z))) kept_deck.push_back(deck(z));
                }
                const auto n = static_cast<int>(kept_deck.size());
                bool fits = false;  // some split: water [0, i), deck [i, j), water [j, n)
                for (int i = 0; i <= n && !fits; ++i)
                    for (int j = i; j <= n && !fits; ++j) {
                        bool ok = true;
                        for (int k = 0; k < n && ok; ++k)
                            ok = kept_deck[static_cast<std::size_t>(k)] == (k >= i && k < j);
                        fits = ok;
                    }
                const float z = min_z(r, c);
                if (!fits || !has_deck || (std::isfinite(z) && !deck(z) && !water(z))) continue;
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
