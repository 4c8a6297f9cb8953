// SPDX-License-Identifier: Apache-2.0
// refine_building_rim: the one-cell rim of each building decided by its points, not by its highest return
// (extract_buildings step 3b, when the survey's raised points are counted).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/kernels/label/connected_components.hpp"

namespace lidarfx {

/// Settings of refine_building_rim.
struct building_rim_options {
    /// A rim cell is building when at least this share of its points are raised (stand the candidates'
    /// min_height_m above the terrain); in (0, 1]. Half: the cell is building when most of its area is roof, as
    /// far as evenly spread points tell, the rule by which a classified survey's cells are building or not.
    double min_raised_share = 0.5;
    /// A cell outside a building joins it only when its surface lies within this of the surface of a building
    /// cell beside it, metres; >= 0. A roof's eave cell lies at the roof's height; a crown beside a roof seldom
    /// does.
    double join_height_m = 0.5;
};

/// What refine_building_rim changed.
struct building_rim_result {
    std::size_t joined = 0;  ///< cells that joined a building
    std::size_t left = 0;    ///< cells that left their building
};

/// Decides the rim of the buildings 1..count of `building_id` by the survey's points (in place), in three
/// rounds, each decided on the ids as the round before left them (so the result does not depend on the order
/// of the cells):
///  1. a building cell with points and an 8-neighbour outside its building leaves it when fewer than
///     min_raised_share of its points are raised (a wall's cell: the DSM keeps the eave's highest return, yet
///     most points lie on the ground in front of it); a building all of whose cells would leave stays whole;
///  2. a cell of id 0 with points (not one that just left) joins a building beside it whose cell's surface `z`
///     lies within join_height_m of its own, when at least min_raised_share of its points are raised (an eave
///     whose pulses split on the roof's edge: vegetation by its returns, yet roof). It takes, of such
///     neighbours across an edge, the one closest in height (ties: the lowest id); with none across an edge,
///     the closest across a corner, and only when a cell beside it across an edge is of that building after
///     the joins across an edge, so no building gains a part that touches it at a corner only;
///  3. a building cell with points that the leaving cells left without a neighbour of its building across an
///     edge leaves too (no one-cell parts), unless such cells are all its building has left.
/// `points` and `raised` count each cell's points and, of them, the raised ones (count_points_above against
/// the terrain the candidates were cut from). Cells of ids outside 0..count are left as they are and never
/// joined. A building never loses its last cell; buildings keep their ids. O(cells).
/// @throws invalid_input on an option out of range, shapes that differ, or a cell with more raised points
/// than points.
inline building_rim_result refine_building_rim(raster_view<std::int32_t> building_id, std::size_t count,
                                               raster_view<const float> z, raster_view<const std::uint32_t> points,
                                               raster_view<const std::uint32_t> raised,
                                               const building_rim_options& opt = {});

// ---- implementation ----

namespace detail {

inline void check_building_rim(const building_rim_options& opt, const char* function)
{
    require(opt.min_raised_share > 0 && opt.min_raised_share <= 1, function, "min_raised_share", "in (0, 1]",
            opt.min_raised_share);
    require(opt.join_height_m >= 0 && opt.join_height_m < 1e300, function, "join_height_m", "finite and >= 0",
            opt.join_height_m);
}

/// The building of cell (r, c) of `ids` when it is one of 1..count, else 0.
inline std::int32_t building_of(raster_view<const std::int32_t> ids, std::size_t count, std::ptrdiff_t r,
                                std::ptrdiff_t c)
{
    const std::int32_t b = ids(r, c);
    return b > 0 && static_cast<std::size_t>(b) <= count ? b : 0;
}

/// After refine_building_rim: drops, in place, the 4-connected pieces of buildings 1..count smaller than
/// min_cells (a wall's cells that left may cut a corner or a narrow wing off), then renumbers the buildings left
/// by decreasing footprint (cells), ties by their old id. Cells of other ids are left as they are. Returns the
/// number of buildings left. O(cells).
inline std::size_t drop_small_pieces(raster_view<std::int32_t> building_id, std::size_t count, std::size_t min_cells);

}  // namespace detail

inline building_rim_result refine_building_rim(raster_view<std::int32_t> building_id, std::size_t count,
                                               raster_view<const float> z, raster_view<const std::uint32_t> points,
                                               raster_view<const std::uint32_t> raised, const building_rim_options& opt)
{
    constexpr const char* function = "refine_building_rim";
    detail::check_building_rim(opt, function);
    detail::require_same_shape(building_id, z, function, "building_id", "z");
    detail::require_same_shape(building_id, points, function, "building_id", "points");
    detail::require_same_shape(building_id, raised, function, "building_id", "raised");
    detail::require_counts_within(raised, points, function, "raised must not exceed points in any cell");
    const std::ptrdiff_t rows = building_id.rows(), cols = building_id.cols();
    const auto id_of = [&](std::ptrdiff_t r, std::ptrdiff_t c) {
        return detail::building_of(building_id, count, r, c);
    };
    std::vector<std::size_t> cells(count + 1, 0);
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c) ++cells[static_cast<std::size_t>(id_of(r, c))];
    struct change {
        std::ptrdiff_t r, c;
        std::int32_t id;
        bool corner;
    };
    const auto is_raised = [&](std::ptrdiff_t r, std::ptrdiff_t c) {
        return static_cast<double>(raised(r, c)) >= opt.min_raised_share * points(r, c);
    };
    // 1. Cells that leave, decided on the ids as they are (a building all of whose cells would leave stays whole).
    std::vector<change> leaves;
    std::vector<std::size_t> leaving(count + 1, 0);
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const std::int32_t own = id_of(r, c);
            if (own == 0 || points(r, c) == 0 || is_raised(r, c)) continue;
            bool on_rim = false;
            for (std::ptrdiff_t dr = -1; dr <= 1 && !on_rim; ++dr)
                for (std::ptrdiff_t dc = -1; dc <= 1 && !on_rim; ++dc) {
                    const std::ptrdiff_t rr = r + dr, cc = c + dc;
                    on_rim = rr >= 0 && cc >= 0 && rr < rows && cc < cols && id_of(rr, cc) != own;
                }
            if (!on_rim) continue;
            leaves.push_back({r, c, 0, false});
            ++leaving[static_cast<std::size_t>(own)];
        }
    }
    building_rim_result out;
    std::vector<bool> stays_whole(count + 1, false);
    for (std::size_t b = 1; b <= count; ++b) stays_whole[b] = leaving[b] >= cells[b];
    for (const change& ch : leaves) {
        const auto b = static_cast<std::size_t>(building_id(ch.r, ch.c));
        if (stays_whole[b]) continue;
        building_id(ch.r, ch.c) = 0;
        --cells[b];
        ++out.left;
    }
    // 2. Cells that join (cells of id 0), decided on the ids after the leaves, so that no cell joins through a
    // wall's cell that left: across an edge, or across a corner when a cell beside it across an edge is of that
    // building after the joins across an edge. A cell that left is not raised, so it does not come back.
    std::vector<change> joins;
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            if (building_id(r, c) != 0 || points(r, c) == 0 || !is_raised(r, c)) continue;
            const double zc = static_cast<double>(z(r, c));
            // The closest in height across an edge (ties: the lowest id); without one, across a corner.
            std::int32_t best[2] = {0, 0};  // across an edge, across a corner
            double best_dz[2] = {0, 0};
            for (std::ptrdiff_t dr = -1; dr <= 1; ++dr) {
                for (std::ptrdiff_t dc = -1; dc <= 1; ++dc) {
                    const std::ptrdiff_t rr = r + dr, cc = c + dc;
                    if ((dr == 0 && dc == 0) || rr < 0 || cc < 0 || rr >= rows || cc >= cols) continue;
                    const std::int32_t nb = id_of(rr, cc);
                    if (nb == 0) continue;
                    const double dz = std::fabs(zc - static_cast<double>(z(rr, cc)));
                    if (!(dz <= opt.join_height_m)) continue;
                    const int k = dr != 0 && dc != 0 ? 1 : 0;
                    if (best[k] == 0 || dz < best_dz[k] || (dz == best_dz[k] && nb < best[k]))
                        best[k] = nb, best_dz[k] = dz;
                }
            }
            if (best[0] != 0)
                joins.push_back({r, c, best[0], false});
            else if (best[1] != 0)
                joins.push_back({r, c, best[1], true});
        }
    }
    const auto has_edge_neighbour = [&](std::ptrdiff_t r, std::ptrdiff_t c, std::int32_t b) {
        return (r > 0 && building_id(r - 1, c) == b) || (r + 1 < rows && building_id(r + 1, c) == b) ||
               (c > 0 && building_id(r, c - 1) == b) || (c + 1 < cols && building_id(r, c + 1) == b);
    };
    const auto join = [&](const change& ch) {
        building_id(ch.r, ch.c) = ch.id;
        ++cells[static_cast<std::size_t>(ch.id)];
        ++out.joined;
    };
    for (const change& ch : joins)
        if (!ch.corner) join(ch);
    std::vector<change> corner_joins;  // decided on the ids after the joins across an edge
    for (const change& ch : joins)
        if (ch.corner && has_edge_neighbour(ch.r, ch.c, ch.id)) corner_joins.push_back(ch);
    for (const change& ch : corner_joins) join(ch);
    // 3. A cell that the leaving cells cut off from its building (no edge neighbour of it left) leaves too;
    // decided on the ids after the joins.
    std::vector<change> cut_off;
    for (const change& ch : leaves) {
        for (std::ptrdiff_t dr = -1; dr <= 1; ++dr) {
            for (std::ptrdiff_t dc = -1; dc <= 1; ++dc) {
                const std::ptrdiff_t rr = ch.r + dr, cc = ch.c + dc;
                if (rr < 0 || cc < 0 || rr >= rows || cc >= cols) continue;
                const std::int32_t b = id_of(rr, cc);
                if (b == 0 || points(rr, cc) == 0 || cells[static_cast<std::size_t>(b)] <= 1 ||
                    has_edge_neighbour(rr, cc, b))
                    continue;
                cut_off.push_back({rr, cc, b, false});
            }
        }
    }
    std::sort(cut_off.begin(), cut_off.end(),
              [](const change& a, const change& b) { return a.r != b.r ? a.r < b.r : a.c < b.c; });
    cut_off.erase(std::unique(cut_off.begin(), cut_off.end(),
                              [](const change& a, const change& b) { return a.r == b.r && a.c == b.c; }),
                  cut_off.end());  // a cell beside two leaving cells is listed twice
    std::vector<std::size_t> cut(count + 1, 0);
    for (const change& ch : cut_off) ++cut[static_cast<std::size_t>(ch.id)];
    for (const change& ch : cut_off) {
        const auto b = static_cast<std::size_t>(ch.id);
        if (cut[b] >= cells[b]) continue;  // all the building has left: it keeps these cells
        building_id(ch.r, ch.c) = 0;
        ++out.left;
    }
    return out;
}

