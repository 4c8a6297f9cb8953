// SPDX-License-Identifier: Apache-2.0
// grow_roof_surfaces: roof surfaces grown from the planar cells of each building, small ones dissolved, and
// the remaining building cells given to the nearest surface in height (extract_buildings steps 4 and 5).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/plane_fit.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/pipelines/buildings/local_planes.hpp"

namespace lidarfx {

/// Settings of grow_roof_surfaces and dissolve_small_surfaces.
struct grow_roof_surfaces_options {
    double plane_angle_deg = 6.0;  ///< largest angle between a cell's normal and its surface's mean normal; (0, 90)
    double step_m = 0.3;           ///< largest height step between neighbours of one surface beyond the slope, m; > 0
    double min_surface_m2 = 4.0;   ///< smaller surfaces are given to their neighbours, m^2; >= 0
};

/// Roof surfaces of the building cells, as regions of a raster.
struct roof_regions {
    raster<std::int32_t> region;  ///< surface of each cell, 1..count; 0 = none
    raster<std::uint8_t> core;    ///< 1 = the cell joined its surface by growing (the cells its plane is fitted to)
    std::int32_t count = 0;       ///< number of surfaces
};

/// Sums for the least-squares plane of each surface (index = surface id; [0] unused), over x = col * cell_m
/// (east) and y = -row * cell_m (north), z in metres, added in raster order. core_only: over the surface's core
/// cells, or all its cells when it has fewer than 3 core cells (cells given to a surface later, eaves mixed with
/// the wall or filled holes, do not tilt it); else over all its cells. O(cells). Never throws (shapes unchecked).
inline std::vector<plane_sums> fit_roof_regions(const roof_regions& regions, raster_view<const float> z, double cell_m,
                                                bool core_only = true);

/// Regions of planar cells (is_planar) of each building, grown in order of increasing local RMS (ties by raster
/// order) over 4-neighbours of the same building that are planar, whose normal lies within plane_angle_deg of
/// the region's mean normal (mean of the cells' a, b) and whose height differs from the neighbour's by at most
/// step_m beyond the mean slope. Every grown cell is core. z in metres, cell_m in metres.
/// O(cells log cells).
/// @throws invalid_input on bad options or cell_m, or if z, building_id and lp differ in shape.
inline roof_regions grow_roof_surfaces(raster_view<const float> z, raster_view<const std::int32_t> building_id,
                                       const local_planes_result& lp, double cell_m,
                                       const local_planes_options& planar = {},
                                       const grow_roof_surfaces_options& opt = {});

/// Dissolves the surfaces with fewer than max(1, min_surface_m2 / cell_m^2) fit cells (fit_roof_regions) and
/// renumbers the others in order; a building 1..building_count left without a surface becomes one surface (no
/// core cells), numbered after them in building order. O(cells).
/// @throws invalid_input on bad options or cell_m, or if the shapes differ.
inline void dissolve_small_surfaces(roof_regions& regions, raster_view<const float> z,
                                    raster_view<const std::int32_t> building_id, std::size_t building_count,
                                    double cell_m, const grow_roof_surfaces_options& opt = {});

/// Gives every building cell without a surface, layer by layer, to the 8-neighbour surface of the same building
/// whose plane (fit_roof_regions, fitted once before) lies nearest its height (ties to the smaller id); the
/// decisions of one layer read only earlier layers. Cells no surface reaches keep 0. O(cells x layers).
/// @throws invalid_input if cell_m is not finite and > 0 or the shapes differ.
inline void assign_remaining_cells(roof_regions& regions, raster_view<const float> z,
                                   raster_view<const std::int32_t> building_id, double cell_m);

namespace detail {

inline void check_grow_roof_surfaces(const grow_roof_surfaces_options& opt, const char* function)
{
    require(opt.plane_angle_deg > 0 && opt.plane_angle_deg < 90, function, "plane_angle_deg", "in (0, 90)",
            opt.plane_angle_deg);
    require_positive(opt.step_m, function, "step_m");
    require(opt.min_surface_m2 >= 0 && opt.min_surface_m2 < 1e300, function, "min_surface_m2", "finite and >= 0",
            opt.min_surface_m2);
}

/// {a, b, c, rms} of the least-squares plane z = a x + b y + c of `s` (core/plane_fit.hpp): a = b = 0 and
/// c = mean when the points are degenerate (collinear or < 3).
inline std::array<double, 4> plane_abc_rms(const plane_sums& s) noexcept
{
    const plane_fit f = fit_plane(s);
    return {f.a, f.b, f.c, f.rms};
}

inline void check_regions_shape(const roof_regions& regions, raster_view<const float> z,
                                raster_view<const std::int32_t> building_id, const char* function)
{
    require_same_shape(z, building_id, function, "z", "building_id");
    require_same_shape(z, regions.region, function, "z", "regions");
}

}  // namespace detail

// ---- implementation ----

inline std::vector<plane_sums> fit_roof_regions(const roof_regions& regions, raster_view<const float> z, double cell_m,
                                                bool core_only)
{
    std::vector<plane_sums> sums(static_cast<std::size_t>(regions.count) + 1), all(sums.size());
    for (std::ptrdiff_t r = 0; r < z.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < z.cols(); ++c) {
            const auto g = static_cast<std::size_t>(regions.region(r, c));
            if (g == 0) continue;
            const double x = static_cast<double>(c) * cell_m, y = -static_cast<double>(r) * cell_m;
            all[g].add(x, y, static_cast<double>(z(r, c)));
            if (regions.core(r, c)) sums[g].add(x, y, static_cast<double>(z(r, c)));
        }
    }
    if (!core_only) return all;
    for (std::size_t g = 1; g < sums.size(); ++g) {
        if (sums[g].n < 3) sums[g] = all[g];
    }
    return sums;
}

