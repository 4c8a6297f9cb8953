// SPDX-License-Identifier: Apache-2.0
// Implementation of kernels/filter/slope_aspect.hpp: Horn's 3 x 3 gradient with its rules for missing cells, and slope
// and aspect per cell. Included at the end of slope_aspect.hpp, after the declarations it defines; not a public header.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

namespace detail {

/// Horn's gradient along one axis from three lines across it (weights 1, 2, 1), each line given by the cells
/// behind, at and ahead of the centre line (NaN = missing or outside). A line contributes its centred difference
/// when both ends exist, a one-sided difference against its middle cell when one end exists, and nothing
/// otherwise; the contributions are averaged with their weights. Cells are never invented, so a plane gives its
/// exact gradient whatever is missing. Returns dz per cell step, NaN when no line contributes.
inline double horn_axis(const double (&behind)[3], const double (&middle)[3], const double (&ahead)[3]) noexcept
{
    double sum = 0.0, weight = 0.0;
    for (int k = 0; k < 3; ++k) {
        const bool has_behind = !std::isnan(behind[k]), has_middle = !std::isnan(middle[k]),
                   has_ahead = !std::isnan(ahead[k]);
        double step;
        if (has_behind && has_ahead) {
            step = (ahead[k] - behind[k]) / 2;
        } else if (has_ahead && has_middle) {
            step = ahead[k] - middle[k];
        } else if (has_behind && has_middle) {
            step = middle[k] - behind[k];
        } else {
            continue;
        }
        const double w = k == 1 ? 2.0 : 1.0;
        sum += w * step;
        weight += w;
    }
    return weight > 0 ? sum / weight : std::numeric_limits<double>::quiet_NaN();
}

/// Slope and aspect of one cell from its gradient (east = dz/dx towards east, north = dz/dy towards
/// north, both in m/m), in float (8 lanes with AVX2, 16 with AVX-512). With hi = max(|east|, |north|) and
/// t = min/max in [0, 1]: |grad| = hi * sqrt(1 + t^2) and the aspect is atan(t) reflected into its quadrant,
/// so nothing here stops a loop from vectorizing (no atan2, no std::sqrt, no select that picks a constant over
/// a computed value). Aspect = azimuth of the down-slope direction (-east, -north), clockwise from north.
inline void slope_aspect_cell(float east, float north, float flat_slope_deg, float& slope, float& aspect) noexcept
{
    const float ax = std::fabs(east), ay = std::fabs(north);
    const float hi = ax > ay ? ax : ay, lo = ax > ay ? ay : ax;
    const float t = lo / (hi > std::numeric_limits<float>::min() ? hi : std::numeric_limits<float>::min());
    const float s = atan_deg(hi * sqrt_one_plus(t * t));
    // Reflections k - a are computed for every cell and picked by bit masks (fast_math.hpp: a select with
    // arithmetic in one arm keeps the loop scalar on AVX2 and SSE, which have no masked arithmetic).
    // Degrees from the nearer of the two axes, [0, 45]: t <= 1, so atan_unit directly (atan_deg's reflection
    // for t > 1 would repeat the comparison ax > ay, and compilers then branch and stop vectorizing).
    float a = atan_unit(t) * static_cast<float>(180 / std::numbers::pi);
    a = reflect_if(ax > ay, 90.0f, a);      // from north, down-slope direction in the NE quadrant
    a = reflect_if(north > 0, 180.0f, a);   // down-slope points south
    a = reflect_if(east > 0, 360.0f, a);    // down-slope points west
    a = select_bits(a >= 360.0f, 0.0f, a);  // 360 - tiny rounds to 360
    const bool is_flat = s <= flat_slope_deg;
    // NaN aspect for flat cells and NaN slopes, by adding NaN or 0 (s - s) rather than selecting: a select
    // against a constant makes compilers branch around the atan, and the loop no longer vectorizes.
    const float nan_if_flat = is_flat ? std::numeric_limits<float>::quiet_NaN() : 0.0f;
    slope = s;
    aspect = a + nan_if_flat + (s - s);
}

/// The flat flag of a cell from its slope: 1 where slope <= flat_slope_deg, 0 otherwise and for NaN (written by
/// a loop of its own: a byte store in the slope loop keeps it scalar on SSE2).
inline std::uint8_t is_flat_slope(float slope, float flat_slope_deg) noexcept
{
    return static_cast<std::uint8_t>(slope <= flat_slope_deg);
}

/// General path for one cell: a 3x3 window read with NaN for cells beyond the border, Horn's weighted mean of
/// whatever differences exist (horn_axis) along each axis.
inline void slope_aspect_general(raster_view<const float> z, std::ptrdiff_t r, std::ptrdiff_t c, double cell_m,
                                 float flat_slope_deg, float& slope, float& aspect) noexcept
{
    const double nan = std::numeric_limits<double>::quiet_NaN();
    double w[3][3];  // w[1 + dr][1 + dc]
    for (int dr = -1; dr <= 1; ++dr) {
        for (int dc = -1; dc <= 1; ++dc) {
            const std::ptrdiff_t rr = r + dr, cc = c + dc;
            w[dr + 1][dc + 1] =
                rr < 0 || rr >= z.rows() || cc < 0 || cc >= z.cols() ? nan : static_cast<double>(z(rr, cc));
        }
    }
    if (std::isnan(w[1][1])) {
        slope = aspect = std::numeric_limits<float>::quiet_NaN();
        return;
    }
    // East: lines are the rows, behind = west column. North: lines are the columns, behind = south row.
    const double west[3] = {w[0][0], w[1][0], w[2][0]}, mid_col[3] = {w[0][1], w[1][1], w[2][1]},
                 east_col[3] = {w[0][2], w[1][2], w[2][2]};
    const double east = horn_axis(west, mid_col, east_col) / cell_m;
    const double north = horn_axis(w[2], w[1], w[0]) / cell_m;
    slope_aspect_cell(static_cast<float>(east), static_cast<float>(north), flat_slope_deg, slope, aspect);
}

/// Rows [r0, r1). Interior cells take Horn's formula directly, in two loops compilers vectorize (gradients,
/// then slope and aspect; one loop mixing float loads with double arithmetic does not vectorize). A NaN anywhere
/// in the window makes that result NaN, and such cells, the border rows and the border columns are redone by
/// the general path. Differences of floats are exact in double, so each gradient is rounded
/// once (to float, for the slope and aspect loop).
inline void slope_aspect_rows(raster_view<const float> z, raster_view<float> slope, raster_view<float> aspect,
                              raster_view<std::uint8_t> flat, double cell_m, double flat_slope_deg, std::ptrdiff_t r0,
                              std::ptrdiff_t r1)
{
    const std::ptrdiff_t rows = z.rows(), cols = z.cols();
    const double scale = 1.0 / (8.0 * cell_m);
    const float flat_deg = float_at_most(flat_slope_deg);
    std::vector<float> east_row(static_cast<std::size_t>(cols)), north_row(static_cast<std::size_t>(cols));
    float* east = east_row.data();
    float* north = north_row.data();
    for (std::ptrdiff_t r = r0; r < r1; ++r) {
        float* s = slope.row(r);
        float* a = aspect.row(r);
        std::uint8_t* f = flat.row(r);
        const float* m = z.row(r);
        const bool interior = r > 0 && r + 1 < rows;
        if (interior) {
            const float* n = z.row(r - 1);
            const float* so = z.row(r + 1);
            for (std::ptrdiff_t c = 1; c + 1 < cols; ++c) {
                // (m[c] - m[c]) is 0, or NaN for a NaN centre, which sends the cell to the general path.
                east[c] = static_cast<float>(((static_cast<double>(n[c + 1]) - n[c - 1]) +
                                              2.0 * (static_cast<double>(m[c + 1]) - m[c - 1]) +
                                              (static_cast<double>(so[c + 1]) - so[c - 1])) *
                                                 scale +
                                             (static_cast<double>(m[c]) - m[c]));
                north[c] = static_cast<float>(((static_cast<double>(n[c - 1]) - so[c - 1]) +
                                               2.0 * (static_cast<double>(n[c]) - so[c]) +
                                               (static_cast<double>(n[c + 1]) - so[c + 1])) *
                                              scale);
            }
            for (std::ptrdiff_t c = 1; c + 1 < cols; ++c) {
                slope_aspect_cell(east[c], north[c], flat_deg, s[c], a[c]);
            }
        }
        const auto general = [&](std::ptrdiff_t c) { slope_aspect_general(z, r, c, cell_m, flat_deg, s[c], a[c]); };
        if (!interior) {
            for (std::ptrdiff_t c = 0; c < cols; ++c) general(c);
        } else {
            general(0);
            if (cols > 1) general(cols - 1);
            // Cells next to a NaN: found by a vectorized scan first, as most rows have none.
            bool any_nan = false;
            for (std::ptrdiff_t c = 1; c + 1 < cols; ++c) any_nan |= s[c] != s[c];
            if (any_nan) {
                for (std::ptrdiff_t c = 1; c + 1 < cols; ++c) {
                    if (s[c] != s[c] && m[c] == m[c]) general(c);
                }
            }
        }
        for (std::ptrdiff_t c = 0; c < cols; ++c) f[c] = is_flat_slope(s[c], flat_deg);
    }
}

}  // namespace detail