inline std::size_t detail::drop_small_pieces(raster_view<std::int32_t> building_id, std::size_t count,
                                             std::size_t min_cells)
{
    const std::ptrdiff_t rows = building_id.rows(), cols = building_id.cols();
    const auto id_of = [&](std::ptrdiff_t r, std::ptrdiff_t c) { return building_of(building_id, count, r, c); };
    // Pieces by flood fill over edge neighbours of the same id; small ones are cleared.
    raster<std::uint8_t> seen(rows, cols);
    std::vector<std::ptrdiff_t> piece, stack;
    std::vector<std::size_t> cells(count + 1, 0);
    for (std::ptrdiff_t r0 = 0; r0 < rows; ++r0) {
        for (std::ptrdiff_t c0 = 0; c0 < cols; ++c0) {
            const std::int32_t b = id_of(r0, c0);
            if (b == 0 || seen(r0, c0)) continue;
            piece.clear();
            stack.assign(1, r0 * cols + c0);
            seen(r0, c0) = 1;
            while (!stack.empty()) {
                const std::ptrdiff_t p = stack.back();
                stack.pop_back();
                piece.push_back(p);
                const std::ptrdiff_t r = p / cols, c = p % cols;
                const std::ptrdiff_t nr[4] = {r - 1, r + 1, r, r}, nc[4] = {c, c, c - 1, c + 1};
                for (int k = 0; k < 4; ++k) {
                    if (nr[k] < 0 || nc[k] < 0 || nr[k] >= rows || nc[k] >= cols) continue;
                    if (seen(nr[k], nc[k]) || building_id(nr[k], nc[k]) != b) continue;
                    seen(nr[k], nc[k]) = 1;
                    stack.push_back(nr[k] * cols + nc[k]);
                }
            }
            if (piece.size() >= min_cells) {
                cells[static_cast<std::size_t>(b)] += piece.size();
                continue;
            }
            for (const std::ptrdiff_t p : piece) building_id(p / cols, p % cols) = 0;
        }
    }
    // New ids by decreasing footprint, ties by the old id: buildings without a cell left rank last and keep none.
    const std::vector<std::int32_t> new_of = rank_components_by_size(cells);
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c)
            if (const std::int32_t b = id_of(r, c); b != 0) building_id(r, c) = new_of[static_cast<std::size_t>(b)];
    return static_cast<std::size_t>(std::count_if(cells.begin() + 1, cells.end(), [](std::size_t n) { return n > 0; }));
}

}  // namespace lidarfx
