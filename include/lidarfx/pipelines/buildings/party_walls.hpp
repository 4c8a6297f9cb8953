// SPDX-License-Identifier: Apache-2.0
// split_party_walls: contiguous blocks split into their buildings where the roofs of two neighbours do not
// meet, a height step or a roof-plane break along their party wall (extract_buildings step 5b, after the roof
// surfaces are merged).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <numeric>
#include <set>
#include <tuple>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/plane_fit.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/pipelines/buildings/building_candidates.hpp"
#include "lidarfx/pipelines/buildings/grow_roof_surfaces.hpp"
#include "lidarfx/pipelines/buildings/merge_roof_surfaces.hpp"

namespace lidarfx {

/// Settings of split_party_walls.
struct party_walls_options {
    /// Two roof surfaces of one block belong to different buildings where, along most of the boundary between
    /// them, their planes differ by more than this at the boundary (beyond what a boundary misplaced by one cell
    /// explains) and so do the surface heights of the cells on either side, metres; > 0. Infinity never splits.
    /// Two roof faces of one building meet along their boundary (a ridge, a hip or a valley); the roofs of two
    /// terraced houses of different heights, or of different pitch or direction, do not.
    double min_step_m = 1.0;
    /// Share of the boundary's cell pairs (edge neighbours, one on each side) that must be such steps; (0, 1].
    /// A dormer's front is a step, its back is not: it stays with its roof.
    double min_wall_share = 0.5;
    /// A part split off a block must cover at least this, m^2; >= 0. Smaller parts stay with the building they
    /// touch: a rear extension, a garage built on, a porch (on the AHN3 crop of Delft the cadastre's buildings
    /// hold such parts of 16-23 m^2 at 3-6 m under the main roof). A terraced house covers 35 m^2 and more.
    double min_part_m2 = 30.0;
};

/// What split_party_walls did.
struct party_walls_result {
    std::size_t count = 0;  ///< buildings after the step: 1..count (by decreasing footprint when split > 0)
    std::size_t split = 0;  ///< buildings that were split (each into two or more)
};

/// Splits the buildings 1..count of `building_id` (in place) at their party walls:
///  1. each roof surface of `regions` (grow_roof_surfaces, merged) is fitted a plane on its core cells
///     (fit_roof_regions). A cell given to a surface afterwards (not core) that lies more than min_step_m / 2
///     off its surface's plane is loose: a small roof face the growth missed, given to the neighbour's roof
///     across the party wall, belongs to neither side yet;
///  2. the boundary between two surfaces of one building is a wall when at least min_wall_share of its
///     edge-neighbour pairs of cells with a surface (not loose) are steps: the two planes, at the midpoint of
///     the pair, differ by more than min_step_m + cell_m x |difference of their slopes along the pair|, and the
///     two cells' heights `z` differ by more than min_step_m;
///  3. the surfaces joined across boundaries that are not walls form a building's parts; a building whose
///     surfaces all lie in one part is left whole. In the others, each part is a piece (its cells may lie
///     apart), and so is each 8-connected group of loose cells and cells without a surface;
///  4. pieces with fewer cells of a surface than cover min_part_m2 join, smallest first, the neighbouring piece
///     of their building (8-neighbours) across whose boundary the heights differ least (mean |z difference|;
///     ties: the longer boundary, the larger piece, the earlier first cell): a chimney, a dormer or an annex
///     never becomes a building, and a missed face joins its own roof at the ridge rather than the neighbour's
///     across the wall;
///  5. two pieces left standing in one building whose boundary is not a step in the heights themselves (fewer
///     than min_wall_share of its edge-neighbour pairs of cells differ by more than min_step_m) are joined, pair
///     by pair: a house whose missed face went with the neighbour stays with it rather than being cut at its
///     ridge. A piece then touching no other piece of its building joins the building's largest piece.
/// When some building was split, all buildings are numbered again by decreasing footprint (ties: the old id,
/// then the first cell in raster order); the cells of a split building's surface that ended in another
/// building than most of the surface's anchored cells (all its cells when none is) take a surface of their
/// own building (assign_remaining_cells over those cells only), and a building left without a surface gets
/// one (all its cells, none core; regions.count grows). Otherwise neither ids nor surfaces change. z in metres
/// on cells of cell_m metres (x east = col x cell_m, y north = -row x cell_m). O(cells log cells).
/// @throws invalid_input on an option out of range, cell_m not finite and > 0, shapes that differ, or a
/// building id outside 0..count or region id outside 0..regions.count.
inline party_walls_result split_party_walls(raster_view<std::int32_t> building_id, std::size_t count,
                                            roof_regions& regions, raster_view<const float> z, double cell_m,
                                            const party_walls_options& opt = {});

namespace detail {

inline void check_party_walls(const party_walls_options& opt, const char* function)
{
    require(opt.min_step_m > 0, function, "min_step_m", "> 0", opt.min_step_m);
    require(opt.min_wall_share > 0 && opt.min_wall_share <= 1, function, "min_wall_share", "in (0, 1]",
            opt.min_wall_share);
    require(opt.min_part_m2 >= 0 && opt.min_part_m2 < 1e300, function, "min_part_m2", "finite and >= 0",
            opt.min_part_m2);
}

/// Cell pairs and steps along the boundary between two surfaces.
struct surface_boundary {
    std::size_t pairs = 0, steps = 0;
    std::int32_t building = 0;  ///< the building both surfaces lie in
    /// Adds another stretch of boundary (pairs and steps; the building stays).
    surface_boundary& operator+=(const surface_boundary& o) noexcept
    {
        pairs += o.pairs;
        steps += o.steps;
        return *this;
    }
};

/// At least `share` of `pairs`, with a little slack so that an exact share (7 of 100 at 0.07) counts.
inline bool at_least_share(std::size_t part, std::size_t pairs, double share) noexcept
{
    return static_cast<double>(part) >= share * static_cast<double>(pairs) - 1e-9;
}

/// The surface of each building cell as split_party_walls steps 1-2 read it: its region, or 0 when the cell is
/// loose (not core and more than min_step_m / 2 off its surface's plane) or has none.
inline raster<std::int32_t> anchored_surfaces(raster_view<const std::int32_t> ids, std::size_t count,
                                              const roof_regions& regions, raster_view<const float> z, double cell_m,
                                              const std::vector<plane_fit>& planes, double min_step_m)
{
    const std::ptrdiff_t rows = ids.rows(), cols = ids.cols();
    raster<std::int32_t> anchored(rows, cols);
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const std::int32_t b = ids(r, c), g = regions.region(r, c);
            if (b <= 0 || static_cast<std::size_t>(b) > count || g <= 0 || g > regions.count) continue;
            const double off = std::abs(static_cast<double>(z(r, c)) -
                                        planes[static_cast<std::size_t>(g)].at(static_cast<double>(c) * cell_m,
                                                                               -static_cast<double>(r) * cell_m));
            anchored(r, c) = regions.core(r, c) || off <= 0.5 * min_step_m ? g : 0;
        }
    }
    return anchored;
}

