// SPDX-License-Identifier: Apache-2.0
// Reference connected components: breadth-first flood fill from each unlabelled cell in raster order.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <utility>
#include <vector>

#include <lidarfx/core/raster.hpp>
#include <lidarfx/kernels/label/connected_components.hpp>

namespace reference {

/// Labels (0 = background, 1.. in raster order of first cells) and sizes (sizes[0] = background), by
/// flooding each component from its first cell with a queue.
template <class View>
lidarfx::components flood_label(const View& m, lidarfx::connectivity conn)
{
    const std::ptrdiff_t rows = m.rows(), cols = m.cols();
    lidarfx::components out{lidarfx::raster<std::int32_t>(rows, cols, 0), {0}};
    const bool eight = conn == lidarfx::connectivity::eight;
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            if (m(r, c) == 0) {
                ++out.sizes[0];
                continue;
            }
            if (out.labels(r, c) != 0) continue;
            const auto label = static_cast<std::int32_t>(out.sizes.size());
            out.sizes.push_back(0);
            std::deque<std::pair<std::ptrdiff_t, std::ptrdiff_t>> queue{{r, c}};
            out.labels(r, c) = label;
            while (!queue.empty()) {
                const auto [y, x] = queue.front();
                queue.pop_front();
                ++out.sizes.back();
                for (std::ptrdiff_t dy = -1; dy <= 1; ++dy) {
                    for (std::ptrdiff_t dx = -1; dx <= 1; ++dx) {
                        if ((dy == 0 && dx == 0) || (!eight && dy != 0 && dx != 0)) continue;
                        const std::ptrdiff_t ny = y + dy, nx = x + dx;
                        if (ny < 0 || ny >= rows || nx < 0 || nx >= cols) continue;
                        if (m(ny, nx) == 0 || out.labels(ny, nx) != 0) continue;
                        out.labels(ny, nx) = label;
                        queue.emplace_back(ny, nx);
                    }
                }
            }
        }
    }
    return out;
}

/// True if a and b partition the cells the same way (same background, labels equal up to a bijection).
inline bool same_partition(const lidarfx::raster<std::int32_t>& a, const lidarfx::raster<std::int32_t>& b)
{
    if (a.rows() != b.rows() || a.cols() != b.cols()) return false;
    std::map<std::int32_t, std::int32_t> ab, ba;
    for (std::ptrdiff_t i = 0; i < a.size(); ++i) {
        const auto x = a.data()[i], y = b.data()[i];
        if ((x == 0) != (y == 0)) return false;
        if (ab.emplace(x, y).first->second != y || ba.emplace(y, x).first->second != x) return false;
    }
    return true;
}

/// The transpose of a raster.
template <class T>
lidarfx::raster<T> transpose(const lidarfx::raster<T>& m)
{
    lidarfx::raster<T> t(m.cols(), m.rows());
    for (std::ptrdiff_t r = 0; r < m.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < m.cols(); ++c) t(c, r) = m(r, c);
    return t;
}

}  // namespace reference
