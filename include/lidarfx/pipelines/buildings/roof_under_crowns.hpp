// SPDX-License-Identifier: Apache-2.0
// join_roof_under_crowns: the part of a roof hidden under an overhanging crown, found by the survey's lowest
// returns (extract_buildings step 3c, when the survey's lowest returns are given).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/pipelines/buildings/local_planes.hpp"

namespace lidarfx {

/// Settings of join_roof_under_crowns.
struct roof_under_crowns_options {
    /// A cell joins a building when its lowest raised point lies within this of the roof plane carried from the
    /// building cell beside it, plus half the plane's fall across a cell ((|a| + |b|) · cell_m from its highest
    /// corner to its lowest: where in the cell the lowest point lies), metres; >= 0.
    double plane_tolerance_m = 0.3;
    /// How far under crowns a roof is followed from the cells the building had, metres; >= 0; 0 = not at all.
    /// A crown reaches a few metres over a roof.
    double max_reach_m = 6;
    /// A cell joins only when at least this share of its points are raised; in (0, 1]. Beyond a wall a crown's
    /// cell holds raised points too, but the pulses that pass its foliage end on the ground (about a third of its
    /// points); a cell at the wall under the crown keeps most of its points on the roof.
    double min_raised_share = 0.9;
};

/// What join_roof_under_crowns changed.
struct roof_under_crowns_result {
    /// The cells that joined a building (row · cols + column), round by round in raster order; cells.size() of them.
    std::vector<std::ptrdiff_t> cells;
};

/// Joins to the buildings 1..count of `building_id` (in place) the cells of id 0 where a crown hides their roof,
/// and writes their roof elevation into `surface` (metres; the DSM the buildings were cut from, which holds the
/// crown there). Under a crown the highest return is foliage, so the cell was left out of the building as
/// vegetation; yet its pulses' returns stand above the terrain, and the lowest of them lies on the roof. In rounds
/// (at most max_reach_m / cell_m), each decided on the ids as the round before left them (so the result does not
/// depend on the order of the cells), a cell of id 0 joins when
///  - at least min_raised_share of its points are raised (`raised` of `points`: they stand the candidates'
///    min_height_m above the terrain, as refine_building_rim counts them), and
///  - the lowest of its raised points (`lowest`, NaN = none; count_points_above gives both) lies within
///    plane_tolerance_m + f / 2 of the roof plane of a building cell beside it across an edge, carried to its
///    centre and lowered by half the roof's fall across a cell: z + a·dx + b·dy - f / 2, with that cell's
///    surface z and local plane slopes a (east) and b (north), f = (|a| + |b|) · cell_m the plane's fall across a cell
///    (the surface z of a DSM is a cell's highest point, a lowest return lies below the cell's centre; a cell's highest
///    return lies above its centre, its lowest below).
/// It takes the building whose plane fits best (ties: the lowest id, then north, west, east, south). A joined cell
/// carries that plane on unchanged, its surface set to the plane's height there (z + a·dx + b·dy): every joined cell
/// lies within the tolerance of the roof's own plane, so a chain of joins cannot drift along a crown's underside or
/// a slope. Building cells keep their plane from `planes` (local_planes of the
/// buildings on `surface`). Cells of ids outside 0..count are left as they are and never joined. O(cells) plus
/// O(joined cells + candidates beside them) per round; memory beyond the arguments: the candidates beside the
/// buildings and the joined cells' slopes.
/// @throws invalid_input on an option out of range, shapes that differ, cell_m not > 0, or a cell with more
/// raised points than points.
inline roof_under_crowns_result join_roof_under_crowns(raster_view<std::int32_t> building_id, std::size_t count,
                                                       raster_view<float> surface, const local_planes_result& planes,
                                                       raster_view<const float> lowest,
                                                       raster_view<const std::uint32_t> points,
                                                       raster_view<const std::uint32_t> raised, double cell_m,
                                                       const roof_under_crowns_options& opt = {});

// ---- implementation ----

namespace detail {

inline void check_roof_under_crowns(const roof_under_crowns_options& opt, const char* function)
{
    require(opt.plane_tolerance_m >= 0 && opt.plane_tolerance_m < 1e300, function, "plane_tolerance_m",
            "finite and >= 0", opt.plane_tolerance_m);
    require(opt.max_reach_m >= 0 && opt.max_reach_m < 1e300, function, "max_reach_m", "finite and >= 0",
            opt.max_reach_m);
    require(opt.min_raised_share > 0 && opt.min_raised_share <= 1, function, "min_raised_share", "in (0, 1]",
            opt.min_raised_share);
}

/// The slopes of a roof plane carried into a joined cell (east, north; metres per metre).
struct carried_slopes {
    float a = 0, b = 0;
};

}  // namespace detail

inline roof_under_crowns_result join_roof_under_crowns(raster_view<std::int32_t> building_id, std::size_t count,
                                                       raster_view<float> surface, const local_planes_result& planes,
                                                       raster_view<const float> lowest,
                                                       raster_view<const std::uint32_t> points,
                                                       raster_view<const std::uint32_t> raised, double cell_m,
                                                       const roof_under_crowns_options& opt)
{
    constexpr const char* function = "join_roof_under_crowns";
    detail::check_roof_under_crowns(opt, function);
    detail::require_positive(cell_m, function, "cell_m");
    detail::require_same_shape(building_id, surface, function, "building_id", "surface");
    detail::require_same_shape(building_id, planes.a, function, "building_id", "planes.a");
    detail::require_same_shape(building_id, planes.b, function, "building_id", "planes.b");
    detail::require_same_shape(building_id, lowest, function, "building_id", "lowest");
    detail::require_same_shape(building_id, points, function, "building_id", "points");
    detail::require_same_shape(building_id, raised, function, "building_id", "raised");
    detail::require_counts_within(raised, points, function, "raised must not exceed points in any cell");
    roof_under_crowns_result res;
    const std::ptrdiff_t rows = building_id.rows(), cols = building_id.cols();
    // No chain of joins is longer than rows + cols cells: clamping there keeps a huge reach exact.
    const auto rounds =
        static_cast<long long>(std::min(std::floor(opt.max_reach_m / cell_m + 1e-9), static_cast<double>(rows + cols)));
    if (rows == 0 || cols == 0 || count == 0 || rounds == 0) return res;

    const auto building_at = [&](std::ptrdiff_t r, std::ptrdiff_t c) -> std::int32_t {
        const std::int32_t b = building_id(r, c);
        return b > 0 && static_cast<std::size_t>(b) <= count ? b : 0;
    };
    // The plane a building cell carries: its surface height with its local plane's slopes, or, for a joined cell,
    // the slopes it carries on (held for the joined cells only: they are few).
    std::unordered_map<std::ptrdiff_t, detail::carried_slopes> joined_slopes;
    const auto slopes_at = [&](std::ptrdiff_t r, std::ptrdiff_t c) {
        const auto it = joined_slopes.find(r * cols + c);
        return it != joined_slopes.end() ? it->second : detail::carried_slopes{planes.a(r, c), planes.b(r, c)};
    };
    // A candidate: id 0, with min_raised_share of its points raised and a lowest raised point.
    const auto candidate = [&](std::ptrdiff_t r, std::ptrdiff_t c) {
        return building_id(r, c) == 0 && points(r, c) > 0 &&
               static_cast<double>(raised(r, c)) >= opt.min_raised_share * static_cast<double>(points(r, c)) &&
               std::isfinite(lowest(r, c));
    };
    struct join {
        std::ptrdiff_t r, c;
        std::int32_t building;
        float z;
        detail::carried_slopes slopes;
    };
    std::vector<join> joins;
    // Edge neighbours in the tie order: north, west, east, south.
    constexpr int dr[4] = {-1, 0, 0, 1}, dc[4] = {0, -1, 1, 0};
    const auto inside = [&](std::ptrdiff_t r, std::ptrdiff_t c) { return r >= 0 && r < rows && c >= 0 && c < cols; };
    // The candidates beside a building cell: first those beside the buildings as they are, then those beside a cell
    // that joined in the last round.
    std::vector<std::ptrdiff_t> frontier;
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            if (!candidate(r, c)) continue;
            bool beside = false;
            for (int k = 0; k < 4 && !beside; ++k)
                beside = inside(r + dr[k], c + dc[k]) && building_at(r + dr[k], c + dc[k]) > 0;
            if (beside) frontier.push_back(r * cols + c);
        }
    for (long long round = 0; round < rounds && !frontier.empty(); ++round) {
        joins.clear();
        for (const std::ptrdiff_t i : frontier) {
            const std::ptrdiff_t r = i / cols, c = i % cols;
            if (!candidate(r, c)) continue;
            const double low = lowest(r, c);
            std::int32_t best = 0;
            double best_miss = 0;
            float best_z = 0;
            detail::carried_slopes best_slopes;
            for (int k = 0; k < 4; ++k) {
                const std::ptrdiff_t rr = r + dr[k], cc = c + dc[k];
                if (!inside(rr, cc)) continue;
                const std::int32_t b = building_at(rr, cc);
                if (b == 0) continue;
                const detail::carried_slopes p = slopes_at(rr, cc);
                // From the neighbour's centre to this one's: x east (columns), y north (rows upwards).
                const double dx = static_cast<double>(-dc[k]) * cell_m, dy = static_cast<double>(dr[k]) * cell_m;
                const double z = static_cast<double>(surface(rr, cc)) + p.a * dx + p.b * dy;
                // The plane's fall across the cell, from its highest corner to its lowest.
                const double fall = (std::abs(static_cast<double>(p.a)) + std::abs(static_cast<double>(p.b))) * cell_m;
                const double miss = std::abs(low - (z - 0.5 * fall));
                if (!(miss <= opt.plane_tolerance_m + 0.5 * fall)) continue;
                if (best == 0 || miss < best_miss || (miss == best_miss && b < best)) {
                    best = b;
                    best_miss = miss;
                    best_z = static_cast<float>(z);
                    best_slopes = p;
                }
            }
            if (best > 0) joins.push_back({r, c, best, best_z, best_slopes});
        }
        frontier.clear();
        for (const join& j : joins) {
            building_id(j.r, j.c) = j.building;
            surface(j.r, j.c) = j.z;
            joined_slopes[j.r * cols + j.c] = j.slopes;
            res.cells.push_back(j.r * cols + j.c);
            for (int k = 0; k < 4; ++k) {
                const std::ptrdiff_t rr = j.r + dr[k], cc = j.c + dc[k];
                if (inside(rr, cc) && candidate(rr, cc)) frontier.push_back(rr * cols + cc);
            }
        }
        std::sort(frontier.begin(), frontier.end());
        frontier.erase(std::unique(frontier.begin(), frontier.end()), frontier.end());
    }
    return res;
}

}  // namespace lidarfx
