// SPDX-License-Identifier: Apache-2.0
// building_heights: the terrain, eave and ridge elevations and the footprint area of every building
// (extract_buildings step 6).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// Heights of one building, metres, and its footprint.
struct building_height {
    double ground_z = 0;      ///< mean terrain elevation under the footprint, metres
    double eave_z = 0;        ///< 5th percentile of the roof elevation, metres
    double ridge_z = 0;       ///< 99th percentile of the roof elevation, metres
    double footprint_m2 = 0;  ///< cells x cell_m^2
};

/// Heights of buildings 1..count of `building_id` (element b - 1 for building b): ground_z = mean of `ground`
/// over the building's cells; eave_z and ridge_z = the elements at floor(q x (n - 1)) of its n roof elevations
/// `z` sorted (q = 0.05 and 0.99; no interpolation); footprint = n x cell_m^2. A building without cells gets
/// zeros. Elevations in metres. O(cells log cells).
/// @throws invalid_input if the shapes differ or a building id is outside [0, count].
inline std::vector<building_height> building_heights(raster_view<const float> z, raster_view<const float> ground,
                                                     raster_view<const std::int32_t> building_id, std::size_t count,
                                                     double cell_m);

// ---- implementation ----

inline std::vector<building_height> building_heights(raster_view<const float> z, raster_view<const float> ground,
                                                     raster_view<const std::int32_t> building_id, std::size_t count,
                                                     double cell_m)
{
    constexpr const char* function = "building_heights";
    detail::require_same_shape(z, ground, function, "z", "ground");
    detail::require_same_shape(z, building_id, function, "z", "building_id");
    std::vector<std::vector<float>> heights(count);
    std::vector<double> ground_sum(count, 0.0);
    for (std::ptrdiff_t r = 0; r < z.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < z.cols(); ++c) {
            const std::int32_t b = building_id(r, c);
            if (b == 0) continue;
            detail::require(b > 0 && static_cast<std::size_t>(b) <= count, function, "building_id", "in [0, count]", b);
            heights[static_cast<std::size_t>(b) - 1].push_back(z(r, c));
            ground_sum[static_cast<std::size_t>(b) - 1] += static_cast<double>(ground(r, c));
        }
    }
    std::vector<building_height> out(count);
    for (std::size_t b = 0; b < count; ++b) {
        auto& h = heights[b];
        if (h.empty()) continue;
        std::sort(h.begin(), h.end());
        const auto at = [&](double q) {
            return static_cast<double>(h[static_cast<std::size_t>(q * static_cast<double>(h.size() - 1))]);
        };
        out[b].eave_z = at(0.05);
        out[b].ridge_z = at(0.99);
        out[b].ground_z = ground_sum[b] / static_cast<double>(h.size());
        out[b].footprint_m2 = static_cast<double>(h.size()) * (cell_m * cell_m);
    }
    return out;
}

}  // namespace lidarfx
