// SPDX-License-Identifier: Apache-2.0
// local_planes: a least-squares plane around every building cell (edge-preserving window choice), the planar
// test on it, and drop_rough_buildings, which drops candidate parts too rough to be roofs (extract_buildings
// step 3).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/plane_fit.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// Settings of local_planes, is_planar and drop_rough_buildings.
struct local_planes_options {
    double plane_window_m = 1.5;     ///< half-side of the window of each cell's local plane fit, metres (>= 1 cell)
    double plane_rms_m = 0.12;       ///< a cell whose local fit leaves an RMS below this x (1 + tan^2 tilt) (plus
                                     ///< slope_rms_share, see plane_tolerance) is planar, metres; > 0
    double slope_rms_share = 0.15;   ///< extra planar tolerance per metre of rise across a cell (plane_tolerance)
    double min_planar_share = 0.25;  ///< a building needs this share of planar cells, else it is rough (a tree)
};

/// Per building cell: the local plane z = a x + b y + c (a slope east, b slope north, metres per metre) and the
/// RMS it leaves, metres; NaN for cells outside buildings and where no window has 6 cells.
struct local_planes_result {
    raster<float> a, b, rms;
};

/// Local planes of the building cells (id != 0) of a surface z (metres, cells of cell_m metres): a least-squares
/// plane over the cells of the same id in the square window of half-side w = max(1, round(plane_window_m /
/// cell_m)) cells around each cell (at least 6 cells); each cell then takes, of the windows holding it (centres
/// within w cells, same id), the fit that leaves the least RMS (edge-preserving, as the Kuwahara filter), so a
/// cell beside a ridge keeps its own face's normal. O(cells * (2 w + 1)^2). Same bits for any run.threads.
/// @throws invalid_input on bad options or cell_m, or if z and id differ in shape.
inline local_planes_result local_planes(raster_view<const float> z, raster_view<const std::int32_t> id, double cell_m,
                                        const local_planes_options& opt = {}, const execution& run = {});

/// RMS a plane of squared gradient g2 (tan^2 tilt) may leave and still count as planar, metres: plane_rms_m x
/// (1 + g2) + slope_rms_share x tan(tilt) x cell_m (steep faces scatter more within a cell: a cell's highest
/// return wanders over tan(tilt) x cell_m). Never throws.
inline double plane_tolerance(const local_planes_options& opt, double g2, double cell_m) noexcept
{
    return opt.plane_rms_m * (1.0 + g2) + opt.slope_rms_share * std::sqrt(g2) * cell_m;
}

/// True when cell (r, c) has a local plane whose RMS is below its plane_tolerance. Never throws.
inline bool is_planar(const local_planes_result& lp, std::ptrdiff_t r, std::ptrdiff_t c, double cell_m,
                      const local_planes_options& opt) noexcept
{
    if (!std::isfinite(lp.rms(r, c))) return false;
    const double g2 = static_cast<double>(lp.a(r, c)) * lp.a(r, c) + static_cast<double>(lp.b(r, c)) * lp.b(r, c);
    return static_cast<double>(lp.rms(r, c)) < plane_tolerance(opt, g2, cell_m);
}

/// Drops, in place, the parts 1..count of `building_id` where less than min_planar_share of the cells are planar
/// (is_planar): rough surfaces, tree crowns without returns. The others keep their order and are renumbered
/// 1..kept. Returns {kept, dropped}. O(cells).
/// @throws invalid_input if the shapes differ or min_planar_share is not in [0, 1].
inline std::array<std::size_t, 2> drop_rough_buildings(raster_view<std::int32_t> building_id, std::size_t count,
                                                       const local_planes_result& lp, double cell_m,
                                                       const local_planes_options& opt = {});

namespace detail {

inline void check_local_planes(const local_planes_options& opt, const char* function)
{
    require_positive(opt.plane_window_m, function, "plane_window_m");
    require_positive(opt.plane_rms_m, function, "plane_rms_m");
    require(opt.slope_rms_share >= 0 && opt.slope_rms_share < 1e300, function, "slope_rms_share", "finite and >= 0",
            opt.slope_rms_share);
    require(opt.min_planar_share >= 0 && opt.min_planar_share <= 1, function, "min_planar_share", "in [0, 1]",
            opt.min_planar_share);
}

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

}  // namespace detail

// ---- implementation ----

