// SPDX-License-Identifier: Apache-2.0
// Implementation of raylines_shadow (kernels/solar/raylines_shadow.hpp): the sweeps of steep lines, and of shallow
// lines as steep lines of the transposed raster, that carry the running shadow key of every line family.
#pragma once
// Included at the end of its public header, which declares what is defined here.

#include <algorithm>
#include <array>
#include <cassert>
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

/// The default observer of shadow_steep_block's running limits: none.
struct no_seen_limits {
    void operator()(std::ptrdiff_t, std::ptrdiff_t, std::ptrdiff_t, const double*) const noexcept {}
};

/// One row's cells [a, b), which lie on lines of every family: the owner family compares each cell's key
/// z + (col_lift + rl) with the running maximum of its line (own[c]) and writes 1 (lit), 0 or nan_cell, then
/// every family (the owner and the K others) raises its lines' maxima with the key. The families' arrays are
/// disjoint, so the loops carry no dependency. Cell c's height and output are zr[c * Stride] and o[c * Stride]
/// (Stride > 1: a tile of the transposed raster); `lit` is scratch of the row's length.
template <std::size_t K, std::ptrdiff_t Stride>
void shadow_row_fused(const float* zr, const double* col_lift, double rl, double* own, std::array<double*, K> other,
                      double* lit, std::uint8_t* o, std::uint8_t nan_cell, std::ptrdiff_t a, std::ptrdiff_t b) noexcept
{
    const float* __restrict z = zr;
    const double* __restrict lift = col_lift;
    double* __restrict m0 = own;
    std::uint8_t* __restrict out = o;
    if constexpr (K == 0 && Stride == 1) {
        // The owner alone, on contiguous cells: two loops that vectorize, the lit cells passing through `lit` as 1.0
        // or 0.0 (a select between a double compare and a byte store, or a NaN test, in one loop keeps GCC from
        // vectorizing it).
        double* __restrict l = lit;
        for (std::ptrdiff_t c = a; c < b; ++c) {
            const double key = static_cast<double>(z[c * Stride]) + (lift[c] + rl);
            const double m = m0[c];
            l[c] = m > key ? 0.0 : 1.0;
            m0[c] = key > m ? key : m;  // false for a NaN key: NaN cells cast no shadow
        }
        const float nan_value = nan_cell;
        for (std::ptrdiff_t c = a; c < b; ++c) {
            // 1, 0, or nan_cell for a NaN height: exact float arithmetic on small integers.
            const float t = static_cast<float>(l[c]), nan = z[c * Stride] != z[c * Stride] ? 1.0f : 0.0f;
            out[c * Stride] = static_cast<std::uint8_t>(static_cast<std::int32_t>(t + nan * (nan_value - t)));
        }
    } else {
        // With other families, or strided cells, one scalar pass that keeps the key in a register beats two.
        (void)lit;
        double* __restrict m1 = K > 0 ? other[0] : nullptr;
        double* __restrict m2 = K > 1 ? other[K > 1 ? 1 : 0] : nullptr;
        double* __restrict m3 = K > 2 ? other[K > 2 ? 2 : 0] : nullptr;
        for (std::ptrdiff_t c = a; c < b; ++c) {
            const float h = z[c * Stride];
            const double key = static_cast<double>(h) + (lift[c] + rl);
            const double m = m0[c];
            const std::uint8_t v = m > key ? 0 : 1;
            out[c * Stride] = h != h ? nan_cell : v;
            m0[c] = key > m ? key : m;  // false for a NaN key: NaN cells cast no shadow
            if constexpr (K > 0) m1[c] = key > m1[c] ? key : m1[c];
            if constexpr (K > 1) m2[c] = key > m2[c] ? key : m2[c];
            if constexpr (K > 2) m3[c] = key > m3[c] ? key : m3[c];
        }
    }
}

/// Raises the running maxima of one family's lines (lim[c]: the line through column c) with the keys of the row's
/// cells [a, b) (heights zr[c * Stride]).
template <std::ptrdiff_t Stride>
void shadow_row_raise(const float* zr, const double* col_lift, double rl, double* lim, std::ptrdiff_t a,
                      std::ptrdiff_t b) noexcept
{
    const float* __restrict z = zr;
    const double* __restrict lift = col_lift;
    double* __restrict m = lim;
    for (std::ptrdiff_t c = a; c < b; ++c) {
        const double key = static_cast<double>(z[c * Stride]) + (lift[c] + rl);
        m[c] = key > m[c] ? key : m[c];
    }
}

