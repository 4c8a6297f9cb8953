// SPDX-License-Identifier: Apache-2.0
// extract_buildings: buildings, their roof surfaces and outlines from a surface model (dissertation 3.2.1),
// with roof faces split by normal direction and trees rejected by returns and roughness.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
#include <numeric>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/grid.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/plane_fit.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/kernels/interpolate/idw_fill.hpp"
#include "lidarfx/kernels/label/connected_components.hpp"
#include "lidarfx/kernels/vector/polygonize.hpp"
#include "lidarfx/pipelines/buildings/ground_model.hpp"

namespace lidarfx {

/// Settings of extract_buildings. Defaults are for 0.25-1 m cells of a first-return DSM.
struct extract_buildings_options {
    ground_model_options ground = {};  ///< edges (>= 45 deg), edge objects (>= 10 cells), hulls, IDW (ground_model)
    double min_height_m = 2.5;         ///< building surface where z - ground > this, metres; > 0
    double min_area_m2 = 50.0;         ///< buildings of a smaller footprint are dropped, m^2; >= 0
    /// 1 = vegetation (e.g. rasterize_result::multiple_returns of first returns, or vegetation_mask); never a
    /// building. Empty (the default) = no return information. Same shape as the DSM when given.
    raster_view<const std::uint8_t> vegetation = {};
    double plane_window_m = 1.5;     ///< half-side of the window of each cell's local plane fit, metres (>= 1 cell)
    double plane_rms_m = 0.12;       ///< a cell whose local fit leaves an RMS below this x (1 + tan^2 tilt) (plus
                                     ///< slope_rms_share, see plane_tolerance) is planar, metres; > 0
    double slope_rms_share = 0.15;   ///< extra planar tolerance per metre of rise across a cell (see plane_tolerance)
    double plane_angle_deg = 6.0;    ///< largest angle between a cell's normal and its surface's mean normal; > 0
    double step_m = 0.3;             ///< largest height step between neighbours of one surface beyond the slope, m
    double merge_rms_m = 0.1;        ///< adjacent surfaces merge while one plane fits both with an RMS <=
                                     ///< plane_tolerance x merge_rms_m / plane_rms_m, metres; >= 0
    double min_surface_m2 = 4.0;     ///< smaller surfaces are given to their neighbours, m^2; >= 0
    double min_planar_share = 0.25;  ///< a building needs this share of planar cells, else it is rough (a tree)
    double x0 = 0.0;                 ///< world x of the west edge of column 0 (outlines), metres
    double y0 = std::numeric_limits<double>::quiet_NaN();  ///< world y of the north edge of row 0; NaN = rows * cell_m
    execution run = {};  ///< threads, progress, cancellation (core/parallel.hpp); never changes the result
};

/// One planar roof surface.
struct roof_surface {
    std::int32_t id = 0;            ///< 1-based, by decreasing area over the whole raster (as in surface_id)
    std::int32_t building = 0;      ///< id of its building
    double tilt_deg = 0;            ///< 0 horizontal .. 90 vertical, of the least-squares plane of its cells
    double azimuth_deg = 0;         ///< down-slope direction, clockwise from north, [0, 360); 0 if tilt < 1 deg
    double horizontal_area_m2 = 0;  ///< cells x cell_m^2
    double area_m2 = 0;             ///< sloped area = horizontal / cos(tilt), m^2
};

/// One building.
struct building_record {
    std::int32_t id = 0;                 ///< 1-based, by decreasing footprint area (as in building_id)
    std::vector<polygon> outline;        ///< building cells outlined (polygonize: exterior counter-clockwise)
    double ground_z = 0;                 ///< mean terrain elevation under the footprint, metres
    double eave_z = 0;                   ///< 5th percentile of the roof elevation, metres
    double ridge_z = 0;                  ///< 99th percentile of the roof elevation, metres
    double roof_area_horizontal_m2 = 0;  ///< footprint area (cells x cell_m^2)
    double roof_area_sloped_m2 = 0;      ///< sum of its surfaces' sloped areas
    std::vector<std::int32_t> surfaces;  ///< ids of its roof surfaces, largest first
};

/// Buildings of a surface model.
struct extract_buildings_result {
    raster<std::int32_t> building_id;        ///< building of each cell, 0 = none
    raster<std::int32_t> surface_id;         ///< roof surface of each building cell, 0 = none
    raster<float> ground;                    ///< terrain elevation used (DTM), metres
    raster<std::uint8_t> edges;              ///< angular value >= edge angle (ground_model)
    raster<std::uint8_t> vegetation;         ///< vegetation cells as used (input mask, grown into empty cells)
    std::vector<building_record> buildings;  ///< buildings[i].id == i + 1
    std::vector<roof_surface> surfaces;      ///< surfaces[i].id == i + 1
    std::size_t rejected_rough = 0;          ///< candidates dropped as too rough to be roofs (trees without returns)
};

namespace detail {

/// {a, b, c, rms} of the least-squares plane z = a x + b y + c of `s` (core/plane_fit.hpp): a = b = 0 and
/// c = mean when the points are degenerate (collinear or < 3).
inline std::array<double, 4> plane_abc_rms(const plane_sums& s) noexcept
{
    const plane_fit f = fit_plane(s);
    return {f.a, f.b, f.c, f.rms};
}

inline void check_extract_buildings(double cell_m, const extract_buildings_options& opt, const char* function)
{
    check_ground_model(cell_m, opt.ground, function);
    require_positive(opt.min_height_m, function, "min_height_m");
    require(opt.min_area_m2 >= 0 && opt.min_area_m2 < 1e300, function, "min_area_m2", "finite and >= 0",
            opt.min_area_m2);
    require_positive(opt.plane_window_m, function, "plane_window_m");
    require_positive(opt.plane_rms_m, function, "plane_rms_m");
    require(opt.slope_rms_share >= 0 && opt.slope_rms_share < 1e300, function, "slope_rms_share", "finite and >= 0",
            opt.slope_rms_share);
    require(opt.plane_angle_deg > 0 && opt.plane_angle_deg < 90, function, "plane_angle_deg", "in (0, 90)",
            opt.plane_angle_deg);
    require_positive(opt.step_m, function, "step_m");
    require(opt.merge_rms_m >= 0 && opt.merge_rms_m < 1e300, function, "merge_rms_m", "finite and >= 0",
            opt.merge_rms_m);
    require(opt.min_surface_m2 >= 0 && opt.min_surface_m2 < 1e300, function, "min_surface_m2", "finite and >= 0",
            opt.min_surface_m2);
    require(opt.min_planar_share >= 0 && opt.min_planar_share <= 1, function, "min_planar_share", "in [0, 1]",
            opt.min_planar_share);
    require(std::isfinite(opt.x0) && !std::isinf(opt.y0), function, "x0 and y0 must be finite (y0 may be NaN)");
}

/// RMS a plane of squared gradient g2 (tan^2 tilt) may leave and still count as planar: plane_rms_m x (1 +
/// g2), plus slope_rms_share x tan(tilt) x cell_m (a cell's highest return wanders over tan(tilt) x cell_m).
inline double plane_tolerance(const extract_buildings_options& opt, double g2, double cell_m) noexcept
{
    return opt.plane_rms_m * (1.0 + g2) + opt.slope_rms_share * std::sqrt(g2) * cell_m;
}

/// Per building cell: local plane (a, b) and RMS over the cells of the same building within `w` cells.
struct local_planes {
    raster<float> a, b, rms;
};

/// Calls f(rr, cc) for the cells of the (2 w + 1)^2 window around (r, c), clipped to the raster, that have the
/// same id as (r, c), in raster order.
template <class F>
void for_window_of_same_id(raster_view<const std::int32_t> id, std::ptrdiff_t r, std::ptrdiff_t c, std::ptrdiff_t w,
                           F&& f)
{
    const std::int32_t me = id(r, c);
    for (std::ptrdiff_t rr = std::max<std::ptrdiff_t>(0, r - w); rr <= std::min(id.rows() - 1, r + w); ++rr)
        for (std::ptrdiff_t cc = std::max<std::ptrdiff_t>(0, c - w); cc <= std::min(id.cols() - 1, c + w); ++cc)
            if (id(rr, cc) == me) f(rr, cc);
}

inline local_planes fit_local_planes(raster_view<const float> z, raster_view<const std::int32_t> id, double cell_m,
                                     std::ptrdiff_t w, int threads, const char* function)
{
    const std::ptrdiff_t rows = z.rows(), cols = z.cols();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    local_planes lp{raster<float>(rows, cols, nan), raster<float>(rows, cols, nan), raster<float>(rows, cols, nan)};
    // Calls f(r, c) for every building cell, rows split over the threads.
    const auto each_building_cell = [&](auto&& f) {
        parallel_for_rows(
            rows, 16, threads,
            [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
                for (std::ptrdiff_t r = r0; r < r1; ++r)
                    for (std::ptrdiff_t c = 0; c < cols; ++c)
                        if (id(r, c) != 0) f(r, c);
            },
            {}, function);
    };
    each_building_cell([&](std::ptrdiff_t r, std::ptrdiff_t c) {
        plane_sums s;
        for_window_of_same_id(id, r, c, w, [&](std::ptrdiff_t rr, std::ptrdiff_t cc) {
            s.add(static_cast<double>(cc - c) * cell_m, static_cast<double>(r - rr) * cell_m,
                  static_cast<double>(z(rr, cc)) - static_cast<double>(z(r, c)));
        });
        if (s.n < 6) return;
        const auto f = plane_abc_rms(s);
        lp.a(r, c) = static_cast<float>(f[0]);
        lp.b(r, c) = static_cast<float>(f[1]);
        lp.rms(r, c) = static_cast<float>(f[3]);
    });
    // Edge-preserving choice (as the Kuwahara filter): each cell takes the fit of the window, among those
    // holding it (centres within w cells, same building), that leaves the least RMS; a cell next to a ridge
    // so takes the window lying on its own face.
    local_planes best{lp.a, lp.b, lp.rms};
    each_building_cell([&](std::ptrdiff_t r, std::ptrdiff_t c) {
        float least = std::numeric_limits<float>::infinity();
        for_window_of_same_id(id, r, c, w, [&](std::ptrdiff_t rr, std::ptrdiff_t cc) {
            if (!(lp.rms(rr, cc) < least)) return;
            least = lp.rms(rr, cc);
            best.a(r, c) = lp.a(rr, cc);
            best.b(r, c) = lp.b(rr, cc);
            best.rms(r, c) = least;
        });
    });
    return best;
}

/// Root of x in a union-find forest (path halving).
inline std::int32_t uf_find(std::vector<std::int32_t>& parent, std::int32_t x) noexcept
{
    while (parent[static_cast<std::size_t>(x)] != x) {
        parent[static_cast<std::size_t>(x)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
        x = parent[static_cast<std::size_t>(x)];
    }
    return x;
}

}  // namespace detail

/// Buildings of a surface model (dissertation 3.2.1, DESIGN.md section 6), `dsm` in metres (first-return
/// max_z; NaN = no return), cells of cell_m metres, `ground` an optional terrain model of the same shape
/// (e.g. min_z of class 2; NaN cells are filled by IDW; an empty view = find it by ground_model):
///  1. ground_model: DSM holes filled by IDW; edges = angular value >= 45 deg; 8-connected edge objects of
///     >= n cells; one convex hull each; ground = cells outside all hulls, IDW inside (unless `ground` given).
///  2. Building cells: inside a hull, z - ground > min_height_m, not vegetation (the vegetation mask, grown
///     into empty DSM cells next to it); 4-connected parts with holes under min_area_m2 filled; parts
///     smaller than min_area_m2 dropped; parts where less than min_planar_share of the cells are planar
///     (local fit RMS below plane_tolerance) dropped as rough (canopy). Numbered by area, largest first.
///  3. Surfaces (beyond the seed, which splits by height level only): a least-squares plane over the
///     building's cells in the square window of half-side plane_window_m around each cell; each cell then
///     takes, of the windows holding it, the one with the least RMS (edge-preserving, as the Kuwahara
///     filter), so cells beside a ridge keep their own face's normal; planar cells (RMS below
///     plane_tolerance) grown into regions (4-neighbours within plane_angle_deg of the region's mean normal and
///     within step_m of its slope); regions under min_surface_m2 dissolved; every other building cell (eaves,
///     ridges, wall tops) given, layer by layer, to the neighbouring surface whose plane is nearest its height
///     (the seed's rule, with fitted planes); adjacent surfaces merged, best pair first, while one plane fits
///     both with an RMS <= plane_tolerance x merge_rms_m / plane_rms_m. Planes are fitted to the grown cells
///     only (cells given later do not tilt them). Numbered by area, largest first.
/// Tilt and azimuth from each surface's least-squares plane; outlines from polygonize (exterior counter-
/// clockwise) on the grid {x0, y0, cell_m}. O(cells * ((2 w + 1)^2 + radius^2 + idw_k)), w the window
/// in cells. Same result for any thread count.
/// @throws invalid_input on bad options, shapes that differ, or a DSM without a finite cell; cancelled if
/// run.progress returns false.
template <raster_input In>
extract_buildings_result extract_buildings(const In& dsm, double cell_m, raster_view<const float> ground,
                                           const extract_buildings_options& opt = {})
{
    constexpr const char* function = "extract_buildings";
    detail::check_extract_buildings(cell_m, opt, function);
    const std::ptrdiff_t rows = dsm.rows(), cols = dsm.cols();
    if (!ground.empty()) detail::require_same_shape(dsm, ground, function, "dsm", "ground");
    if (!opt.vegetation.empty()) detail::require_same_shape(dsm, opt.vegetation, function, "dsm", "vegetation");
    extract_buildings_result out;
    out.building_id = raster<std::int32_t>(rows, cols);
    out.surface_id = raster<std::int32_t>(rows, cols);
    out.vegetation = raster<std::uint8_t>(rows, cols);
    if (rows == 0 || cols == 0) return out;
    const double cell2 = cell_m * cell_m;
    const int threads = opt.run.threads;

    // 1. Terrain, edges and hulls.
    ground_model_options gopt = opt.ground;
    gopt.run = {threads, {}};
    ground_model_result gm = ground_model(dsm, cell_m, gopt);
    detail::report(opt.run.progress, 0.3, function);
    if (!ground.empty()) {
        raster<float> given(rows, cols);
        bool any = false;
        for (std::ptrdiff_t r = 0; r < rows; ++r) {
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                const float v = ground(r, c);
                given(r, c) = std::isfinite(v) ? v : std::numeric_limits<float>::quiet_NaN();
                any = any || std::isfinite(v);
            }
        }
        detail::require(any, function, "ground has no finite cell: pass an empty view to estimate the terrain");
        idw_fill(given, gm.ground, cell_m,
                 idw_fill_options{.k = gopt.idw_k, .power = gopt.idw_power, .run = {threads, {}}});
    }
    const raster<float>& z = gm.surface;