/// The boundaries between the anchored surfaces of each building of `ids` (1..count), keyed by (smaller,
/// larger) surface id, with their step pairs as split_party_walls step 2 counts them.
inline std::map<std::pair<std::int32_t, std::int32_t>, surface_boundary> surface_boundaries(
    raster_view<const std::int32_t> ids, raster_view<const std::int32_t> anchored, raster_view<const float> z,
    double cell_m, const std::vector<plane_fit>& planes, double min_step_m)
{
    const std::ptrdiff_t rows = ids.rows(), cols = ids.cols();
    std::map<std::pair<std::int32_t, std::int32_t>, surface_boundary> boundaries;
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const std::int32_t g = anchored(r, c);
            if (g <= 0) continue;
            for (int k = 0; k < 2; ++k) {  // south and east neighbours
                const std::ptrdiff_t rr = r + (k == 0 ? 1 : 0), cc = c + (k == 1 ? 1 : 0);
                if (rr >= rows || cc >= cols || ids(rr, cc) != ids(r, c)) continue;
                const std::int32_t h = anchored(rr, cc);
                if (h <= 0 || h == g) continue;
                const plane_fit& p = planes[static_cast<std::size_t>(g)];
                const plane_fit& q = planes[static_cast<std::size_t>(h)];
                const double x = (static_cast<double>(c) + 0.5 * k) * cell_m;
                const double y = -(static_cast<double>(r) + 0.5 * (1 - k)) * cell_m;
                const double slope_gap = k == 1 ? std::abs(p.a - q.a) : std::abs(p.b - q.b);
                const bool planes_apart = std::abs(p.at(x, y) - q.at(x, y)) > min_step_m + cell_m * slope_gap;
                const bool cells_apart =
                    std::abs(static_cast<double>(z(r, c)) - static_cast<double>(z(rr, cc))) > min_step_m;
                surface_boundary& s = boundaries[{std::min(g, h), std::max(g, h)}];
                s.building = ids(r, c);
                ++s.pairs;
                s.steps += planes_apart && cells_apart ? 1 : 0;
            }
        }
    }
    return boundaries;
}