inline roof_regions grow_roof_surfaces(raster_view<const float> z, raster_view<const std::int32_t> building_id,
                                       const local_planes_result& lp, double cell_m, const local_planes_options& planar,
                                       const grow_roof_surfaces_options& opt)
{
    constexpr const char* function = "grow_roof_surfaces";
    detail::require_positive(cell_m, function, "cell_m");
    detail::check_local_planes(planar, function);
    detail::check_grow_roof_surfaces(opt, function);
    detail::require_same_shape(z, building_id, function, "z", "building_id");
    detail::require_same_shape(z, lp.rms, function, "z", "lp");
    const std::ptrdiff_t rows = z.rows(), cols = z.cols();
    roof_regions out{raster<std::int32_t>(rows, cols), raster<std::uint8_t>(rows, cols), 0};
    const auto idx = [cols](std::ptrdiff_t r, std::ptrdiff_t c) { return static_cast<std::size_t>(r * cols + c); };
    const auto x_of = [&](std::ptrdiff_t c) { return static_cast<double>(c) * cell_m; };
    const auto y_of = [&](std::ptrdiff_t r) { return -static_cast<double>(r) * cell_m; };
    std::int32_t* region = out.region.data();
    std::vector<std::size_t> seeds;
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            if (building_id(r, c) != 0 && is_planar(lp, r, c, cell_m, planar)) seeds.push_back(idx(r, c));
        }
    }
    std::stable_sort(seeds.begin(), seeds.end(),
                     [&](std::size_t p, std::size_t q) { return lp.rms.data()[p] < lp.rms.data()[q]; });
    constexpr std::ptrdiff_t dr4[] = {-1, 1, 0, 0}, dc4[] = {0, 0, -1, 1};
    std::vector<std::size_t> queue;
    for (const std::size_t s : seeds) {
        if (region[s] != 0) continue;
        const std::int32_t id = ++out.count;
        region[s] = id;
        out.core.data()[s] = 1;
        queue.assign(1, s);
        double sa = lp.a.data()[s], sb = lp.b.data()[s], n = 1;
        for (std::size_t head = 0; head < queue.size(); ++head) {
            const std::size_t p = queue[head];
            const auto pr = static_cast<std::ptrdiff_t>(p) / cols, pc = static_cast<std::ptrdiff_t>(p) % cols;
            for (int k = 0; k < 4; ++k) {
                const std::ptrdiff_t rr = pr + dr4[k], cc = pc + dc4[k];
                if (rr < 0 || cc < 0 || rr >= rows || cc >= cols) continue;
                const std::size_t q = idx(rr, cc);
                if (region[q] != 0 || building_id(rr, cc) != building_id(pr, pc) ||
                    !is_planar(lp, rr, cc, cell_m, planar))
                    continue;
                const double ma = sa / n, mb = sb / n;
                if (normal_angle_deg(lp.a.data()[q], lp.b.data()[q], ma, mb) > opt.plane_angle_deg) continue;
                const double expected = ma * (x_of(cc) - x_of(pc)) + mb * (y_of(rr) - y_of(pr));
                if (std::abs(static_cast<double>(z(rr, cc)) - static_cast<double>(z(pr, pc)) - expected) > opt.step_m)
                    continue;
                region[q] = id;
                out.core.data()[q] = 1;
                sa += lp.a.data()[q];
                sb += lp.b.data()[q];
                n += 1;
                queue.push_back(q);
            }
        }
    }
    return out;
}