/// The running maxima of a block of lines [k0, k1) in every family (`limits`, n = k1 - k0 per family, from
/// -infinity), and per-row scratch.
struct shadow_block_limits {
    std::ptrdiff_t k0, k1;
    std::vector<double> limits;
    std::vector<double*> lim;            ///< per family: lim[f][c], the line through column c of the current row
    std::vector<std::ptrdiff_t> c0, c1;  ///< per family: the current row's columns on lines [k0, k1)
    std::vector<double> lit;             ///< per column: the owner's lit cells of the current row, 1.0 or 0.0
    shadow_block_limits(std::size_t families, std::ptrdiff_t first, std::ptrdiff_t last, std::ptrdiff_t cols)
        : k0(first),
          k1(last),
          limits(families * static_cast<std::size_t>(last - first), -std::numeric_limits<double>::infinity()),
          lim(families),
          c0(families),
          c1(families),
          lit(static_cast<std::size_t>(cols))
    {
    }
};

/// Row r of a sweep (major index r, columns [0, cols)), for lines [k0, k1) of every family: every family raises
/// its lines' maxima with the row's keys, and the family that owns the row first compares the keys with them. A
/// family's lines hold one cell of a row each, so cells and families may be taken in any order: the columns every
/// family covers go through one fused pass (owner and up to three others), the rest family by family. Before the
/// owner compares, seen(r, c0, c1, lim) may read lim[c], the running maximum key before cell (r, c). Heights and
/// outputs at zr[c * Stride] and o[c * Stride].
template <std::ptrdiff_t Stride, class SeenLimits>
void shadow_row(const line_families& fam, std::ptrdiff_t r, std::ptrdiff_t cols, shadow_block_limits& b,
                const float* zr, const double* col_lift, double rl, std::uint8_t* o, std::uint8_t nan_cell,
                SeenLimits& seen)
{
    const std::size_t ri = static_cast<std::size_t>(r), families = fam.lines.size();
    const std::size_t n = static_cast<std::size_t>(b.k1 - b.k0);
    // Each family's columns of this row, and the columns all of them cover (shifts differ by at most one).
    std::ptrdiff_t all0 = 0, all1 = cols, any0 = cols, any1 = 0;
    for (std::size_t f = 0; f < families; ++f) {
        const std::ptrdiff_t s = fam.shifts[f][ri];
        b.c0[f] = std::max<std::ptrdiff_t>(0, b.k0 + s);
        b.c1[f] = std::min(cols, b.k1 + s);
        b.lim[f] = b.limits.data() + f * n - (b.k0 + s);
        all0 = std::max(all0, b.c0[f]);
        all1 = std::min(all1, b.c1[f]);
        any0 = std::min(any0, b.c0[f]);
        any1 = std::max(any1, b.c1[f]);
    }
    // A row without cells of the owner's lines may still hold cells of another family's lines: they raise them.
    if (any0 >= any1) return;
    all1 = std::max(all0, all1);
    const std::size_t owner = fam.owner[ri];
    seen(r, b.c0[owner], b.c1[owner], static_cast<const double*>(b.lim[owner]));
    for (std::size_t f = 0; f < families; ++f) {  // columns outside [all0, all1)
        const auto edge = [&](std::ptrdiff_t e0, std::ptrdiff_t e1) {
            if (f == owner) {
                shadow_row_fused<0, Stride>(zr, col_lift, rl, b.lim[f], {}, b.lit.data(), o, nan_cell, e0, e1);
            } else {
                shadow_row_raise<Stride>(zr, col_lift, rl, b.lim[f], e0, e1);
            }
        };
        edge(b.c0[f], std::min(b.c1[f], all0));
        edge(std::max(b.c0[f], all1), b.c1[f]);
    }
    std::array<double*, 3> others{};
    std::size_t k = 0, f = 0;
    for (; f < families && k < 3; ++f)
        if (f != owner) others[k++] = b.lim[f];
    double* own = b.lim[owner];
    switch (k) {
        case 0:
            shadow_row_fused<0, Stride>(zr, col_lift, rl, own, {}, b.lit.data(), o, nan_cell, all0, all1);
            break;
        case 1:
            shadow_row_fused<1, Stride>(zr, col_lift, rl, own, {others[0]}, b.lit.data(), o, nan_cell, all0, all1);
            break;
        case 2:
            shadow_row_fused<2, Stride>(zr, col_lift, rl, own, {others[0], others[1]}, b.lit.data(), o, nan_cell, all0,
                                        all1);
            break;
        default:
            shadow_row_fused<3, Stride>(zr, col_lift, rl, own, others, b.lit.data(), o, nan_cell, all0, all1);
            break;
    }
    for (; f < families; ++f)
        if (f != owner) shadow_row_raise<Stride>(zr, col_lift, rl, b.lim[f], all0, all1);
}

