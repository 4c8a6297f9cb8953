// SPDX-License-Identifier: Apache-2.0
// horizon_map: the horizon elevation angle of every cell towards one azimuth in O(cells), by a sweep along
// parallel ray lines keeping the upper convex hull of the profile behind each cell; and a stack of n azimuths.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
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
#include "lidarfx/kernels/solar/ray_lines.hpp"

namespace lidarfx {

/// Settings of horizon_map and horizon_stack.
struct horizon_map_options {
    /// Families of parallel ray lines, as raylines_shadow_options::line_phases, in [1, 64]: each cell's horizon is
    /// read along the line of the family nearest its centre (at most 1 / (2 line_phases) cells off). 1 (default)
    /// is one sweep; each further family costs one more sweep, except along the grid axes and diagonals.
    int line_phases = 1;
    execution run = {};  ///< threads, progress and cancellation (core/parallel.hpp); never changes the result
};

/// Horizon maps towards n evenly spaced azimuths.
struct horizon_stack_result {
    std::vector<double> azimuth_deg;         ///< azimuth of each map: i * 360 / n, clockwise from north
    std::vector<raster<float>> horizon_deg;  ///< horizon_deg[i]: the horizon_map towards azimuth_deg[i]
};

/// A point of the upper convex hull that horizon_hull_step keeps: position along a walk and height.
struct horizon_hull_point {
    double t, z;  ///< position along the walk (m) and height (m)
};

/// One step of a horizon sweep along a line of cells (horizon_map and the facade sky views use it): the tangent of the
/// horizon angle (>= 0) at (t, z) over the points of `hull` (the upper convex hull of the profile behind, t
/// increasing), then (t, z) joins the hull. Hull points that fall on or below the chord from their predecessor to (t,
/// z) can be the highest angle neither from here nor from any later point, so they are dropped; the last one kept is
/// the tangent point. Amortized O(1).
inline double horizon_hull_step(horizon_hull_point* hull, std::ptrdiff_t& n, double t, double z) noexcept
{
    while (n >= 2) {
        const horizon_hull_point a = hull[n - 2], b = hull[n - 1];
        if ((b.z - a.z) * (t - a.t) <= (z - a.z) * (b.t - a.t)) {
            --n;
        } else {
            break;
        }
    }
    double tangent = 0.0;
    if (n >= 1 && hull[n - 1].z > z) tangent = (hull[n - 1].z - z) / (t - hull[n - 1].t);
    hull[n++] = {t, z};
    return tangent;
}

namespace detail {

/// Tangents to degrees over o[c0, c1): a separate loop, so the arctangent vectorizes (NaN stays NaN).
/// For double outputs (tangents kept for sky_view_factor) nothing is converted.
template <class T>
void tangents_to_degrees(T* o, std::ptrdiff_t c0, std::ptrdiff_t c1) noexcept
{
    if constexpr (std::is_same_v<T, float>) {
        atan_deg_span(o + c0, o + c0, c1 - c0);
    }
}

/// Which cells of a line family a sweep writes: those of the major indices i with owner[i] == family, or every
/// cell when owner is null (one family). The other cells still join their lines' hulls.
struct family_cells {
    const std::uint8_t* owner = nullptr;
    std::uint8_t family = 0;
    bool writes(std::ptrdiff_t i) const noexcept { return owner == nullptr || owner[i] == family; }
};

/// Steep lines [k0, k1): a sweep over rows in walk order with one hull per line (cache-friendly reads).
template <class T>
void horizon_steep_block(raster_view<const float> z, raster_view<T> out, const ray_lines& l, double cell_m,
                         family_cells own, std::ptrdiff_t k0, std::ptrdiff_t k1)
{
    const std::ptrdiff_t rows = z.rows(), cols = z.cols(), lines = k1 - k0;
    std::vector<horizon_hull_point> hulls(static_cast<std::size_t>(lines * rows));
    std::vector<std::ptrdiff_t> sizes(static_cast<std::size_t>(lines), 0);
    const double a = l.dcol * cell_m, b = l.drow * cell_m;
    const T nan = std::numeric_limits<T>::quiet_NaN();
    for (std::ptrdiff_t i = 0; i < rows; ++i) {
        const std::ptrdiff_t r = l.forward() ? i : rows - 1 - i;
        const std::ptrdiff_t s = l.shift(r);
        const std::ptrdiff_t c0 = std::max<std::ptrdiff_t>(0, k0 + s), c1 = std::min(cols, k1 + s);
        const float* zr = z.row(r);
        const double tr = (static_cast<double>(r) + 0.5) * b;
        const bool writes = own.writes(r);  // else another family writes this row: only the hulls grow
        T* o = out.row(r);
        for (std::ptrdiff_t c = c0; c < c1; ++c) {
            if (zr[c] != zr[c]) {
                if (writes) o[c] = nan;
                continue;
            }
            const std::ptrdiff_t line = c - s - k0;
            const double tangent =
                horizon_hull_step(hulls.data() + line * rows, sizes[static_cast<std::size_t>(line)],
                                  (static_cast<double>(c) + 0.5) * a + tr, static_cast<double>(zr[c]));
            if (writes) o[c] = static_cast<T>(tangent);
        }
        if (writes) tangents_to_degrees(o, c0, c1);  // these lines' cells of row r are all written now
    }
}

/// Shallow lines [k0, k1): a sweep over rows and, within a row, over the lines' columns in walk order (as in
/// raylines_shadow), one hull per line. With several families, the degrees conversion waits for the end.
template <class T>
void horizon_shallow_block(raster_view<const float> z, raster_view<T> out, const ray_lines& l, double cell_m,
                           const std::vector<std::ptrdiff_t>& sh, family_cells own, std::ptrdiff_t k0,
                           std::ptrdiff_t k1)
{
    const std::ptrdiff_t rows = z.rows(), cols = z.cols(), lines = k1 - k0;
    std::vector<horizon_hull_point> hulls(static_cast<std::size_t>(lines * cols));
    std::vector<std::ptrdiff_t> sizes(static_cast<std::size_t>(lines), 0);
    const double a = l.dcol * cell_m, b = l.drow * cell_m;
    const bool fwd = l.forward();
    const T nan = std::numeric_limits<T>::quiet_NaN();
    const auto [lo, hi] = ray_lines::rows_of(sh, k0, k1, rows);
    for (std::ptrdiff_t i = lo; i < hi; ++i) {
        const std::ptrdiff_t r = l.rows_forward() ? i : lo + hi - 1 - i;
        const auto [c0, c1] = l.columns(sh, r, k0, k1);
        const float* zr = z.row(r);
        T* o = out.row(r);
        const double tr = (static_cast<double>(r) + 0.5) * b;
        for (std::ptrdiff_t j = c0; j < c1; ++j) {
            const std::ptrdiff_t c = fwd ? j : c0 + c1 - 1 - j;
            const bool writes = own.writes(c);
            if (zr[c] != zr[c]) {
                if (writes) o[c] = nan;
                continue;
            }
            const std::ptrdiff_t line = r - sh[static_cast<std::size_t>(c)] - k0;
            const double tangent =
                horizon_hull_step(hulls.data() + line * cols, sizes[static_cast<std::size_t>(line)],
                                  (static_cast<double>(c) + 0.5) * a + tr, static_cast<double>(zr[c]));
            if (writes) o[c] = static_cast<T>(tangent);
        }
        if (own.owner == nullptr) tangents_to_degrees(o, c0, c1);  // these lines' cells of row r are all written now
    }
}

/// Refuses bad horizon_map_options: line_phases outside [1, 64] or run.threads < 0.
inline void check_horizon_options(const horizon_map_options& opt, const char* fn)
{
    require(opt.line_phases >= 1 && opt.line_phases <= 64, fn, "line_phases", "in [1, 64]", opt.line_phases);
    check_execution(opt.run, fn);
}

/// Horizon angles in degrees (T = float) or horizon tangents (T = double) of every cell towards azimuth_deg, each
/// cell from the line family of opt.line_phases nearest its centre.
template <class T>
void horizon_map_view(raster_view<const float> z, raster_view<T> out, double cell_m, double azimuth_deg,
                      const horizon_map_options& opt, const char* fn)
{
    const ray_lines l = make_ray_lines(azimuth_deg, z.rows(), z.cols());
    const line_families fam = make_line_families(l, opt.line_phases);
    const bool one = fam.lines.size() == 1;
    const std::size_t families = fam.lines.size();
    for (std::size_t f = 0; f < families; ++f) {
        const ray_lines& lf = fam.lines[f];
        const family_cells own{one ? nullptr : fam.owner.data(), static_cast<std::uint8_t>(f)};
        const std::ptrdiff_t first = lf.first_line();
        const std::vector<std::ptrdiff_t>& sh = fam.shifts[f];
        const double from = static_cast<double>(f) / static_cast<double>(families);
        // Blocks of lines fixed by the input; each line is swept by one thread, so any split gives the same bits.
        parallel_for_rows(
            lf.count(), 64, opt.run.threads,
            [&](std::ptrdiff_t b0, std::ptrdiff_t b1) {
                if (lf.steep) {
                    horizon_steep_block(z, out, lf, cell_m, own, first + b0, first + b1);
                } else {
                    horizon_shallow_block(z, out, lf, cell_m, sh, own, first + b0, first + b1);
                }
            },
            progress_phase(opt.run.progress, from, from + 1.0 / static_cast<double>(families)), fn);
    }
    if (!one && !l.steep && std::is_same_v<T, float>) {  // shallow sweeps left their tangents for here
        parallel_for_rows(z.rows(), 64, opt.run.threads, [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
            for (std::ptrdiff_t r = r0; r < r1; ++r) tangents_to_degrees(out.row(r), 0, z.cols());
        });
    }
}

}  // namespace detail

/// Horizon elevation angle of every cell looking towards `azimuth_deg` (into form): max(0, max over the
/// non-NaN cells q before p on p's ray line of atan((z_q - z_p) / (t_p - t_q))), degrees in [0, 90). Ray lines
/// as in raylines_shadow (kernels/solar/ray_lines.hpp), t = projection of the cell centre on the walk away
/// from the azimuth, in metres. A sweep keeping the upper convex hull of the profile behind each cell
/// (Stewart 1998): O(rows * cols) per line family. With opt.line_phases = P families, each cell's line is the
/// one of the family nearest its centre (as in raylines_shadow with the same P), so the cell is lit by a sun of
/// this azimuth and elevation e exactly when its horizon is <= e (up to rounding). Beyond the raster border
/// nothing rises above the horizontal, so a cell with nothing higher towards the azimuth, the border cells facing
/// it, and a flat plane give 0. NaN cells give NaN and hide nothing. Azimuth clockwise from north (row 0 north).
/// @throws invalid_input if shapes differ, cell_m is not finite and > 0, the azimuth is not finite,
/// line_phases is outside [1, 64] or run.threads < 0; cancelled if asked to stop.
template <raster_input In, class Out>
requires raster_output_of<Out, float>
void horizon_map(const In& dsm, Out&& horizon_deg, double cell_m, double azimuth_deg,
                 const horizon_map_options& opt = {})
{
    constexpr const char* fn = "horizon_map";
    detail::require_positive(cell_m, fn, "cell_m");
    detail::require(std::isfinite(azimuth_deg), fn, "azimuth_deg", "finite", azimuth_deg);
    detail::check_horizon_options(opt, fn);
    detail::require_same_shape(dsm, horizon_deg, fn, "dsm", "horizon_deg");
    detail::with_float_view(dsm, [&](raster_view<const float> z) {
        detail::write_through<float>(std::forward<Out>(horizon_deg), [&](raster_view<float> out) {
            detail::require(!detail::overlaps(z, out), fn, "horizon_deg must not overlap dsm");
            detail::horizon_map_view(z, out, cell_m, azimuth_deg, opt, fn);
        });
    });
}

/// Horizon elevation angle towards one azimuth (returning form); see the into form. Degrees in [0, 90),
/// NaN on NaN cells. O(rows * cols) per line family.
template <raster_input In>
raster<float> horizon_map(const In& dsm, double cell_m, double azimuth_deg, const horizon_map_options& opt = {})
{
    raster<float> out(dsm.rows(), dsm.cols());
    horizon_map(dsm, out, cell_m, azimuth_deg, opt);
    return out;
}

/// Horizon maps towards `directions` azimuths i * 360 / directions (i = 0 .. directions - 1), each as
/// horizon_map; progress runs once from 0 to 1 over all of them. Memory: directions * rows * cols floats.
/// O(directions * rows * cols) per line family. @throws invalid_input as horizon_map, or if directions < 1.
template <raster_input In>
horizon_stack_result horizon_stack(const In& dsm, double cell_m, int directions, const horizon_map_options& opt = {})
{
    constexpr const char* fn = "horizon_stack";
    detail::require(directions >= 1, fn, "directions", ">= 1", directions);
    detail::require_positive(cell_m, fn, "cell_m");
    detail::check_horizon_options(opt, fn);
    horizon_stack_result result;
    detail::with_float_view(dsm, [&](raster_view<const float> z) {
        for (int i = 0; i < directions; ++i) {
            const double azimuth = 360.0 * i / directions;
            horizon_map_options step = opt;
            step.run.progress = detail::progress_phase(opt.run.progress, static_cast<double>(i) / directions,
                                                       static_cast<double>(i + 1) / directions);
            raster<float> map(z.rows(), z.cols());
            detail::horizon_map_view(z, map.view(), cell_m, azimuth, step, fn);
            result.azimuth_deg.push_back(azimuth);
            result.horizon_deg.push_back(std::move(map));
        }
    });
    return result;
}

}  // namespace lidarfx