inline local_planes_result local_planes(raster_view<const float> z, raster_view<const std::int32_t> id, double cell_m,
                                        const local_planes_options& opt, const execution& run)
{
    constexpr const char* function = "local_planes";
    detail::require_positive(cell_m, function, "cell_m");
    detail::check_local_planes(opt, function);
    detail::check_execution(run, function);
    detail::require_same_shape(z, id, function, "z", "id");
    const std::ptrdiff_t rows = z.rows(), cols = z.cols();
    const auto w = std::max<std::ptrdiff_t>(1, std::lround(opt.plane_window_m / cell_m));
    const float nan = std::numeric_limits<float>::quiet_NaN();
    local_planes_result lp{raster<float>(rows, cols, nan), raster<float>(rows, cols, nan),
                           raster<float>(rows, cols, nan)};
    // Calls f(r, c) for every building cell, rows split over the threads.
    const auto each_building_cell = [&](auto&& f) {
        parallel_for_rows(
            rows, 16, run.threads,
            [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
                for (std::ptrdiff_t r = r0; r < r1; ++r)
                    for (std::ptrdiff_t c = 0; c < cols; ++c)
                        if (id(r, c) != 0) f(r, c);
            },
            {}, function);
    };
    each_building_cell([&](std::ptrdiff_t r, std::ptrdiff_t c) {
        plane_sums s;
        detail::for_window_of_same_id(id, r, c, w, [&](std::ptrdiff_t rr, std::ptrdiff_t cc) {
            s.add(static_cast<double>(cc - c) * cell_m, static_cast<double>(r - rr) * cell_m,
                  static_cast<double>(z(rr, cc)) - static_cast<double>(z(r, c)));
        });
        if (s.n < 6) return;
        const plane_fit f = fit_plane(s);
        lp.a(r, c) = static_cast<float>(f.a);
        lp.b(r, c) = static_cast<float>(f.b);
        lp.rms(r, c) = static_cast<float>(f.rms);
    });
    // Edge-preserving choice (as the Kuwahara filter): each cell takes the fit of the window, among those
    // holding it, that leaves the least RMS; a cell next to a ridge so takes the window lying on its own face.
    local_planes_result best{lp.a, lp.b, lp.rms};
    each_building_cell([&](std::ptrdiff_t r, std::ptrdiff_t c) {
        float least = std::numeric_limits<float>::infinity();
        detail::for_window_of_same_id(id, r, c, w, [&](std::ptrdiff_t rr, std::ptrdiff_t cc) {
            if (!(lp.rms(rr, cc) < least)) return;
            least = lp.rms(rr, cc);
            best.a(r, c) = lp.a(rr, cc);
            best.b(r, c) = lp.b(rr, cc);
            best.rms(r, c) = least;
        });
    });
    return best;
}

inline std::array<std::size_t, 2> drop_rough_buildings(raster_view<std::int32_t> building_id, std::size_t count,
                                                       const local_planes_result& lp, double cell_m,
                                                       const local_planes_options& opt)
{
    constexpr const char* function = "drop_rough_buildings";
    detail::require(opt.min_planar_share >= 0 && opt.min_planar_share <= 1, function, "min_planar_share", "in [0, 1]",
                    opt.min_planar_share);
    detail::require_same_shape(building_id, lp.rms, function, "building_id", "lp");
    std::vector<std::size_t> planar(count + 1, 0), cells(count + 1, 0);
    for (std::ptrdiff_t r = 0; r < building_id.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < building_id.cols(); ++c) {
            const auto b = static_cast<std::size_t>(building_id(r, c));
            if (b == 0) continue;
            ++cells[b];
            planar[b] += is_planar(lp, r, c, cell_m, opt) ? 1 : 0;
        }
    }
    std::vector<std::int32_t> renumber(count + 1, 0);
    std::int32_t next = 0;
    std::size_t dropped = 0;
    for (std::size_t b = 1; b <= count; ++b) {
        if (static_cast<double>(planar[b]) >= opt.min_planar_share * static_cast<double>(cells[b]))
            renumber[b] = ++next;
        else
            ++dropped;
    }
    for (std::ptrdiff_t r = 0; r < building_id.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < building_id.cols(); ++c)
            building_id(r, c) = renumber[static_cast<std::size_t>(building_id(r, c))];
    return {static_cast<std::size_t>(next), dropped};
}

}  // namespace lidarfx
