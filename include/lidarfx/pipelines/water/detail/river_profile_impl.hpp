// SPDX-License-Identifier: Apache-2.0
// Implementation of river_profile (included at the end of pipelines/water/river_profile.hpp).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/kernels/filter/geodesic_distance.hpp"
#include "lidarfx/kernels/stats/isotonic_regression.hpp"
#include "lidarfx/pipelines/water/lake_level.hpp"

namespace lidarfx {

namespace detail {

inline void validate(const river_profile_options& o, const char* fn)
{
    const auto positive = [fn](double v, const char* name) {
        require(std::isfinite(v) && v > 0, fn, name, "finite and > 0", v);
    };
    positive(o.section_spacing_m, "section_spacing_m");
    positive(o.deck_clearance_m, "deck_clearance_m");
    positive(o.floor_window_m, "floor_window_m");
    positive(o.level_window_m, "level_window_m");
    positive(o.return_tolerance_m, "return_tolerance_m");
    positive(o.level_tolerance_m, "level_tolerance_m");
    positive(o.mode_window_m, "mode_window_m");
    require(o.min_return_share >= 0 && o.min_return_share <= 1, fn, "min_return_share", "in [0, 1]",
            o.min_return_share);
    positive(o.weir_min_drop_m, "weir_min_drop_m");
    require(o.lowest_mode_share > 0 && o.lowest_mode_share <= 1, fn, "lowest_mode_share", "in (0, 1]",
            o.lowest_mode_share);
}

/// The median of the lowest window of `width` in the sorted `values` whose count reaches `share` of the densest
/// window's (and at least 3, or the densest window's count when that is smaller): among the windows starting within
/// `width` above that one, the densest. NaN when empty. Sorts `values`.
inline double lowest_dense_window_median(std::vector<float>& values, double width, double share)
{
    if (values.empty()) return NAN;
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    std::vector<std::size_t> count(n);
    for (std::size_t from = 0, to = 0; from < n; ++from) {
        to = std::max(to, from);
        while (to < n && static_cast<double>(values[to]) <= static_cast<double>(values[from]) + width) ++to;
        count[from] = to - from;
    }
    const std::size_t densest = *std::max_element(count.begin(), count.end());
    const double enough = std::min(static_cast<double>(densest), std::max(3.0, share * static_cast<double>(densest)));
    std::size_t first = 0;
    while (static_cast<double>(count[first]) < enough) ++first;
    std::size_t best = first;
    for (std::size_t from = first; from < n && static_cast<double>(values[from]) <= values[first] + width; ++from)
        if (count[from] > count[best]) best = from;
    return values[best + count[best] / 2];
}

/// Fills the NaN entries of `level` by linear interpolation (in index) between the nearest finite entries on
/// either side, or the nearest one's value at the ends; all NaN stays all NaN.
inline void interpolate_gaps(std::vector<double>& level)
{
    const std::size_t n = level.size();
    std::size_t prev = n;  // last finite index seen (n = none yet)
    for (std::size_t k = 0; k < n; ++k) {
        if (std::isnan(level[k])) continue;
        if (prev == n) {
            for (std::size_t j = 0; j < k; ++j) level[j] = level[k];
        } else {
            for (std::size_t j = prev + 1; j < k; ++j) {
                const double t = static_cast<double>(j - prev) / static_cast<double>(k - prev);
                level[j] = level[prev] + t * (level[k] - level[prev]);
            }
        }
        prev = k;
    }
    if (prev != n)
        for (std::size_t j = prev + 1; j < n; ++j) level[j] = level[prev];
}

/// Slope of the least-squares line through (k, level[k]) weighted by weight[k], over finite levels with weight > 0.
inline double weighted_slope(const std::vector<double>& level, const std::vector<std::size_t>& weight)
{
    double sw = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (std::size_t k = 0; k < level.size(); ++k) {
        if (weight[k] == 0 || std::isnan(level[k])) continue;
        const double w = static_cast<double>(weight[k]), x = static_cast<double>(k);
        sw += w;
        sx += w * x;
        sy += w * level[k];
        sxx += w * x * x;
        sxy += w * x * level[k];
    }
    const double den = sw * sxx - sx * sx;
    return den > 0 ? (sw * sxy - sx * sy) / den : 0.0;
}

/// Counts into p.weirs the falls of at least `weir_min_drop_m` between neighbouring sections of p.level_m, and
/// puts the largest fall (0 when none) into p.largest_step_m.
inline void count_weirs(river_profile& p, double weir_min_drop_m)
{
    p.weirs = 0;
    p.largest_step_m = 0;
    for (std::size_t k = 0; k + 1 < p.level_m.size(); ++k) {
        const double fall = p.level_m[k] - p.level_m[k + 1];
        if (fall >= weir_min_drop_m) ++p.weirs;
        p.largest_step_m = std::max(p.largest_step_m, fall);
    }
}

/// A weir's crest as a straight line; offset() is a cell centre's signed distance to it, in cells, negative on the
/// upper pool's side.
struct crest_line {
    double row = 0, col = 0;                ///< a point of the line, raster cells
    double normal_row = 0, normal_col = 0;  ///< its unit normal, pointing to the lower pool

