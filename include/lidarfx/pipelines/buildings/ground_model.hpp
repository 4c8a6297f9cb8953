// SPDX-License-Identifier: Apache-2.0
// ground_model: a terrain model (DTM) of an unclassified surface model by the dissertation's hull-and-IDW
// route (3.2.1): steep edges -> edge objects -> one convex hull each -> ground outside the hulls -> IDW inside.
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
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/kernels/filter/angular_filter.hpp"
#include "lidarfx/kernels/interpolate/idw_fill.hpp"
#include "lidarfx/kernels/label/connected_components.hpp"

namespace lidarfx {

/// Settings of ground_model.
struct ground_model_options {
    double edge_angle_deg = 45.0;     ///< edge where the angular value >= this, degrees (dissertation: 45); in (0, 90)
    int angular_radius_cells = 2;     ///< window half-size of the angular filter, cells (2 = "two tiers"); >= 1
    std::size_t min_edge_cells = 10;  ///< an edge object (8-connected) needs at least this many cells (the n); >= 1
    int idw_k = 8;                    ///< ground cells averaged per filled cell (idw_fill); >= 1
    double idw_power = 1.0;           ///< IDW weight exponent (1 = dissertation eq. 3); > 0
    execution run = {};               ///< threads, progress, cancellation (core/parallel.hpp); never changes the result
};

/// A terrain model and how it was found, each raster of the DSM's shape.
struct ground_model_result {
    raster<float> surface;         ///< the DSM with its NaN cells (no return) filled by IDW, metres
    raster<float> ground;          ///< terrain elevation (DTM), metres: surface outside the hulls, IDW inside
    raster<std::uint8_t> edges;    ///< 1 = angular value >= edge_angle_deg
    raster<std::int32_t> objects;  ///< edge object of each kept edge cell (1.. by decreasing size), 0 = none
    raster<std::uint8_t> in_hull;  ///< 1 = cell centre inside (or on) the convex hull of some kept edge object
    std::size_t object_count = 0;  ///< kept edge objects
};

namespace detail {

/// Convex hull (Andrew's monotone chain) of integer points (col, row), counter-clockwise in (col, row)
/// axes, collinear points dropped; exact (64-bit cross products). O(n log n).
inline std::vector<std::array<std::int64_t, 2>> convex_hull(std::vector<std::array<std::int64_t, 2>> p)
{
    std::sort(p.begin(), p.end());
    p.erase(std::unique(p.begin(), p.end()), p.end());
    if (p.size() < 3) return p;
    const auto cross = [](const auto& o, const auto& a, const auto& b) {
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
    };
    std::vector<std::array<std::int64_t, 2>> h(2 * p.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
        h[k++] = p[i];
    }
    for (std::size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
        while (k >= t && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
        h[k++] = p[i];
    }
    h.resize(k - 1);
    return h;
}

/// Sets mask(r, c) = 1 for every cell whose centre (c, r) lies inside or on the convex polygon `hull`
/// (counter-clockwise in (col, row) axes; one or two points mark just those cells / that segment's cells).
inline void burn_convex(const std::vector<std::array<std::int64_t, 2>>& hull, raster_view<std::uint8_t> mask)
{
    if (hull.empty()) return;
    std::int64_t r0 = hull[0][1], r1 = r0, c0 = hull[0][0], c1 = c0;
    for (const auto& v : hull) {
        r0 = std::min(r0, v[1]);
        r1 = std::max(r1, v[1]);
        c0 = std::min(c0, v[0]);
        c1 = std::max(c1, v[0]);
    }
    const std::size_t n = hull.size();
    for (std::int64_t r = r0; r <= r1; ++r) {
        for (std::int64_t c = c0; c <= c1; ++c) {
            bool inside = true;
            for (std::size_t i = 0; i < n && inside; ++i) {
                const auto& a = hull[i];
                const auto& b = hull[(i + 1) % n];
                const std::int64_t cr = (b[0] - a[0]) * (r - a[1]) - (b[1] - a[1]) * (c - a[0]);
                if (n >= 3)
                    inside = cr >= 0;
                else if (n == 2)
                    inside = cr == 0 && std::min(a[0], b[0]) <= c && c <= std::max(a[0], b[0]) &&
                             std::min(a[1], b[1]) <= r && r <= std::max(a[1], b[1]);
            }
            if (n == 1) inside = r == hull[0][1] && c == hull[0][0];
            if (inside) mask(static_cast<std::ptrdiff_t>(r), static_cast<std::ptrdiff_t>(c)) = 1;
        }
    }
}

inline void check_ground_model(double cell_m, const ground_model_options& opt, const char* function)
{
    require_positive(cell_m, function, "cell_m");
    require(opt.edge_angle_deg > 0 && opt.edge_angle_deg < 90, function, "edge_angle_deg", "in (0, 90)",
            opt.edge_angle_deg);
    require(opt.angular_radius_cells >= 1, function, "angular_radius_cells", ">= 1", opt.angular_radius_cells);
    require(opt.min_edge_cells >= 1, function, "min_edge_cells", ">= 1", opt.min_edge_cells);
    require(opt.idw_k >= 1, function, "idw_k", ">= 1", opt.idw_k);
    require_positive(opt.idw_power, function, "idw_power");
    check_execution(opt.run, function);
}

}  // namespace detail

/// Terrain model of a surface model without ground classes (dissertation 3.2.1): (1) NaN cells of `dsm`
/// (no return) are filled by IDW (idw_fill, idw_k nearest, weight 1 / d^idw_power); (2) edges = cells whose
/// angular value (angular_filter, angular_radius_cells) is >= edge_angle_deg: a neighbour x metres away
/// may differ by at most x * tan(edge_angle_deg) metres within one plane; (3) 8-connected edge objects of
/// fewer than min_edge_cells cells are dropped; (4) one convex hull per kept object, over its cell centres;
/// (5) ground = the surface at cells outside every hull; inside the hulls it is IDW of the ground cells.
/// nDSM = surface - ground (see ndsm). Elevations in metres, cell_m the cell size in metres. O(cells * (
/// radius^2 + idw_k)) plus the hulls' bounding boxes. Same bits for any thread count.
/// @throws invalid_input on bad options, cell_m not finite and > 0, or a DSM without a finite cell
/// ("...: dsm has no finite cell"); cancelled if run.progress returns false.
template <raster_input In>
ground_model_result ground_model(const In& dsm, double cell_m, const ground_model_options& opt = {})
{
    constexpr const char* function = "ground_model";
    detail::check_ground_model(cell_m, opt, function);
    const std::ptrdiff_t rows = dsm.rows(), cols = dsm.cols();
    ground_model_result out;
    out.surface = raster<float>(rows, cols);
    out.ground = raster<float>(rows, cols);
    out.edges = raster<std::uint8_t>(rows, cols);
    out.in_hull = raster<std::uint8_t>(rows, cols);
    out.objects = raster<std::int32_t>(rows, cols);
    if (rows == 0 || cols == 0) return out;
    bool any = false, holes = false;
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const auto v = static_cast<float>(dsm(r, c));
            out.surface(r, c) = v;
            any = any || std::isfinite(v);
            holes = holes || !std::isfinite(v);
        }
    }
    detail::require(any, function, "dsm has no finite cell: pass a surface model with at least one return");
    const idw_fill_options fill{.k = opt.idw_k, .radius_m = 0, .power = opt.idw_power, .run = {opt.run.threads, {}}};
    if (holes) {
        raster<float> raw = out.surface;
        for (auto& v : raw) v = std::isfinite(v) ? v : std::numeric_limits<float>::quiet_NaN();
        idw_fill(raw, out.surface, cell_m, fill);
    }
    const raster<float> angle =
        angular_filter(out.surface, cell_m,
                       angular_filter_options{.radius_cells = opt.angular_radius_cells, .run = {opt.run.threads, {}}});
    detail::report(opt.run.progress, 0.3, function);
    const auto threshold = static_cast<float>(opt.edge_angle_deg);
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) out.edges(r, c) = angle(r, c) >= threshold ? 1 : 0;
    }
    components objects = connected_components(
        out.edges, connected_components_options{.conn = connectivity::eight, .run = {opt.run.threads, {}}});
    rank_by_size(objects);
    std::size_t kept = 0;
    while (kept < objects.count() && objects.sizes[kept + 1] >= opt.min_edge_cells) ++kept;
    out.object_count = kept;
    std::vector<std::vector<std::array<std::int64_t, 2>>> points(kept);
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const auto l = static_cast<std::size_t>(objects.labels(r, c));
            if (l == 0 || l > kept) continue;
            out.objects(r, c) = static_cast<std::int32_t>(l);
            points[l - 1].push_back({c, r});
        }
    }
    for (auto& p : points) detail::burn_convex(detail::convex_hull(std::move(p)), out.in_hull.view());
    detail::report(opt.run.progress, 0.5, function);

    raster<float> known(rows, cols, std::numeric_limits<float>::quiet_NaN());
    bool any_ground = false;
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            if (out.in_hull(r, c)) continue;
            known(r, c) = out.surface(r, c);
            any_ground = true;
        }
    }
    if (any_ground)
        idw_fill(known, out.ground, cell_m, fill);
    else
        out.ground = out.surface;  // hulls cover everything: no ground to interpolate from, nDSM = 0
    detail::report(opt.run.progress, 1.0, function);
    return out;
}

/// nDSM = surface - ground per cell (heights above the terrain, metres); NaN where either is NaN.
/// @throws invalid_input if the shapes differ.
template <raster_input Surface, raster_input Ground>
raster<float> ndsm(const Surface& surface, const Ground& ground)
{
    detail::require_same_shape(surface, ground, "ndsm", "surface", "ground");
    raster<float> out(surface.rows(), surface.cols());
    for (std::ptrdiff_t r = 0; r < surface.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < surface.cols(); ++c) {
            out(r, c) = static_cast<float>(surface(r, c)) - static_cast<float>(ground(r, c));
        }
    }
    return out;
}

}  // namespace lidarfx
