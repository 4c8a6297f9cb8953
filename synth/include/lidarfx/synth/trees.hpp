// SPDX-License-Identifier: Apache-2.0
// Trees for synthetic scenes: ellipsoidal crowns, scattered placement and multi-return laser pulses.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "lidarfx/core/las_class.hpp"
#include "lidarfx/synth/point_set.hpp"
#include "lidarfx/synth/random.hpp"

namespace lidarfx::synth {

/// A tree: stem position and ground height, and a crown shaped as the upper half of an ellipsoid whose
/// equator sits halfway between the crown base and the top.
struct tree {
    double x = 0, y = 0;        ///< stem position, metres
    double ground_z = 0;        ///< ground elevation at the stem, metres
    double crown_radius_m = 3;  ///< horizontal crown radius, metres, > 0
    double crown_base_m = 4;    ///< crown base above ground, metres, >= 1.5
    double height_m = 12;       ///< tree top above ground, metres, > crown_base_m + 1
    double intensity = 90;      ///< mean first-return intensity of the foliage
    /// The crown may reach over roofs (its base stands above them): a pulse that meets it over a roof gives
    /// crown_over_roof_returns. Trees without it never cover a roof (roofs hide them).
    bool over_roofs = false;

    /// Height of the crown surface above ground at (px, py): mid + semi * sqrt(1 - rho^2/R^2) with
    /// mid, semi the crown's half-height centre and half-height; a negative number outside the crown.
    double crown_top(double px, double py) const noexcept
    {
        const double dx = px - x, dy = py - y;
        const double q = 1.0 - (dx * dx + dy * dy) / (crown_radius_m * crown_radius_m);
        if (q <= 0) return -1.0;
        const double semi = 0.5 * (height_m - crown_base_m);
        return crown_base_m + semi + semi * std::sqrt(q);
    }
};

/// Size ranges of scattered trees (uniform in each range).
struct tree_size {
    double min_radius_m = 2.0, max_radius_m = 5.0;   ///< crown radius, metres
    double min_height_m = 8.0, max_height_m = 22.0;  ///< total height, metres (>= 6)
    double min_intensity = 50, max_intensity = 140;  ///< mean first-return intensity
};

/// Scatters trees over [0, size_m]^2 on a jittered lattice of `spacing_m`: in each lattice cell a tree of
/// random size is proposed (position jittered by up to 0.4 spacing) and kept with probability
/// probability(x, y, crown_radius_m), which returns 0 where trees must not stand (water, roads, roofs).
/// ground_z(x, y) gives the stem's ground elevation. Deterministic from `random`. O(cells).
template <class Probability, class Ground>
std::vector<tree> scatter_trees(rng& random, double size_m, double spacing_m, const tree_size& size,
                                Probability&& probability, Ground&& ground_z)
{
    std::vector<tree> trees;
    const auto n = static_cast<long long>(std::ceil(size_m / spacing_m));
    for (long long i = 0; i < n; ++i) {
        for (long long j = 0; j < n; ++j) {
            tree t;
            t.x = (static_cast<double>(j) + 0.5 + 0.4 * random.triangular()) * spacing_m;
            t.y = (static_cast<double>(i) + 0.5 + 0.4 * random.triangular()) * spacing_m;
            t.crown_radius_m = random.uniform(size.min_radius_m, size.max_radius_m);
            t.height_m = random.uniform(size.min_height_m, size.max_height_m);
            t.crown_base_m = std::max(1.5, t.height_m * random.uniform(0.25, 0.5));
            t.intensity = random.uniform(size.min_intensity, size.max_intensity);
            const double keep = random.uniform();
            if (t.x < 0 || t.y < 0 || t.x > size_m || t.y > size_m) continue;
            if (keep >= probability(t.x, t.y, t.crown_radius_m)) continue;
            t.ground_z = ground_z(t.x, t.y);
            trees.push_back(t);
        }
    }
    return trees;
}

/// Returns of one pulse that hits a crown whose surface is `crown_top_m` above the ground at the
/// footprint (ground elevation `ground_z`, ground intensity `ground_intensity`). With probability 0.1
/// the pulse passes through a gap and gives one ground return; otherwise 2 (45 %), 3 (35 %) or 4 (20 %)
/// returns: the first within 0.3 m below the crown surface, intermediate ones spread between 1 m (or
/// 30 % of the crown base) and the first, sorted downwards, and the last on the ground (85 %) or on
/// understorey 0.3-0.9 m up. Energy splits between returns, so intensity falls by 0.55 per return and the
/// ground return gets 40 % of the ground's intensity. Calls emit(z, intensity, return_number,
/// number_of_returns, classification) from the first return to the last. O(returns).
template <class Emit>
void tree_returns(const tree& t, double crown_top_m, double ground_z, double ground_intensity, rng& random, Emit&& emit)
{
    if (random.chance(0.1)) {
        emit(ground_z, ground_intensity, 1, 1, las_class::ground);
        return;
    }
    const double u = random.uniform();
    const int n = u < 0.45 ? 2 : u < 0.8 ? 3 : 4;
    double heights[4] = {crown_top_m - 0.3 * random.uniform(), 0, 0, 0};
    const double low = std::max(1.0, 0.3 * t.crown_base_m), high = std::max(low, heights[0] - 0.5);
    for (int k = 1; k < n - 1; ++k) heights[k] = random.uniform(low, high);
    if (n == 4 && heights[1] < heights[2]) std::swap(heights[1], heights[2]);  // downwards
    heights[n - 1] = random.chance(0.85) ? 0.0 : random.uniform(0.3, 0.9);
    double energy = 1.0;
    for (int k = 0; k < n; ++k) {
        const double h = heights[k];
        const bool on_ground = h == 0.0;
        const double intensity =
            on_ground ? 0.4 * ground_intensity : energy * t.intensity * (1.0 + 0.2 * random.triangular());
        const std::uint8_t cls = on_ground ? las_class::ground
                                 : h > 2.0 ? las_class::high_vegetation
                                           : las_class::low_vegetation;
        emit(ground_z + h, intensity, k + 1, n, cls);
        energy *= 0.55;
    }
}

/// Returns of one pulse that hits the crown of `t` (t.over_roofs) where it reaches over a roof: the crown's
/// surface at elevation `crown_top_z`, the roof below at `roof_z` with intensity `roof_intensity`. As
/// tree_returns with the roof in place of the ground: with probability 0.1 one roof return; otherwise 2, 3 or 4
/// returns, the first within 0.3 m below the crown surface, intermediate ones between the crown's base
/// (t.ground_z + t.crown_base_m, kept above the roof) and 0.5 m below the first, and the last on the roof with 40 %
/// of its intensity. Crown returns are high vegetation, roof returns building. O(returns).
template <class Emit>
void crown_over_roof_returns(const tree& t, double crown_top_z, double roof_z, double roof_intensity, rng& random,
                             Emit&& emit)
{
    if (random.chance(0.1)) {
        emit(roof_z, roof_intensity * (1.0 + 0.1 * random.triangular()), 1, 1, las_class::building);
        return;
    }
    const double u = random.uniform();
    const int n = u < 0.45 ? 2 : u < 0.8 ? 3 : 4;
    double heights[4] = {crown_top_z - 0.3 * random.uniform(), 0, 0, 0};
    const double low = std::max(roof_z + 0.5, t.ground_z + t.crown_base_m), high = std::max(low, heights[0] - 0.5);
    for (int k = 1; k < n - 1; ++k) heights[k] = random.uniform(low, high);
    if (n == 4 && heights[1] < heights[2]) std::swap(heights[1], heights[2]);  // downwards
    heights[n - 1] = roof_z;
    double energy = 1.0;
    for (int k = 0; k < n; ++k) {
        const bool on_roof = k == n - 1;
        const double intensity =
            on_roof ? 0.4 * roof_intensity : energy * t.intensity * (1.0 + 0.2 * random.triangular());
        emit(heights[k], intensity, k + 1, n, on_roof ? las_class::building : las_class::high_vegetation);
        energy *= 0.55;
    }
}

}  // namespace lidarfx::synth