/// Steep lines [k0, k1) of every family: a sweep over rows in walk order (shadow_row). seen as in shadow_row (a
/// facade's shadow limit, pipelines/buildings/facade_lit.hpp).
template <class SeenLimits = no_seen_limits>
void shadow_steep_block(raster_view<const float> z, raster_view<std::uint8_t> out, const line_families& fam,
                        const shadow_lifts& lift, std::uint8_t nan_cell, std::ptrdiff_t k0, std::ptrdiff_t k1,
                        SeenLimits&& seen = {})
{
    const std::ptrdiff_t rows = z.rows(), cols = z.cols();
    shadow_block_limits block(fam.lines.size(), k0, k1, cols);
    const bool forward = fam.lines.front().forward();
    for (std::ptrdiff_t i = 0; i < rows; ++i) {
        const std::ptrdiff_t r = forward ? i : rows - 1 - i;
        shadow_row<1>(fam, r, cols, block, z.row(r), lift.col_lift.data(), lift.row_lift[static_cast<std::size_t>(r)],
                      out.row(r), nan_cell, seen);
    }
}

/// Shallow lines [k0, k1) of every family, swept as the steep lines of the transposed raster (see transposed):
/// shadow_row's sweep, with row r' and column c' of the sweep at column r' and row c' of z and out. The
/// sweep takes 16 rows' at a time: their cells are copied from z into a small tile (the 16 contiguous floats of
/// each row of z side by side), swept there, and written back 16 bytes per row of out, so z and out are read and
/// written a cache line at a time and the tile stays in the first-level cache. seen as in shadow_row,
/// called with the row' (a column of z) and columns' (rows of z).
template <class SeenLimits = no_seen_limits>
void shadow_transposed_block(raster_view<const float> z, raster_view<std::uint8_t> out, const line_families& fam,
                             const shadow_lifts& lift, std::uint8_t nan_cell, std::ptrdiff_t k0, std::ptrdiff_t k1,
                             SeenLimits&& seen = {})
{
    constexpr std::ptrdiff_t chunk = 16;
    const std::ptrdiff_t rows = z.cols(), cols = z.rows(), n = k1 - k0;  // of the transposed raster
    const std::size_t families = fam.lines.size();
    shadow_block_limits block(families, k0, k1, cols);
    // A chunk's columns' span lines [k0, k1) of every family across 16 rows': n plus at most 16 |slope| + 1 shifts.
    const std::size_t span = static_cast<std::size_t>(n + 2 * chunk + 2);
    std::vector<float> tile(chunk * span);        // tile[(c - lo) * chunk + j]: row' c0 + j, column' c
    std::vector<std::uint8_t> lit(chunk * span);  // the same layout
    const bool forward = fam.lines.front().forward();
    // Columns' [lo, hi) of row' r on lines [k0, k1) of some family, and of its owner family.
    const auto span_of = [&](std::ptrdiff_t r, bool owner_only) {
        std::ptrdiff_t lo = cols, hi = 0;
        for (std::size_t f = 0; f < families; ++f) {
            if (owner_only && fam.owner[static_cast<std::size_t>(r)] != f) continue;
            const std::ptrdiff_t s = fam.shifts[f][static_cast<std::size_t>(r)];
            lo = std::min(lo, std::max<std::ptrdiff_t>(0, k0 + s));
            hi = std::max(hi, std::min(cols, k1 + s));
        }
        return std::array<std::ptrdiff_t, 2>{lo, hi};
    };
    for (std::ptrdiff_t i0 = 0; i0 < rows; i0 += chunk) {
        const std::ptrdiff_t i1 = std::min(rows, i0 + chunk);
        // Rows' of this chunk are z's columns [c0, c0 + m); tile row j holds column c0 + j.
        const std::ptrdiff_t m = i1 - i0, c0 = forward ? i0 : rows - i1;
        std::ptrdiff_t lo = cols, hi = 0;
        for (std::ptrdiff_t j = 0; j < m; ++j) {
            const auto [a, b] = span_of(c0 + j, false);
            lo = std::min(lo, a);
            hi = std::max(hi, b);
        }
        assert(hi <= lo || static_cast<std::size_t>(hi - lo) <= span);
        for (std::ptrdiff_t r = lo; r < hi; ++r) {
            const float* zr = z.row(r) + c0;
            float* t = tile.data() + (r - lo) * chunk;
            if (m == chunk) {
                std::copy_n(zr, chunk, t);  // a fixed size: a few vector moves, no call
            } else {
                std::copy_n(zr, m, t);
            }
        }
        for (std::ptrdiff_t step = 0; step < m; ++step) {
            const std::ptrdiff_t j = forward ? step : m - 1 - step, r = c0 + j;
            // Column' c of row' r is zt[c * chunk] and its output o[c * chunk].
            const float* zt = tile.data() + j - lo * chunk;
            std::uint8_t* o = lit.data() + j - lo * chunk;
            shadow_row<chunk>(fam, r, cols, block, zt, lift.col_lift.data(), lift.row_lift[static_cast<std::size_t>(r)],
                              o, nan_cell, seen);
        }
        // Back to out, row by row: each row' wrote the cells of its owner family's lines [k0, k1) only.
        std::array<std::array<std::ptrdiff_t, 2>, chunk> own;
        for (std::ptrdiff_t j = 0; j < m; ++j) own[static_cast<std::size_t>(j)] = span_of(c0 + j, true);
        // Rows inside every row's own span take the tile's bytes whole; the few at the spans' ends, cell by cell.
        std::ptrdiff_t all_lo = lo, all_hi = hi;
        for (std::ptrdiff_t j = 0; j < m; ++j) {
            all_lo = std::max(all_lo, own[static_cast<std::size_t>(j)][0]);
            all_hi = std::min(all_hi, own[static_cast<std::size_t>(j)][1]);
        }
        for (std::ptrdiff_t r = lo; r < hi; ++r) {
            std::uint8_t* orow = out.row(r) + c0;
            const std::uint8_t* l = lit.data() + (r - lo) * chunk;
            if (r >= all_lo && r < all_hi && m == chunk) {
                std::copy_n(l, chunk, orow);
                continue;
            }
            for (std::ptrdiff_t j = 0; j < m; ++j) {
                const auto [a, b] = own[static_cast<std::size_t>(j)];
                if (r >= a && r < b) orow[j] = l[j];
            }
        }
    }
}

