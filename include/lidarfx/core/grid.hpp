// SPDX-License-Identifier: Apache-2.0
// grid: north-up georeferencing of a raster (upper-left corner, square cell size, extents).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <optional>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// Row/column index of a cell.
struct cell_index {
    std::ptrdiff_t row = 0, col = 0;
    friend constexpr bool operator==(const cell_index&, const cell_index&) = default;
};

/// Fractional cell coordinates: the centre of cell (r, c) is (r + 0.5, c + 0.5). Named members, so a
/// (row, col) pair is never mistaken for a world (x, y) pair.
struct cell_coords {
    double row = 0, col = 0;
    friend constexpr bool operator==(const cell_coords&, const cell_coords&) = default;
};

/// The library's one box of cells: rows row_min..row_max and columns col_min..col_max, both inclusive.
/// Default-constructed it is empty (row_max < row_min). World rectangles are `bounds`.
struct cell_box {
    std::ptrdiff_t row_min = 0, col_min = 0, row_max = -1, col_max = -1;
    constexpr bool empty() const noexcept { return row_max < row_min || col_max < col_min; }
    constexpr std::ptrdiff_t rows() const noexcept { return empty() ? 0 : row_max - row_min + 1; }
    constexpr std::ptrdiff_t cols() const noexcept { return empty() ? 0 : col_max - col_min + 1; }
    /// Grows the box to hold cell (r, c).
    constexpr void extend(std::ptrdiff_t r, std::ptrdiff_t c) noexcept
    {
        if (empty()) {
            *this = {r, c, r, c};
            return;
        }
        row_min = r < row_min ? r : row_min;
        row_max = r > row_max ? r : row_max;
        col_min = c < col_min ? c : col_min;
        col_max = c > col_max ? c : col_max;
    }
    friend constexpr bool operator==(const cell_box&, const cell_box&) = default;
};

/// Axis-aligned world rectangle in projected metres (xmin <= xmax, ymin <= ymax).
struct bounds {
    double xmin = 0, ymin = 0, xmax = 0, ymax = 0;
    friend constexpr bool operator==(const bounds&, const bounds&) = default;
};

/// North-up georeferencing with square cells. Cell (r, c) covers x in [x0 + c*cell, x0 + (c+1)*cell) and
/// y in (y0 - (r+1)*cell, y0 - r*cell]; its centre is (x0 + (c + 0.5)*cell, y0 - (r + 0.5)*cell).
/// Row 0 is the north edge, x grows east (column), y grows north. Units: projected metres.
///
/// Edge rule, one for lookup and sizing. cell_of works on the fractional coordinates
/// col = (x - x0) / cell and row = (y0 - y) / cell, computed in double exactly as written (to_cell_coords):
/// a point is inside when 0 <= col <= cols and 0 <= row <= rows, and lands in (floor(row), floor(col)),
/// except that col == cols and row == rows (the east and south borders) fold into the last column and row.
/// So a point on an interior lattice line belongs to the cell east of it (vertical line) or south of it
/// (horizontal line), as GDAL locates a point in a pixel of a north-up geotransform; the outer borders are
/// closed. snapped_grid sizes its grid with these same expressions, so every point of its bounds lands in
/// it. PDAL's writers.gdal (binmode) bins the same way along x but counts rows from its south-west origin,
/// so a point on an interior horizontal lattice line goes to the cell north of it there, and a maximum on
/// a lattice line opens an extra, otherwise empty column or row, where lidarfx folds it into the last one.
struct grid {
    double x0 = 0;            ///< world x of the west edge of column 0, metres
    double y0 = 0;            ///< world y of the north edge of row 0, metres
    double cell = 1;          ///< cell size, metres, > 0
    std::ptrdiff_t rows = 0;  ///< number of rows (north to south), >= 0
    std::ptrdiff_t cols = 0;  ///< number of columns (west to east), >= 0

    /// Throws invalid_input naming `function` if cell is not finite and > 0, rows or cols < 0, rows x cols
    /// exceeds max_raster_cells (2^40, core/raster_view.hpp), or the corners (x0, y0), (x1(), y1()) are not
    /// finite. Every function taking a grid calls it; the members below assume a valid grid.
    void validate(const char* function = "grid") const
    {
        detail::require_positive(cell, function, "grid.cell");
        detail::require(rows >= 0, function, "grid.rows", ">= 0", rows);
        detail::require(cols >= 0, function, "grid.cols", ">= 0", cols);
        detail::require_raster_cells(rows, cols, function, "grid.rows x grid.cols");
        detail::require(std::isfinite(x0) && std::isfinite(y0), function, "grid corner (x0, y0) must be finite");
        detail::require(std::isfinite(x1()) && std::isfinite(y1()), function,
                        "grid extent (x0 + cols * cell, y0 - rows * cell) must be finite");
    }

