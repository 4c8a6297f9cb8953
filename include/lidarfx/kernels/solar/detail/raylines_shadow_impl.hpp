// SPDX-License-Identifier: Apache-2.0
// Implementation of raylines_shadow (kernels/solar/raylines_shadow.hpp): the line families of a sun position and
// the sweeps of steep and shallow lines that carry the running shadow key.
#pragma once
// Included at the end of its public header, which declares what is defined here.

#include <algorithm>
#include <array>
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

namespace detail {

/// The line families of one sun position (see raylines_shadow_options::line_phases): the families in use, and
/// for every major index (row if steep, column if shallow) the family that writes its cells.
struct shadow_families {
    std::vector<ray_lines> lines;                     ///< the families some major index uses
    std::vector<std::vector<std::ptrdiff_t>> shifts;  ///< shifts() of each
    std::vector<std::uint8_t> owner;                  ///< per major index: position of its family in `lines`
    std::ptrdiff_t first = 0, last = 0;               ///< line indices [first, last) holding a cell in any family
};

inline shadow_families make_shadow_families(const ray_lines& l, int phases)
{
    shadow_families f;
    std::vector<int> of(static_cast<std::size_t>(l.major()));
    std::vector<int> slot(static_cast<std::size_t>(phases), -1);
    for (std::ptrdiff_t i = 0; i < l.major(); ++i) of[static_cast<std::size_t>(i)] = line_phase_of(l.slope, i, phases);
    for (const int j : of) slot[static_cast<std::size_t>(j)] = 0;
    for (int j = 0; j < phases; ++j) {
        if (slot[static_cast<std::size_t>(j)] < 0) continue;
        slot[static_cast<std::size_t>(j)] = static_cast<int>(f.lines.size());
        ray_lines lf = l;
        lf.phase = 0.5 + static_cast<double>(j) / phases;
        f.shifts.push_back(lf.shifts());
        const std::ptrdiff_t first = lf.first_line();
        f.first = f.lines.empty() ? first : std::min(f.first, first);
        f.last = f.lines.empty() ? first + lf.count() : std::max(f.last, first + lf.count());
        f.lines.push_back(lf);
    }
    f.owner.resize(of.size());
    for (std::size_t i = 0; i < of.size(); ++i)
        f.owner[i] = static_cast<std::uint8_t>(slot[static_cast<std::size_t>(of[i])]);
    return f;
}

/// Steep lines [k0, k1) of every family: a sweep over rows in walk order. Each row's keys are computed once;
/// every family then raises the running maximum key of its lines (`limit`, one array per family), and the
/// family that owns the row first compares the row's keys with it. A family's lines hold contiguous cells in
/// one row and are independent, so the inner loops carry no dependency.
inline void shadow_steep_block(raster_view<const float> z, raster_view<std::uint8_t> out, const shadow_families& fam,
                               const shadow_lifts& lift, std::uint8_t nan_cell, std::ptrdiff_t k0, std::ptrdiff_t k1)
{
    const std::ptrdiff_t rows = z.rows(), cols = z.cols(), n = k1 - k0;
    const std::size_t families = fam.lines.size();
    std::vector<double> limits(families * static_cast<std::size_t>(n), -std::numeric_limits<double>::infinity());
    std::vector<double> keys(static_cast<std::size_t>(cols));
    const double* col_lift = lift.col_lift.data();
    const bool forward = fam.lines.front().forward();
    for (std::ptrdiff_t i = 0; i < rows; ++i) {
        const std::ptrdiff_t r = forward ? i : rows - 1 - i;
        const std::size_t ri = static_cast<std::size_t>(r);
        // Columns of this row on lines [k0, k1) of some family (shifts differ by at most one between families).
        std::ptrdiff_t lo = cols, hi = 0;
        for (std::size_t f = 0; f < families; ++f) {
            lo = std::min(lo, std::max<std::ptrdiff_t>(0, k0 + fam.shifts[f][ri]));
            hi = std::max(hi, std::min(cols, k1 + fam.shifts[f][ri]));
        }
        if (lo >= hi) continue;
        const float* zr = z.row(r);
        const double rl = lift.row_lift[ri];
        double* key = keys.data();
        for (std::ptrdiff_t c = lo; c < hi; ++c) key[c] = static_cast<double>(zr[c]) + (col_lift[c] + rl);
        for (std::size_t f = 0; f < families; ++f) {
            const std::ptrdiff_t s = fam.shifts[f][ri];
            const std::ptrdiff_t c0 = std::max<std::ptrdiff_t>(0, k0 + s), c1 = std::min(cols, k1 + s);
            double* lim = limits.data() + f * static_cast<std::size_t>(n) - (k0 + s);  // lim[c]: line through (r, c)
            if (fam.owner[ri] == f) {
                std::uint8_t* o = out.row(r);
                for (std::ptrdiff_t c = c0; c < c1; ++c) {
                    const double m = lim[c];
                    const std::uint8_t v = m > key[c] ? 0 : 1;
                    o[c] = zr[c] != zr[c] ? nan_cell : v;
                    lim[c] = key[c] > m ? key[c] : m;  // false for a NaN key: NaN cells cast no shadow
                }
            } else {
                for (std::ptrdiff_t c = c0; c < c1; ++c) lim[c] = key[c] > lim[c] ? key[c] : lim[c];
            }
        }
    }
}

/// Shallow lines [k0, k1) of every family: a sweep over rows (in the order of the walk's row direction) and,
/// within a row, over each family's columns of these lines in walk order; a line crosses a row in a run of
/// adjacent columns, so every line still meets its cells in walk order. A column's cells are written by the
/// family that owns the column.
inline void shadow_shallow_block(raster_view<const float> z, raster_view<std::uint8_t> out, const shadow_families& fam,
                                 const shadow_lifts& lift, std::uint8_t nan_cell, std::ptrdiff_t k0, std::ptrdiff_t k1)
{
    const std::ptrdiff_t rows = z.rows(), cols = z.cols(), n = k1 - k0;
    const std::size_t families = fam.lines.size();
    std::vector<double> limits(families * static_cast<std::size_t>(n), -std::numeric_limits<double>::infinity());
    std::vector<double> keys(static_cast<std::size_t>(cols));
    const ray_lines& l = fam.lines.front();
    const bool fwd = l.forward();
    std::array<const std::ptrdiff_t*, 64> shift{};
    for (std::size_t f = 0; f < families; ++f) shift[f] = fam.shifts[f].data();
    std::ptrdiff_t lo_row = rows, hi_row = 0;
    for (std::size_t f = 0; f < families; ++f) {
        const auto [a, b] = ray_lines::rows_of(fam.shifts[f], k0, k1, rows);
        lo_row = std::min(lo_row, a);
        hi_row = std::max(hi_row, b);
    }
    for (std::ptrdiff_t i = lo_row; i < hi_row; ++i) {
        const std::ptrdiff_t r = l.rows_forward() ? i : lo_row + hi_row - 1 - i;
        const float* zr = z.row(r);
        std::uint8_t* o = out.row(r);
        const double rl = lift.row_lift[static_cast<std::size_t>(r)];
        std::array<std::array<std::ptrdiff_t, 2>, 64> span;  // each family's columns [c0, c1) of this row
        std::ptrdiff_t lo = cols, hi = 0;
        for (std::size_t f = 0; f < families; ++f) {
            span[f] = fam.lines[f].columns(fam.shifts[f], r, k0, k1);
            if (span[f][0] < span[f][1]) {
                lo = std::min(lo, span[f][0]);
                hi = std::max(hi, span[f][1]);
            }
        }
        double* key = keys.data();
        for (std::ptrdiff_t c = lo; c < hi; ++c)
            key[c] = static_cast<double>(zr[c]) + (lift.col_lift[static_cast<std::size_t>(c)] + rl);
        if (families == 1) {  // one chain per line: the plain walk
            double* lim = limits.data() - k0;
            for (std::ptrdiff_t j = lo; j < hi; ++j) {
                const std::ptrdiff_t c = fwd ? j : lo + hi - 1 - j;
                double& m = lim[r - shift[0][c]];
                o[c] = zr[c] != zr[c] ? nan_cell : (m > key[c] ? 0 : 1);
                m = key[c] > m ? key[c] : m;  // false for a NaN key: NaN cells cast no shadow
            }
            continue;
        }
        // Columns in walk order, every family at each column: the families' running maxima are independent
        // chains, so interleaving them hides the latency of each chain (consecutive cells of one line).
        for (std::ptrdiff_t j = lo; j < hi; ++j) {
            const std::ptrdiff_t c = fwd ? j : lo + hi - 1 - j;
            const double kc = key[c];
            const std::size_t own = fam.owner[static_cast<std::size_t>(c)];
            for (std::size_t f = 0; f < families; ++f) {
                if (c < span[f][0] || c >= span[f][1]) continue;
                double& m = limits[f * static_cast<std::size_t>(n) + static_cast<std::size_t>(r - shift[f][c] - k0)];
                if (f == own) o[c] = zr[c] != zr[c] ? nan_cell : (m > kc ? 0 : 1);
                m = kc > m ? kc : m;  // false for a NaN key: NaN cells cast no shadow
            }
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
    const shadow_families fam = make_shadow_families(l, opt.line_phases);
    // Blocks of lines fixed by the input; each line of each family is walked by one thread and each cell is
    // written by one family, so any split gives the same bits.
    const std::ptrdiff_t block = 512;
    parallel_for_rows(
        fam.last - fam.first, block, opt.run.threads,
        [&](std::ptrdiff_t b0, std::ptrdiff_t b1) {
            if (l.steep) {
                shadow_steep_block(z, out, fam, lift, opt.nan_cell, fam.first + b0, fam.first + b1);
            } else {
                shadow_shallow_block(z, out, fam, lift, opt.nan_cell, fam.first + b0, fam.first + b1);
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
/// the running maximum key of the line. With opt.line_phases = P families of lines (phases 0.5 + j / P), cell p
/// takes its line from family line_phase_of(slope, major index of p, P), the one nearest its centre:
/// O(P * rows * cols) at most, O(rows * cols) along the axes and diagonals. Azimuth clockwise from north (row 0 north,
/// columns east); elevation above the horizon, degrees: e <= 0 -> all shadow, e >= 90 -> all lit. NaN cells cast no
/// shadow. @throws invalid_input if shapes differ, cell_m is not finite and > 0, an angle is not finite,
/// elevation is outside [-90, 90], line_phases is outside [1, 64], run.threads < 0 or out overlaps dsm; cancelled if
/// run.progress says stop.
template <raster_input In, class Out>
requires raster_output_of<Out, std::uint8_t>
void raylines_shadow(const In& dsm, Out&& lit, double cell_m, double sun_azimuth_deg, double sun_elevation_deg,
                     const raylines_shadow_options& opt)
{
    constexpr const char* fn = "raylines_shadow";
    detail::require_positive(cell_m, fn, "cell_m");
    detail::require(std::isfinite(sun_azimuth_deg), fn, "sun_azimuth_deg", "finite", sun_azimuth_deg);
    detail::require(sun_elevation_deg >= -90.0 && sun_elevation_deg <= 90.0, fn, "sun_elevation_deg", "in [-90, 90]",
                    sun_elevation_deg);
    detail::require(opt.line_phases >= 1 && opt.line_phases <= 64, fn, "line_phases", "in [1, 64]", opt.line_phases);
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
                                     const raylines_shadow_options& opt)
{
    raster<std::uint8_t> lit(dsm.rows(), dsm.cols());
    raylines_shadow(dsm, lit, cell_m, sun_azimuth_deg, sun_elevation_deg, opt);
    return lit;
}

}  // namespace lidarfx
