// SPDX-License-Identifier: Apache-2.0
// shadow_probes: raylines_shadow's sweep that also reads, at chosen cells (probes), the shadow key of the cells
// before them on their ray line, so that a point at any height above a probe cell is known lit or shaded (a
// facade, a tree top, a sensor) from the same single sweep.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/kernels/solar/ray_lines.hpp"
#include "lidarfx/kernels/solar/raylines_shadow.hpp"

namespace lidarfx {

/// Probe cells of a rows x cols raster, listed row by row (each row's by column) and column by column (each
/// column's by row), as the steep and shallow sweeps meet them.
struct shadow_probes {
    std::vector<std::ptrdiff_t> row, col;           ///< probe k lies at cell (row[k], col[k])
    std::vector<std::size_t> row_first, col_first;  ///< size rows + 1 and cols + 1
    std::vector<std::int32_t> in_row, in_col;       ///< row r's probes: in_row[row_first[r] .. row_first[r + 1])
};

/// The probes at cells (row[k], col[k]) of a rows x cols raster, k < 2^31. O(rows + cols + probes log probes).
/// @throws invalid_input if the lists differ in length or a cell lies outside the raster.
inline shadow_probes make_shadow_probes(std::ptrdiff_t rows, std::ptrdiff_t cols, std::vector<std::ptrdiff_t> row,
                                        std::vector<std::ptrdiff_t> col)
{
    constexpr const char* fn = "make_shadow_probes";
    detail::require(row.size() == col.size(), fn, "row and col", "of one length", row.size());
    detail::require(row.size() < static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()), fn, "probes",
                    "fewer than 2^31", row.size());
    shadow_probes p{std::move(row), std::move(col), {}, {}, {}, {}};
    for (std::size_t k = 0; k < p.row.size(); ++k) {
        detail::require(p.row[k] >= 0 && p.row[k] < rows && p.col[k] >= 0 && p.col[k] < cols, fn, "probe cell",
                        "inside the raster", k);
    }
    // Probes sorted by their minor index, then placed by their major one (a counting sort, stable): each row's
    // probes come by column and each column's by row.
    const auto sort_by = [&](const std::vector<std::ptrdiff_t>& major, const std::vector<std::ptrdiff_t>& minor,
                             std::ptrdiff_t majors, std::vector<std::size_t>& first, std::vector<std::int32_t>& in) {
        std::vector<std::int32_t> order(p.row.size());
        for (std::size_t k = 0; k < order.size(); ++k) order[k] = static_cast<std::int32_t>(k);
        std::stable_sort(order.begin(), order.end(), [&](std::int32_t a, std::int32_t b) {
            return minor[static_cast<std::size_t>(a)] < minor[static_cast<std::size_t>(b)];
        });
        first.assign(static_cast<std::size_t>(majors) + 1, 0);
        for (const std::ptrdiff_t m : major) ++first[static_cast<std::size_t>(m) + 1];
        for (std::size_t m = 0; m < static_cast<std::size_t>(majors); ++m) first[m + 1] += first[m];
        std::vector<std::size_t> next(first.begin(), first.end() - 1);
        in.resize(order.size());
        for (const std::int32_t k : order) in[next[static_cast<std::size_t>(major[static_cast<std::size_t>(k)])]++] = k;
    };
    sort_by(p.row, p.col, rows, p.row_first, p.in_row);
    sort_by(p.col, p.row, cols, p.col_first, p.in_col);
    return p;
}

/// z with rows and columns swapped (cols x rows): the z_transposed of raylines_shadow_probed, made once for many
/// suns. Columns in blocks on `threads` (0 = all cores). O(rows * cols).
inline raster<float> transposed_dsm(raster_view<const float> z, int threads = 1)
{
    raster<float> t(z.cols(), z.rows());
    parallel_for_rows(z.cols(), 64, threads, [&](std::ptrdiff_t c0, std::ptrdiff_t c1) {
        for (std::ptrdiff_t c = c0; c < c1; ++c)
            for (std::ptrdiff_t r = 0; r < z.rows(); ++r) t(c, r) = z(r, c);
    });
    return t;
}

namespace detail {

/// Probes in row (by_row) or column `major` whose column (row) lies in [lo, hi).
inline std::span<const std::int32_t> probes_between(const shadow_probes& p, bool by_row, std::ptrdiff_t major,
                                                    std::ptrdiff_t lo, std::ptrdiff_t hi)
{
    const std::vector<std::size_t>& first = by_row ? p.row_first : p.col_first;
    const std::vector<std::int32_t>& in = by_row ? p.in_row : p.in_col;
    const std::vector<std::ptrdiff_t>& minor = by_row ? p.col : p.row;
    const auto m = static_cast<std::size_t>(major);
    const std::int32_t* b = in.data() + first[m];
    const std::int32_t* e = in.data() + first[m + 1];
    const auto at = [&](std::int32_t k) { return minor[static_cast<std::size_t>(k)]; };
    const auto from = std::partition_point(b, e, [&](std::int32_t k) { return at(k) < lo; });
    const auto to = std::partition_point(from, e, [&](std::int32_t k) { return at(k) < hi; });
    return {from, static_cast<std::size_t>(to - from)};
}

}  // namespace detail