    constexpr double x1() const noexcept { return x0 + static_cast<double>(cols) * cell; }  ///< east edge
    constexpr double y1() const noexcept { return y0 - static_cast<double>(rows) * cell; }  ///< south edge
    constexpr bounds extent() const noexcept { return {x0, y1(), x1(), y0}; }
    /// World rectangle covered by the cells of `b` (outer cell edges); b must not be empty.
    constexpr bounds extent(const cell_box& b) const noexcept
    {
        return {x0 + static_cast<double>(b.col_min) * cell, y0 - static_cast<double>(b.row_max + 1) * cell,
                x0 + static_cast<double>(b.col_max + 1) * cell, y0 - static_cast<double>(b.row_min) * cell};
    }
    constexpr std::ptrdiff_t size() const noexcept { return rows * cols; }  ///< cells; <= max_raster_cells when valid

    /// World coordinates (x, y) of the centre of cell (r, c).
    constexpr std::array<double, 2> center(std::ptrdiff_t r, std::ptrdiff_t c) const noexcept
    {
        return {x0 + (static_cast<double>(c) + 0.5) * cell, y0 - (static_cast<double>(r) + 0.5) * cell};
    }

    /// Fractional cell coordinates of world point (x, y): row = (y0 - y)/cell, col = (x - x0)/cell (cell
    /// centres at k + 0.5).
    constexpr cell_coords to_cell_coords(double x, double y) const noexcept
    {
        return {(y0 - y) / cell, (x - x0) / cell};
    }

    /// World coordinates (x, y) of fractional cell coordinates (inverse of to_cell_coords).
    constexpr std::array<double, 2> to_world(double row, double col) const noexcept
    {
        return {x0 + col * cell, y0 - row * cell};
    }
    constexpr std::array<double, 2> to_world(cell_coords rc) const noexcept { return to_world(rc.row, rc.col); }

    /// The cell holding world point (x, y), or nullopt when outside (the edge rule above): interior lattice
    /// lines belong to the cell east / south of them, points on the east or south edge of the grid to the
    /// last column / row, so the closed extent is covered; NaN gives nullopt. O(1).
    std::optional<cell_index> cell_of(double x, double y) const noexcept
    {
        const cell_coords at = to_cell_coords(x, y);
        const double fc = at.col, fr = at.row;
        if (!(fc >= 0 && fr >= 0 && fc <= static_cast<double>(cols) && fr <= static_cast<double>(rows))) {
            return std::nullopt;
        }
        auto c = static_cast<std::ptrdiff_t>(fc), r = static_cast<std::ptrdiff_t>(fr);
        if (c == cols) --c;
        if (r == rows) --r;
        if (c < 0 || r < 0) return std::nullopt;  // empty grid
        return cell_index{r, c};
    }

    constexpr bool contains(std::ptrdiff_t r, std::ptrdiff_t c) const noexcept
    {
        return r >= 0 && c >= 0 && r < rows && c < cols;
    }

    /// Sub-grid of nr x nc cells starting at (r0, c0); the window may extend past this grid (halos),
    /// it keeps the same cell lattice. @throws invalid_input if nr or nc < 0, nr x nc exceeds
    /// max_raster_cells, or the window's corners are not finite.
    grid window(std::ptrdiff_t r0, std::ptrdiff_t c0, std::ptrdiff_t nr, std::ptrdiff_t nc) const
    {
        constexpr const char* function = "grid::window";
        detail::require(nr >= 0 && nc >= 0, function, "window extents must be >= 0");
        detail::require_raster_cells(nr, nc, function, "nr x nc");
        const grid w{x0 + static_cast<double>(c0) * cell, y0 - static_cast<double>(r0) * cell, cell, nr, nc};
        detail::require(std::isfinite(w.x0) && std::isfinite(w.y0) && std::isfinite(w.x1()) && std::isfinite(w.y1()),
                        function, [&] {
                            return detail::concat("window corners must be finite (got a window at row ", r0, ", col ",
                                                  c0, " of cells of ", cell, ")");
                        });
        return w;
    }

    friend constexpr bool operator==(const grid&, const grid&) = default;
};

/// True when a and b have the same cell size and their cell lattices coincide (corners differ by whole
/// cells, within `tolerance_cells` of a cell), so rasters on them can be combined cell by cell after an
/// integer offset.
inline bool aligned(const grid& a, const grid& b, double tolerance_cells = 1e-6) noexcept
{
    if (std::abs(a.cell - b.cell) > tolerance_cells * a.cell) return false;
    const double dx = (b.x0 - a.x0) / a.cell, dy = (a.y0 - b.y0) / a.cell;
    return std::abs(dx - std::round(dx)) <= tolerance_cells && std::abs(dy - std::round(dy)) <= tolerance_cells;
}

/// Offset (rows, cols) of b's cell (0, 0) in a's lattice. @throws invalid_input unless aligned(a, b).
inline cell_index offset_of(const grid& a, const grid& b)
{
    detail::require(aligned(a, b), "offset_of", "grids are not aligned (different cell size or lattice)");
    return {static_cast<std::ptrdiff_t>(std::llround((a.y0 - b.y0) / a.cell)),
            static_cast<std::ptrdiff_t>(std::llround((b.x0 - a.x0) / a.cell))};
}