template <raster_input In, class SlopeOut, class AspectOut, class FlatOut>
requires raster_output_of<SlopeOut, float> && raster_output_of<AspectOut, float> &&
    raster_output_of<FlatOut, std::uint8_t>
void slope_aspect(const In& z, SlopeOut&& slope_deg, AspectOut&& aspect_deg, FlatOut&& flat, double cell_m,
                  const slope_aspect_options& opt)
{
    constexpr const char* fn = "slope_aspect";
    detail::require_positive(cell_m, fn, "cell_m");
    detail::require(opt.flat_slope_deg >= 0.0 && opt.flat_slope_deg < 90.0, fn, "flat_slope_deg", "in [0, 90)",
                    opt.flat_slope_deg);
    detail::check_execution(opt.run, fn);
    detail::require_same_shape(z, slope_deg, fn, "z", "slope_deg");
    detail::require_same_shape(z, aspect_deg, fn, "z", "aspect_deg");
    detail::require_same_shape(z, flat, fn, "z", "flat");
    detail::with_float_view(z, [&](raster_view<const float> zv) {
        detail::write_through<float>(std::forward<SlopeOut>(slope_deg), [&](raster_view<float> s) {
            detail::write_through<float>(std::forward<AspectOut>(aspect_deg), [&](raster_view<float> a) {
                detail::write_through<std::uint8_t>(std::forward<FlatOut>(flat), [&](raster_view<std::uint8_t> f) {
                    detail::require(!detail::overlaps(zv, s) && !detail::overlaps(zv, a) && !detail::overlaps(zv, f) &&
                                        !detail::overlaps(s, a) && !detail::overlaps(s, f) && !detail::overlaps(a, f),
                                    fn, "outputs must not overlap z or each other");
                    parallel_for_rows(
                        zv.rows(), 64, opt.run.threads,
                        [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
                            detail::slope_aspect_rows(zv, s, a, f, cell_m, opt.flat_slope_deg, r0, r1);
                        },
                        opt.run.progress, fn);
                });
            });
        });
    });
}

template <raster_input In>
slope_aspect_result slope_aspect(const In& z, double cell_m, const slope_aspect_options& opt)
{
    // Every cell is written, by the worker that computes it: the pages are first touched in parallel.
    slope_aspect_result result{raster<float>(z.rows(), z.cols(), uninitialized),
                               raster<float>(z.rows(), z.cols(), uninitialized),
                               raster<std::uint8_t>(z.rows(), z.cols(), uninitialized)};
    slope_aspect(z, result.slope_deg, result.aspect_deg, result.flat, cell_m, opt);
    return result;
}

}  // namespace lidarfx
