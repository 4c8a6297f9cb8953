// SPDX-License-Identifier: Apache-2.0
// number_roof_surfaces: the final roof surfaces, numbered by area, each with the tilt, azimuth and areas of its
// least-squares plane (extract_buildings step 6).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/pipelines/buildings/grow_roof_surfaces.hpp"

namespace lidarfx {

/// One planar roof surface.
struct roof_surface {
    std::int32_t id = 0;            ///< 1-based, by decreasing area over the whole raster (as in surface_id)
    std::int32_t building = 0;      ///< id of its building
    double tilt_deg = 0;            ///< 0 horizontal .. 90 vertical, of the least-squares plane of its cells
    double azimuth_deg = 0;         ///< down-slope direction, clockwise from north, [0, 360); 0 if tilt < 1 deg
    double horizontal_area_m2 = 0;  ///< cells x cell_m^2
    double area_m2 = 0;             ///< sloped area = horizontal / cos(tilt), m^2
};

/// The numbered roof surfaces of a raster.
struct number_roof_surfaces_result {
    raster<std::int32_t> surface_id;     ///< surface of each cell, 0 = none
    std::vector<roof_surface> surfaces;  ///< surfaces[i].id == i + 1
};

/// Numbers the surfaces of `regions` by their number of cells, largest first (ties by first cell in raster
/// order), and describes each: its building (building_id at its cells), tilt and azimuth from the least-squares
/// plane of its core cells (fit_roof_regions; all its cells when it has fewer than 3 core cells), horizontal
/// area = cells x cell_m^2 and sloped area = horizontal area / cos(tilt). Angles in degrees, azimuth clockwise
/// from north (the down-slope direction; 0 when the tilt is under 1 degree). O(cells + surfaces log surfaces).
/// @throws invalid_input if cell_m is not finite and > 0 or the shapes differ.
inline number_roof_surfaces_result number_roof_surfaces(const roof_regions& regions, raster_view<const float> z,
                                                        raster_view<const std::int32_t> building_id, double cell_m);

// ---- implementation ----

inline number_roof_surfaces_result number_roof_surfaces(const roof_regions& regions, raster_view<const float> z,
                                                        raster_view<const std::int32_t> building_id, double cell_m)
{
    constexpr const char* function = "number_roof_surfaces";
    detail::require_positive(cell_m, function, "cell_m");
    detail::check_regions_shape(regions, z, building_id, function);
    const std::ptrdiff_t rows = z.rows(), cols = z.cols();
    const auto count = static_cast<std::size_t>(regions.count);
    const auto sums = fit_roof_regions(regions, z, cell_m, false);
    const auto planes_fit = fit_roof_regions(regions, z, cell_m);
    std::vector<std::int32_t> owner(count + 1, 0);
    std::vector<std::size_t> first_cell(count + 1, static_cast<std::size_t>(rows * cols));
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const auto g = static_cast<std::size_t>(regions.region(r, c));
            if (g == 0) continue;
            owner[g] = building_id(r, c);
            first_cell[g] = std::min(first_cell[g], static_cast<std::size_t>(r * cols + c));
        }
    }
    std::vector<std::int32_t> order;
    for (std::int32_t g = 1; g <= regions.count; ++g) {
        if (sums[static_cast<std::size_t>(g)].n > 0) order.push_back(g);
    }
    std::sort(order.begin(), order.end(), [&](std::int32_t p, std::int32_t q) {
        const auto& a = sums[static_cast<std::size_t>(p)];
        const auto& b = sums[static_cast<std::size_t>(q)];
        if (a.n != b.n) return a.n > b.n;
        return first_cell[static_cast<std::size_t>(p)] < first_cell[static_cast<std::size_t>(q)];
    });
    number_roof_surfaces_result out{raster<std::int32_t>(rows, cols), {}};
    std::vector<std::int32_t> surface_of(count + 1, 0);
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
        s.horizontal_area_m2 = sums[g].n * (cell_m * cell_m);
        s.area_m2 = s.horizontal_area_m2 * std::sqrt(1.0 + grad * grad);
        surface_of[g] = s.id;
        out.surfaces.push_back(s);
    }
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c)
            out.surface_id(r, c) = surface_of[static_cast<std::size_t>(regions.region(r, c))];
    return out;
}

}  // namespace lidarfx