/// The boundary between two pieces: its 8-neighbour cell pairs and the sum of their |z difference|.
struct piece_boundary {
    std::size_t pairs = 0;
    double rise_m = 0;
    double mean_rise_m() const noexcept { return rise_m / static_cast<double>(pairs); }
    piece_boundary& operator+=(const piece_boundary& o) noexcept
    {
        pairs += o.pairs;
        rise_m += o.rise_m;
        return *this;
    }
};

/// The boundaries between pieces, kept both ways: graph[p][q] and graph[q][p] hold the same sums B (B += B).
template <class B>
using piece_graph = std::vector<std::map<std::size_t, B>>;

/// Adds `stretch` to the boundary between pieces p and q.
template <class B>
void add_boundary(piece_graph<B>& graph, std::size_t p, std::size_t q, const B& stretch)
{
    graph[p][q] += stretch;
    graph[q][p] += stretch;
}

/// Piece `gone` joins `keep`: gone's boundaries with the other pieces are added to keep's, and the boundary
/// between the two goes.
template <class B>
void contract_boundaries(piece_graph<B>& graph, std::size_t gone, std::size_t keep)
{
    for (const auto& [j, e] : graph[gone]) {
        graph[j].erase(gone);
        if (j != keep) add_boundary(graph, j, keep, e);
    }
    graph[gone].clear();
}

/// The pieces of split_party_walls (the cells of one building and one part, or an 8-connected group of its loose
/// cells and cells without a surface) and what joined what.
struct wall_pieces {
    struct piece {
        std::int32_t building = 0;
        std::size_t cells = 0, first = 0;  ///< cells, and the first in raster order (row * cols + col)
        std::size_t anchored = 0;          ///< cells with a surface (not loose)
    };
    raster<std::int32_t> index;      ///< piece of each cell + 1; 0 = not a building cell of the step
    std::vector<piece> pieces;       ///< by their first cell in raster order
    std::vector<std::size_t> owner;  ///< the piece each piece joined; itself while it stands

    std::size_t standing(std::size_t i) const noexcept
    {
        while (owner[i] != i) i = owner[i];
        return i;
    }
    /// The standing piece of cell (r, c), which must belong to one.
    std::size_t standing_at(std::ptrdiff_t r, std::ptrdiff_t c) const noexcept
    {
        return standing(static_cast<std::size_t>(index(r, c) - 1));
    }
    /// Piece `gone` joins piece `keep`.
    void join(std::size_t gone, std::size_t keep) noexcept
    {
        owner[gone] = keep;
        pieces[keep].cells += pieces[gone].cells;
        pieces[keep].first = std::min(pieces[keep].first, pieces[gone].first);
        pieces[keep].anchored += pieces[gone].anchored;
    }
};

/// Steps 1-3 of split_party_walls: the part (root surface) of each surface, joined across boundaries that are
/// not walls, and the buildings (1..count) whose anchored cells lie in two or more parts; part is empty when no
/// building does.
struct surface_parts_result {
    std::vector<std::int32_t> part;
    std::vector<bool> in_step;
};

