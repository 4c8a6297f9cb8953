// SPDX-License-Identifier: Apache-2.0
// Implementation of geodesic_distance (included at the end of kernels/filter/geodesic_distance.hpp).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <numbers>
#include <queue>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"

namespace lidarfx {

inline raster<float> geodesic_distance(raster_view<const std::uint8_t> inside, std::ptrdiff_t from_row,
                                       std::ptrdiff_t from_col, double cell_m)
{
    constexpr const char* fn = "geodesic_distance";
    detail::require_positive(cell_m, fn, "cell_m");
    const std::ptrdiff_t rows = inside.rows(), cols = inside.cols();
    detail::require(from_row >= 0 && from_row < rows && from_col >= 0 && from_col < cols, fn,
                    "the start cell must lie inside the raster");
    detail::require(inside(from_row, from_col) != 0, fn, "the start cell must lie inside the mask");
    constexpr double infinity = std::numeric_limits<double>::infinity();
    std::vector<double> best(static_cast<std::size_t>(rows * cols), infinity);
    using entry = std::pair<double, std::ptrdiff_t>;  // (distance, row-major index): ties settle by index
    std::priority_queue<entry, std::vector<entry>, std::greater<>> open;
    const std::ptrdiff_t start = from_row * cols + from_col;
    best[static_cast<std::size_t>(start)] = 0;
    open.push({0.0, start});
    const double diagonal = cell_m * std::numbers::sqrt2;
    while (!open.empty()) {
        const auto [d, k] = open.top();
        open.pop();
        if (d > best[static_cast<std::size_t>(k)]) continue;
        const std::ptrdiff_t r = k / cols, c = k % cols;
        for (std::ptrdiff_t dr = -1; dr <= 1; ++dr) {
            for (std::ptrdiff_t dc = -1; dc <= 1; ++dc) {
                const std::ptrdiff_t rr = r + dr, cc = c + dc;
                if ((dr == 0 && dc == 0) || rr < 0 || rr >= rows || cc < 0 || cc >= cols || !inside(rr, cc)) continue;
                const double next = d + (dr != 0 && dc != 0 ? diagonal : cell_m);
                double& known = best[static_cast<std::size_t>(rr * cols + cc)];
                if (next < known) {
                    known = next;
                    open.push({next, rr * cols + cc});
                }
            }
        }
    }
    raster<float> out(rows, cols);
    for (std::ptrdiff_t k = 0; k < rows * cols; ++k)
        out.data()[k] = static_cast<float>(best[static_cast<std::size_t>(k)]);
    return out;
}

}  // namespace lidarfx
