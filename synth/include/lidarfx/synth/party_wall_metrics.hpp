// SPDX-License-Identifier: Apache-2.0
// Party-wall metrics: how found buildings split the touching houses of a family town's terraced rows and
// semi-detached pairs (town_family.hpp, party_wall_truth) at their shared walls, and whether they cut single
// houses in two (tests and the benchmark bench/party_walls share them).
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/grid.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/synth/render.hpp"
#include "lidarfx/synth/town_family.hpp"

namespace lidarfx::synth {

/// A party wall counts as separable (its two roofs tell the houses apart) when its step_share is at least this.
inline constexpr double separable_step_share = 0.5;

/// A found building covers a truth building's cells when it holds at least this share of them (its dominant
/// found building).
inline constexpr double dominant_cover_share = 0.5;

/// A truth building counts as cut in two when two or more found buildings each cover at least this much of it, m^2.
inline constexpr double split_piece_m2 = 15.0;

/// Counts over one or more towns of how found buildings treat party walls and houses.
/// A wall is split when both its houses have a dominant found building (the one covering >= 50 % of the house's
/// truth cells) and the two differ.
struct party_wall_scores {
    std::size_t buildings = 0;           ///< truth buildings (detached houses, garages and sheds, row houses)
    std::size_t row_houses = 0;          ///< truth buildings on at least one party wall
    std::size_t walls_separable = 0;     ///< party walls with step_share >= separable_step_share
    std::size_t walls_split = 0;         ///< of them, the walls split (wanted: all)
    std::size_t walls_merged = 0;        ///< the other party walls: one roof to the eye, so merging is expected
    std::size_t walls_merged_split = 0;  ///< of them, the walls split anyway
    std::size_t houses_split = 0;        ///< truth buildings two or more found buildings each cover split_piece_m2 of

    /// Pools the counts of another town.
    void add(const party_wall_scores& o) noexcept
    {
        buildings += o.buildings;
        row_houses += o.row_houses;
        walls_separable += o.walls_separable;
        walls_split += o.walls_split;
        walls_merged += o.walls_merged;
        walls_merged_split += o.walls_merged_split;
        houses_split += o.houses_split;
    }
};

/// Cells of each truth building (index = building id; 0 = no building) and, per truth building, how many of its
/// cells each found building holds. The found raster is sampled at each truth cell's centre (its cell on
/// found_grid by grid::cell_of; outside found_grid = no building), so it may lie on another grid.
struct truth_cover {
    std::vector<std::size_t> cells;                                ///< truth cells of each building id
    std::vector<std::map<std::int32_t, std::size_t>> found_cells;  ///< per building id: found id -> cells (id > 0)
};

/// The truth_cover of `found` (found building ids, 0 = none, on found_grid) over the truth's buildings.
/// @throws invalid_input when found does not have found_grid's shape.
inline truth_cover cover_of(const scene_truth& truth, const raster<std::int32_t>& found, const grid& found_grid)
{
    detail::require(found.rows() == found_grid.rows && found.cols() == found_grid.cols, "cover_of",
                    "the found raster must have found_grid's rows and cols");
    truth_cover cover;
    cover.cells.assign(truth.footprints.size() + 1, 0);
    cover.found_cells.resize(truth.footprints.size() + 1);
    const grid& g = truth.g;
    for (std::ptrdiff_t r = 0; r < g.rows; ++r) {
        for (std::ptrdiff_t c = 0; c < g.cols; ++c) {
            const auto id = static_cast<std::size_t>(truth.building_id(r, c));
            if (id == 0) continue;
            ++cover.cells[id];
            const auto [x, y] = g.center(r, c);
            const auto at = found_grid.cell_of(x, y);
            const std::int32_t f = at ? found(at->row, at->col) : 0;
            if (f > 0) ++cover.found_cells[id][f];
        }
    }
    return cover;
}

/// The found building covering most of truth building `id`'s cells when it covers >= dominant_cover_share of
/// them; 0 if none does.
inline std::int32_t dominant_found(const truth_cover& cover, std::int32_t id)
{
    const auto k = static_cast<std::size_t>(id);
    std::int32_t best = 0;
    std::size_t best_cells = 0;
    for (const auto& [f, n] : cover.found_cells[k]) {
        if (n > best_cells) {
            best = f;
            best_cells = n;
        }
    }
    const bool dominant = static_cast<double>(best_cells) >= dominant_cover_share * static_cast<double>(cover.cells[k]);
    return best_cells > 0 && dominant ? best : 0;
}

/// True when two or more found buildings each cover >= split_piece_m2 of truth building `id` (cells of
/// cell_m metres).
inline bool house_split(const truth_cover& cover, std::int32_t id, double cell_m)
{
    std::size_t pieces = 0;
    for (const auto& [f, n] : cover.found_cells[static_cast<std::size_t>(id)])
        pieces += static_cast<double>(n) * cell_m * cell_m >= split_piece_m2 ? 1 : 0;
    return pieces >= 2;
}

/// Scores found buildings (`found`, ids > 0, 0 = none, on found_grid, which may differ from the truth grid)
/// against a town's truth and party walls (town_family_scene::party_walls): see party_wall_scores.
/// @throws invalid_input when found does not have found_grid's shape.
inline party_wall_scores score_party_walls(const scene_truth& truth, const std::vector<party_wall_truth>& walls,
                                           const raster<std::int32_t>& found, const grid& found_grid)
{
    const truth_cover cover = cover_of(truth, found, found_grid);
    party_wall_scores s;
    s.buildings = truth.footprints.size();
    std::vector<bool> on_wall(truth.footprints.size() + 1, false);
    for (const auto& w : walls) {
        on_wall[static_cast<std::size_t>(w.a)] = on_wall[static_cast<std::size_t>(w.b)] = true;
        const std::int32_t fa = dominant_found(cover, w.a), fb = dominant_found(cover, w.b);
        const bool split = fa != 0 && fb != 0 && fa != fb;
        if (w.step_share >= separable_step_share) {
            ++s.walls_separable;
            s.walls_split += split ? 1 : 0;
        } else {
            ++s.walls_merged;
            s.walls_merged_split += split ? 1 : 0;
        }
    }
    for (std::size_t id = 1; id <= truth.footprints.size(); ++id) {
        s.row_houses += on_wall[id] ? 1 : 0;
        s.houses_split += house_split(cover, static_cast<std::int32_t>(id), truth.g.cell) ? 1 : 0;
    }
    return s;
}

}  // namespace lidarfx::synth
