// SPDX-License-Identifier: Apache-2.0
// Reference inverse distance weighting: for every hole, every data cell of the raster is a candidate;
// candidates within the radius are sorted by (squared distance, row, col) and the first k are averaged.
#pragma once

#include <lidarfx/core/raster.hpp>
#include <lidarfx/core/raster_view.hpp>
#include <lidarfx/kernels/interpolate/idw_fill.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <tuple>
#include <vector>

namespace reference {

/// Brute-force lidarfx::idw_fill: O(holes x data cells x log). Holes are NaN cells, data cells finite ones.
inline lidarfx::raster<float> idw_fill(lidarfx::raster_view<const float> z, double cell_m,
                                       const lidarfx::idw_fill_options& opt)
{
    struct candidate {
        std::int64_t d2;
        std::ptrdiff_t r, c;
        float z;
    };
    std::vector<candidate> data;
    for (std::ptrdiff_t r = 0; r < z.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < z.cols(); ++c)
            if (std::isfinite(z(r, c))) data.push_back({0, r, c, z(r, c)});

    lidarfx::raster<float> out(z.rows(), z.cols());
    std::vector<candidate> near;
    for (std::ptrdiff_t r = 0; r < z.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < z.cols(); ++c) {
            out(r, c) = z(r, c);
            if (!std::isnan(z(r, c))) continue;
            near.clear();
            for (candidate d : data) {
                d.d2 = (d.r - r) * (d.r - r) + (d.c - c) * (d.c - c);
                // Inclusive radius, with the documented tolerance of 1e-9 cells.
                const bool within =
                    opt.radius_m == 0 || std::sqrt(static_cast<double>(d.d2)) <= opt.radius_m / cell_m + 1e-9;
                if (within) near.push_back(d);
            }
            std::sort(near.begin(), near.end(), [](const candidate& a, const candidate& b) {
                return std::tie(a.d2, a.r, a.c) < std::tie(b.d2, b.r, b.c);
            });
            if (near.size() > static_cast<std::size_t>(opt.k)) near.resize(static_cast<std::size_t>(opt.k));
            if (near.empty()) continue;  // stays NaN
            double weights = 0, weighted = 0;
            for (const candidate& n : near) {
                const double w = 1.0 / std::pow(cell_m * std::sqrt(static_cast<double>(n.d2)), opt.power);
                weights += w;
                weighted += w * n.z;
            }
            out(r, c) = static_cast<float>(weighted / weights);
        }
    }
    return out;
}

}  // namespace reference
