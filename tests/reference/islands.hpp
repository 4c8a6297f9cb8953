// SPDX-License-Identifier: Apache-2.0
// Plain reference for filling small islands: label every land component of the whole raster by BFS and
// fill those that are small, away from the border, and next to exactly one body.
#pragma once

#include <cstdint>
#include <queue>
#include <vector>

#include <lidarfx/core/raster.hpp>

namespace reference {

inline void fill_small_islands(lidarfx::raster<std::int32_t>& labels, std::size_t max_hole_cells)
{
    const std::ptrdiff_t rows = labels.rows(), cols = labels.cols();
    std::vector<std::uint8_t> seen(static_cast<std::size_t>(rows * cols), 0);
    const lidarfx::raster<std::int32_t> original = labels;
    for (std::ptrdiff_t start = 0; start < rows * cols; ++start) {
        if (seen[start] || original.data()[start] != 0) continue;
        std::vector<std::ptrdiff_t> part{start};
        seen[start] = 1;
        bool border = false;
        std::int32_t owner = 0;
        for (std::size_t q = 0; q < part.size(); ++q) {
            const std::ptrdiff_t r = part[q] / cols, c = part[q] % cols;
            if (r == 0 || c == 0 || r == rows - 1 || c == cols - 1) border = true;
            const std::ptrdiff_t nb[4][2] = {{r - 1, c}, {r + 1, c}, {r, c - 1}, {r, c + 1}};
            for (const auto& p : nb) {
                if (p[0] < 0 || p[1] < 0 || p[0] >= rows || p[1] >= cols) continue;
                const auto j = p[0] * cols + p[1];
                const auto l = original.data()[j];
                if (l != 0) {
                    owner = owner == 0 ? l : owner == l ? l : -1;
                } else if (!seen[j]) {
                    seen[j] = 1;
                    part.push_back(j);
                }
            }
        }
        if (!border && owner > 0 && part.size() < max_hole_cells)
            for (const auto i : part) labels.data()[i] = owner;
    }
}

}  // namespace reference