inline void dissolve_small_surfaces(roof_regions& regions, raster_view<const float> z,
                                    raster_view<const std::int32_t> building_id, std::size_t building_count,
                                    double cell_m, const grow_roof_surfaces_options& opt)
{
    constexpr const char* function = "dissolve_small_surfaces";
    detail::require_positive(cell_m, function, "cell_m");
    detail::check_grow_roof_surfaces(opt, function);
    detail::check_regions_shape(regions, z, building_id, function);
    const auto sums = fit_roof_regions(regions, z, cell_m);
    const double min_surface_cells = opt.min_surface_m2 / (cell_m * cell_m);
    std::vector<std::int32_t> renumber(static_cast<std::size_t>(regions.count) + 1, 0);
    std::int32_t next = 0;
    for (std::int32_t g = 1; g <= regions.count; ++g) {
        if (sums[static_cast<std::size_t>(g)].n >= std::max(1.0, min_surface_cells))
            renumber[static_cast<std::size_t>(g)] = ++next;
    }
    const std::ptrdiff_t rows = z.rows(), cols = z.cols();
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            regions.region(r, c) = renumber[static_cast<std::size_t>(regions.region(r, c))];
            if (regions.region(r, c) == 0) regions.core(r, c) = 0;
        }
    }
    regions.count = next;
    // A building with no surface left becomes one surface.
    std::vector<std::int32_t> whole(building_count + 1, 0);
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const auto b = static_cast<std::size_t>(building_id(r, c));
            if (b != 0 && regions.region(r, c) != 0) whole[b] = -1;
        }
    }
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const auto b = static_cast<std::size_t>(building_id(r, c));
            if (b == 0 || whole[b] < 0) continue;
            if (whole[b] == 0) whole[b] = ++regions.count;
            regions.region(r, c) = whole[b];
        }
    }
}

inline void assign_remaining_cells(roof_regions& regions, raster_view<const float> z,
                                   raster_view<const std::int32_t> building_id, double cell_m)
{
    constexpr const char* function = "assign_remaining_cells";
    detail::require_positive(cell_m, function, "cell_m");
    detail::check_regions_shape(regions, z, building_id, function);
    const auto sums = fit_roof_regions(regions, z, cell_m);
    std::vector<std::array<double, 4>> planes(sums.size());
    for (std::size_t g = 1; g < sums.size(); ++g) planes[g] = detail::plane_abc_rms(sums[g]);
    const std::ptrdiff_t rows = z.rows(), cols = z.cols();
    std::int32_t* region = regions.region.data();
    std::vector<std::size_t> frontier, next_frontier;
    std::vector<std::pair<std::size_t, std::int32_t>> taken;
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const auto p = static_cast<std::size_t>(r * cols + c);
            if (building_id(r, c) != 0 && region[p] == 0) frontier.push_back(p);
        }
    }
    while (!frontier.empty()) {
        taken.clear();
        next_frontier.clear();
        for (const std::size_t p : frontier) {
            const auto pr = static_cast<std::ptrdiff_t>(p) / cols, pc = static_cast<std::ptrdiff_t>(p) % cols;
            const double x = static_cast<double>(pc) * cell_m, y = -static_cast<double>(pr) * cell_m;
            std::int32_t best = 0;
            double best_d = std::numeric_limits<double>::infinity();
            for (std::ptrdiff_t dr = -1; dr <= 1; ++dr) {
                for (std::ptrdiff_t dc = -1; dc <= 1; ++dc) {
                    const std::ptrdiff_t rr = pr + dr, cc = pc + dc;
                    if (rr < 0 || cc < 0 || rr >= rows || cc >= cols) continue;
                    const std::int32_t g = region[static_cast<std::size_t>(rr * cols + cc)];
                    if (g <= 0 || building_id(rr, cc) != building_id(pr, pc)) continue;
                    const auto& f = planes[static_cast<std::size_t>(g)];
                    const double d = std::abs(static_cast<double>(z(pr, pc)) - (f[0] * x + f[1] * y + f[2]));
                    if (d < best_d || (d == best_d && g < best)) {
                        best_d = d;
                        best = g;
                    }
                }
            }
            if (best > 0)
                taken.emplace_back(p, best);
            else
                next_frontier.push_back(p);
        }
        if (taken.empty()) break;  // cells no surface reaches (cannot happen after dissolve_small_surfaces)
        for (const auto& [p, g] : taken) region[p] = g;
        frontier.swap(next_frontier);
    }
}

}  // namespace lidarfx