inline surface_parts_result surface_parts(raster_view<const std::int32_t> ids, std::size_t count,
                                          const roof_regions& regions, raster_view<const std::int32_t> anchored,
                                          raster_view<const float> z, double cell_m,
                                          const std::vector<plane_fit>& planes, const party_walls_options& opt)
{
    surface_parts_result out{std::vector<std::int32_t>(static_cast<std::size_t>(regions.count) + 1),
                             std::vector<bool>(count + 1, false)};
    std::iota(out.part.begin(), out.part.end(), 0);
    for (const auto& [pair, s] : surface_boundaries(ids, anchored, z, cell_m, planes, opt.min_step_m)) {
        if (at_least_share(s.steps, s.pairs, opt.min_wall_share)) continue;
        const std::int32_t a = uf_find(out.part, pair.first), b = uf_find(out.part, pair.second);
        out.part[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
    }
    for (std::int32_t g = 1; g <= regions.count; ++g) out.part[static_cast<std::size_t>(g)] = uf_find(out.part, g);
    std::vector<std::int32_t> first_part(count + 1, 0);
    bool any = false;
    for (std::ptrdiff_t r = 0; r < ids.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < ids.cols(); ++c) {
            if (anchored(r, c) <= 0) continue;
            const auto b = static_cast<std::size_t>(ids(r, c));
            const std::int32_t p = out.part[static_cast<std::size_t>(anchored(r, c))];
            if (first_part[b] == 0) first_part[b] = p;
            if (first_part[b] != p) any = out.in_step[b] = true;
        }
    if (!any) return {};
    return out;
}

/// Step 3's pieces: 8-connected cells of one building in the step and one part (-1 for loose cells and cells
/// without a surface); the pieces of one part are joined into its first. Other buildings get none.
inline wall_pieces number_wall_pieces(raster_view<const std::int32_t> ids, raster_view<const std::int32_t> anchored,
                                      const surface_parts_result& parts)
{
    const std::ptrdiff_t rows = ids.rows(), cols = ids.cols();
    const std::vector<std::int32_t>& part = parts.part;
    const auto building_at = [&](std::ptrdiff_t r, std::ptrdiff_t c) {
        const std::int32_t b = ids(r, c);
        return b > 0 && parts.in_step[static_cast<std::size_t>(b)] ? b : 0;
    };
    const auto part_at = [&](std::ptrdiff_t r, std::ptrdiff_t c) {
        const std::int32_t g = anchored(r, c);
        return g > 0 ? part[static_cast<std::size_t>(g)] : -1;
    };
    wall_pieces out{raster<std::int32_t>(rows, cols), {}, {}};
    std::vector<std::int32_t> piece_part;
    std::vector<std::ptrdiff_t> stack;
    for (std::ptrdiff_t r0 = 0; r0 < rows; ++r0) {
        for (std::ptrdiff_t c0 = 0; c0 < cols; ++c0) {
            const std::int32_t b = building_at(r0, c0);
            if (b == 0 || out.index(r0, c0) != 0) continue;
            const std::int32_t own_part = part_at(r0, c0);
            piece_part.push_back(own_part);
            const auto index = static_cast<std::int32_t>(out.pieces.size()) + 1;
            out.pieces.push_back({b, 0, static_cast<std::size_t>(r0 * cols + c0), 0});
            wall_pieces::piece& p = out.pieces.back();
            out.index(r0, c0) = index;
            stack.assign(1, r0 * cols + c0);
            while (!stack.empty()) {
                const std::ptrdiff_t cell = stack.back();
                stack.pop_back();
                ++p.cells;
                p.anchored += own_part > 0 ? 1 : 0;
                const std::ptrdiff_t r = cell / cols, c = cell % cols;
                for (std::ptrdiff_t rr = std::max<std::ptrdiff_t>(r - 1, 0); rr <= std::min(r + 1, rows - 1); ++rr)
                    for (std::ptrdiff_t cc = std::max<std::ptrdiff_t>(c - 1, 0); cc <= std::min(c + 1, cols - 1);
                         ++cc) {
                        if (out.index(rr, cc) != 0 || building_at(rr, cc) != b || part_at(rr, cc) != own_part) continue;
                        out.index(rr, cc) = index;
                        stack.push_back(rr * cols + cc);
                    }
            }
        }
    }
    out.owner.resize(out.pieces.size());
    std::iota(out.owner.begin(), out.owner.end(), std::size_t{0});
    std::map<std::pair<std::int32_t, std::int32_t>, std::size_t> first_of_part;  // (building, part) -> piece
    for (std::size_t i = 0; i < out.pieces.size(); ++i) {
        if (piece_part[i] <= 0) continue;
        const auto [at, fresh] = first_of_part.try_emplace({out.pieces[i].building, piece_part[i]}, i);
        if (!fresh) out.join(i, at->second);
    }
    return out;
}

/// Step 4: standing pieces with fewer than min_cells anchored cells join, smallest first, the neighbouring piece
/// of their building across whose boundary (8-neighbour pairs) the heights differ least.
inline void join_small_pieces(wall_pieces& w, raster_view<const float> z, std::size_t min_cells)
{
    const std::ptrdiff_t rows = z.rows(), cols = z.cols();
    const std::size_t n = w.pieces.size();
    piece_graph<piece_boundary> touching(n);
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            if (w.index(r, c) == 0) continue;
            const std::size_t p = w.standing_at(r, c);
            constexpr std::ptrdiff_t dr[4] = {0, 1, 1, 1}, dc[4] = {1, -1, 0, 1};  // each 8-neighbour pair once
            for (int k = 0; k < 4; ++k) {
                const std::ptrdiff_t rr = r + dr[k], cc = c + dc[k];
                if (cc < 0 || rr >= rows || cc >= cols || w.index(rr, cc) == 0) continue;
                const std::size_t q = w.standing_at(rr, cc);
                if (q == p || w.pieces[q].building != w.pieces[p].building) continue;
                add_boundary(
                    touching, p, q,
                    piece_boundary{1, std::abs(static_cast<double>(z(r, c)) - static_cast<double>(z(rr, cc)))});
            }
        }
    }
    const auto small = [&](std::size_t i) { return w.pieces[i].anchored < min_cells || w.pieces[i].anchored == 0; };
    const auto key = [&](std::size_t i) { return std::tuple{w.pieces[i].cells, w.pieces[i].first, i}; };
    std::set<std::tuple<std::size_t, std::size_t, std::size_t>> waiting;  // small pieces, smallest first
    for (std::size_t i = 0; i < n; ++i)
        if (w.owner[i] == i && small(i)) waiting.insert(key(i));
    while (!waiting.empty()) {
        const std::size_t chosen = std::get<2>(*waiting.begin());
        waiting.erase(waiting.begin());
        if (touching[chosen].empty()) continue;  // a building in one small piece stays as it is
        std::size_t into = n;
        const auto better = [&](std::size_t j, const piece_boundary& e) {
            if (into == n) return true;
            const piece_boundary& best = touching[chosen].at(into);
            if (e.mean_rise_m() != best.mean_rise_m()) return e.mean_rise_m() < best.mean_rise_m();
            if (e.pairs != best.pairs) return e.pairs > best.pairs;
            if (w.pieces[j].cells != w.pieces[into].cells) return w.pieces[j].cells > w.pieces[into].cells;
            return w.pieces[j].first < w.pieces[into].first;
        };
        for (const auto& [j, e] : touching[chosen])
            if (better(j, e)) into = j;
        waiting.erase(key(into));
        w.join(chosen, into);
        if (small(into)) waiting.insert(key(into));
        contract_boundaries(touching, chosen, into);
    }
}

