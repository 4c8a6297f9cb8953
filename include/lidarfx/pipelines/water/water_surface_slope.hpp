// SPDX-License-Identifier: Apache-2.0
// water_surface_slope: the slope of the least-squares plane through the lowest returns around each cell.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// Options of water_surface_slope.
struct water_surface_slope_options {
    int radius_cells = 3;        ///< the plane is fitted to the (2 r + 1)² window around a cell (7 × 7: with 2-3 cm
                                 ///< range noise its slope is known to about 0.1 % at 2 m cells), >= 1. Default 3
    std::size_t min_cells = 12;  ///< fewer cells with a return in the window give NaN (unknown), >= 3. Default 12
    double band_m = 0.15;        ///< only returns within this of the cell's own min z are fitted (water next to a
                                 ///< bank sees the water, not the bank; on a beach rising 1-6 % the band still
                                 ///< spans several cells), metres, > 0. Default 0.15 (the level gate)
    execution run = {};          ///< threads (rows are independent; same result for any count)
};

namespace detail {

/// One offset (x, y) of water_surface_slope's window over `count` cells of a row: the sums of the
/// neighbours nb[c] within ±band of the cell's own z0[c] (NaN on either side: left out). Branch-free over
/// separate arrays, so it vectorizes.
inline void slope_sums(const float* __restrict nb, const float* __restrict z0, std::ptrdiff_t count,
                       float x, float y, float band, float* __restrict n, float* __restrict sx, float* __restrict sy,
                       float* __restrict sxx, float* __restrict syy, float* __restrict sxy, float* __restrict sz,
                       float* __restrict sxz, float* __restrict syz) noexcept
{
    const float xx = x * x, yy = y * y, xy = x * y;
    for (std::ptrdiff_t c = 0; c < count; ++c) {
        const float d = nb[c] - z0[c];
        const bool in = std::fabs(d) <= band;
        // Bit-mask selects: a plain `in ? d : 0` keeps the loop scalar on AVX2 (no masked arithmetic).
        const float m = select_bits(in, 1.0f, 0.0f), dz = select_bits(in, d, 0.0f);
        n[c] += m;
        sx[c] += m * x;
        sy[c] += m * y;
        sxx[c] += m * xx;
        syy[c] += m * yy;
        sxy[c] += m * xy;
        sz[c] += dz;
        sxz[c] += dz * x;
        syz[c] += dz * y;
    }
}

}  // namespace detail

/// Slope of the water surface test: per cell, the magnitude of the gradient of the least-squares plane
/// z = a + b·x + c·y through the min z of the (2·radius_cells + 1)² window (clipped at the raster border)
/// that lie within band_m of the cell's own, sqrt(b² + c²) in metres per metre (0 = level); NaN where the
/// cell has no return, the window holds fewer than min_cells such returns, or they lie on a line. A water
/// surface is level to the range noise (a river falls a few mm per metre at most); beaches, banks and
/// meadows rising from the water are not. cell_m in metres.
/// O(cells · (2·radius_cells + 1)²), vectorized along rows.
/// @throws invalid_input on cell_m <= 0 or options out of range.
inline raster<float> water_surface_slope(raster_view<const float> min_z, double cell_m,
                                         const water_surface_slope_options& opt = {})
{
    constexpr const char* fn = "water_surface_slope";
    detail::require_positive(cell_m, fn, "cell_m");
    detail::require(opt.radius_cells >= 1, fn, "radius_cells", ">= 1", opt.radius_cells);
    detail::require(opt.min_cells >= 3, fn, "min_cells", ">= 3", opt.min_cells);
    detail::require(opt.band_m > 0, fn, "band_m", "> 0", opt.band_m);
    detail::check_execution(opt.run, fn);
    const std::ptrdiff_t rows = min_z.rows(), cols = min_z.cols(), k = opt.radius_cells;
    raster<float> out(rows, cols, NAN);
    const float band = static_cast<float>(opt.band_m);
    const auto need = static_cast<float>(opt.min_cells);
    // Per row, the window's sums are accumulated offset by offset over the whole row (contiguous, so the
    // loops vectorize), in float: heights enter relative to the cell's own, within ±band_m.
    parallel_for_rows(rows, 16, opt.run.threads, [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
        const auto n_cols = static_cast<std::size_t>(cols);
        std::vector<float> sums(9 * n_cols);
        float* n = sums.data();
        float* sx = n + n_cols;
        float* sy = sx + n_cols;
        float* sxx = sy + n_cols;
        float* syy = sxx + n_cols;
        float* sxy = syy + n_cols;
        float* sz = sxy + n_cols;
        float* sxz = sz + n_cols;
        float* syz = sxz + n_cols;
        for (std::ptrdiff_t r = r0; r < r1; ++r) {
            std::fill(sums.begin(), sums.end(), 0.0f);
            const float* z0 = min_z.row(r);
            for (std::ptrdiff_t dr = -k; dr <= k; ++dr) {
                if (r + dr < 0 || r + dr >= rows) continue;
                const float* zr = min_z.row(r + dr);
                const auto y = static_cast<float>(dr);
                for (std::ptrdiff_t dc = -k; dc <= k; ++dc) {
                    const auto x = static_cast<float>(dc);
                    const std::ptrdiff_t c0 = std::max<std::ptrdiff_t>(0, -dc), c1 = std::min(cols, cols - dc);
                    detail::slope_sums(zr + c0 + dc, z0 + c0, c1 - c0, x, y, band, n + c0, sx + c0, sy + c0, sxx + c0,
                                       syy + c0, sxy + c0, sz + c0, sxz + c0, syz + c0);
                }
            }
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                if (!(n[c] >= need)) continue;
                // Centre the sums on the mean position: the slopes solve the 2 × 2 system of the covariances.
                const double w = n[c];
                const double cxx = sxx[c] - static_cast<double>(sx[c]) * sx[c] / w;
                const double cyy = syy[c] - static_cast<double>(sy[c]) * sy[c] / w;
                const double cxy = sxy[c] - static_cast<double>(sx[c]) * sy[c] / w;
                const double cxz = sxz[c] - static_cast<double>(sx[c]) * sz[c] / w;
                const double cyz = syz[c] - static_cast<double>(sy[c]) * sz[c] / w;
                const double det = cxx * cyy - cxy * cxy;
                if (!(det > 1e-6 * (cxx * cyy + 1))) continue;
                const double b = (cxz * cyy - cyz * cxy) / det, g = (cyz * cxx - cxz * cxy) / det;
                out(r, c) = static_cast<float>(std::sqrt(b * b + g * g) / cell_m);
            }
        }
    }, {}, fn);
    return out;
}

}  // namespace lidarfx
