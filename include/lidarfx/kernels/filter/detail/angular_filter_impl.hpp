// SPDX-License-Identifier: Apache-2.0
// Implementation of kernels/filter/angular_filter.hpp: the inverse-distance table, one pass per window offset near the
// border and an unrolled window inside, over strips of rows. Included at the end of angular_filter.hpp, after the
// declarations it defines; not a public header.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <type_traits>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

namespace detail {

/// Factors 1 / (cell_m * sqrt(a^2 + b^2)) for 0 <= a, b <= radius, row-major by a (0 at a = b = 0). An offset
/// (dr, dc) uses entry (|dr|, |dc|); every path of the kernel reads the same float factors, so all agree exactly.
inline std::vector<float> inverse_distances(double cell_m, int radius)
{
    const std::ptrdiff_t n = radius + 1;
    std::vector<float> inv(static_cast<std::size_t>(n * n), 0.0f);
    for (std::ptrdiff_t a = 0; a < n; ++a) {
        for (std::ptrdiff_t b = 0; b < n; ++b) {
            if (a + b > 0)
                inv[a * n + b] = static_cast<float>(1.0 / (cell_m * std::sqrt(static_cast<double>(a * a + b * b))));
        }
    }
    return inv;
}

/// best[c] = max(best[c], |z(r+dr, c+dc) - z(r, c)| * inv_d) for the columns c in [c0, c1) whose neighbour
/// lies inside the row: one pass over the columns per window offset (a loop compilers vectorize). A NaN ratio
/// compares false and so never wins, which skips NaN neighbours without a branch.
inline void angular_offset_pass(const float* centre, const float* other, float* best, std::ptrdiff_t cols,
                                std::ptrdiff_t dc, float inv_d, std::ptrdiff_t c0, std::ptrdiff_t c1) noexcept
{
    c0 = std::max(c0, -dc);
    c1 = std::min(c1, cols - dc);
    for (std::ptrdiff_t c = c0; c < c1; ++c) {
        const float ratio = std::fabs(other[c + dc] - centre[c]) * inv_d;
        best[c] = ratio > best[c] ? ratio : best[c];
    }
}

/// best[c] = the steepest ratio |dz| / d for the cells [c0, c1) of a row whose whole (2R+1)^2 window lies
/// inside the raster (NaN for a NaN centre), R known at compile time: the window is unrolled and every value
/// stays in registers. The offsets (+-a, +-b) and (+-b, +-a) share one distance, so their largest |dz| is taken
/// first and multiplied once: rounding is monotone, so max(|dz|) * f equals max(|dz| * f) bit for bit.
/// With Finite (every value of the window rows known finite) the maxima run on the bit patterns of |dz| as
/// unsigned integers (non-negative floats order as their bits), which takes them off the floating-point units
/// that the subtractions and products need. Otherwise they run in float: d > l ? d : l is a single max
/// instruction and is false for a NaN difference (a NaN neighbour, or inf - inf), so NaN neighbours are
/// skipped in the vector loop itself, as the passes skip them; on bits a NaN would win and need a select per
/// offset (that select made the kernel ~10 % slower). Both give the same maxima bit for bit.
template <int R, bool Finite>
void angular_interior(const float* centre, std::ptrdiff_t row_stride, float* best, std::ptrdiff_t c0, std::ptrdiff_t c1,
                      const float* inv_d) noexcept
{
    constexpr std::uint32_t magnitude = 0x7fffffffu;
    for (std::ptrdiff_t c = c0; c < c1; ++c) {
        const float p = centre[c];
        std::uint32_t largest[R + 1][R + 1] = {};  // by (min(|dr|, |dc|), max(|dr|, |dc|)), bits of max |dz|
        float widest[R + 1][R + 1] = {};           // the same maxima as floats, without Finite
#pragma GCC unroll 8
        for (int dr = -R; dr <= R; ++dr) {
#pragma GCC unroll 8
            for (int dc = -R; dc <= R; ++dc) {
                if (dr == 0 && dc == 0) continue;
                const int a = std::min(std::abs(dr), std::abs(dc)), b = std::max(std::abs(dr), std::abs(dc));
                if constexpr (Finite) {
                    const std::uint32_t d =
                        std::bit_cast<std::uint32_t>(p - centre[dr * row_stride + c + dc]) & magnitude;
                    largest[a][b] = d > largest[a][b] ? d : largest[a][b];
                } else {  // d > l ? d : l is one float max, false for a NaN d: skipped without a select
                    const float d = std::fabs(p - centre[dr * row_stride + c + dc]);
                    widest[a][b] = d > widest[a][b] ? d : widest[a][b];
                }
            }
        }
        float steepest = 0.0f;
#pragma GCC unroll 8
        for (int a = 0; a <= R; ++a) {
#pragma GCC unroll 8
            for (int b = a; b <= R; ++b) {
                if (b == 0) continue;  // the centre
                const float dz = Finite ? std::bit_cast<float>(largest[a][b]) : widest[a][b];
                const float ratio = dz * inv_d[a * (R + 1) + b];
                steepest = ratio > steepest ? ratio : steepest;
            }
        }
        if constexpr (Finite) {
            best[c] = steepest;
        } else {  // a NaN centre gives NaN
            best[c] = select_bits(p == p, steepest, std::numeric_limits<float>::quiet_NaN());
        }
    }
}

/// Whether every value of x[0, n) is finite (neither NaN nor infinite): the largest magnitude bit pattern
/// lies below that of infinity.
inline bool all_finite(const float* x, std::ptrdiff_t n) noexcept
{
    std::uint32_t widest = 0;
    for (std::ptrdiff_t i = 0; i < n; ++i) {
        const std::uint32_t b = std::bit_cast<std::uint32_t>(x[i]) & 0x7fffffffu;
        widest = b > widest ? b : widest;
    }
    return widest < 0x7f800000u;
}

/// The unrolled kernel for radius R on one row, the unchecked variant where the window rows are all finite.
template <int R>
void angular_interior_row(const float* centre, std::ptrdiff_t row_stride, float* best, std::ptrdiff_t cols, bool finite,
                          const float* inv_d) noexcept
{
    if (finite) {
        angular_interior<R, true>(centre, row_stride, best, R, cols - R, inv_d);
    } else {
        angular_interior<R, false>(centre, row_stride, best, R, cols - R, inv_d);
    }
}

/// The steepest ratio |dz| / d of cell (r, c) over its window clipped at the raster border, one neighbour at a
/// time, with the same float factors and the same NaN rule as the passes (a NaN ratio never wins).
inline float angular_cell(raster_view<const float> z, std::ptrdiff_t r, std::ptrdiff_t c, std::ptrdiff_t rad,
                          const float* inv_d) noexcept
{
    const float p = z(r, c);
    float steepest = 0.0f;
    for (std::ptrdiff_t rr = std::max<std::ptrdiff_t>(0, r - rad); rr <= std::min(z.rows() - 1, r + rad); ++rr) {
        for (std::ptrdiff_t cc = std::max<std::ptrdiff_t>(0, c - rad); cc <= std::min(z.cols() - 1, c + rad); ++cc) {
            const float ratio = std::fabs(z(rr, cc) - p) * inv_d[std::abs(rr - r) * (rad + 1) + std::abs(cc - c)];
            steepest = ratio > steepest ? ratio : steepest;  // the centre adds 0 (inv_d[0] = 0) or NaN
        }
    }
    return steepest;
}

/// Rows [r0, r1) of the angular filter: the largest ratio |dz| / d per cell, then one atan per cell.
/// Radii 1-3 run the unrolled kernel on cells whose window lies inside the raster and clipped per-offset
/// passes on the others (rows and columns within `radius` of the border); larger radii run the passes only.
inline void angular_filter_rows(raster_view<const float> z, raster_view<float> out, double cell_m, int radius,
                                std::ptrdiff_t r0, std::ptrdiff_t r1)
{
    const std::ptrdiff_t rows = z.rows(), cols = z.cols(), rad = radius;
    const std::vector<float> inv_d = inverse_distances(cell_m, radius);
    std::vector<float> best_row(static_cast<std::size_t>(cols));
    float* best = best_row.data();
    // Rows are checked for non-finite values once each, in order, as they enter the window (and so the cache).
    std::ptrdiff_t next_to_check = std::max<std::ptrdiff_t>(0, r0 - rad), last_non_finite = -1;
    for (std::ptrdiff_t r = r0; r < r1; ++r) {
        const float* centre = z.row(r);
        const bool unrolled = radius <= 3 && r >= rad && r + rad < rows && cols > 2 * rad;
        if (unrolled) {
            for (; next_to_check <= r + rad; ++next_to_check) {
                if (!all_finite(z.row(next_to_check), cols)) last_non_finite = next_to_check;
            }
            const bool finite = last_non_finite < r - rad;
            const auto stride = z.row_stride();
            if (radius == 1) angular_interior_row<1>(centre, stride, best, cols, finite, inv_d.data());
            if (radius == 2) angular_interior_row<2>(centre, stride, best, cols, finite, inv_d.data());
            if (radius == 3) angular_interior_row<3>(centre, stride, best, cols, finite, inv_d.data());
            // The `rad` columns at each end, one cell at a time (a pass per offset would cost a call per offset).
            for (std::ptrdiff_t c : {std::ptrdiff_t{0}, cols - rad}) {
                for (std::ptrdiff_t cc = c; cc < c + rad; ++cc) {
                    const float steepest = angular_cell(z, r, cc, rad, inv_d.data());
                    best[cc] = centre[cc] == centre[cc] ? steepest : std::numeric_limits<float>::quiet_NaN();
                }
            }
        } else {
            std::fill(best_row.begin(), best_row.end(), 0.0f);
            for (std::ptrdiff_t dr = std::max(-rad, -r); dr <= std::min(rad, rows - 1 - r); ++dr) {
                for (std::ptrdiff_t dc = -rad; dc <= rad; ++dc) {
                    if (dr == 0 && dc == 0) continue;
                    const float inv = inv_d[std::abs(dr) * (rad + 1) + std::abs(dc)];
                    angular_offset_pass(centre, z.row(r + dr), best, cols, dc, inv, 0, cols);
                }
            }
            // A NaN centre gives NaN through atan. (Kept out of the atan loop: a select there between the atan
            // and a constant makes compilers branch around the atan, and the loop no longer vectorizes.)
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                best[c] = centre[c] == centre[c] ? best[c] : std::numeric_limits<float>::quiet_NaN();
            }
        }
        atan_deg_span(best, out.row(r), cols);
    }
}