/// Step 5: standing pieces of one building whose boundary (edge-neighbour pairs) steps by more than min_step_m
/// along less than min_wall_share of it are joined, pair by pair, until no such boundary is left; then a piece
/// that touches no other piece of its building joins the building's largest piece.
inline void join_unstepped_pieces(wall_pieces& w, raster_view<const float> z, const party_walls_options& opt)
{
    const std::ptrdiff_t rows = z.rows(), cols = z.cols();
    const std::size_t n = w.pieces.size();
    piece_graph<surface_boundary> between(n);
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            if (w.index(r, c) == 0) continue;
            const std::size_t p = w.standing_at(r, c);
            for (int k = 0; k < 2; ++k) {  // south and east neighbours
                const std::ptrdiff_t rr = r + (k == 0 ? 1 : 0), cc = c + (k == 1 ? 1 : 0);
                if (rr >= rows || cc >= cols || w.index(rr, cc) == 0) continue;
                const std::size_t q = w.standing_at(rr, cc);
                if (p == q || w.pieces[p].building != w.pieces[q].building) continue;
                const bool step =
                    std::abs(static_cast<double>(z(r, c)) - static_cast<double>(z(rr, cc))) > opt.min_step_m;
                add_boundary(between, p, q, surface_boundary{1, step ? 1u : 0u, 0});
            }
        }
    }
    const auto unstepped = [&](const surface_boundary& e) {
        return !at_least_share(e.steps, e.pairs, opt.min_wall_share);
    };
    for (std::size_t keep = 0; keep < n; ++keep) {
        for (;;) {  // joins into `keep` until its boundaries all step
            const auto found = std::find_if(between[keep].begin(), between[keep].end(),
                                            [&](const auto& entry) { return unstepped(entry.second); });
            if (found == between[keep].end()) break;
            const std::size_t gone = found->first;
            w.join(gone, keep);
            contract_boundaries(between, gone, keep);
        }
    }
    // A standing piece that touches no other piece of its building (a part apart from the block) stays with the
    // building's largest piece.
    std::map<std::int32_t, std::size_t> largest;
    for (std::size_t i = 0; i < n; ++i) {
        if (w.owner[i] != i) continue;
        auto [at, fresh] = largest.try_emplace(w.pieces[i].building, i);
        if (!fresh && w.pieces[i].cells > w.pieces[at->second].cells) at->second = i;
    }
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t main = largest[w.pieces[i].building];
        if (w.owner[i] == i && i != main && between[i].empty()) w.join(i, main);
    }
}

