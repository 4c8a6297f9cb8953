// SPDX-License-Identifier: Apache-2.0
// water_surface_slope: the slope of the least-squares plane through the lowest returns around each cell.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>
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

/// water_surface_slope's sums for the cells [c0, c1) of row `z0` whose whole (2R+1)² window lies inside the
/// raster, R known at compile time: the window is unrolled and the sums stay in registers (the per-offset
/// passes of slope_sums read and write nine row arrays per offset). Same sums bit for bit: the six sums of
/// the mask times x, y, x², y², xy are small integers, exact in float in any order, and are taken per window
/// row; sz, sxz and syz add in the passes' order (row by row, column by column).
template <int R>
[[gnu::noinline, LIDARFX_VECTORIZE]] void slope_sums_window(const float* z0, std::ptrdiff_t row_stride,
                                                            std::ptrdiff_t c0, std::ptrdiff_t c1, float band,
                                                            float* __restrict n, float* __restrict sx,
                                                            float* __restrict sy, float* __restrict sxx,
                                                            float* __restrict syy, float* __restrict sxy,
                                                            float* __restrict sz, float* __restrict sxz,
                                                            float* __restrict syz) noexcept
{
    LIDARFX_IVDEP
    for (std::ptrdiff_t c = c0; c < c1; ++c) {
        const float p = z0[c];
        float a_n = 0, a_sx = 0, a_sy = 0, a_sxx = 0, a_syy = 0, a_sxy = 0, a_sz = 0, a_sxz = 0, a_syz = 0;
#pragma GCC unroll 16
        for (int dr = -R; dr <= R; ++dr) {
            const auto y = static_cast<float>(dr);
            float row_n = 0, row_sx = 0, row_sxx = 0;
#pragma GCC unroll 16
            for (int dc = -R; dc <= R; ++dc) {
                const auto x = static_cast<float>(dc);
                const float d = z0[dr * row_stride + c + dc] - p;
                const bool in = std::fabs(d) <= band;
                const float m = select_bits(in, 1.0f, 0.0f), dz = select_bits(in, d, 0.0f);
                row_n += m;
                row_sx += m * x;
                row_sxx += m * (x * x);
                a_sz += dz;
                a_sxz += dz * x;
                a_syz += dz * y;
            }
            a_n += row_n;
            a_sy += row_n * y;
            a_syy += row_n * (y * y);
            a_sx += row_sx;
            a_sxy += row_sx * y;
            a_sxx += row_sxx;
        }
        n[c] = a_n;
        sx[c] = a_sx;
        sy[c] = a_sy;
        sxx[c] = a_sxx;
        syy[c] = a_syy;
        sxy[c] = a_sxy;
        sz[c] = a_sz;
        sxz[c] = a_sxz;
        syz[c] = a_syz;
    }
}

}  // namespace detail

/// Slope of the water surface test: per cell, the magnitude of the gradient of the least-squares plane
/// z = a + b·x + c·y through the min z of the (2·radius_cells + 1)² window (clipped at the raster border)
/// that lie within band_m of the cell's own, sqrt(b² + c²) in metres per metre (0 = level); NaN where the
/// cell has no return, the window holds fewer than min_cells such returns, or they lie on a line. A water
/// surface is level to the range noise (a river falls a few mm per metre at most); beaches, banks and
/// meadows rising from the water are not. cell_m in metres.
/// O(cells · (2·radius_cells + 1)²), vectorized along rows, the window unrolled for radius_cells <= 4.
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
    raster<float> out(rows, cols, uninitialized);  // every cell is written
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
        std::vector<float> squared(n_cols);  // the squared slope per cell of the row, NaN where unknown
        for (std::ptrdiff_t r = r0; r < r1; ++r) {
            const float* z0 = min_z.row(r);
            // Rows and columns whose window lies inside: the unrolled window (radii 1-4); the rest, and
            // every cell for larger radii, by passes per offset. The passes add to sums that start at 0: all
            // of them, or with the window (which writes its columns) the k at each end.
            const bool inside = k <= 4 && r >= k && r + k < rows && cols > 2 * k;
            if (!inside) std::fill(sums.begin(), sums.end(), 0.0f);
            if (inside) {
                for (float* s : {n, sx, sy, sxx, syy, sxy, sz, sxz, syz}) {
                    std::fill(s, s + k, 0.0f);
                    std::fill(s + (cols - k), s + cols, 0.0f);
                }
                const auto stride = min_z.row_stride();
                const std::ptrdiff_t e = cols - k;
                if (k == 1)
                    detail::slope_sums_window<1>(z0, stride, k, e, band, n, sx, sy, sxx, syy, sxy, sz, sxz, syz);
                if (k == 2)
                    detail::slope_sums_window<2>(z0, stride, k, e, band, n, sx, sy, sxx, syy, sxy, sz, sxz, syz);
                if (k == 3)
                    detail::slope_sums_window<3>(z0, stride, k, e, band, n, sx, sy, sxx, syy, sxy, sz, sxz, syz);
                if (k == 4)
                    detail::slope_sums_window<4>(z0, stride, k, e, band, n, sx, sy, sxx, syy, sxy, sz, sxz, syz);
            }
            for (std::ptrdiff_t dr = -k; dr <= k; ++dr) {
                if (r + dr < 0 || r + dr >= rows) continue;
                const float* zr = min_z.row(r + dr);
                const auto y = static_cast<float>(dr);
                for (std::ptrdiff_t dc = -k; dc <= k; ++dc) {
                    const auto x = static_cast<float>(dc);
                    const std::ptrdiff_t c0 = std::max<std::ptrdiff_t>(0, -dc), c1 = std::min(cols, cols - dc);
                    // With the window done, only the k columns at each end.
                    for (const auto& [a, b] : inside ? std::array{std::pair{c0, k}, std::pair{cols - k, c1}}
                                                     : std::array{std::pair{c0, c1}, std::pair{c1, c1}}) {
                        if (b <= a) continue;
                        detail::slope_sums(zr + a + dc, z0 + a, b - a, x, y, band, n + a, sx + a, sy + a, sxx + a,
                                           syy + a, sxy + a, sz + a, sxz + a, syz + a);
                    }
                }
            }
            // Centre the sums on the mean position: the slopes solve the 2 × 2 system of the covariances. Every
            // cell is computed and the unknown ones masked to NaN, so that the loop vectorizes; the square root
            // (a libm call that compilers keep scalar for errno) runs in a loop of its own.
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                const double w = 1.0 / n[c];  // one division per cell, not five
                const double mx = sx[c] * w, my = sy[c] * w;
                const double cxx = sxx[c] - mx * sx[c];
                const double cyy = syy[c] - my * sy[c];
                const double cxy = sxy[c] - mx * sy[c];
                const double cxz = sxz[c] - mx * sz[c];
                const double cyz = syz[c] - my * sz[c];
                const double det = cxx * cyy - cxy * cxy;
                const bool known = (n[c] >= need) & (det > 1e-6 * (cxx * cyy + 1));  // & not &&: no branch
                const double inv = 1.0 / det;
                const double b = (cxz * cyy - cyz * cxy) * inv, g = (cyz * cxx - cxz * cxy) * inv;
                const double nan = std::numeric_limits<double>::quiet_NaN();
                squared[c] = static_cast<float>(detail::select_bits(known, b * b + g * g, nan));
            }
            detail::sqrt_span(squared.data(), out.view().row(r), cols, static_cast<float>(1 / cell_m));
        }
    }, {}, fn);
    return out;
}

}  // namespace lidarfx
