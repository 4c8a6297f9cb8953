// SPDX-License-Identifier: Apache-2.0
// Implementation of join_channel_parts (included at the end of pipelines/water/join_channel_parts.hpp).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>
#include <queue>
#include <tuple>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/kernels/label/connected_components.hpp"
#include "lidarfx/kernels/vector/convex_hull.hpp"
#include "lidarfx/pipelines/water/hydro_body_shape.hpp"
#include "lidarfx/pipelines/water/lake_level.hpp"

namespace lidarfx {

namespace detail {

inline void validate(const channel_join_options& o, const char* fn)
{
    require(std::isfinite(o.max_gap_m) && o.max_gap_m >= 0, fn, "max_gap_m", "finite and >= 0", o.max_gap_m);
    require(std::isfinite(o.min_part_width_m) && o.min_part_width_m >= 0, fn, "min_part_width_m", "finite and >= 0",
            o.min_part_width_m);
    require(o.min_contact_share > 0 && o.min_contact_share <= 1, fn, "min_contact_share", "in (0, 1]",
            o.min_contact_share);
    require(std::isfinite(o.max_width_ratio) && o.max_width_ratio >= 1, fn, "max_width_ratio", "finite and >= 1",
            o.max_width_ratio);
    require(std::isfinite(o.min_elongation) && o.min_elongation >= 1, fn, "min_elongation", "finite and >= 1",
            o.min_elongation);
    require(o.max_level_step_m >= 0, fn, "max_level_step_m", ">= 0", o.max_level_step_m);
}

using grid_cell = std::array<std::ptrdiff_t, 2>;  // (row, col)

/// What one part's search found of another part: its closest approach and its cells near it.
struct facing_cells {
    double closest_m = std::numeric_limits<double>::infinity();  ///< path length to its nearest cell, metres
    std::vector<grid_cell> cells;                                ///< its cells within 3 cells of closest_m
};

/// Shortest paths from the cells of `label` over land (label 0), at most `reach_m` long, to the cells of every
/// other part they meet (paths end there); per part met, its closest approach and facing cells.
inline std::map<std::int32_t, facing_cells> parts_within_reach(raster_view<const std::int32_t> labels,
                                                               std::int32_t label, const cell_box& box, double reach_m,
                                                               double cell_m)
{
    const auto grow = static_cast<std::ptrdiff_t>(
                          std::min(std::ceil(reach_m / cell_m), static_cast<double>(labels.rows() + labels.cols()))) +
                      2;
    const cell_box win{std::max<std::ptrdiff_t>(0, box.row_min - grow), std::max<std::ptrdiff_t>(0, box.col_min - grow),
                       std::min(labels.rows() - 1, box.row_max + grow),
                       std::min(labels.cols() - 1, box.col_max + grow)};
    const std::ptrdiff_t cols = win.cols();
    constexpr double infinity = std::numeric_limits<double>::infinity();
    std::vector<double> best(static_cast<std::size_t>(win.rows() * cols), infinity);
    using entry = std::pair<double, std::ptrdiff_t>;  // (metres, index in the window): ties settle by index
    std::priority_queue<entry, std::vector<entry>, std::greater<>> open;
    for (std::ptrdiff_t r = box.row_min; r <= box.row_max; ++r)
        for (std::ptrdiff_t c = box.col_min; c <= box.col_max; ++c)
            if (labels(r, c) == label) {
                const std::ptrdiff_t k = (r - win.row_min) * cols + (c - win.col_min);
                best[static_cast<std::size_t>(k)] = 0;
                open.push({0.0, k});
            }
    const double diagonal = cell_m * std::numbers::sqrt2, other_limit = reach_m + diagonal;
    std::map<std::int32_t, std::vector<std::pair<double, grid_cell>>> met;
    while (!open.empty()) {
        const auto [d, k] = open.top();
        open.pop();
        if (d > best[static_cast<std::size_t>(k)]) continue;
        const std::ptrdiff_t r = win.row_min + k / cols, c = win.col_min + k % cols;
        for (std::ptrdiff_t dr = -1; dr <= 1; ++dr)
            for (std::ptrdiff_t dc = -1; dc <= 1; ++dc) {
                const std::ptrdiff_t rr = r + dr, cc = c + dc;
                if ((dr == 0 && dc == 0) || rr < win.row_min || rr > win.row_max || cc < win.col_min ||
                    cc > win.col_max)
                    continue;
                const std::int32_t l = labels(rr, cc);
                const double next = d + (dr != 0 && dc != 0 ? diagonal : cell_m);
                if (l == label || next > (l == 0 ? reach_m : other_limit)) continue;
                double& known = best[static_cast<std::size_t>((rr - win.row_min) * cols + (cc - win.col_min))];
                if (next >= known) continue;
                known = next;
                if (l == 0) open.push({next, (rr - win.row_min) * cols + (cc - win.col_min)});
            }
    }
    for (std::ptrdiff_t r = win.row_min; r <= win.row_max; ++r)
        for (std::ptrdiff_t c = win.col_min; c <= win.col_max; ++c)
            if (const std::int32_t l = labels(r, c); l != 0 && l != label) {
                const double d = best[static_cast<std::size_t>((r - win.row_min) * cols + (c - win.col_min))];
                if (std::isfinite(d)) met[l].push_back({d, {r, c}});
            }
    std::map<std::int32_t, facing_cells> found;
    for (auto& [l, cells] : met) {
        facing_cells& f = found[l];
        for (const auto& dc : cells) f.closest_m = std::min(f.closest_m, dc.first);
        for (const auto& dc : cells)
            if (dc.first <= f.closest_m + 3 * cell_m) f.cells.push_back(dc.second);
    }
    return found;
}

/// Squared distance between two cell centres, in cells².
inline double cell_distance2(const grid_cell& a, const grid_cell& b)
{
    const auto dr = static_cast<double>(a[0] - b[0]), dc = static_cast<double>(a[1] - b[1]);
    return dr * dr + dc * dc;
}

/// How far `cells` spread: the distance between the two farthest of them by two sweeps, plus one cell, metres.
inline double spread_m(const std::vector<grid_cell>& cells, double cell_m)
{
    const auto farthest = [&](const grid_cell& from) {
        return *std::max_element(cells.begin(), cells.end(), [&](const grid_cell& a, const grid_cell& b) {
            return cell_distance2(from, a) < cell_distance2(from, b);
        });
    };
    const grid_cell a = farthest(cells.front()), b = farthest(a);
    return (std::sqrt(cell_distance2(a, b)) + 1) * cell_m;
}

/// Gives `label` to the land cells of `labels` whose centre lies inside the convex hull of `cells` (or within
/// half a cell of its edges). Returns how many.
inline std::size_t fill_hull(raster_view<std::int32_t> labels, const std::vector<grid_cell>& cells, std::int32_t label,
                             cell_box& box)
{
    std::vector<cell_point> points;  // (col, row)
    for (const grid_cell& g : cells) points.push_back({g[1], g[0]});
    const std::vector<cell_point> hull = convex_hull(std::move(points));
    if (hull.size() < 3) return 0;
    cell_box span;
    for (const cell_point& h : hull) span.extend(h[1], h[0]);
    std::size_t filled = 0;
    for (std::ptrdiff_t r = span.row_min; r <= span.row_max; ++r)
        for (std::ptrdiff_t c = span.col_min; c <= span.col_max; ++c) {
            if (labels(r, c) != 0) continue;
            bool inside = true;  // counter-clockwise in (col, row): inside is left of every edge
            for (std::size_t i = 0; i < hull.size() && inside; ++i) {
                const cell_point& a = hull[i];
                const cell_point& b = hull[(i + 1) % hull.size()];
                const auto dc = static_cast<double>(b[0] - a[0]), dr = static_cast<double>(b[1] - a[1]);
                const double left = dc * static_cast<double>(r - a[1]) - dr * static_cast<double>(c - a[0]);
                inside = left >= -0.5 * std::hypot(dc, dr);
            }
            if (!inside) continue;
            labels(r, c) = label;
            box.extend(r, c);
            ++filled;
        }
    return filled;
}

/// The elongation (hydro_body_shape) of parts `a` and `b` of `labels` taken as one body, with the land in the
/// convex hull of their facing cells (what a join across a gap adds); 0 when that body is not 8-connected (a third
/// body in the way, facing cells on one line).
inline double joined_elongation(raster_view<const std::int32_t> labels, std::int32_t a, std::int32_t b,
                                const cell_box& box_a, const cell_box& box_b, const std::vector<grid_cell>& facing,
                                double cell_m)
{
    const cell_box u{std::min(box_a.row_min, box_b.row_min), std::min(box_a.col_min, box_b.col_min),
                     std::max(box_a.row_max, box_b.row_max), std::max(box_a.col_max, box_b.col_max)};
    raster<std::int32_t> both(u.rows(), u.cols(), 0);
    for (std::ptrdiff_t r = 0; r < u.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < u.cols(); ++c) {
            const std::int32_t l = labels(u.row_min + r, u.col_min + c);
            both(r, c) = l == a || l == b ? 1 : (l == 0 ? 0 : -1);
        }
    std::vector<grid_cell> local;
    for (const grid_cell& g : facing) local.push_back({g[0] - u.row_min, g[1] - u.col_min});
    cell_box whole{0, 0, u.rows() - 1, u.cols() - 1};
    fill_hull(both, local, 1, whole);
    const cell_box all{0, 0, u.rows() - 1, u.cols() - 1};
    if (connected_components(body_mask(both, 1, all)).count() != 1) return 0;  // the fill does not link them
    return measure_hydro_body_shape(both, 1, all, cell_m).elongation();
}

/// The median of the finite `heights` at `cells` (the upper one of an even count), NaN when none.
inline double median_height(raster_view<const float> heights, const std::vector<grid_cell>& cells)
{
    std::vector<float> v;
    for (const grid_cell& g : cells)
        if (const float z = heights(g[0], g[1]); std::isfinite(z)) v.push_back(z);
    return upper_median_in_place(v);
}

}  // namespace detail

inline std::vector<channel_join> join_channel_parts(raster_view<std::int32_t> labels, std::vector<cell_box>& box,
                                                    raster_view<const float> heights, double cell_m,
                                                    const channel_join_options& opt)
{
    constexpr const char* fn = "join_channel_parts";
    detail::require_same_shape(labels, heights, fn, "labels", "heights");
    detail::require_positive(cell_m, fn, "cell_m");
    detail::validate(opt, fn);
    std::vector<std::size_t> cells(box.size(), 0);
    for (std::ptrdiff_t r = 0; r < labels.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < labels.cols(); ++c) {
            const std::int32_t l = labels(r, c);
            detail::require(l >= 0, fn, "labels", ">= 0", l);
            const auto u = static_cast<std::size_t>(l);
            detail::require(u < box.size() && (l == 0 || (r >= box[u].row_min && r <= box[u].row_max &&
                                                          c >= box[u].col_min && c <= box[u].col_max)),
                            fn, "every label must lie inside its box");
            ++cells[u];
        }
    // The parts wide enough to be a river's, and their shapes.
    const double cell_area = cell_m * cell_m;
    std::vector<hydro_body_shape> shape(box.size());
    std::vector<char> wide(box.size(), 0);
    for (std::size_t l = 1; l < box.size(); ++l) {
        if (cells[l] == 0 || static_cast<double>(cells[l]) * cell_area < opt.min_part_width_m * opt.min_part_width_m)
            continue;
        shape[l] = measure_hydro_body_shape(labels, static_cast<std::int32_t>(l), box[l], cell_m);
        wide[l] = shape[l].width_m >= opt.min_part_width_m;
    }
    // What each wide part sees of the others.
    std::vector<std::map<std::int32_t, detail::facing_cells>> sees(box.size());
    for (std::size_t l = 1; l < box.size(); ++l)
        if (wide[l])
            sees[l] = detail::parts_within_reach(labels, static_cast<std::int32_t>(l), box[l], opt.max_gap_m, cell_m);
    // Decide each pair, then join transitively to the smallest label.
    std::vector<std::int32_t> root(box.size());
    std::iota(root.begin(), root.end(), 0);
    const auto find = [&root](std::int32_t l) {
        while (root[static_cast<std::size_t>(l)] != l) l = root[static_cast<std::size_t>(l)];
        return l;
    };
    struct accepted {
        std::int32_t a, b;
        double gap_m, contact_m;
        std::vector<detail::grid_cell> facing;
    };
    std::vector<accepted> pairs;
    for (std::size_t a = 1; a < box.size(); ++a)
        for (const auto& [b, of_b] : sees[a]) {
            const auto ub = static_cast<std::size_t>(b);
            if (ub <= a || !wide[ub] || !sees[ub].contains(static_cast<std::int32_t>(a))) continue;
            const detail::facing_cells& of_a = sees[ub].at(static_cast<std::int32_t>(a));
            const double narrow = std::min(shape[a].width_m, shape[ub].width_m);
            const double broad = std::max(shape[a].width_m, shape[ub].width_m);
            const bool touch = std::min(of_a.closest_m, of_b.closest_m) <= cell_m * std::numbers::sqrt2 + 1e-9;
            const double gap_m = touch ? 0.0 : std::min(of_a.closest_m, of_b.closest_m) - cell_m;
            const double contact_m =
                std::min(detail::spread_m(of_a.cells, cell_m), detail::spread_m(of_b.cells, cell_m));
            if (broad > opt.max_width_ratio * narrow || contact_m < opt.min_contact_share * narrow ||
                (!touch && contact_m > 2 * broad))
                continue;
            const double step_m =
                std::abs(detail::median_height(heights, of_a.cells) - detail::median_height(heights, of_b.cells));
            if (step_m > opt.max_level_step_m) continue;  // NaN (no heights on a side) does not refuse
            accepted p{static_cast<std::int32_t>(a), b, gap_m, contact_m, of_a.cells};
            p.facing.insert(p.facing.end(), of_b.cells.begin(), of_b.cells.end());
            if (detail::joined_elongation(labels, p.a, p.b, box[a], box[ub], p.facing, cell_m) < opt.min_elongation)
                continue;
            const std::int32_t ra = find(p.a), rb = find(p.b);
            root[static_cast<std::size_t>(std::max(ra, rb))] = std::min(ra, rb);
            pairs.push_back(std::move(p));
        }
    // Relabel to the channel's smallest label, then give the land under each deck to it.
    for (std::size_t l = 1; l < box.size(); ++l) {
        const std::int32_t to = find(static_cast<std::int32_t>(l));
        if (to == static_cast<std::int32_t>(l)) continue;
        const cell_box from = box[l];
        for (std::ptrdiff_t r = from.row_min; r <= from.row_max; ++r)
            for (std::ptrdiff_t c = from.col_min; c <= from.col_max; ++c)
                if (labels(r, c) == static_cast<std::int32_t>(l)) {
                    labels(r, c) = to;
                    box[static_cast<std::size_t>(to)].extend(r, c);
                }
        box[l] = {};
    }
    std::vector<channel_join> joins;
    for (accepted& p : pairs) {
        const std::int32_t kept = find(p.a);
        channel_join j{kept, p.a, p.b, p.gap_m, p.contact_m, 0};
        if (p.gap_m > 0) j.gap_cells = detail::fill_hull(labels, p.facing, kept, box[static_cast<std::size_t>(kept)]);
        joins.push_back(j);
    }
    std::sort(joins.begin(), joins.end(), [](const channel_join& x, const channel_join& y) {
        return std::tuple{x.kept, x.part_a, x.part_b} < std::tuple{y.kept, y.part_a, y.part_b};
    });
    return joins;
}

}  // namespace lidarfx
