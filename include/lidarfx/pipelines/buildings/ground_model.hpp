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
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/kernels/filter/angular_filter.hpp"
#include "lidarfx/kernels/interpolate/idw_fill.hpp"
#include "lidarfx/kernels/label/connected_components.hpp"
#include "lidarfx/kernels/vector/convex_hull.hpp"

namespace lidarfx {

/// Settings of ground_model.
struct ground_model_options {
    double edge_angle_deg = 45.0;     ///< edge where the angular value >= this, degrees (dissertation: 45); in (0, 90)
    int angular_radius_cells = 2;     ///< window half-size of the angular filter, cells (2 = "two tiers"); >= 1
    std::size_t min_edge_cells = 10;  ///< an edge object (8-connected) needs at least this many cells (the n); >= 1
    int idw_k = 8;                    ///< ground cells averaged per filled cell (idw_fill); >= 1
    double idw_power = 1.0;           ///< IDW weight exponent (1 = dissertation eq. 3); > 0
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

/// Terrain model of a surface model without ground classes (dissertation 3.2.1): (1) NaN cells of `dsm`
/// (no return) are filled by IDW (idw_fill, idw_k nearest, weight 1 / d^idw_power); (2) edges = cells whose
/// angular value (angular_filter, angular_radius_cells) is >= edge_angle_deg: a neighbour x metres away
/// may differ by at most x * tan(edge_angle_deg) metres within one plane; (3) 8-connected edge objects of
/// fewer than min_edge_cells cells are dropped; (4) one convex hull per kept object, over its cell centres;
/// (5) ground = the surface at cells outside every hull; inside the hulls it is IDW of the ground cells.
/// nDSM = surface - ground (see ndsm). Elevations in metres, cell_m the cell size in metres. O(cells * (
/// radius^2 + idw_k)) plus the hulls' bounding boxes. Same bits for any thread count.
/// `run`: threads, progress and cancellation (core/parallel.hpp); never changes the result.
/// @throws invalid_input on bad options or run, cell_m not finite and > 0, or a DSM without a finite cell
/// ("...: dsm has no finite cell"); cancelled if run.progress returns false.
template <raster_input In>
ground_model_result ground_model(const In& dsm, double cell_m, const ground_model_options& opt = {},
                                 const execution& run = {});

/// Replaces terrain.ground by a given terrain model `ground` (metres, the terrain's shape; e.g. min_z of
/// class 2), its NaN and infinite cells filled by IDW from the finite ones (idw_fill with opt.idw_k and
/// opt.idw_power, run.threads); terrain.surface, edges and hulls stay. cell_m in metres. O(cells * idw_k).
/// `run`: threads (its progress is not called); never changes the result.
/// @throws invalid_input if the shapes differ, cell_m is not finite and > 0, an option or run is out of range,
/// or `ground` has no finite cell.
inline void replace_ground(ground_model_result& terrain, raster_view<const float> ground, double cell_m,
                           const ground_model_options& opt = {}, const execution& run = {});

/// A given terrain model `ground` with its NaN and infinite cells filled by IDW from the finite ones, exactly as
/// replace_ground fills it: the terrain extract_buildings cuts its candidates from when given `ground` (count
/// raised points against it). @throws as replace_ground.
inline raster<float> fill_ground(raster_view<const float> ground, double cell_m, const ground_model_options& opt = {},
                                 const execution& run = {});

/// nDSM = surface - ground per cell (heights above the terrain, metres); NaN where either is NaN.
/// @throws invalid_input if the shapes differ.
template <raster_input Surface, raster_input Ground>
raster<float> ndsm(const Surface& surface, const Ground& ground);

// ---- implementation ----

namespace detail {

inline void check_ground_model(double cell_m, const ground_model_options& opt, const char* function)
{
    require_positive(cell_m, function, "cell_m");
    require(opt.edge_angle_deg > 0 && opt.edge_angle_deg < 90, function, "edge_angle_deg", "in (0, 90)",
            opt.edge_angle_deg);
    require(opt.angular_radius_cells >= 1, function, "angular_radius_cells", ">= 1", opt.angular_radius_cells);
    require(opt.min_edge_cells >= 1, function, "min_edge_cells", ">= 1", opt.min_edge_cells);
    require(opt.idw_k >= 1, function, "idw_k", ">= 1", opt.idw_k);
    require_positive(opt.idw_power, function, "idw_power");
}

}  // namespace detail

template <raster_input In>
ground_model_result ground_model(const In& dsm, double cell_m, const ground_model_options& opt, const execution& run)
{
    constexpr const char* function = "ground_model";
    detail::check_ground_model(cell_m, opt, function);
    detail::check_execution(run, function);
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
    const idw_fill_options fill{.k = opt.idw_k, .radius_m = 0, .power = opt.idw_power, .run = {run.threads, {}}};
    if (holes) {
        raster<float> raw = out.surface;
        for (auto& v : raw) v = std::isfinite(v) ? v : std::numeric_limits<float>::quiet_NaN();
        idw_fill(raw, out.surface, cell_m, fill);
    }
    const raster<float> angle =
        angular_filter(out.surface, cell_m,
                       angular_filter_options{.radius_cells = opt.angular_radius_cells, .run = {run.threads, {}}});
    detail::report(run.progress, 0.3, function);
    const auto threshold = static_cast<float>(opt.edge_angle_deg);
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) out.edges(r, c) = angle(r, c) >= threshold ? 1 : 0;
    }
    components objects = connected_components(
        out.edges, connected_components_options{.conn = connectivity::eight, .run = {run.threads, {}}});
    rank_by_size(objects);
    std::size_t kept = 0;
    while (kept < objects.count() && objects.sizes[kept + 1] >= opt.min_edge_cells) ++kept;
    out.object_count = kept;
    std::vector<std::vector<cell_point>> points(kept);
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const auto l = static_cast<std::size_t>(objects.labels(r, c));
            if (l == 0 || l > kept) continue;
            out.objects(r, c) = static_cast<std::int32_t>(l);
            points[l - 1].push_back({c, r});
        }
    }
    for (auto& p : points) burn_convex(convex_hull(std::move(p)), out.in_hull.view());
    detail::report(run.progress, 0.5, function);

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
    detail::report(run.progress, 1.0, function);
    return out;
}

namespace detail {

/// fill_ground, its errors naming `function`.
inline raster<float> filled_ground(raster_view<const float> ground, double cell_m, const ground_model_options& opt,
                                   const execution& run, const char* function);

}  // namespace detail

inline void replace_ground(ground_model_result& terrain, raster_view<const float> ground, double cell_m,
                           const ground_model_options& opt, const execution& run)
{
    detail::require_same_shape(terrain.ground, ground, "replace_ground", "terrain", "ground");
    terrain.ground = detail::filled_ground(ground, cell_m, opt, run, "replace_ground");
}

inline raster<float> fill_ground(raster_view<const float> ground, double cell_m, const ground_model_options& opt,
                                 const execution& run)
{
    return detail::filled_ground(ground, cell_m, opt, run, "fill_ground");
}

namespace detail {

inline raster<float> filled_ground(raster_view<const float> ground, double cell_m, const ground_model_options& opt,
                                   const execution& run, const char* function)
{
    detail::check_ground_model(cell_m, opt, function);
    detail::check_execution(run, function);
    const std::ptrdiff_t rows = ground.rows(), cols = ground.cols();
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
    raster<float> filled(rows, cols);
    idw_fill(given, filled, cell_m, idw_fill_options{.k = opt.idw_k, .power = opt.idw_power, .run = {run.threads, {}}});
    return filled;
}

}  // namespace detail

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