    double offset(std::ptrdiff_t r, std::ptrdiff_t c) const
    {
        return (static_cast<double>(r) - row) * normal_row + (static_cast<double>(c) - col) * normal_col;
    }
};

/// How well the best line at one angle separates the two pools.
struct crest_separation {
    std::size_t misplaced = 0;  ///< the fewest cells on the wrong side of the line
    double position = 0;        ///< the middle of the line's positions that leave that few, along the normal, cells
};

/// How well a line square to the normal at `angle` (radians, in (row, col)) separates `cells` ((row, col, side)
/// with side 0 upper pool, 1 lower pool), over every position of the line (upper cells past it along the normal,
/// lower cells before it are on the wrong side). O(n log n) in the n cells.
inline crest_separation separate_pools(const std::vector<std::array<double, 3>>& cells, double angle)
{
    const double nr = std::cos(angle), nc = std::sin(angle);
    std::vector<std::pair<double, bool>> along(cells.size());
    std::size_t upper = 0;
    for (std::size_t i = 0; i < cells.size(); ++i) {
        along[i] = {cells[i][0] * nr + cells[i][1] * nc, cells[i][2] == 0};
        upper += cells[i][2] == 0;
    }
    std::sort(along.begin(), along.end());
    // Before the first cell every upper cell lies past the line; after cell i, the line lies between i and i + 1.
    std::size_t misplaced = upper, fewest = upper, first = 0, last = 0;  // the line after cells first-1 .. last-1
    for (std::size_t i = 0; i < along.size(); ++i) {
        misplaced = along[i].second ? misplaced - 1 : misplaced + 1;
        if (misplaced < fewest)
            fewest = misplaced, first = last = i + 1;
        else if (misplaced == fewest)
            last = i + 1;
    }
    const auto gap_middle = [&](std::size_t after) {  // the middle of the gap after `after` cells
        if (after == 0) return along.front().first - 0.5;
        if (after == along.size()) return along.back().first + 0.5;
        return 0.5 * (along[after - 1].first + along[after].first);
    };
    return {fewest, 0.5 * (gap_middle(first) + gap_middle(last))};
}

/// Fits the crest of a straight weir. `side` holds 0 (upper pool), 1 (lower pool) or another value (not known,
/// or elsewhere) per cell. The crest's direction is the one whose line leaves the fewest upper and lower cells on
/// the wrong side (separate_pools every 3°, then every 0.25° around the best; the middle of the best run): it uses
/// every cell of both pools, so a crest seen over a short stretch, beside a dropout patch, still gets its
/// direction. A cell the crest crosses holds returns of the lower pool, so its lowest return puts it there: the
/// upper cells are those wholly upstream, whose centres lie at least h = (|cos| + |sin|) / 2 cells before the
/// crest, and the line that separates the pools best lies h before it. The crest is straight when the best line
/// leaves at most `max_misplaced_share` of the cells on the wrong side (stray returns) and each pool holds at
/// least 4 cells; false otherwise. Across a stretch without returns the line lies in the middle of it. O(n log n) per
/// angle in the n cells of the two pools.
inline bool fit_crest_line(const raster<std::int8_t>& side, double max_misplaced_share, crest_line& line)
{
    std::vector<std::array<double, 3>> cells;
    std::size_t upper = 0;
    for (std::ptrdiff_t r = 0; r < side.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < side.cols(); ++c) {
            if (side(r, c) != 0 && side(r, c) != 1) continue;
            cells.push_back({static_cast<double>(r), static_cast<double>(c), static_cast<double>(side(r, c))});
            upper += side(r, c) == 0;
        }
    if (upper < 4 || cells.size() - upper < 4) return false;
    constexpr double pi = 3.14159265358979323846, degree = pi / 180;
    const auto best_angle = [&](double from, double step, int steps) {
        std::vector<std::size_t> misplaced(static_cast<std::size_t>(steps));
        for (int i = 0; i < steps; ++i)
            misplaced[static_cast<std::size_t>(i)] = separate_pools(cells, from + i * step).misplaced;
        const std::size_t fewest = *std::min_element(misplaced.begin(), misplaced.end());
        int run_start = -1, best_start = 0, best_length = 0;  // the longest run of angles at the fewest
        for (int i = 0; i <= steps; ++i) {
            const bool at_fewest = i < steps && misplaced[static_cast<std::size_t>(i)] == fewest;
            if (at_fewest && run_start < 0) run_start = i;
            if (!at_fewest && run_start >= 0) {
                if (i - run_start > best_length) best_start = run_start, best_length = i - run_start;
                run_start = -1;
            }
        }
        return from + (best_start + 0.5 * (best_length - 1)) * step;
    };
    const double coarse = best_angle(0, 3 * degree, 120);
    const double angle = best_angle(coarse - 3 * degree, 0.25 * degree, 25);
    const crest_separation best = separate_pools(cells, angle);
    const double nr = std::cos(angle), nc = std::sin(angle), h = 0.5 * (std::abs(nr) + std::abs(nc));
    line = {(best.position + h) * nr, (best.position + h) * nc, nr, nc};
    return static_cast<double>(best.misplaced) <= max_misplaced_share * static_cast<double>(cells.size());
}

/// Gives the cells of `side` holding `which` and lying within `reach` cells of `line` the side their centre lies
/// on (a centre on the line keeps its value).
inline void take_side_of_line(raster<std::int8_t>& side, const crest_line& line, std::int8_t which, double reach)
{
    for (std::ptrdiff_t r = 0; r < side.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < side.cols(); ++c)
            if (const double d = line.offset(r, c); side(r, c) == which && std::abs(d) <= reach && d != 0)
                side(r, c) = d < 0 ? 0 : 1;
}

/// Counts the cells of each of the n sections of `p.section` into `p.cells` and puts their mean (row, col) into
/// `p.centre` ((0, 0) for a section without cells).
inline void count_section_cells(river_profile& p, std::size_t n)
{
    p.cells.assign(n, 0);
    p.centre.assign(n, {0.0, 0.0});
    for (std::ptrdiff_t r = 0; r < p.box.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < p.box.cols(); ++c)
            if (const std::int32_t k = p.section(r, c); k >= 0) {
                const auto u = static_cast<std::size_t>(k);
                ++p.cells[u];
                p.centre[u][0] += static_cast<double>(p.box.row_min + r);
                p.centre[u][1] += static_cast<double>(p.box.col_min + c);
            }
    for (std::size_t k = 0; k < n; ++k)
        if (p.cells[k] > 0) {
            p.centre[k][0] /= static_cast<double>(p.cells[k]);
            p.centre[k][1] /= static_cast<double>(p.cells[k]);
        }
}

/// Keeps a side of a weir only where it is connected to its own pool: a cell of `side` 0 (upper) that is not
/// 8-connected through upper cells to an upper cell of a section <= a becomes lower, and a lower cell not
/// connected to a lower cell of a section >= b becomes upper (a stray low or high return far from the crest does
/// not move its cell to the other pool).
inline void keep_connected_sides(raster<std::int8_t>& side, const raster<std::int32_t>& section, std::size_t a,
                                 std::size_t b)
{
    raster<std::uint8_t> reached(side.rows(), side.cols(), 0);
    std::vector<std::ptrdiff_t> front;
    const auto sec = [&](std::ptrdiff_t r, std::ptrdiff_t c) { return static_cast<std::size_t>(section(r, c)); };
    for (std::ptrdiff_t r = 0; r < side.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < side.cols(); ++c)
            if ((side(r, c) == 0 && sec(r, c) <= a) || (side(r, c) == 1 && sec(r, c) >= b)) {
                reached(r, c) = 1;
                front.push_back(r * side.cols() + c);
            }
    for (std::size_t i = 0; i < front.size(); ++i) {
        const std::ptrdiff_t r = front[i] / side.cols(), c = front[i] % side.cols();
        for (std::ptrdiff_t dr = -1; dr <= 1; ++dr)
            for (std::ptrdiff_t dc = -1; dc <= 1; ++dc) {
                const std::ptrdiff_t rr = r + dr, cc = c + dc;
                if (rr < 0 || rr >= side.rows() || cc < 0 || cc >= side.cols() || reached(rr, cc) ||
                    side(rr, cc) != side(r, c))
                    continue;
                reached(rr, cc) = 1;
                front.push_back(rr * side.cols() + cc);
            }
    }
    for (std::ptrdiff_t r = 0; r < side.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < side.cols(); ++c)
            if ((side(r, c) == 0 || side(r, c) == 1) && !reached(r, c))
                side(r, c) = static_cast<std::int8_t>(1 - side(r, c));
}

/// Re-cuts the sections around each weir along the weir itself. The falls between neighbouring sections are
/// measured against the river's own: the median fall over the `background` sections either side (more than a
/// zone's 2 · reach + 1). A weir zone is a
/// run of at most 2 · reach + 1 neighbouring sections [a, b] that each fall more than a quarter of weir_min_drop_m
/// beyond that median and by at least weir_min_drop_m beyond it in all (a steep river is not a weir). Zones are
/// found first; around each (reach sections either side, not into the next zone) each cell takes the upper level
/// `level[a]` or the lower `level[b]`, whichever its water height is nearer. Heights further than
/// return_tolerance_m from both, and cells without one, take the side of a straight crest fitted to the cells with
/// heights (fit_crest_line) within `line_reach_cells` of it, else the side of the nearest cell that has one, by
/// 8-connected steps; a side keeps only the cells connected to its own pool (keep_connected_sides); the cells
/// within one cell of a straight crest take the side their centre lies on. Upper cells downstream of a join section a,
/// lower cells upstream of b join section b, cells left between take the nearer of a and b; the sections between are
/// left without cells at the lower level. Updates cells and centre; a section left without cells is no longer measured.
/// O(cells of the box + 145 m log m) per weir, with m cells of known side around it.
inline void cut_sections_at_weirs(river_profile& p, raster_view<const float> water_z, std::size_t reach,
                                  std::size_t background, double line_reach_cells, const river_profile_options& opt)
{
    const std::size_t n = p.level_m.size();
    const cell_box& box = p.box;
    if (n < 2) return;
    std::vector<double> fall(n - 1), excess(n - 1);
    for (std::size_t k = 0; k + 1 < n; ++k) fall[k] = p.level_m[k] - p.level_m[k + 1];
    for (std::size_t k = 0; k + 1 < n; ++k) {
        std::vector<float> near;
        for (std::size_t t = k > background ? k - background : 0; t <= std::min(n - 2, k + background); ++t)
            near.push_back(static_cast<float>(fall[t]));
        excess[k] = fall[k] - upper_median_in_place(near);
    }
    std::vector<std::array<std::size_t, 2>> zones;
    for (std::size_t s = 0; s + 1 < n;) {
        if (excess[s] <= 0.25 * opt.weir_min_drop_m) {
            ++s;
            continue;
        }
        std::size_t a = s, b = s + 1;
        double total = excess[s];
        while (b + 1 < n && excess[b] > 0.25 * opt.weir_min_drop_m) total += excess[b++];
        s = b;
        if (total >= opt.weir_min_drop_m && b - a <= 2 * reach + 1) zones.push_back({a, b});
    }
    for (std::size_t z = 0; z < zones.size(); ++z) {
        const auto [a, b] = zones[z];
        const double upper = p.level_m[a], lower = p.level_m[b];
        const std::size_t lo = std::max(z > 0 ? zones[z - 1][1] + 1 : 0, a > reach ? a - reach : 0);
        const std::size_t hi = std::min({n - 1, b + reach, z + 1 < zones.size() ? zones[z + 1][0] - 1 : n - 1});
        // Sides: 0 upper, 1 lower, 2 not known yet, -1 outside the zone.
        raster<std::int8_t> side(box.rows(), box.cols(), -1);
        std::vector<std::ptrdiff_t> front;
        for (std::ptrdiff_t r = 0; r < box.rows(); ++r)
            for (std::ptrdiff_t c = 0; c < box.cols(); ++c) {
                const std::int32_t k = p.section(r, c);
                if (k < 0 || static_cast<std::size_t>(k) < lo || static_cast<std::size_t>(k) > hi) continue;
                const float h = water_z(box.row_min + r, box.col_min + c);
                const double du = std::abs(h - upper), dl = std::abs(h - lower);
                side(r, c) = std::isfinite(h) && std::min(du, dl) <= opt.return_tolerance_m ? (du < dl ? 0 : 1) : 2;
                if (side(r, c) < 2) front.push_back(r * box.cols() + c);
            }
        // A straight crest seen from the cells with heights settles the cells without one near it: a dropout
        // patch across the crest does not take the side of whichever pool's returns lie nearest.
        crest_line line;
        const bool straight = fit_crest_line(side, 0.05, line);
        if (straight) take_side_of_line(side, line, 2, line_reach_cells);
        for (std::size_t i = 0; i < front.size(); ++i) {  // breadth-first: the nearest known cell's side
            const std::ptrdiff_t r = front[i] / box.cols(), c = front[i] % box.cols();
            for (std::ptrdiff_t dr = -1; dr <= 1; ++dr)
                for (std::ptrdiff_t dc = -1; dc <= 1; ++dc) {
                    const std::ptrdiff_t rr = r + dr, cc = c + dc;
                    if (rr < 0 || rr >= box.rows() || cc < 0 || cc >= box.cols() || side(rr, cc) != 2) continue;
                    side(rr, cc) = side(r, c);
                    front.push_back(rr * box.cols() + cc);
                }
        }
        keep_connected_sides(side, p.section, a, b);
        if (straight) {
            take_side_of_line(side, line, 0, 1);
            take_side_of_line(side, line, 1, 1);
        }
        for (std::ptrdiff_t r = 0; r < box.rows(); ++r)
            for (std::ptrdiff_t c = 0; c < box.cols(); ++c) {
                std::int32_t& k = p.section(r, c);
                if (k < 0) continue;
                const auto u = static_cast<std::size_t>(k);
                if (side(r, c) == 0 && u > a) k = static_cast<std::int32_t>(a);
                if (side(r, c) == 1 && u < b) k = static_cast<std::int32_t>(b);
                if (u > a && u < b && (side(r, c) < 0 || side(r, c) == 2))  // a cell no side reached
                    k = static_cast<std::int32_t>(u - a <= b - u ? a : b);
            }
        for (std::size_t k = a + 1; k < b; ++k) p.level_m[k] = lower;
    }
    count_section_cells(p, n);
    for (std::size_t k = 0; k < n; ++k)
        if (p.cells[k] == 0) {
            p.returns[k] = 0;
            p.measured_m[k] = NAN;
        }
}

}  // namespace detail

inline river_profile trace_river_profile(raster_view<const std::int32_t> labels, std::int32_t label,
                                         const cell_box& box, const hydro_body_shape& shape,
                                         raster_view<const float> water_z, double cell_m,
                                         const river_profile_options& opt)
{
    constexpr const char* fn = "trace_river_profile";
    detail::require_same_shape(labels, water_z, fn, "labels", "water_z");
    detail::require_positive(cell_m, fn, "cell_m");
    detail::validate(opt, fn);
    detail::check_body_box(labels, box, fn);
    const raster<std::uint8_t> mask = body_mask(labels, label, box);
    const std::ptrdiff_t ar = shape.end_a[0] - box.row_min, ac = shape.end_a[1] - box.col_min;
    detail::require(ar >= 0 && ar < mask.rows() && ac >= 0 && ac < mask.cols() && mask(ar, ac), fn,
                    "shape.end_a must be a cell of the body");
    const raster<float> distance = geodesic_distance(mask, ar, ac, cell_m);
    const double spacing = std::max(opt.section_spacing_m, cell_m);

    river_profile p;
    p.box = box;
    p.section = raster<std::int32_t>(box.rows(), box.cols(), -1);
    std::int32_t last = -1;
    for (std::ptrdiff_t r = 0; r < mask.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < mask.cols(); ++c)
            if (std::isfinite(distance(r, c))) {
                p.section(r, c) = static_cast<std::int32_t>(std::floor(distance(r, c) / spacing));
                last = std::max(last, p.section(r, c));
            }
    const auto n = static_cast<std::size_t>(last + 1);
    detail::count_section_cells(p, n);
    std::vector<std::vector<float>> heights(n);
    for (std::ptrdiff_t r = 0; r < mask.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < mask.cols(); ++c)
            if (const std::int32_t k = p.section(r, c); k >= 0)
                if (const float z = water_z(box.row_min + r, box.col_min + c); std::isfinite(z))
                    heights[static_cast<std::size_t>(k)].push_back(z);

    // 1. decks: cells far above the low water nearby; 2. the local level and the water returns near it.
    std::vector<double> quartile(n), median(n);
    for (std::size_t s = 0; s < n; ++s) {
        std::vector<float> copy = heights[s];
        quartile[s] = detail::quantile_in_place(copy, 0.25);
    }
    const auto window = [&](const std::vector<double>& values, std::size_t s, double length_m, double q) {
        const auto reach = static_cast<std::size_t>(std::floor(0.5 * length_m / spacing));
        std::vector<float> near;
        for (std::size_t t = s > reach ? s - reach : 0; t <= std::min(n - 1, s + reach); ++t)
            if (!std::isnan(values[t])) near.push_back(static_cast<float>(values[t]));
        return q == 0.5 ? detail::upper_median_in_place(near) : detail::quantile_in_place(near, q);
    };
    for (std::size_t s = 0; s < n; ++s) {
        const double deck = window(quartile, s, opt.floor_window_m, 0.1) + opt.deck_clearance_m;
        std::erase_if(heights[s], [&](float z) { return z >= deck; });
        std::vector<float> copy = heights[s];
        median[s] = detail::lowest_dense_window_median(copy, opt.mode_window_m, opt.lowest_mode_share);
    }
    p.measured_m.assign(n, NAN);
    p.returns.assign(n, 0);
    for (std::size_t s = 0; s < n; ++s) {
        const double local = window(median, s, opt.level_window_m, 0.5);
        if (std::isnan(local)) continue;
        std::vector<float> water;
        for (const float z : heights[s])
            if (std::abs(z - local) <= opt.return_tolerance_m) water.push_back(z);
        const double measured = detail::lowest_dense_window_median(water, opt.mode_window_m, opt.lowest_mode_share);
        const bool enough = static_cast<double>(water.size()) >= opt.min_return_share * static_cast<double>(p.cells[s]);
        if (enough && !water.empty() && std::abs(measured - local) <= opt.level_tolerance_m) {
            p.returns[s] = water.size();
            p.measured_m[s] = measured;
        }
    }

    // 3. downstream is where the measured levels fall.
    if (detail::weighted_slope(p.measured_m, p.returns) > 0) {
        for (auto& k : p.section)
            if (k >= 0) k = last - k;
        std::reverse(p.measured_m.begin(), p.measured_m.end());
        std::reverse(p.returns.begin(), p.returns.end());
        std::reverse(p.cells.begin(), p.cells.end());
        std::reverse(p.centre.begin(), p.centre.end());
    }

    // 4. the monotone fit of the measured sections, without those far from it (up to 3 rounds); the others
    // interpolated.
    for (int round = 0; round <= 3; ++round) {
        std::vector<double> values, weights;
        for (std::size_t s = 0; s < n; ++s)
            if (p.returns[s] > 0) {
                values.push_back(p.measured_m[s]);
                weights.push_back(static_cast<double>(p.returns[s]));
            }
        const std::vector<double> fit = isotonic_regression(values, weights, monotone_direction::non_increasing);
        p.level_m.assign(n, NAN);
        bool dropped = false;
        for (std::size_t s = 0, i = 0; s < n; ++s) {
            if (p.returns[s] == 0) continue;
            p.level_m[s] = fit[i++];
            if (round < 3 && std::abs(p.measured_m[s] - p.level_m[s]) > opt.level_tolerance_m) {
                p.returns[s] = 0;
                p.measured_m[s] = NAN;
                dropped = true;
            }
        }
        if (!dropped) break;
    }
    detail::interpolate_gaps(p.level_m);
    // 5. weirs: the sections around each follow it.
    if (opt.cut_sections_at_weirs) {
        const auto reach = static_cast<std::size_t>(std::ceil(0.5 * shape.width_m / spacing)) + 1;
        // The river's own fall: the median over more sections than a weir zone holds, so that a weir's fall
        // spread over the sections interpolated across it stays above it.
        const auto background =
            static_cast<std::size_t>(std::floor(0.5 * opt.level_window_m / spacing)) + 2 * reach + 1;
        detail::cut_sections_at_weirs(p, water_z, reach, background, (0.5 * shape.width_m + spacing) / cell_m, opt);
    }
    detail::count_weirs(p, opt.weir_min_drop_m);
    return p;
}

}  // namespace lidarfx
