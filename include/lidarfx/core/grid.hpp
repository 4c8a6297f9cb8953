// SPDX-License-Identifier: Apache-2.0
// grid: north-up georeferencing of a raster (upper-left corner, square cell size, extents).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <optional>

#include "lidarfx/core/error.hpp"

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
struct grid {
    double x0 = 0;              ///< world x of the west edge of column 0, metres
    double y0 = 0;              ///< world y of the north edge of row 0, metres
    double cell = 1;            ///< cell size, metres, > 0
    std::ptrdiff_t rows = 0;    ///< number of rows (north to south), >= 0
    std::ptrdiff_t cols = 0;    ///< number of columns (west to east), >= 0

    /// Throws invalid_input naming `function` if cell <= 0, extents < 0, or the corner is not finite.
    void validate(const char* function = "grid") const
    {
        detail::require_positive(cell, function, "grid.cell");
        detail::require(rows >= 0, function, "grid.rows", ">= 0", rows);
        detail::require(cols >= 0, function, "grid.cols", ">= 0", cols);
        detail::require(std::isfinite(x0) && std::isfinite(y0), function, "grid corner (x0, y0) must be finite");
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
    constexpr std::ptrdiff_t size() const noexcept { return rows * cols; }

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

    /// The cell holding world point (x, y), or nullopt when outside. Points on the east or south edge of
    /// the grid belong to the last column / row, so the closed extent is covered; NaN gives nullopt.
    std::optional<cell_index> cell_of(double x, double y) const noexcept
    {
        const double fc = (x - x0) / cell, fr = (y0 - y) / cell;
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
    /// it keeps the same cell lattice. @throws invalid_input if nr or nc < 0.
    grid window(std::ptrdiff_t r0, std::ptrdiff_t c0, std::ptrdiff_t nr, std::ptrdiff_t nc) const
    {
        detail::require(nr >= 0 && nc >= 0, "grid::window", "window extents must be >= 0");
        return {x0 + static_cast<double>(c0) * cell, y0 - static_cast<double>(r0) * cell, cell, nr, nc};
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

/// Smallest grid of cell_m-metre cells whose corners lie on multiples of cell_m and whose extent covers `b`
/// (closed: a point on the east/south edge falls in the last cell). @throws invalid_input on cell_m <= 0 or
/// a bad box.
inline grid snapped_grid(const bounds& b, double cell_m)
{
    detail::require_positive(cell_m, "snapped_grid", "cell_m");
    detail::require(std::isfinite(b.xmin) && std::isfinite(b.xmax) && std::isfinite(b.ymin) &&
                        std::isfinite(b.ymax) && b.xmin <= b.xmax && b.ymin <= b.ymax,
                    "snapped_grid", "bounds must be finite with min <= max");
    const double x0 = std::floor(b.xmin / cell_m) * cell_m;
    const double y0 = std::ceil(b.ymax / cell_m) * cell_m;
    auto cols = static_cast<std::ptrdiff_t>(std::floor((b.xmax - x0) / cell_m)) + 1;
    auto rows = static_cast<std::ptrdiff_t>(std::floor((y0 - b.ymin) / cell_m)) + 1;
    // A maximum exactly on a lattice line would open an extra empty cell; the closed-edge rule covers it.
    if (cols > 1 && x0 + static_cast<double>(cols - 1) * cell_m >= b.xmax) --cols;
    if (rows > 1 && y0 - static_cast<double>(rows - 1) * cell_m <= b.ymin) --rows;
    return {x0, y0, cell_m, rows, cols};
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
constexpr std::array<double, 6> to_gdal(const grid& g) noexcept { return {g.x0, g.cell, 0.0, g.y0, 0.0, -g.cell}; }

}  // namespace lidarfx
