// SPDX-License-Identifier: Apache-2.0
// Reference geodesic distance: Bellman-Ford, relaxing every 8-neighbour edge of the mask until nothing changes.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

#include <lidarfx/core/raster.hpp>
#include <lidarfx/core/raster_view.hpp>

namespace reference {

/// Shortest path lengths in double from (from_row, from_col) over the cells with inside != 0, steps of cell_m to
/// a row or column neighbour and cell_m * sqrt(2) to a diagonal one, written as float; +inf off the mask and where
/// no path leads. Sweeps all cells, relaxing each one's 8 edges, until a sweep changes nothing.
/// O(cells * sweeps), sweeps <= cells.
inline lidarfx::raster<float> geodesic_bellman_ford(lidarfx::raster_view<const std::uint8_t> inside,
                                                    std::ptrdiff_t from_row, std::ptrdiff_t from_col, double cell_m)
{
    const std::ptrdiff_t rows = inside.rows(), cols = inside.cols();
    const double infinity = std::numeric_limits<double>::infinity();
    std::vector<std::vector<double>> d(static_cast<std::size_t>(rows),
                                       std::vector<double>(static_cast<std::size_t>(cols), infinity));
    const auto at = [&](std::ptrdiff_t r, std::ptrdiff_t c) -> double& {
        return d[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)];
    };
    at(from_row, from_col) = 0;
    for (bool changed = true; changed;) {
        changed = false;
        for (std::ptrdiff_t r = 0; r < rows; ++r)
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                if (inside(r, c) == 0 || at(r, c) == infinity) continue;
                for (std::ptrdiff_t dr = -1; dr <= 1; ++dr)
                    for (std::ptrdiff_t dc = -1; dc <= 1; ++dc) {
                        const std::ptrdiff_t rr = r + dr, cc = c + dc;
                        if (rr < 0 || rr >= rows || cc < 0 || cc >= cols || inside(rr, cc) == 0) continue;
                        if (dr == 0 && dc == 0) continue;
                        const double step = dr != 0 && dc != 0 ? cell_m * std::numbers::sqrt2 : cell_m;
                        if (at(r, c) + step < at(rr, cc)) {
                            at(rr, cc) = at(r, c) + step;
                            changed = true;
                        }
                    }
            }
    }
    lidarfx::raster<float> out(rows, cols);
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c) out(r, c) = static_cast<float>(at(r, c));
    return out;
}

}  // namespace reference