/// One sun position's sweep (0 < elevation < 90) over the ray lines `l` of its azimuth (make_ray_lines of the
/// raster's shape), with `lift` = make_shadow_lifts(l, cell_m, tan elevation), and opt.line_phases families:
///   - lit: raylines_shadow's output for this sun and `opt` (1 lit, 0 shadow, opt.nan_cell on NaN cells), bit for
///     bit;
///   - limit[k]: the largest shadow key z_q + (col_lift[c_q] + row_lift[r_q]) of the non-NaN cells q before probe
///     k's cell on its line (the line of the family that owns the cell; -infinity if none). A point of height h
///     above probe cell (r, c) is lit iff !(limit[k] > h + (col_lift[c] + row_lift[r])): raylines_shadow's test
///     with h in place of the cell's height.
/// Shallow lines are swept as steep lines of the transposed raster: in small tiles of z or, when z_transposed
/// (z with rows and columns swapped, e.g. kept for many suns) is given, along its rows, and then `lit` is
/// transposed too (cols x rows). O(line_phases * rows * cols + probes); blocks of lines fixed by the input, so
/// any thread count (opt.run.threads) gives the same bits; opt.run.progress is told the blocks done and may
/// cancel. The sun and cell size are the caller's to check (make_shadow_lifts takes any).
/// @throws invalid_input if the lines, lifts, lit, z_transposed or the probes do not fit z's shape or line_phases is
/// outside [1, 64]; cancelled if run.progress says stop.
inline void raylines_shadow_probed(raster_view<const float> z, raster_view<const float> z_transposed,
                                   const ray_lines& l, const shadow_lifts& lift, const shadow_probes& probes,
                                   std::vector<double>& limit, raster_view<std::uint8_t> lit,
                                   const raylines_shadow_options& opt = {.nan_cell = 0, .line_phases = 1})
{
    constexpr const char* fn = "raylines_shadow_probed";
    const bool along_rows = l.steep || !z_transposed.empty();
    const bool flip = !l.steep && !z_transposed.empty();
    detail::require(opt.line_phases >= 1 && opt.line_phases <= 64, fn, "line_phases", "in [1, 64]", opt.line_phases);
    detail::check_execution(opt.run, fn);
    detail::require(lit.rows() == (flip ? z.cols() : z.rows()) && lit.cols() == (flip ? z.rows() : z.cols()), fn, "lit",
                    "of z's shape (transposed with z_transposed on shallow lines)", lit.rows());
    detail::require(z_transposed.empty() || (z_transposed.rows() == z.cols() && z_transposed.cols() == z.rows()), fn,
                    "z_transposed", "z's shape transposed", z_transposed.rows());
    detail::require(l.rows == z.rows() && l.cols == z.cols(), fn, "lines", "made for z's shape", l.rows);
    detail::require(lift.row_lift.size() == static_cast<std::size_t>(z.rows()) &&
                        lift.col_lift.size() == static_cast<std::size_t>(z.cols()),
                    fn, "lift", "made from the lines", lift.row_lift.size());
    detail::require(probes.row_first.size() == static_cast<std::size_t>(z.rows()) + 1 &&
                        probes.col_first.size() == static_cast<std::size_t>(z.cols()) + 1,
                    fn, "probes", "made for z's shape", probes.row_first.size());
    limit.assign(probes.row.size(), -std::numeric_limits<double>::infinity());
    const ray_lines s = l.steep ? l : detail::transposed(l);
    // The transposed sweep's lifts are the same numbers, swapped (see detail::transposed).
    const shadow_lifts swept = l.steep ? lift : shadow_lifts{lift.row_lift, lift.col_lift};
    const detail::line_families fam = detail::make_line_families(s, opt.line_phases);
    const auto seen = [&](std::ptrdiff_t major, std::ptrdiff_t lo, std::ptrdiff_t hi, const double* lim) {
        for (const std::int32_t k : detail::probes_between(probes, l.steep, major, lo, hi)) {
            const auto u = static_cast<std::size_t>(k);
            limit[u] = lim[l.steep ? probes.col[u] : probes.row[u]];
        }
    };
    parallel_for_rows(
        fam.last - fam.first, 512, opt.run.threads,
        [&](std::ptrdiff_t b0, std::ptrdiff_t b1) {
            if (along_rows) {
                detail::shadow_steep_block(l.steep ? z : z_transposed, lit, fam, swept, opt.nan_cell, fam.first + b0,
                                           fam.first + b1, seen);
            } else {
                detail::shadow_transposed_block(z, lit, fam, swept, opt.nan_cell, fam.first + b0, fam.first + b1, seen);
            }
        },
        opt.run.progress, fn);
}

}  // namespace lidarfx
