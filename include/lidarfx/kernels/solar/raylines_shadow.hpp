// SPDX-License-Identifier: Apache-2.0
// raylines_shadow: cast shadows of a surface model for one sun position in O(cells), by walking parallel
// lines away from the sun and carrying a shadow-height limit (dissertation 3.2.3).
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
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/kernels/solar/ray_lines.hpp"

namespace lidarfx {

/// Settings of raylines_shadow.
struct raylines_shadow_options {
    std::uint8_t nan_cell = 255;  ///< output of a NaN (no-data) cell: neither lit (1) nor shadow (0) by default
    execution run = {};           ///< threads, progress and cancellation (core/parallel.hpp); never changes the result
};

namespace detail {

/// The per-row and per-column parts of key(r, c) = z + t(r, c) * tan(elevation) (see raylines_shadow), so
/// that key = z + (col_lift[c] + row_lift[r]) evaluates identically wherever it is computed.
struct shadow_lifts {
    std::vector<double> col_lift, row_lift;
};

inline shadow_lifts make_shadow_lifts(const ray_lines& l, double cell_m, double tan_elevation)
{
    shadow_lifts s{std::vector<double>(static_cast<std::size_t>(l.cols)),
                   std::vector<double>(static_cast<std::size_t>(l.rows))};
    const double a = l.dcol * cell_m * tan_elevation, b = l.drow * cell_m * tan_elevation;
    for (std::ptrdiff_t c = 0; c < l.cols; ++c) s.col_lift[static_cast<std::size_t>(c)] = (static_cast<double>(c) + 0.5) * a;
    for (std::ptrdiff_t r = 0; r < l.rows; ++r) s.row_lift[static_cast<std::size_t>(r)] = (static_cast<double>(r) + 0.5) * b;
    return s;
}

/// Steep lines [k0, k1): a sweep over rows in walk order, each line's running maximum key in `limit`. The
/// cells of these lines in one row are contiguous, and distinct lines are independent, so the inner loop
/// has no carried dependency.
inline void shadow_steep_block(raster_view<const float> z, raster_view<std::uint8_t> out, const ray_lines& l,
                               const shadow_lifts& lift, std::uint8_t nan_cell, std::ptrdiff_t k0, std::ptrdiff_t k1)
{
    std::vector<double> limit(static_cast<std::size_t>(k1 - k0), -std::numeric_limits<double>::infinity());
    const std::ptrdiff_t rows = z.rows(), cols = z.cols();
    const double* col_lift = lift.col_lift.data();
    for (std::ptrdiff_t i = 0; i < rows; ++i) {
        const std::ptrdiff_t r = l.forward() ? i : rows - 1 - i;
        const std::ptrdiff_t s = l.shift(r);
        const std::ptrdiff_t c0 = std::max<std::ptrdiff_t>(0, k0 + s), c1 = std::min(cols, k1 + s);
        const float* zr = z.row(r);
        std::uint8_t* o = out.row(r);
        double* lim = limit.data() - (k0 + s);  // lim[c] is the limit of the line through (r, c)
        const double rl = lift.row_lift[static_cast<std::size_t>(r)];
        for (std::ptrdiff_t c = c0; c < c1; ++c) {
            const double key = static_cast<double>(zr[c]) + (col_lift[c] + rl);
            const double m = lim[c];
            const std::uint8_t v = m > key ? 0 : 1;
            o[c] = zr[c] != zr[c] ? nan_cell : v;
            lim[c] = key > m ? key : m;  // false for a NaN key: NaN cells cast no shadow
        }
    }
}

/// Shallow lines [k0, k1): a sweep over rows (in the order of the walk's row direction) and, within a row, over
/// the columns of these lines in walk order; a line crosses a row in a run of adjacent columns, so every line
/// still meets its cells in walk order.
inline void shadow_shallow_block(raster_view<const float> z, raster_view<std::uint8_t> out, const ray_lines& l,
                                 const shadow_lifts& lift, const std::vector<std::ptrdiff_t>& sh,
                                 std::uint8_t nan_cell, std::ptrdiff_t k0, std::ptrdiff_t k1)
{
    std::vector<double> limit(static_cast<std::size_t>(k1 - k0), -std::numeric_limits<double>::infinity());
    const std::ptrdiff_t rows = z.rows();
    const bool fwd = l.forward();
    const auto [lo, hi] = ray_lines::rows_of(sh, k0, k1, rows);
    for (std::ptrdiff_t i = lo; i < hi; ++i) {
        const std::ptrdiff_t r = l.rows_forward() ? i : lo + hi - 1 - i;
        const auto [c0, c1] = l.columns(sh, r, k0, k1);
        const float* zr = z.row(r);
        std::uint8_t* o = out.row(r);
        const double rl = lift.row_lift[static_cast<std::size_t>(r)];
        for (std::ptrdiff_t j = c0; j < c1; ++j) {
            const std::ptrdiff_t c = fwd ? j : c0 + c1 - 1 - j;
            double& m = limit[static_cast<std::size_t>(r - sh[static_cast<std::size_t>(c)] - k0)];
            const double key = static_cast<double>(zr[c]) + (lift.col_lift[static_cast<std::size_t>(c)] + rl);
            const std::uint8_t v = m > key ? 0 : 1;
            o[c] = zr[c] != zr[c] ? nan_cell : v;
            m = key > m ? key : m;
        }
    }
}

inline void raylines_shadow_view(raster_view<const float> z, raster_view<std::uint8_t> out, double cell_m,
                                 double sun_azimuth_deg, double sun_elevation_deg, const raylines_shadow_options& opt)
{
    constexpr const char* fn = "raylines_shadow";
    const std::ptrdiff_t rows = z.rows(), cols = z.cols();
    if (sun_elevation_deg <= 0.0 || sun_elevation_deg >= 90.0) {
        // Below the horizon nothing is lit; at the zenith nothing casts a shadow.
        const std::uint8_t all = sun_elevation_deg >= 90.0 ? 1 : 0;
        parallel_for_rows(
            rows, 256, opt.run.threads,
            [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
                for (std::ptrdiff_t r = r0; r < r1; ++r)
                    for (std::ptrdiff_t c = 0; c < cols; ++c) out(r, c) = z(r, c) != z(r, c) ? opt.nan_cell : all;
            },
            opt.run.progress, fn);
        return;
    }
    const ray_lines l = make_ray_lines(sun_azimuth_deg, rows, cols);
    const shadow_lifts lift = make_shadow_lifts(l, cell_m, std::tan(sun_elevation_deg * (std::numbers::pi / 180.0)));
    const std::ptrdiff_t first = l.first_line();
    const std::vector<std::ptrdiff_t> sh = l.shifts();
    // Blocks of lines fixed by the input; each line is walked by one thread, so any split gives the same bits.
    const std::ptrdiff_t block = 512;
    parallel_for_rows(
        l.count(), block, opt.run.threads,
        [&](std::ptrdiff_t b0, std::ptrdiff_t b1) {
            if (l.steep) {
                shadow_steep_block(z, out, l, lift, opt.nan_cell, first + b0, first + b1);
            } else {
                shadow_shallow_block(z, out, l, lift, sh, opt.nan_cell, first + b0, first + b1);
            }
        },
        opt.run.progress, fn);
}

}  // namespace detail

/// Cast shadows for one sun position (into form): 1 = lit, 0 = shadow, `opt.nan_cell` (default 255) for NaN
/// cells. Ray lines (dissertation 3.2.3): parallel digital lines along the sun azimuth cover every cell once
/// (kernels/solar/ray_lines.hpp); walking each away from the sun, cell p is in shadow iff an earlier non-NaN
/// cell q on its line has z_q - (t_p - t_q) tan(e) > z_p, with t the projection of the cell centre on the walk
/// direction in metres. Computed as key = z + t tan(e) (evaluated as z + (col_lift[c] + row_lift[r])) against
/// the running maximum key of the line: O(rows * cols). Azimuth clockwise from north (row 0 north, columns
/// east); elevation above the horizon, degrees: e <= 0 -> all shadow, e >= 90 -> all lit. NaN cells cast no
/// shadow. @throws invalid_input if shapes differ, cell_m is not finite and > 0, an angle is not finite,
/// elevation is outside [-90, 90], run.threads < 0 or out overlaps dsm; cancelled if run.progress says stop.
template <raster_input In, class Out>
requires raster_output_of<Out, std::uint8_t>
void raylines_shadow(const In& dsm, Out&& lit, double cell_m, double sun_azimuth_deg, double sun_elevation_deg,
                     const raylines_shadow_options& opt = {})
{
    constexpr const char* fn = "raylines_shadow";
    detail::require_positive(cell_m, fn, "cell_m");
    detail::require(std::isfinite(sun_azimuth_deg), fn, "sun_azimuth_deg", "finite", sun_azimuth_deg);
    detail::require(sun_elevation_deg >= -90.0 && sun_elevation_deg <= 90.0, fn, "sun_elevation_deg",
                    "in [-90, 90]", sun_elevation_deg);
    detail::check_execution(opt.run, fn);
    detail::require_same_shape(dsm, lit, fn, "dsm", "lit");
    detail::with_float_view(dsm, [&](raster_view<const float> z) {
        detail::write_through<std::uint8_t>(std::forward<Out>(lit), [&](raster_view<std::uint8_t> out) {
            detail::require(!detail::overlaps(z, out), fn, "lit must not overlap dsm");
            detail::raylines_shadow_view(z, out, cell_m, sun_azimuth_deg, sun_elevation_deg, opt);
        });
    });
}

/// Cast shadows for one sun position (returning form): see the into form. dsm heights and cell_m in metres,
/// angles in degrees (azimuth clockwise from north, elevation above the horizon). O(rows * cols).
template <raster_input In>
raster<std::uint8_t> raylines_shadow(const In& dsm, double cell_m, double sun_azimuth_deg, double sun_elevation_deg,
                                     const raylines_shadow_options& opt = {})
{
    raster<std::uint8_t> lit(dsm.rows(), dsm.cols());
    raylines_shadow(dsm, lit, cell_m, sun_azimuth_deg, sun_elevation_deg, opt);
    return lit;
}

}  // namespace lidarfx