inline void check_angular_filter(double cell_m, const angular_filter_options& opt)
{
    require_positive(cell_m, "angular_filter", "cell_m");
    require(opt.radius_cells >= 1, "angular_filter", "radius_cells", ">= 1", opt.radius_cells);
    check_execution(opt.run, "angular_filter");
}

}  // namespace detail

template <raster_input In, class Out>
requires raster_output_of<Out, float>
void angular_filter(const In& z, Out&& out, double cell_m, const angular_filter_options& opt)
{
    detail::check_angular_filter(cell_m, opt);
    detail::require_same_shape(z, out, "angular_filter", "z", "out");
    detail::with_float_view(z, [&](raster_view<const float> zv) {
        detail::write_through<float>(std::forward<Out>(out), [&](raster_view<float> o) {
            detail::require(!detail::overlaps(zv, o), "angular_filter", "out must not overlap z");
            // No neighbour lies further than the raster's extent: a larger radius changes nothing but the cost.
            const int radius =
                static_cast<int>(std::min<std::ptrdiff_t>(opt.radius_cells, std::max(zv.rows(), zv.cols())));
            parallel_for_rows(
                o.rows(), 64, opt.run.threads,
                [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
                    detail::angular_filter_rows(zv, o, cell_m, radius, r0, r1);
                },
                opt.run.progress, "angular_filter");
        });
    });
}

template <raster_input In>
raster<float> angular_filter(const In& z, double cell_m, const angular_filter_options& opt)
{
    raster<float> out(z.rows(), z.cols(), uninitialized);  // every cell is written
    angular_filter(z, out, cell_m, opt);
    return out;
}

template <raster_input In>
raster<float> angular_filter(const In& z, double cell_m, int radius_cells)
{
    return angular_filter(z, cell_m, angular_filter_options{.radius_cells = radius_cells});
}

}  // namespace lidarfx
