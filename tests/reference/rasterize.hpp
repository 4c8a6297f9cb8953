// SPDX-License-Identifier: Apache-2.0
// Reference rasterization: every point looked up with grid::cell_of, each cell's values kept and reduced
// at the end. Slow and obviously correct; the tests compare lidarfx::rasterize against it bit for bit.
#pragma once

#include <lidarfx/core/grid.hpp>
#include <lidarfx/core/point_cloud.hpp>
#include <lidarfx/kernels/points/rasterize.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

namespace reference {

/// Per-point reference of lidarfx::rasterize for clouds whose intensities are integers (so a plain double
/// sum is exact): min/max of the z of each cell (a zero extreme as +0), mean = sum / count, flags from
/// number_of_returns.
template <lidarfx::point_cloud C>
lidarfx::rasterize_result rasterize(const C& cloud, const lidarfx::grid& g)
{
    const auto cells = static_cast<std::size_t>(g.rows * g.cols);
    std::vector<std::vector<double>> z(cells), intensity(cells);
    std::vector<int> multiple(cells, 0);
    lidarfx::rasterize_result out;
    out.g = g;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const double x = cloud.x(i), y = cloud.y(i), zi = cloud.z(i);
        if (std::isnan(x) || std::isnan(y) || std::isnan(zi) || std::isinf(x) || std::isinf(y) || std::isinf(zi)) {
            ++out.points_nan;
            continue;
        }
        const auto at = g.cell_of(x, y);
        if (!at) {
            ++out.points_outside;
            continue;
        }
        const auto k = static_cast<std::size_t>(at->row * g.cols + at->col);
        z[k].push_back(zi);
        intensity[k].push_back(lidarfx::intensity_of(cloud, i));
        if (lidarfx::number_of_returns_of(cloud, i) > 1) multiple[k] += 1;
        ++out.points_used;
    }
    const float nan = std::numeric_limits<float>::quiet_NaN();
    out.min_z = lidarfx::raster<float>(g.rows, g.cols, nan);
    out.max_z = lidarfx::raster<float>(g.rows, g.cols, nan);
    out.mean_intensity = lidarfx::raster<float>(g.rows, g.cols, 0.0f);
    out.count = lidarfx::raster<std::uint32_t>(g.rows, g.cols, 0u);
    out.dropout = lidarfx::raster<std::uint8_t>(g.rows, g.cols, 1);
    out.multiple_returns = lidarfx::raster<std::uint8_t>(g.rows, g.cols, 0);
    out.multiple_return_count = lidarfx::raster<std::uint32_t>(g.rows, g.cols, 0u);
    for (std::ptrdiff_t r = 0; r < g.rows; ++r) {
        for (std::ptrdiff_t c = 0; c < g.cols; ++c) {
            const auto k = static_cast<std::size_t>(r * g.cols + c);
            if (z[k].empty()) continue;
            double sum = 0;
            for (double v : intensity[k]) sum += v;
            // A zero extreme is +0, whatever the sign of the zeros (or of tiny z that round to zero) was.
            out.min_z(r, c) = static_cast<float>(*std::min_element(z[k].begin(), z[k].end())) + 0.0f;
            out.max_z(r, c) = static_cast<float>(*std::max_element(z[k].begin(), z[k].end())) + 0.0f;
            out.mean_intensity(r, c) = static_cast<float>(sum / static_cast<double>(z[k].size()));
            out.count(r, c) = static_cast<std::uint32_t>(z[k].size());
            out.dropout(r, c) = 0;
            out.multiple_returns(r, c) = static_cast<std::uint8_t>(multiple[k] > 0);
            out.multiple_return_count(r, c) = static_cast<std::uint32_t>(multiple[k]);
        }
    }
    return out;
}

/// True when a and b have the same shape and the same bytes (so NaN equals NaN).
template <class T>
bool same_bits(const lidarfx::raster<T>& a, const lidarfx::raster<T>& b)
{
    return a.rows() == b.rows() && a.cols() == b.cols() &&
           (a.size() == 0 || std::memcmp(a.data(), b.data(), sizeof(T) * static_cast<std::size_t>(a.size())) == 0);
}

/// True when every raster, the grid and the point counters of a and b are identical.
inline bool same_bits(const lidarfx::rasterize_result& a, const lidarfx::rasterize_result& b)
{
    return a.g == b.g && same_bits(a.min_z, b.min_z) && same_bits(a.max_z, b.max_z) &&
           same_bits(a.mean_intensity, b.mean_intensity) && same_bits(a.count, b.count) &&
           same_bits(a.dropout, b.dropout) && same_bits(a.multiple_returns, b.multiple_returns) &&
           same_bits(a.multiple_return_count, b.multiple_return_count) && a.points_used == b.points_used &&
           a.points_outside == b.points_outside && a.points_nan == b.points_nan;
}

}  // namespace reference
