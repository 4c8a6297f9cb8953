// SPDX-License-Identifier: Apache-2.0
// facade_lit: which facade sub-patches the sun lights at one sun position, from one ray-line sweep of the
// surface model (the shadow-height limit of raylines_shadow, read at each sub-patch's height).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
#include <span>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/kernels/solar/ray_lines.hpp"
#include "lidarfx/kernels/solar/raylines_shadow.hpp"
#include "lidarfx/kernels/solar/shadow_probes.hpp"
#include "lidarfx/pipelines/buildings/facade_observers.hpp"
#include "lidarfx/pipelines/buildings/facade_patches.hpp"

namespace lidarfx {

/// Settings of facade_lit.
struct facade_lit_options {
    execution run = {};  ///< threads, progress and cancellation (core/parallel.hpp); never changes the result
};

namespace detail {

/// cos theta of a vertical wall facing facing_deg under a sun at (azimuth, elevation): cos e cos(A_sun - A_facing)
/// (cos_incidence with tilt 90), exactly 0 when the sun is in the wall plane (A_sun - A_facing = +-90 degrees).
inline double facade_cos_incidence(double sun_azimuth_deg, double sun_elevation_deg, double facing_deg) noexcept
{
    return std::cos(sun_elevation_deg * (std::numbers::pi / 180.0)) * sincos_deg(sun_azimuth_deg - facing_deg)[1];
}

/// Refuses sub-patches whose cells lie outside a rows x cols raster.
inline void require_facade_cells(std::span<const facade_patch> patches, std::ptrdiff_t rows, std::ptrdiff_t cols,
                                 const char* fn)
{
    for (std::size_t i = 0; i < patches.size(); ++i) {
        const facade_patch& p = patches[i];
        if (p.front_row < 0 || p.front_row >= rows || p.front_col < 0 || p.front_col >= cols) {
            throw invalid_input(concat(fn, ": patches[", i, "] faces cell (", p.front_row, ", ", p.front_col,
                                       ") outside the ", rows, " x ", cols,
                                       " DSM; pass the sub-patches facade_patches made from this DSM"));
        }
    }
}

/// Lit state of sub-patch p from its observer's limit, given cos_theta = facade_cos_incidence for p's wall: the
/// sun in front of the wall plane (cos_theta > 0) and the key of the point (front cell centre, height_m) not below
/// the limit. A sun in the wall plane lights nothing.
inline std::uint8_t facade_patch_lit(const facade_patch& p, double cos_theta, double limit,
                                     const shadow_lifts& lift) noexcept
{
    if (cos_theta <= 0.0) return 0;
    const double key = p.height_m + (lift.col_lift[static_cast<std::size_t>(p.front_col)] +
                                     lift.row_lift[static_cast<std::size_t>(p.front_row)]);
    return limit > key ? 0 : 1;
}

/// facade_cos_incidence for one sun position, looked up for the four grid facings (0, 90, 180, 270: every wall
/// of facade_patches) and computed for any other.
struct facade_cos_table {
    double sun_azimuth_deg, sun_elevation_deg;
    double grid[4];
    facade_cos_table(double azimuth_deg, double elevation_deg) noexcept
        : sun_azimuth_deg(azimuth_deg), sun_elevation_deg(elevation_deg)
    {
        for (int k = 0; k < 4; ++k) grid[k] = facade_cos_incidence(azimuth_deg, elevation_deg, 90.0 * k);
    }
    double operator()(double facing_deg) const noexcept
    {
        if (facing_deg == 0.0) return grid[0];
        if (facing_deg == 90.0) return grid[1];
        if (facing_deg == 180.0) return grid[2];
        if (facing_deg == 270.0) return grid[3];
        return facade_cos_incidence(sun_azimuth_deg, sun_elevation_deg, facing_deg);
    }
};

}  // namespace detail

/// Lit state of every facade sub-patch for one sun position: 1 lit, 0 shadow. A sub-patch is seen from its
/// observer point, the centre of its front cell (half a cell in front of the wall) at height_m. It is lit iff
/// the sun is in front of the wall plane (cos e cos(A_sun - A_facing) > 0, exactly 0 in the plane) and no non-NaN cell
/// q before the front cell on its ray line (raylines_shadow's lines along the sun azimuth, kernels/solar/ray_lines.hpp)
/// rises above the sun ray: z_q + t_q tan e <= height_m + t_p tan e for all such q (t the projection on the walk
/// away from the sun, metres) -- raylines_shadow's test with the observer's height in place of the cell's. Sun
/// at or below the horizon: nothing lit; at the zenith: nothing (the sun is in the wall plane). One sweep over
/// the raster: O(rows * cols + patches). @throws invalid_input if cell_m is not finite and > 0, an angle is not
/// finite, the elevation is outside [-90, 90], run.threads < 0 or a sub-patch lies outside the DSM.
template <raster_input Dsm>
std::vector<std::uint8_t> facade_lit(const Dsm& dsm, std::span<const facade_patch> patches, double cell_m,
                                     double sun_azimuth_deg, double sun_elevation_deg,
                                     const facade_lit_options& opt = {})
{
    constexpr const char* fn = "facade_lit";
    detail::require_positive(cell_m, fn, "cell_m");
    detail::require(std::isfinite(sun_azimuth_deg), fn, "sun_azimuth_deg", "finite", sun_azimuth_deg);
    detail::require(sun_elevation_deg >= -90.0 && sun_elevation_deg <= 90.0, fn, "sun_elevation_deg", "in [-90, 90]",
                    sun_elevation_deg);
    detail::check_execution(opt.run, fn);
    detail::require_facade_cells(patches, dsm.rows(), dsm.cols(), fn);
    std::vector<std::uint8_t> out(patches.size(), 0);
    if (sun_elevation_deg <= 0.0 || sun_elevation_deg >= 90.0) {
        detail::report(opt.run.progress, 1.0, fn);
        return out;
    }
    detail::with_float_view(dsm, [&](raster_view<const float> z) {
        const std::span<const facade_patch> subs = patches;
        const detail::facade_observers obs = detail::make_facade_observers(z.rows(), z.cols(), subs);
        const ray_lines l = make_ray_lines(sun_azimuth_deg, z.rows(), z.cols());
        const shadow_lifts lift =
            make_shadow_lifts(l, cell_m, std::tan(sun_elevation_deg * (std::numbers::pi / 180.0)));
        std::vector<double> limit;
        raster<std::uint8_t> lit(z.rows(), z.cols());
        raylines_shadow_probed(z, {}, l, lift, obs.probes, limit, lit.view(),
                               {.nan_cell = 0, .line_phases = 1, .run = {.threads = opt.run.threads}});
        const detail::facade_cos_table cos_theta(sun_azimuth_deg, sun_elevation_deg);
        for (std::size_t i = 0; i < subs.size(); ++i) {
            const auto o = static_cast<std::size_t>(obs.index(subs[i].front_row, subs[i].front_col));
            out[i] = detail::facade_patch_lit(subs[i], cos_theta(subs[i].facing_azimuth_deg), limit[o], lift);
        }
    });
    detail::report(opt.run.progress, 1.0, fn);
    return out;
}

}  // namespace lidarfx
