// SPDX-License-Identifier: Apache-2.0
// ray_lines: the parallel digital lines along one azimuth that cover every cell of a raster exactly once,
// shared by raylines_shadow and horizon_map.
//
// Geometry (cell units, x east = column, row south; row 0 is north). A walk "away from azimuth A" moves in
// the direction (dcol, drow) = (-sin A, +cos A). If |drow| >= |dcol| the lines are *steep*: one cell per
// row, the line with index k holding the cells (r, k + shift(r)); otherwise they are *shallow*: one cell per
// column, line k holding (k + shift(c), c). shift(i) = floor(0.5 + i * slope) with slope = dcol / drow
// (steep) or drow / dcol (shallow), i.e. each line is the nearest-cell rendering of a straight line through
// cell centres. For any fixed row (column) k -> k + shift is a bijection, so every cell lies on exactly one
// line. A *phase* phi moves every line across itself: shift(i) = floor(phi + i * slope) renders the straight
// line offset by phi - 0.5 cells; phi = 0.5 (the default) puts a line through the centre of every cell of
// major index 0, and a cell of major index i lies exactly on its line's straight line when
// frac(phi + i * slope) = 0.5 (see line_phase_of). Along a line the walk visits rows (steep) or columns (shallow) in
// the order that increases
//   t(r, c) = ((c + 0.5) * dcol + (r + 0.5) * drow) * cell_m,
// the projection of the cell centre on the walk direction (metres); t grows strictly along every line.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <vector>

namespace lidarfx {

/// (sin, cos) of an angle in degrees, exact (0, +-1) at multiples of 90 degrees so that rays along the
/// grid axes stay in one row or column.
inline std::array<double, 2> sincos_deg(double deg) noexcept
{
    double a = std::fmod(deg, 360.0);
    if (a < 0) a += 360.0;
    if (a == 0.0) return {0.0, 1.0};
    if (a == 90.0) return {1.0, 0.0};
    if (a == 180.0) return {0.0, -1.0};
    if (a == 270.0) return {-1.0, 0.0};
    const double rad = a * (std::numbers::pi / 180.0);
    return {std::sin(rad), std::cos(rad)};
}

/// The family of lines that walks away from an azimuth (clockwise from north) over a rows x cols raster (see the
/// geometry above): every cell lies on exactly one line, and along a line the walk visits the cells in the order
/// of increasing t. make_ray_lines builds it; raylines_shadow, horizon_map, sky_view_factor and the facade sweeps
/// walk it. Cheap to copy (a few numbers).
struct ray_lines {
    double dcol = 0, drow = 1;  ///< unit walk direction: columns (east) and rows (south) per unit length
    bool steep = true;          ///< one cell per row (|drow| >= |dcol|), else one cell per column
    double slope = 0;           ///< steep: columns per row, dcol / drow; shallow: rows per column, drow / dcol
    std::ptrdiff_t rows = 0, cols = 0;
    double phase = 0.5;  ///< phi in shift(i) = floor(phi + i * slope), in [0.5, 1.5)