/// Shallow lines, swept as steep ones: in the transposed raster (row' = column, column' = row) a shallow line of
/// `l` holds one cell per row', at column' k + shift(row'), with the same slope, shifts, phases and families, and
/// its walk visits rows' in the same order. The lifts swap too (col_lift' = row_lift and row_lift' = col_lift),
/// and z + (col_lift' + row_lift') adds the same two numbers, so every key and every output bit is the one a
/// walk in the raster's own layout gives. Steep sweeps carry no dependency from one cell to the next, which a
/// walk along shallow lines in row order cannot avoid.
inline ray_lines transposed(const ray_lines& l) noexcept
{
    ray_lines t = l;
    t.dcol = l.drow;
    t.drow = l.dcol;
    t.steep = !l.steep;
    t.rows = l.cols;
    t.cols = l.rows;
    return t;
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
    const double tan_e = std::tan(sun_elevation_deg * (std::numbers::pi / 180.0));
    // Shallow lines are swept as steep lines of the transposed raster (see transposed).
    const ray_lines s = l.steep ? l : transposed(l);
    const shadow_lifts lift = make_shadow_lifts(s, cell_m, tan_e);
    const line_families fam = make_line_families(s, opt.line_phases);
    // Blocks of lines fixed by the input; each line of each family is walked by one thread and each cell is
    // written by one family, so any split gives the same bits.
    const std::ptrdiff_t block = 512;
    parallel_for_rows(
        fam.last - fam.first, block, opt.run.threads,
        [&](std::ptrdiff_t b0, std::ptrdiff_t b1) {
            if (l.steep) {
                shadow_steep_block(z, out, fam, lift, opt.nan_cell, fam.first + b0, fam.first + b1);
            } else {
                shadow_transposed_block(z, out, fam, lift, opt.nan_cell, fam.first + b0, fam.first + b1);
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
