// SPDX-License-Identifier: Apache-2.0
// Implementation of tiling/tile_plan.hpp: the memory model's bounds, the cell ranges of file boxes, and the plan and
// reader assignment. Included at the end of tile_plan.hpp, after the declarations it defines; not a public header.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/grid.hpp"

namespace lidarfx {

namespace detail {

/// Cells of the largest with_halo box of a plan with edge t: min(t + 2h, rows) x min(t + 2h, cols). An upper
/// bound of every tile's with_halo and, for a plan whose tiles reach both grid borders, its maximum.
inline double tile_halo_cells_bound(const grid& g, std::ptrdiff_t t, std::ptrdiff_t h) noexcept
{
    const double side = static_cast<double>(t) + 2.0 * static_cast<double>(h);
    return std::min(side, static_cast<double>(g.rows)) * std::min(side, static_cast<double>(g.cols));
}

/// peak = grid cells x bytes_per_cell + tiles_in_flight x (halo cells x bytes_per_tile_cell
///        + chunk_points x bytes_per_point), bytes.
inline double tile_plan_peak(const grid& g, double halo_cells, const tile_plan_options& opt) noexcept
{
    return static_cast<double>(g.size()) * opt.bytes_per_cell +
           static_cast<double>(opt.tiles_in_flight) *
               (halo_cells * opt.bytes_per_tile_cell + static_cast<double>(opt.chunk_points) * opt.bytes_per_point);
}

/// v rounded up to 3 significant digits and written with at most 3 (for cell sizes proposed in messages).
inline std::string round_up_3_digits(double v)
{
    const double scale = std::pow(10.0, std::floor(std::log10(v)) - 2);
    std::ostringstream os;
    os.precision(3);
    os << std::ceil(v / scale) * scale;
    return os.str();
}

/// The closed range [lo, hi] of cells along one axis that a coordinate range [a, b] (fractional cell
/// coordinates, a <= b) can land in by grid::cell_of: floor of each, the far border folded into the last
/// cell. False when the range misses the n cells. to_cell_coords is monotone in x and y (a subtraction and a
/// division, each correctly rounded), so every point of the box lands inside [lo, hi].
inline bool cell_range(double a, double b, std::ptrdiff_t n, std::ptrdiff_t& lo, std::ptrdiff_t& hi) noexcept
{
    const double last = static_cast<double>(n);
    if (b < 0 || a > last) return false;
    lo = a <= 0 ? 0 : std::min(static_cast<std::ptrdiff_t>(a), n - 1);
    hi = b >= last ? n - 1 : static_cast<std::ptrdiff_t>(b);
    return true;
}

/// The cells a file box can land in by grid::cell_of (see cell_range); false when it misses the grid.
inline bool file_cell_range(const grid& g, const bounds& b, cell_box& out) noexcept
{
    const cell_coords nw = g.to_cell_coords(b.xmin, b.ymax), se = g.to_cell_coords(b.xmax, b.ymin);
    return cell_range(nw.row, se.row, g.rows, out.row_min, out.row_max) &&
           cell_range(nw.col, se.col, g.cols, out.col_min, out.col_max);
}

/// Cells of a and b in common.
inline double shared_cells(const cell_box& a, const cell_box& b) noexcept
{
    const auto rows = std::min(a.row_max, b.row_max) - std::max(a.row_min, b.row_min) + 1;
    const auto cols = std::min(a.col_max, b.col_max) - std::max(a.col_min, b.col_min) + 1;
    return rows > 0 && cols > 0 ? static_cast<double>(rows) * static_cast<double>(cols) : 0.0;
}

/// Fraction of [a, b] inside [lo, hi] (world metres); a degenerate [a, a] counts 1 when `inside` says so.
inline double overlap_fraction(double a, double b, double lo, double hi, bool inside) noexcept
{
    if (b <= a) return inside ? 1.0 : 0.0;
    return std::max(0.0, std::min(b, hi) - std::max(a, lo)) / (b - a);
}

/// Validates make_tile_plan's arguments. @throws invalid_input as make_tile_plan documents.
inline void check_tile_plan(const grid& g, std::span<const survey_file_extent> files, const tile_plan_options& opt,
                            const char* function)
{
    g.validate(function);
    require(g.rows >= 1 && g.cols >= 1, function, "the survey grid must have at least one cell");
    require(opt.tile_edge_m >= 0 && opt.tile_edge_m <= 1.0e300, function, "tile_edge_m", "finite and >= 0",
            opt.tile_edge_m);
    require(opt.halo_cells >= 0, function, "halo_cells", ">= 0", opt.halo_cells);
    require(opt.bytes_per_cell >= 0 && opt.bytes_per_cell <= 1.0e300, function, "bytes_per_cell", "finite and >= 0",
            opt.bytes_per_cell);
    require(opt.bytes_per_tile_cell >= 0 && opt.bytes_per_tile_cell <= 1.0e300, function, "bytes_per_tile_cell",
            "finite and >= 0", opt.bytes_per_tile_cell);
    require(opt.bytes_per_point >= 0 && opt.bytes_per_point <= 1.0e300, function, "bytes_per_point", "finite and >= 0",
            opt.bytes_per_point);
    require(opt.tiles_in_flight >= 1, function, "tiles_in_flight", ">= 1", opt.tiles_in_flight);
    for (std::size_t i = 0; i < files.size(); ++i) {
        const bounds& b = files[i].box;
        require(std::isfinite(b.xmin) && std::isfinite(b.xmax) && std::isfinite(b.ymin) && std::isfinite(b.ymax) &&
                    b.xmin <= b.xmax && b.ymin <= b.ymax,
                function, [&] {
                    return concat("file ", i, ": extent must be finite with min <= max (got (", b.xmin, ", ", b.ymin,
                                  ", ", b.xmax, ", ", b.ymax, "))");
                });
    }
}

/// The largest tile edge in [1, longest grid side] cells whose memory bound fits opt.memory_budget_bytes (the
/// bound grows with the edge: a bisection), 0 if none does.
inline std::ptrdiff_t largest_fitting_tile_edge(const grid& g, const tile_plan_options& opt)
{
    const double budget = static_cast<double>(opt.memory_budget_bytes);
    const auto fits = [&](std::ptrdiff_t t) {
        return tile_plan_peak(g, tile_halo_cells_bound(g, t, opt.halo_cells), opt) <= budget;
    };
    if (!fits(1)) return 0;
    std::ptrdiff_t lo = 1, hi = std::max(g.rows, g.cols);
    while (lo < hi) {
        const std::ptrdiff_t mid = lo + (hi - lo + 1) / 2;
        if (fits(mid))
            lo = mid;
        else
            hi = mid - 1;
    }
    return lo;
}

/// Throws the refusal for a budget that not even 1-cell tiles fit: the chunk buffers alone exceed it, or the
/// survey grid does not fit beside them (the message then names the cell size at which it would).
[[noreturn]] inline void refuse_tile_plan_budget(const grid& g, const tile_plan_options& opt, const char* function)
{
    const double budget = static_cast<double>(opt.memory_budget_bytes);
    const double buffers = static_cast<double>(opt.tiles_in_flight) *
                           (tile_halo_cells_bound(g, 1, opt.halo_cells) * opt.bytes_per_tile_cell +
                            static_cast<double>(opt.chunk_points) * opt.bytes_per_point);
    const double grid_bytes = static_cast<double>(g.size()) * opt.bytes_per_cell;
    if (buffers >= budget || opt.bytes_per_cell <= 0) {
        throw invalid_input(concat(function, ": the chunk buffers alone (", buffers, " bytes for tiles_in_flight ",
                                   opt.tiles_in_flight, " x chunk_points ", opt.chunk_points,
                                   ") exceed memory_budget_bytes ", budget,
                                   ": lower chunk_points or tiles_in_flight, or raise the budget"));
    }
    // The cell size c at which (ceil(width / c) + 1) x (ceil(height / c) + 1) cells fit the rest.
    const double width = static_cast<double>(g.cols) * g.cell, height = static_cast<double>(g.rows) * g.cell;
    const double room = (budget - buffers) / opt.bytes_per_cell;
    double c = g.cell * std::sqrt(static_cast<double>(g.size()) / std::max(room, 1.0));
    while ((std::ceil(width / c) + 1) * (std::ceil(height / c) + 1) > room) c *= 1.01;
    throw invalid_input(concat(function, ": the survey grid alone (", g.rows, " x ", g.cols, " cells x bytes_per_cell ",
                               opt.bytes_per_cell, " = ", grid_bytes, " bytes) does not fit memory_budget_bytes ",
                               budget, " with the chunk buffers (", buffers, " bytes); a cell of ",
                               round_up_3_digits(c), " m instead of ", g.cell, " m would fit, or raise the budget"));
}

/// The cells a file's box can land in (file_cell_range), false in `inside` when it misses the grid.
struct file_cells {
    bool inside = false;
    cell_box box;
};

/// Tile (tr, tc) of a plan with edge t cells and halo h: its core, its with_halo (clipped to g), the files whose
/// cells meet with_halo and its points estimate.
inline survey_tile make_survey_tile(const grid& g, std::ptrdiff_t tr, std::ptrdiff_t tc, std::ptrdiff_t t,
                                    std::ptrdiff_t h, std::span<const survey_file_extent> files,
                                    const std::vector<file_cells>& reach)
{
    survey_tile tile;
    tile.core = {tr * t, tc * t, std::min(tr * t + t, g.rows) - 1, std::min(tc * t + t, g.cols) - 1};
    // Clipping first keeps huge halos from overflowing.
    tile.with_halo = {std::max<std::ptrdiff_t>(0, tile.core.row_min - std::min(h, tile.core.row_min)),
                      std::max<std::ptrdiff_t>(0, tile.core.col_min - std::min(h, tile.core.col_min)),
                      tile.core.row_max + std::min(h, g.rows - 1 - tile.core.row_max),
                      tile.core.col_max + std::min(h, g.cols - 1 - tile.core.col_max)};
    const bounds core_m = g.extent(tile.core);
    double expected = 0;
    for (std::size_t i = 0; i < files.size(); ++i) {
        const file_cells& f = reach[i];
        if (!f.inside) continue;
        const cell_box& w = tile.with_halo;
        if (f.box.row_max < w.row_min || f.box.row_min > w.row_max || f.box.col_max < w.col_min ||
            f.box.col_min > w.col_max) {
            continue;
        }
        tile.files.push_back(i);
        const bounds& b = files[i].box;
        // A degenerate axis (all points on one line) belongs to the core holding its cell.
        const bool row_in = f.box.row_min >= tile.core.row_min && f.box.row_min <= tile.core.row_max;
        const bool col_in = f.box.col_min >= tile.core.col_min && f.box.col_min <= tile.core.col_max;
        expected += static_cast<double>(files[i].points) *
                    overlap_fraction(b.xmin, b.xmax, core_m.xmin, core_m.xmax, col_in) *
                    overlap_fraction(b.ymin, b.ymax, core_m.ymin, core_m.ymax, row_in);
    }
    tile.points_estimate = static_cast<std::uint64_t>(std::llround(expected));
    return tile;
}

}  // namespace detail

inline tile_plan make_tile_plan(const grid& g, std::span<const survey_file_extent> files, const tile_plan_options& opt)
{
    constexpr const char* function = "make_tile_plan";
    detail::check_tile_plan(g, files, opt, function);
    const std::ptrdiff_t longest = std::max(g.rows, g.cols);
    const double budget = static_cast<double>(opt.memory_budget_bytes);
    const bool limited = opt.memory_budget_bytes > 0;

    std::ptrdiff_t t = longest;
    if (opt.tile_edge_m > 0) {
        const double cells = std::round(opt.tile_edge_m / g.cell);
        t = cells < 1 ? 1 : cells >= static_cast<double>(longest) ? longest : static_cast<std::ptrdiff_t>(cells);
    } else if (limited) {
        t = detail::largest_fitting_tile_edge(g, opt);
    }
    if (limited && t == 0) detail::refuse_tile_plan_budget(g, opt, function);

    tile_plan plan;
    plan.g = g;
    plan.tile_cells = t;
    plan.tile_rows = (g.rows + t - 1) / t;
    plan.tile_cols = (g.cols + t - 1) / t;
    plan.tiles.reserve(static_cast<std::size_t>(plan.tile_rows * plan.tile_cols));
    std::vector<detail::file_cells> reach(files.size());  // computed once for all tiles
    for (std::size_t i = 0; i < files.size(); ++i)
        reach[i].inside = detail::file_cell_range(g, files[i].box, reach[i].box);
    double largest_halo = 0;
    const std::ptrdiff_t h = opt.halo_cells;
    for (std::ptrdiff_t tr = 0; tr < plan.tile_rows; ++tr) {
        for (std::ptrdiff_t tc = 0; tc < plan.tile_cols; ++tc) {
            survey_tile tile = detail::make_survey_tile(g, tr, tc, t, h, files, reach);
            tile.index = plan.tiles.size();
            largest_halo = std::max(
                largest_halo, static_cast<double>(tile.with_halo.rows()) * static_cast<double>(tile.with_halo.cols()));
            plan.tiles.push_back(std::move(tile));
        }
    }
    plan.peak_bytes_estimate = detail::tile_plan_peak(g, largest_halo, opt);

    if (limited && plan.peak_bytes_estimate > budget) {
        const std::ptrdiff_t fit = detail::largest_fitting_tile_edge(g, opt);
        if (fit == 0) detail::refuse_tile_plan_budget(g, opt, function);  // as with an automatic edge
        throw invalid_input(detail::concat(
            function, ": tile_edge_m ", opt.tile_edge_m, " m (", t, " cells, halo ", h, ") needs ",
            plan.peak_bytes_estimate, " bytes, more than memory_budget_bytes ", budget,
            "; the largest tile edge that fits is ", static_cast<double>(fit) * g.cell, " m (", fit, " cells)"));
    }
    return plan;
}

inline std::vector<file_readers> assign_file_readers(const tile_plan& plan, std::span<const survey_file_extent> files,
                                                     std::uint64_t max_handed_points,
                                                     std::vector<double>* handed_per_tile)
{
    constexpr const char* function = "assign_file_readers";
    std::vector<file_readers> readers(files.size(), file_readers{plan.tiles.size(), {}});
    std::vector<std::vector<std::size_t>> listing(files.size());
    for (const auto& t : plan.tiles) {
        for (const std::size_t f : t.files) {
            detail::require(f < files.size(), function, "the plan lists a file beyond `files`");
            listing[f].push_back(t.index);
        }
    }
    const auto cols = static_cast<std::size_t>(std::max<std::ptrdiff_t>(plan.tile_cols, 1));
    const auto next_to = [&](std::size_t a, std::size_t b) {
        const auto d = [](std::size_t u, std::size_t v) { return u > v ? u - v : v - u; };
        return d(a / cols, b / cols) <= 1 && d(a % cols, b % cols) <= 1;
    };
    std::vector<double> handed(plan.tiles.size(), 0.0);
    for (std::size_t f = 0; f < files.size(); ++f) {
        cell_box range;
        if (listing[f].empty() || !detail::file_cell_range(plan.g, files[f].box, range)) continue;
        const double cells = static_cast<double>(range.rows()) * static_cast<double>(range.cols());
        file_readers& r = readers[f];
        double best = -1;
        for (const std::size_t t : listing[f]) {
            const double share = detail::shared_cells(range, plan.tiles[t].with_halo);
            if (share > best) best = share, r.home = t;
        }
        if (max_handed_points == 0) continue;
        for (const std::size_t t : listing[f]) {
            if (t == r.home || !next_to(t, r.home)) continue;
            const double share =
                static_cast<double>(files[f].points) * detail::shared_cells(range, plan.tiles[t].with_halo) / cells;
            if (share <= static_cast<double>(max_handed_points)) {
                r.handed_to.push_back(t);
                handed[t] += share;
            }
        }
    }
    if (handed_per_tile) *handed_per_tile = std::move(handed);
    return readers;
}

inline std::optional<std::size_t> tile_index_of(const tile_plan& plan, double x, double y) noexcept
{
    const std::optional<cell_index> at = plan.g.cell_of(x, y);
    if (!at || plan.tile_cells < 1) return std::nullopt;
    return static_cast<std::size_t>(at->row / plan.tile_cells * plan.tile_cols + at->col / plan.tile_cells);
}

}  // namespace lidarfx