/// The buildings after the split, 1..k by decreasing footprint (ties: the old id, then the first cell in raster
/// order): each standing piece of a building in the step, each other building whole. Written to `building_id`;
/// returns k and the buildings split, or {count, 0} (nothing written) when none was.
inline party_walls_result number_split_buildings(const wall_pieces& w, raster_view<std::int32_t> building_id,
                                                 std::size_t count)
{
    const std::size_t n = w.pieces.size();
    std::vector<wall_pieces::piece> units(n + count);  // pieces, then the buildings 1..count kept whole
    std::vector<std::size_t> standing_pieces(count + 1, 0);
    for (std::size_t i = 0; i < n; ++i) {
        if (w.owner[i] != i) continue;
        units[i] = w.pieces[i];
        ++standing_pieces[static_cast<std::size_t>(w.pieces[i].building)];
    }
    const auto split = static_cast<std::size_t>(
        std::count_if(standing_pieces.begin(), standing_pieces.end(), [](std::size_t k) { return k > 1; }));
    if (split == 0) return {count, 0};
    const std::ptrdiff_t cols = building_id.cols();
    for (std::ptrdiff_t r = 0; r < building_id.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const std::int32_t b = building_id(r, c);
            if (b <= 0 || w.index(r, c) != 0) continue;
            wall_pieces::piece& whole = units[n + static_cast<std::size_t>(b - 1)];
            if (whole.cells++ == 0) whole = {b, 1, static_cast<std::size_t>(r * cols + c), 0};
        }
    std::vector<std::size_t> order;
    for (std::size_t i = 0; i < units.size(); ++i)
        if (units[i].cells > 0) order.push_back(i);
    std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) {
        const wall_pieces::piece &a = units[i], &b = units[j];
        if (a.cells != b.cells) return a.cells > b.cells;
        return a.building != b.building ? a.building < b.building : a.first < b.first;
    });
    std::vector<std::int32_t> new_id(units.size(), 0);
    for (std::size_t k = 0; k < order.size(); ++k) new_id[order[k]] = static_cast<std::int32_t>(k + 1);
    for (std::ptrdiff_t r = 0; r < building_id.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const std::int32_t b = building_id(r, c);
            if (w.index(r, c) != 0)
                building_id(r, c) = new_id[w.standing_at(r, c)];
            else if (b > 0)
                building_id(r, c) = new_id[n + static_cast<std::size_t>(b - 1)];
        }
    return {order.size(), split};
}