/// Smallest grid of cell_m-metre cells whose corners lie on multiples of cell_m and in which every point of
/// `b` (closed: corners and edges included) lands by cell_of. x0 is the largest lattice value k * cell_m
/// (the product as rounded in double) <= xmin, y0 the smallest >= ymax; cols and rows are the smallest
/// counts >= 1 with to_cell_coords(xmax, ymin) <= (rows, cols), the very expressions cell_of tests (the
/// edge rule at grid). A maximum on a lattice line therefore closes the last cell instead of opening an
/// empty one; no rounding can leave a point of b a hair outside. O(1).
/// @throws invalid_input if cell_m is not finite and > 0; b is not finite with min <= max; cell_m is below
/// 2^-36 of the largest |coordinate| of b (lattice lines would lie less than 2^16 doubles apart); the
/// grid would exceed max_raster_cells (2^40); or its corners or span lie beyond the double range (b near
/// +-DBL_MAX). Messages name the bounds and cell_m. A grid it returns passes grid::validate.
inline grid snapped_grid(const bounds& b, double cell_m)
{
    constexpr const char* function = "snapped_grid";
    detail::require_positive(cell_m, function, "cell_m");
    const auto box = [&] { return detail::concat("bounds (", b.xmin, ", ", b.ymin, ", ", b.xmax, ", ", b.ymax, ")"); };
    detail::require(std::isfinite(b.xmin) && std::isfinite(b.xmax) && std::isfinite(b.ymin) && std::isfinite(b.ymax) &&
                        b.xmin <= b.xmax && b.ymin <= b.ymax,
                    function,
                    [&] { return detail::concat("bounds must be finite with min <= max (got ", box(), ")"); });
    const double largest = std::max({std::abs(b.xmin), std::abs(b.xmax), std::abs(b.ymin), std::abs(b.ymax)});
    detail::require(cell_m >= largest * 0x1p-36, function, [&] {
        return detail::concat("cell_m must be >= 2^-36 x the largest |coordinate| of the bounds (got cell_m ", cell_m,
                              " for ", box(), ")");
    });
    // |xmin / cell_m| and the rest are now <= 2^36: every quotient below is finite and far from overflow, and
    // one step corrects what rounding did to the quotient or the product.
    double kx = std::floor(b.xmin / cell_m), ky = std::ceil(b.ymax / cell_m);
    if (kx * cell_m > b.xmin)
        kx -= 1;
    else if ((kx + 1) * cell_m <= b.xmin)
        kx += 1;
    if (ky * cell_m < b.ymax)
        ky += 1;
    else if ((ky - 1) * cell_m >= b.ymax)
        ky -= 1;
    grid g{kx * cell_m, ky * cell_m, cell_m, 0, 0};
    const cell_coords far = g.to_cell_coords(b.xmax, b.ymin);
    // Only bounds within a cell of the largest double, or spanning more than it, fail this: their corners or
    // their distance to the far edge do not exist in double.
    const auto beyond = [&] {
        return detail::concat(box(), " at cell_m ", cell_m, " give a grid beyond the double range");
    };
    detail::require(std::isfinite(g.x0) && std::isfinite(g.y0) && std::isfinite(far.col) && std::isfinite(far.row),
                    function, beyond());
    const double cols = std::max(1.0, std::ceil(far.col)), rows = std::max(1.0, std::ceil(far.row));
    detail::require(rows * cols <= static_cast<double>(max_raster_cells), function, [&] {
        return detail::concat(box(), " at cell_m ", cell_m, " need ", rows, " x ", cols, " cells, more than 2^40");
    });
    g.rows = static_cast<std::ptrdiff_t>(rows);
    g.cols = static_cast<std::ptrdiff_t>(cols);
    detail::require(std::isfinite(g.x1()) && std::isfinite(g.y1()), function, beyond());
    return g;
}

/// Grid from a GDAL geotransform {x0, cell, 0, y0, 0, -cell}.
/// @throws invalid_input if the transform is rotated, not north-up, or its cells are not square.
inline grid from_gdal(const std::array<double, 6>& gt, std::ptrdiff_t rows, std::ptrdiff_t cols)
{
    detail::require(gt[2] == 0 && gt[4] == 0, "from_gdal", "rotated geotransforms are not supported");
    detail::require(gt[1] > 0 && gt[5] < 0, "from_gdal", "geotransform must be north-up (gt[1] > 0, gt[5] < 0)");
    detail::require(std::abs(gt[1] + gt[5]) <= 1e-9 * gt[1], "from_gdal", "-gt[5]", "equal to gt[1] (square cells)",
                    gt[5]);
    grid g{gt[0], gt[3], gt[1], rows, cols};
    g.validate("from_gdal");
    return g;
}

/// GDAL geotransform of a grid: {x0, cell, 0, y0, 0, -cell}.
constexpr std::array<double, 6> to_gdal(const grid& g) noexcept
{
    return {g.x0, g.cell, 0.0, g.y0, 0.0, -g.cell};
}

}  // namespace lidarfx