    /// Offset of line cells at major index i (row if steep, column if shallow).
    std::ptrdiff_t shift(std::ptrdiff_t i) const noexcept
    {
        return static_cast<std::ptrdiff_t>(std::floor(phase + static_cast<double>(i) * slope));
    }
    std::ptrdiff_t major() const noexcept { return steep ? rows : cols; }  ///< cells per line at most
    std::ptrdiff_t minor() const noexcept { return steep ? cols : rows; }
    /// True if the walk visits major indices in increasing order.
    bool forward() const noexcept { return (steep ? drow : dcol) > 0; }
    /// Smallest line index that holds a cell; lines are first_line() .. first_line() + count() - 1.
    std::ptrdiff_t first_line() const noexcept
    {
        const std::ptrdiff_t a = shift(0), b = major() > 0 ? shift(major() - 1) : 0;
        return -(a > b ? a : b);
    }
    std::ptrdiff_t count() const noexcept
    {
        if (rows <= 0 || cols <= 0) return 0;
        const std::ptrdiff_t a = shift(0), b = shift(major() - 1);
        return minor() + (a > b ? a - b : b - a);
    }
    /// shift(i) for every major index i.
    std::vector<std::ptrdiff_t> shifts() const
    {
        std::vector<std::ptrdiff_t> s(static_cast<std::size_t>(major()));
        for (std::ptrdiff_t i = 0; i < major(); ++i) s[static_cast<std::size_t>(i)] = shift(i);
        return s;
    }
    /// Shallow lines: the columns [first, last) of row r that belong to lines [k0, k1), i.e. with
    /// r - k1 < shift(c) <= r - k0; one interval because shift is monotone. `sh` = shifts().
    std::array<std::ptrdiff_t, 2> columns(const std::vector<std::ptrdiff_t>& sh, std::ptrdiff_t r, std::ptrdiff_t k0,
                                          std::ptrdiff_t k1) const
    {
        const auto first_true = [&](auto pred) {
            return static_cast<std::ptrdiff_t>(
                std::partition_point(sh.begin(), sh.end(), [&](std::ptrdiff_t v) { return !pred(v); }) - sh.begin());
        };
        if (slope >= 0) {
            return {first_true([&](std::ptrdiff_t v) { return v > r - k1; }),
                    first_true([&](std::ptrdiff_t v) { return v > r - k0; })};
        }
        return {first_true([&](std::ptrdiff_t v) { return v <= r - k0; }),
                first_true([&](std::ptrdiff_t v) { return v <= r - k1; })};
    }
    /// Rows are swept in this order so that every line's cells come in walk order: increasing if true.
    bool rows_forward() const noexcept { return drow >= 0; }
    /// The rows [first, last) of a raster of `rows` rows holding a cell of lines [k0, k1): r = k + shift(c).
    static std::array<std::ptrdiff_t, 2> rows_of(const std::vector<std::ptrdiff_t>& sh, std::ptrdiff_t k0,
                                                 std::ptrdiff_t k1, std::ptrdiff_t rows) noexcept
    {
        return {std::max<std::ptrdiff_t>(0, k0 + std::min(sh.front(), sh.back())),
                std::min(rows, k1 + std::max(sh.front(), sh.back()))};
    }
};

/// Of `phases` line families with phases 0.5 + j / phases (j = 0 .. phases - 1), the one whose line through a
/// cell of major index i passes nearest that cell's centre: j = round(phases * (1 - frac(i * slope))) mod
/// phases, so the line is at most 1 / (2 phases) cells off the centre.
inline int line_phase_of(double slope, std::ptrdiff_t i, int phases) noexcept
{
    const double x = static_cast<double>(i) * slope;
    const double f = x - std::floor(x);  // frac(i * slope) in [0, 1]
    const int j = static_cast<int>(std::floor(0.5 + static_cast<double>(phases) * (1.0 - f)));
    return j % phases;
}

/// The ray lines walking away from azimuth_deg (degrees clockwise from north; exact along the grid axes) over a
/// rows x cols raster, with phase 0.5 (a line through the centre of every cell of major index 0). O(1), no checks
/// (a non-finite azimuth gives NaN directions).
inline ray_lines make_ray_lines(double azimuth_deg, std::ptrdiff_t rows, std::ptrdiff_t cols) noexcept
{
    const auto [s, c] = sincos_deg(azimuth_deg);
    ray_lines l;
    l.dcol = -s;
    l.drow = c;
    l.steep = std::fabs(l.drow) >= std::fabs(l.dcol);
    l.slope = l.steep ? l.dcol / l.drow : l.drow / l.dcol;
    l.rows = rows;
    l.cols = cols;
    return l;
}

namespace detail {

/// The line families of one azimuth (see raylines_shadow_options::line_phases): `phases` families of lines with
/// phases 0.5 + j / phases, and for every major index (row if steep, column if shallow) the family whose line passes
/// nearest the centres of its cells (line_phase_of), which alone writes them. Only families that own some major index
/// are kept. Used by raylines_shadow and horizon_map.
struct line_families {
    std::vector<ray_lines> lines;                     ///< the families some major index uses
    std::vector<std::vector<std::ptrdiff_t>> shifts;  ///< shifts() of each
    std::vector<std::uint8_t> owner;                  ///< per major index: position of its family in `lines`
    std::ptrdiff_t first = 0, last = 0;               ///< line indices [first, last) holding a cell in any family
};

inline line_families make_line_families(const ray_lines& l, int phases)
{
    line_families f;
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

}  // namespace detail

}  // namespace lidarfx