/// After a split: the cells of a surface that ended in another building than most of its anchored cells (all its
/// cells when none is anchored) leave it and are given to a surface of their own building
/// (assign_remaining_cells over those cells only); a building left without any surface gets one of its own
/// (all its cells, none core). Cells outside the step keep their surfaces. `buildings`: the ids are 0..buildings.
inline void resurface_moved_cells(roof_regions& regions, raster_view<const std::int32_t> building_id,
                                  std::size_t buildings, raster_view<const float> z, double cell_m,
                                  const raster<std::int32_t>& in_step, raster_view<const std::int32_t> anchored)
{
    const std::ptrdiff_t rows = building_id.rows(), cols = building_id.cols();
    const auto surface_at = [&](std::ptrdiff_t r, std::ptrdiff_t c) {
        const std::int32_t g = regions.region(r, c);
        return g > 0 && in_step(r, c) != 0 ? static_cast<std::size_t>(g) : 0;
    };
    // The home of each surface: the building of most of its anchored cells, else of most of its cells.
    const std::size_t surfaces = static_cast<std::size_t>(regions.count) + 1;
    std::vector<std::map<std::int32_t, std::size_t>> held(surfaces), held_anchored(surfaces);
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c)
            if (const std::size_t g = surface_at(r, c)) {
                ++held[g][building_id(r, c)];
                if (anchored(r, c) != 0) ++held_anchored[g][building_id(r, c)];
            }
    std::vector<std::int32_t> home(surfaces, 0);
    for (std::size_t g = 1; g < surfaces; ++g) {
        std::size_t most = 0;
        for (const auto& [b, k] : held_anchored[g].empty() ? held[g] : held_anchored[g])
            if (k > most) most = k, home[g] = b;
    }
    // Cells that move; only they are assigned again (the others' ids hidden from assign_remaining_cells).
    raster<std::int32_t> moving_ids(rows, cols);
    bool moved = false;
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const std::size_t g = surface_at(r, c);
            if (g != 0 && building_id(r, c) != home[g]) {
                regions.region(r, c) = 0;
                regions.core(r, c) = 0;
                moved = true;
            }
            const bool kept_out = regions.region(r, c) == 0 && !(g != 0 && building_id(r, c) != home[g]);
            moving_ids(r, c) = kept_out ? 0 : building_id(r, c);
        }
    if (moved) assign_remaining_cells(regions, z, moving_ids.view(), cell_m);
    // A building without any surface left gets one of its own.
    std::vector<bool> surfaced(buildings + 1, false);
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c)
            if (building_id(r, c) > 0 && regions.region(r, c) > 0)
                surfaced[static_cast<std::size_t>(building_id(r, c))] = true;
    std::vector<std::int32_t> fresh(surfaced.size(), 0);
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const std::int32_t b = building_id(r, c);
            if (b <= 0 || in_step(r, c) == 0 || surfaced[static_cast<std::size_t>(b)]) continue;
            std::int32_t& g = fresh[static_cast<std::size_t>(b)];
            if (g == 0) g = ++regions.count;
            regions.region(r, c) = g;
            regions.core(r, c) = 0;
        }
}

}  // namespace detail

// ---- implementation ----

inline party_walls_result split_party_walls(raster_view<std::int32_t> building_id, std::size_t count,
                                            roof_regions& regions, raster_view<const float> z, double cell_m,
                                            const party_walls_options& opt)
{
    constexpr const char* function = "split_party_walls";
    detail::check_party_walls(opt, function);
    detail::require_positive(cell_m, function, "cell_m");
    detail::require_same_shape(building_id, z, function, "building_id", "z");
    detail::require_same_shape(building_id, regions.region, function, "building_id", "regions");
    detail::require_same_shape(building_id, regions.core, function, "building_id", "regions.core");
    detail::require(regions.count >= 0, function, "regions.count must be >= 0");
    for (std::ptrdiff_t r = 0; r < building_id.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < building_id.cols(); ++c) {
            detail::require(building_id(r, c) >= 0 && static_cast<std::size_t>(building_id(r, c)) <= count, function,
                            "building ids must lie in 0..count");
            detail::require(regions.region(r, c) >= 0 && regions.region(r, c) <= regions.count, function,
                            "region ids must lie in 0..regions.count");
        }
    const std::vector<plane_sums> sums = fit_roof_regions(regions, z, cell_m);
    std::vector<plane_fit> planes(sums.size());
    for (std::size_t g = 1; g < sums.size(); ++g) planes[g] = fit_plane(sums[g]);
    const raster<std::int32_t> anchored =
        detail::anchored_surfaces(building_id, count, regions, z, cell_m, planes, opt.min_step_m);
    const detail::surface_parts_result parts =
        detail::surface_parts(building_id, count, regions, anchored.view(), z, cell_m, planes, opt);
    if (parts.part.empty()) return {count, 0};
    detail::wall_pieces pieces = detail::number_wall_pieces(building_id, anchored.view(), parts);
    detail::join_small_pieces(pieces, z, detail::cells_covering(opt.min_part_m2, cell_m));
    detail::join_unstepped_pieces(pieces, z, opt);
    const party_walls_result result = detail::number_split_buildings(pieces, building_id, count);
    if (result.split > 0)
        detail::resurface_moved_cells(regions, building_id, result.count, z, cell_m, pieces.index, anchored.view());
    return result;
}

}  // namespace lidarfx
