// SPDX-License-Identifier: Apache-2.0
// facade_patches: the vertical walls of a surface model, where a roof edge stands above lower ground, each
// split into stacked sub-patches with their own centre heights (dissertation 3.2.4, Figure 66).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// Settings of facade_patches.
struct facade_patches_options {
    int levels = 8;             ///< sub-patches stacked on each wall, >= 1 (the dissertation's 8)
    double min_height_m = 1.0;  ///< a wall needs roof - ground > this many metres, >= 0
};

/// One facade sub-patch: level `level` of the wall on the border between building cell (row, col) and the
/// lower non-building cell (front_row, front_col) in front of it.
struct facade_patch {
    std::int32_t building_id = 0;     ///< the building the wall belongs to (> 0)
    std::int32_t wall_id = 0;         ///< index of the wall (facade patch), 0, 1, ... in raster order; CSV patch_id
    int level = 0;                    ///< 0 at the bottom .. levels - 1 at the roof edge
    std::ptrdiff_t row = 0, col = 0;  ///< the building cell whose edge the wall hangs from
    std::ptrdiff_t front_row = 0, front_col = 0;  ///< the ground cell the wall faces (4-neighbour of (row, col))
    double facing_azimuth_deg = 0;                ///< outward normal, clockwise from north: 0 N, 90 E, 180 S, 270 W
    double bottom_m = 0, top_m = 0;               ///< the wall's foot (front cell height) and top (roof cell height), m
    double height_m = 0;                          ///< centre height of this sub-patch, m
    double area_m2 = 0;                           ///< cell_m * (top_m - bottom_m) / levels, m^2
};

namespace detail {

/// The four outward directions of a cell's edges: (drow, dcol, facing azimuth) for N, E, S, W.
inline constexpr std::array<std::array<int, 3>, 4> facade_directions{
    {{-1, 0, 0}, {0, 1, 90}, {1, 0, 180}, {0, -1, 270}}};

}  // namespace detail

/// Vertical facade sub-patches of a DSM with a building-id raster (dissertation 3.2.4): for every building cell
/// b (id > 0) and each of its four edge neighbours n (north, east, south, west; row 0 north) that is not building
/// (id 0), not NaN and lower by more than min_height_m, one wall on their shared cell edge, facing from b to n
/// (azimuth 0, 90, 180 or 270), from z_n up to z_b, split into `levels` stacked sub-patches:
///   height_m = z_n + (k + 0.5) (z_b - z_n) / levels,   area_m2 = cell_m (z_b - z_n) / levels   (k = level).
/// Walls are numbered (wall_id) in raster order of b and, per cell, in the order N, E, S, W; the result lists
/// each wall's sub-patches bottom to top. Only edge neighbours make walls: two buildings' cells touching at a
/// corner make none, and a diagonal outline is a staircase of N/E/S/W walls (its wall area is the staircase's,
/// up to sqrt 2 times the diagonal wall's). A wall between two buildings, or on a roof step of one building, is
/// not modelled. O(rows * cols). @throws invalid_input if shapes differ, cell_m is not finite and > 0,
/// levels < 1 or min_height_m is negative or not finite.
template <raster_input Dsm, raster_input Ids>
std::vector<facade_patch> facade_patches(const Dsm& dsm, const Ids& building_id, double cell_m,
                                         const facade_patches_options& opt = {})
{
    constexpr const char* fn = "facade_patches";
    detail::require_positive(cell_m, fn, "cell_m");
    detail::require(opt.levels >= 1, fn, "levels", ">= 1", opt.levels);
    detail::require(opt.min_height_m >= 0.0 && std::isfinite(opt.min_height_m), fn, "min_height_m", "finite and >= 0",
                    opt.min_height_m);
    detail::require_same_shape(dsm, building_id, fn, "dsm", "building_id");
    std::vector<facade_patch> out;
    const std::ptrdiff_t rows = dsm.rows(), cols = dsm.cols();
    std::int32_t wall = 0;
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const auto id = static_cast<std::int32_t>(building_id(r, c));
            const double top = dsm(r, c);
            if (id <= 0 || std::isnan(top)) continue;
            for (const auto& [dr, dc, facing] : detail::facade_directions) {
                const std::ptrdiff_t fr = r + dr, fc = c + dc;
                if (fr < 0 || fr >= rows || fc < 0 || fc >= cols) continue;
                if (static_cast<std::int32_t>(building_id(fr, fc)) != 0) continue;
                const double bottom = dsm(fr, fc);
                if (!(top - bottom > opt.min_height_m)) continue;  // false for a NaN front cell too
                const double step = (top - bottom) / opt.levels;
                for (int k = 0; k < opt.levels; ++k) {
                    facade_patch p;
                    p.building_id = id;
                    p.wall_id = wall;
                    p.level = k;
                    p.row = r;
                    p.col = c;
                    p.front_row = fr;
                    p.front_col = fc;
                    p.facing_azimuth_deg = facing;
                    p.bottom_m = bottom;
                    p.top_m = top;
                    p.height_m = bottom + (k + 0.5) * step;
                    p.area_m2 = cell_m * step;
                    out.push_back(p);
                }
                ++wall;
            }
        }
    }
    return out;
}

}  // namespace lidarfx