    // 2. Building cells.
    if (!opt.vegetation.empty()) {
        for (std::ptrdiff_t r = 0; r < rows; ++r) {
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                bool v = opt.vegetation(r, c) != 0;
                if (!v && !std::isfinite(static_cast<float>(dsm(r, c)))) {
                    for (std::ptrdiff_t dr = -1; dr <= 1 && !v; ++dr) {
                        for (std::ptrdiff_t dc = -1; dc <= 1 && !v; ++dc) {
                            const std::ptrdiff_t rr = r + dr, cc = c + dc;
                            v = rr >= 0 && cc >= 0 && rr < rows && cc < cols && opt.vegetation(rr, cc) != 0;
                        }
                    }
                }
                out.vegetation(r, c) = v ? 1 : 0;
            }
        }
    }
    raster<std::uint8_t> candidate(rows, cols);
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const bool high = static_cast<double>(z(r, c)) - static_cast<double>(gm.ground(r, c)) > opt.min_height_m;
            candidate(r, c) = gm.in_hull(r, c) && high && !out.vegetation(r, c) ? 1 : 0;
        }
    }
    const auto min_cells = static_cast<std::size_t>(std::ceil(opt.min_area_m2 / cell2 - 1e-9));
    candidate = fill_holes(candidate, min_cells > 0 ? min_cells - 1 : 0, connectivity::four);
    components parts =
        connected_components(candidate, connected_components_options{.conn = connectivity::four, .run = {threads, {}}});
    rank_by_size(parts);
    std::size_t kept = 0;
    while (kept < parts.count() && parts.sizes[kept + 1] >= std::max<std::size_t>(1, min_cells)) ++kept;
    for (std::ptrdiff_t i = 0; i < out.building_id.size(); ++i) {
        const auto l = static_cast<std::size_t>(parts.labels.data()[i]);
        out.building_id.data()[i] = l <= kept ? static_cast<std::int32_t>(l) : 0;
    }
    detail::report(opt.run.progress, 0.45, function);

    // 3. Local planes; rough parts (canopy) are dropped and the rest renumbered.
    const auto w = std::max<std::ptrdiff_t>(1, std::lround(opt.plane_window_m / cell_m));
    auto lp = detail::fit_local_planes(z.view(), out.building_id.view(), cell_m, w, threads, function);
    const auto planar_at = [&](std::ptrdiff_t r, std::ptrdiff_t c) {
        if (!std::isfinite(lp.rms(r, c))) return false;
        // Steep faces scatter more within a cell (z varies by tan(tilt) * cell_m across it): the tolerance
        // grows with the secant of the tilt squared.
        const double g2 = static_cast<double>(lp.a(r, c)) * lp.a(r, c) + static_cast<double>(lp.b(r, c)) * lp.b(r, c);
        return static_cast<double>(lp.rms(r, c)) < detail::plane_tolerance(opt, g2, cell_m);
    };
    {
        std::vector<std::size_t> planar(kept + 1, 0), cells(kept + 1, 0);
        for (std::ptrdiff_t r = 0; r < rows; ++r) {
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                const auto b = static_cast<std::size_t>(out.building_id(r, c));
                if (b == 0) continue;
                ++cells[b];
                planar[b] += planar_at(r, c) ? 1 : 0;
            }
        }
        std::vector<std::int32_t> renumber(kept + 1, 0);
        std::int32_t next = 0;
        for (std::size_t b = 1; b <= kept; ++b) {
            const bool smooth = static_cast<double>(planar[b]) >= opt.min_planar_share * static_cast<double>(cells[b]);
            if (smooth)
                renumber[b] = ++next;
            else
                ++out.rejected_rough;
        }
        for (auto& v : out.building_id) v = renumber[static_cast<std::size_t>(v)];
        kept = static_cast<std::size_t>(next);
    }
    detail::report(opt.run.progress, 0.6, function);

    // 4. Regions of planar cells, grown in order of increasing local RMS (ties by raster order).
    const auto idx = [cols](std::ptrdiff_t r, std::ptrdiff_t c) { return static_cast<std::size_t>(r * cols + c); };
    const auto x_of = [&](std::ptrdiff_t c) { return static_cast<double>(c) * cell_m; };
    const auto y_of = [&](std::ptrdiff_t r) { return -static_cast<double>(r) * cell_m; };
    std::vector<std::int32_t> region(static_cast<std::size_t>(rows * cols), 0);
    std::vector<std::size_t> seeds;
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            if (out.building_id(r, c) != 0 && planar_at(r, c)) seeds.push_back(idx(r, c));
        }
    }
    std::stable_sort(seeds.begin(), seeds.end(),
                     [&](std::size_t p, std::size_t q) { return lp.rms.data()[p] < lp.rms.data()[q]; });
    constexpr std::ptrdiff_t dr4[] = {-1, 1, 0, 0}, dc4[] = {0, 0, -1, 1};
    std::int32_t regions = 0;
    std::vector<std::size_t> queue;
    std::vector<std::uint8_t> core(region.size(), 0);  // 1 = cell joined its surface by growing
    for (const std::size_t s : seeds) {
        if (region[s] != 0) continue;
        const std::int32_t id = ++regions;
        region[s] = id;
        core[s] = 1;
        queue.assign(1, s);
        double sa = lp.a.data()[s], sb = lp.b.data()[s], n = 1;
        for (std::size_t head = 0; head < queue.size(); ++head) {
            const std::size_t p = queue[head];
            const auto pr = static_cast<std::ptrdiff_t>(p) / cols, pc = static_cast<std::ptrdiff_t>(p) % cols;
            for (int k = 0; k < 4; ++k) {
                const std::ptrdiff_t rr = pr + dr4[k], cc = pc + dc4[k];
                if (rr < 0 || cc < 0 || rr >= rows || cc >= cols) continue;
                const std::size_t q = idx(rr, cc);
                if (region[q] != 0 || out.building_id.data()[q] != out.building_id.data()[p] || !planar_at(rr, cc))
                    continue;
                const double ma = sa / n, mb = sb / n;
                if (normal_angle_deg(lp.a.data()[q], lp.b.data()[q], ma, mb) > opt.plane_angle_deg) continue;
                const double expected = ma * (x_of(cc) - x_of(pc)) + mb * (y_of(rr) - y_of(pr));
                if (std::abs(static_cast<double>(z.data()[q]) - static_cast<double>(z.data()[p]) - expected) >
                    opt.step_m)
                    continue;
                region[q] = id;
                core[q] = 1;
                sa += lp.a.data()[q];
                sb += lp.b.data()[q];
                n += 1;
                queue.push_back(q);
            }
        }
    }

    // 5. Fit, dissolve small regions, give the other building cells to the nearest plane in height; merge.
    // Planes are fitted to the grown (planar) cells of a surface, so that cells given to it later (eaves
    // mixed with the wall, filled holes) do not tilt it; a surface without any takes all its cells.
    const auto fit_regions = [&](std::int32_t count, bool core_only = true) {
        std::vector<plane_sums> sums(static_cast<std::size_t>(count) + 1), all(sums.size());
        for (std::ptrdiff_t r = 0; r < rows; ++r) {
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                const auto g = static_cast<std::size_t>(region[idx(r, c)]);
                if (g == 0) continue;
                all[g].add(x_of(c), y_of(r), static_cast<double>(z(r, c)));
                if (core[idx(r, c)]) sums[g].add(x_of(c), y_of(r), static_cast<double>(z(r, c)));
            }
        }
        if (!core_only) return all;
        for (std::size_t g = 1; g < sums.size(); ++g) {
            if (sums[g].n < 3) sums[g] = all[g];
        }
        return sums;
    };
    const auto min_surface_cells = opt.min_surface_m2 / cell2;
    const auto grow_into_rest = [&](const std::vector<std::array<double, 4>>& planes) {
        // Layer by layer: a cell next to surfaces takes the one whose plane is nearest its height; decisions
        // of one layer read only earlier layers.
        std::vector<std::size_t> frontier, next_frontier;
        std::vector<std::pair<std::size_t, std::int32_t>> taken;
        for (std::ptrdiff_t r = 0; r < rows; ++r) {
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                if (out.building_id(r, c) != 0 && region[idx(r, c)] == 0) frontier.push_back(idx(r, c));
            }
        }
        while (!frontier.empty()) {
            taken.clear();
            next_frontier.clear();
            for (const std::size_t p : frontier) {
                const auto pr = static_cast<std::ptrdiff_t>(p) / cols, pc = static_cast<std::ptrdiff_t>(p) % cols;
                std::int32_t best = 0;
                double best_d = std::numeric_limits<double>::infinity();
                for (std::ptrdiff_t dr = -1; dr <= 1; ++dr) {
                    for (std::ptrdiff_t dc = -1; dc <= 1; ++dc) {
                        const std::ptrdiff_t rr = pr + dr, cc = pc + dc;
                        if (rr < 0 || cc < 0 || rr >= rows || cc >= cols) continue;
                        const std::size_t q = idx(rr, cc);
                        const std::int32_t g = region[q];
                        if (g <= 0 || out.building_id.data()[q] != out.building_id.data()[p]) continue;
                        const auto& f = planes[static_cast<std::size_t>(g)];
                        const double d =
                            std::abs(static_cast<double>(z.data()[p]) - (f[0] * x_of(pc) + f[1] * y_of(pr) + f[2]));
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
            if (taken.empty()) break;  // cells of buildings without any surface: handled by the caller
            for (const auto& [p, g] : taken) region[p] = g;
            frontier.swap(next_frontier);
        }
    };
    {
        auto sums = fit_regions(regions);
        std::vector<std::int32_t> renumber(static_cast<std::size_t>(regions) + 1, 0);
        std::int32_t next = 0;
        for (std::int32_t g = 1; g <= regions; ++g) {
            if (sums[static_cast<std::size_t>(g)].n >= std::max(1.0, min_surface_cells))
                renumber[static_cast<std::size_t>(g)] = ++next;
        }
        for (std::size_t p = 0; p < region.size(); ++p) {
            region[p] = renumber[static_cast<std::size_t>(region[p])];
            if (region[p] == 0) core[p] = 0;
        }
        regions = next;
        // A building with no surface left becomes one surface.
        std::vector<std::int32_t> whole(kept + 1, 0);
        for (std::size_t p = 0; p < region.size(); ++p) {
            const auto b = static_cast<std::size_t>(out.building_id.data()[p]);
            if (b != 0 && region[p] != 0) whole[b] = -1;
        }
        for (std::size_t p = 0; p < region.size(); ++p) {
            const auto b = static_cast<std::size_t>(out.building_id.data()[p]);
            if (b == 0 || whole[b] < 0) continue;
            if (whole[b] == 0) whole[b] = ++regions;
            region[p] = whole[b];
        }
    }
    {
        auto sums = fit_regions(regions);
        std::vector<std::array<double, 4>> planes(sums.size());
        for (std::size_t g = 1; g < sums.size(); ++g) planes[g] = detail::plane_abc_rms(sums[g]);
        {
            grow_into_rest(planes);
            sums = fit_regions(regions);
            for (std::size_t g = 1; g < sums.size(); ++g) planes[g] = detail::plane_abc_rms(sums[g]);
            // Merge adjacent surfaces of one building while one plane fits both: the pair whose joint fit leaves
            // the least RMS / (1 + tan^2 tilt), while that is <= merge_rms_m.
            std::vector<std::int32_t> parent(static_cast<std::size_t>(regions) + 1);
            std::iota(parent.begin(), parent.end(), 0);
            std::vector<std::pair<std::int32_t, std::int32_t>> pairs;
            for (std::ptrdiff_t r = 0; r < rows; ++r) {
                for (std::ptrdiff_t c = 0; c < cols; ++c) {
                    const std::int32_t g = region[idx(r, c)];
                    if (g <= 0) continue;
                    for (int k = 0; k < 2; ++k) {  // south and east neighbours
                        const std::ptrdiff_t rr = r + (k == 0 ? 1 : 0), cc = c + (k == 1 ? 1 : 0);
                        if (rr >= rows || cc >= cols) continue;
                        const std::int32_t h = region[idx(rr, cc)];
                        if (h > 0 && h != g) pairs.emplace_back(std::min(g, h), std::max(g, h));
                    }
                }
            }
            std::sort(pairs.begin(), pairs.end());
            pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
            for (;;) {
                double least = std::numeric_limits<double>::infinity();
                std::pair<std::int32_t, std::int32_t> chosen{0, 0};
                for (auto& [g, h] : pairs) {
                    g = detail::uf_find(parent, g);
                    h = detail::uf_find(parent, h);
                    if (g == h) continue;
                    plane_sums joint = sums[static_cast<std::size_t>(g)];
                    joint.add(sums[static_cast<std::size_t>(h)]);
                    const auto f =
                        detail::plane_abc_rms(joint);  // RMS relative to the tolerance of planar cells at its slope
                    const double rise =
                        f[3] / detail::plane_tolerance(opt, f[0] * f[0] + f[1] * f[1], cell_m) * opt.plane_rms_m;
                    if (rise < least || (rise == least && std::pair{std::min(g, h), std::max(g, h)} < chosen)) {
                        least = rise;
                        chosen = {std::min(g, h), std::max(g, h)};
                    }
                }
                if (!(least <= opt.merge_rms_m)) break;
                parent[static_cast<std::size_t>(chosen.second)] = chosen.first;
                sums[static_cast<std::size_t>(chosen.first)].add(sums[static_cast<std::size_t>(chosen.second)]);
            }
            for (auto& g : region) {
                if (g > 0) g = detail::uf_find(parent, g);
            }
        }
    }
    detail::report(opt.run.progress, 0.85, function);

    // 6. Number surfaces by area (largest first; ties by first cell), describe them and the buildings.
    const auto sums = fit_regions(regions, false);
    const auto planes_fit = fit_regions(regions);
    std::vector<std::int32_t> owner(static_cast<std::size_t>(regions) + 1, 0);
    std::vector<std::size_t> first_cell(static_cast<std::size_t>(regions) + 1, region.size());
    for (std::size_t p = 0; p < region.size(); ++p) {
        const auto g = static_cast<std::size_t>(region[p]);
        if (g == 0) continue;
        owner[g] = out.building_id.data()[p];
        first_cell[g] = std::min(first_cell[g], p);
    }
    std::vector<std::int32_t> order;
    for (std::int32_t g = 1; g <= regions; ++g) {
        if (sums[static_cast<std::size_t>(g)].n > 0) order.push_back(g);
    }
    std::sort(order.begin(), order.end(), [&](std::int32_t p, std::int32_t q) {
        const auto& a = sums[static_cast<std::size_t>(p)];
        const auto& b = sums[static_cast<std::size_t>(q)];
        if (a.n != b.n) return a.n > b.n;
        return first_cell[static_cast<std::size_t>(p)] < first_cell[static_cast<std::size_t>(q)];
    });
    std::vector<std::int32_t> surface_of(static_cast<std::size_t>(regions) + 1, 0);
    out.buildings.resize(kept);
    for (std::size_t b = 0; b < kept; ++b) out.buildings[b].id = static_cast<std::int32_t>(b + 1);
    for (std::size_t i = 0; i < order.size(); ++i) {
        const auto g = static_cast<std::size_t>(order[i]);
        const auto f = detail::plane_abc_rms(planes_fit[g]);
        roof_surface s;
        s.id = static_cast<std::int32_t>(i + 1);
        s.building = owner[g];
        const double grad = std::hypot(f[0], f[1]);
        s.tilt_deg = std::atan(grad) * 180.0 / std::numbers::pi;
        s.azimuth_deg =
            s.tilt_deg < 1.0 ? 0.0 : std::fmod(std::atan2(-f[0], -f[1]) * 180.0 / std::numbers::pi + 360.0, 360.0);
        s.horizontal_area_m2 = sums[g].n * cell2;
        s.area_m2 = s.horizontal_area_m2 * std::sqrt(1.0 + grad * grad);
        surface_of[g] = s.id;
        auto& rec = out.buildings[static_cast<std::size_t>(s.building - 1)];
        rec.surfaces.push_back(s.id);
        rec.roof_area_sloped_m2 += s.area_m2;
        out.surfaces.push_back(s);
    }
    std::vector<std::vector<float>> heights(kept);
    std::vector<double> ground_sum(kept, 0.0);
    for (std::size_t p = 0; p < region.size(); ++p) {
        out.surface_id.data()[p] = surface_of[static_cast<std::size_t>(region[p])];
        const auto b = static_cast<std::size_t>(out.building_id.data()[p]);
        if (b == 0) continue;
        heights[b - 1].push_back(z.data()[p]);
        ground_sum[b - 1] += static_cast<double>(gm.ground.data()[p]);
    }
    for (std::size_t b = 0; b < kept; ++b) {
        auto& h = heights[b];
        auto& rec = out.buildings[b];
        std::sort(h.begin(), h.end());
        const auto at = [&](double q) {
            return static_cast<double>(h[static_cast<std::size_t>(q * static_cast<double>(h.size() - 1))]);
        };
        rec.eave_z = at(0.05);
        rec.ridge_z = at(0.99);
        rec.ground_z = ground_sum[b] / static_cast<double>(h.size());
        rec.roof_area_horizontal_m2 = static_cast<double>(h.size()) * cell2;
    }
    const double y0 = std::isnan(opt.y0) ? static_cast<double>(rows) * cell_m : opt.y0;
    const grid g{opt.x0, y0, cell_m, rows, cols};
    for (auto& lp_outline : polygonize(out.building_id, g)) {
        out.buildings[static_cast<std::size_t>(lp_outline.label - 1)].outline = std::move(lp_outline.polygons);
    }
    out.ground = std::move(gm.ground);
    out.edges = std::move(gm.edges);
    detail::report(opt.run.progress, 1.0, function);
    return out;
}

/// extract_buildings with the terrain found by ground_model (no ground raster).
template <raster_input In>
extract_buildings_result extract_buildings(const In& dsm, double cell_m, const extract_buildings_options& opt = {})
{
    return extract_buildings(dsm, cell_m, raster_view<const float>{}, opt);
}

}  // namespace lidarfx
