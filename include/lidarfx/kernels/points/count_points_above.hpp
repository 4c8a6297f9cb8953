// SPDX-License-Identifier: Apache-2.0
// count_points_above: per cell, the points standing at least a given height above a reference surface (a
// terrain model): how much of a cell is raised, measured on its points rather than on its highest one.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/grid.hpp"
#include "lidarfx/core/point_cloud.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// Adds to `counts`, per cell of `g`, the points of `cloud` with z >= reference(cell) + height_m (metres; a
/// cell whose reference is NaN counts none). Points go to grid::cell_of, as in rasterize; points outside the
/// grid or with a NaN or infinite coordinate are skipped. Call it chunk by chunk: the counts add up, so any
/// chunking gives the same counts (saturating at 2^32 - 1). O(points).
/// @throws invalid_input on an invalid grid, a height that is not finite, or reference or counts not of g's shape.
template <point_cloud C>
void count_points_above(const C& cloud, const grid& g, raster_view<const float> reference, double height_m,
                        raster_view<std::uint32_t> counts);

/// count_points_above that also lowers `lowest_z`, per cell, to the lowest z of the points it counts (metres; start
/// it at NaN: a cell without such points keeps its value), so that a cell's raised points say both how many they
/// are and where the lowest of them lies (under a crown: the roof beneath it). Any chunking gives the same rasters.
/// @throws invalid_input as count_points_above, and if lowest_z is not of g's shape.
template <point_cloud C>
void count_points_above(const C& cloud, const grid& g, raster_view<const float> reference, double height_m,
                        raster_view<std::uint32_t> counts, raster_view<float> lowest_z);

/// The counts above for one cloud, in a new raster of g's shape.
template <point_cloud C>
raster<std::uint32_t> count_points_above(const C& cloud, const grid& g, raster_view<const float> reference,
                                         double height_m)
{
    g.validate("count_points_above");
    raster<std::uint32_t> counts(g.rows, g.cols);
    count_points_above(cloud, g, reference, height_m, counts.view());
    return counts;
}

// ---- implementation ----

namespace detail {

/// count_points_above's loop; `on_counted(row, col, z)` is called for each point counted.
template <point_cloud C, class OnCounted>
void count_points_above(const C& cloud, const grid& g, raster_view<const float> reference, double height_m,
                        raster_view<std::uint32_t> counts, OnCounted&& on_counted)
{
    constexpr const char* function = "count_points_above";
    g.validate(function);
    detail::require(std::isfinite(height_m), function, "height_m", "finite", height_m);
    detail::require(reference.rows() == g.rows && reference.cols() == g.cols, function,
                    "reference must have the grid's shape");
    detail::require(counts.rows() == g.rows && counts.cols() == g.cols, function, "counts must have the grid's shape");
    const std::size_t n = cloud.size();
    for (std::size_t i = 0; i < n; ++i) {
        const double z = static_cast<double>(cloud.z(i));
        if (!std::isfinite(z)) continue;
        const auto at = g.cell_of(static_cast<double>(cloud.x(i)), static_cast<double>(cloud.y(i)));
        if (!at) continue;
        const float ref = reference(at->row, at->col);
        if (!std::isfinite(ref) || !(z >= static_cast<double>(ref) + height_m)) continue;
        std::uint32_t& k = counts(at->row, at->col);
        if (k != UINT32_MAX) ++k;
        on_counted(at->row, at->col, z);
    }
}

}  // namespace detail

template <point_cloud C>
void count_points_above(const C& cloud, const grid& g, raster_view<const float> reference, double height_m,
                        raster_view<std::uint32_t> counts)
{
    detail::count_points_above(cloud, g, reference, height_m, counts, [](std::ptrdiff_t, std::ptrdiff_t, double) {});
}

template <point_cloud C>
void count_points_above(const C& cloud, const grid& g, raster_view<const float> reference, double height_m,
                        raster_view<std::uint32_t> counts, raster_view<float> lowest_z)
{
    g.validate("count_points_above");
    detail::require(lowest_z.rows() == g.rows && lowest_z.cols() == g.cols, "count_points_above",
                    "lowest_z must have the grid's shape");
    detail::count_points_above(cloud, g, reference, height_m, counts,
                               [&](std::ptrdiff_t r, std::ptrdiff_t c, double z) {
                                   float& low = lowest_z(r, c);
                                   const auto zf = static_cast<float>(z);
                                   if (!(low <= zf)) low = zf;  // NaN: the first
                               });
}

}  // namespace lidarfx
