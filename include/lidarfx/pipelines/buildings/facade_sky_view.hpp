// SPDX-License-Identifier: Apache-2.0
// facade_sky_view: the share of the sky each facade sub-patch sees, from one horizon sweep per azimuth whose
// upper convex hulls are queried at the sub-patch's height; and facade_horizon, the horizon of one azimuth.
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
#include "lidarfx/kernels/solar/horizon_map.hpp"
#include "lidarfx/kernels/solar/ray_lines.hpp"
#include "lidarfx/kernels/solar/sky_view_factor.hpp"
#include "lidarfx/pipelines/buildings/facade_lit.hpp"
#include "lidarfx/pipelines/buildings/facade_observers.hpp"
#include "lidarfx/pipelines/buildings/facade_patches.hpp"

namespace lidarfx {

/// Settings of facade_sky_view and facade_horizon.
struct facade_sky_view_options {
    /// source_share (the dissertation's 1,081 sources, default) or cosine_weighted (view factor of the wall plane).
    sky_view_factor_method method = sky_view_factor_method::source_share;
    int directions = 72;  ///< azimuths i * 360 / directions, clockwise from north; >= 4 (72 = 5 degree steps)
    execution run = {};   ///< threads, progress and cancellation (core/parallel.hpp); never changes the result
};

namespace detail {

/// max(0, max over the hull points of (z_i - h) / (t - t_i)) for a query point (t, h) beyond the hull (t greater
/// than every t_i). On an upper convex hull these slopes rise to the tangent point and fall after it, so a
/// binary search finds it: O(log n).
inline double hull_tangent_at(const horizon_hull_point* hull, std::ptrdiff_t n, double t, double h) noexcept
{
    if (n == 0) return 0.0;
    const auto slope = [&](std::ptrdiff_t i) { return (hull[i].z - h) / (t - hull[i].t); };
    std::ptrdiff_t lo = 0, hi = n - 1;  // the maximum lies in [lo, hi]
    while (lo < hi) {
        const std::ptrdiff_t mid = lo + (hi - lo) / 2;
        if (slope(mid) <= slope(mid + 1)) {
            lo = mid + 1;
        } else {
            hi = mid;
        }
    }
    const double best = slope(lo);
    return best > 0.0 ? best : 0.0;
}

/// Horizon tangents of every sub-patch towards azimuth_deg into tangent[i]: one sweep along the ray lines walking
/// away from the azimuth, each line keeping the upper convex hull of the cells behind (horizon_map's sweep); at
/// an observer cell each of its sub-patches queries the hull at its height before the cell joins it.
inline void facade_horizon_sweep(raster_view<const float> z, const facade_observers& obs,
                                 std::span<const facade_patch> subs, double cell_m, double azimuth_deg,
                                 std::vector<double>& tangent, int threads, const char* fn)
{
    const ray_lines l = make_ray_lines(azimuth_deg, z.rows(), z.cols());
    const std::vector<std::ptrdiff_t> sh = l.shifts();
    const std::ptrdiff_t first = l.first_line(), block = 64, major = l.major();
    const double a = l.dcol * cell_m, b = l.drow * cell_m;
    tangent.assign(subs.size(), 0.0);
    parallel_for_rows(
        l.count(), block, threads,
        [&](std::ptrdiff_t b0, std::ptrdiff_t b1) {
            std::vector<horizon_hull_point> hulls(static_cast<std::size_t>((b1 - b0) * major));
            std::vector<std::ptrdiff_t> sizes(static_cast<std::size_t>(b1 - b0), 0);
            walk_ray_lines(l, sh, first + b0, first + b1, [&](std::ptrdiff_t line, std::ptrdiff_t r, std::ptrdiff_t c) {
                horizon_hull_point* hull = hulls.data() + line * major;
                std::ptrdiff_t& n = sizes[static_cast<std::size_t>(line)];
                const double t = (static_cast<double>(c) + 0.5) * a + (static_cast<double>(r) + 0.5) * b;
                const std::int32_t o = obs.index(r, c);
                if (o >= 0) {
                    for (std::size_t k = obs.first[static_cast<std::size_t>(o)];
                         k < obs.first[static_cast<std::size_t>(o) + 1]; ++k) {
                        const std::size_t i = obs.patches[k];
                        tangent[i] = hull_tangent_at(hull, n, t, subs[i].height_m);
                    }
                }
                const float zc = z(r, c);
                if (zc == zc) horizon_hull_step(hull, n, t, static_cast<double>(zc));
            });
        },
        {}, fn);
}

inline void check_facade_sky_options(const facade_sky_view_options& opt, double cell_m, const char* fn)
{
    require_positive(cell_m, fn, "cell_m");
    require(opt.directions >= 4, fn, "directions", ">= 4", opt.directions);
    check_execution(opt.run, fn);
}

}  // namespace detail

/// Horizon tangent tan(h) >= 0 of every sub-patch towards azimuth_deg: max(0, max over the non-NaN cells q before
/// the front cell p on p's ray line towards the azimuth of (z_q - height_m) / (t_p - t_q)), the ray lines and t of
/// horizon_map (kernels/solar/ray_lines.hpp), seen from the centre of the front cell at the sub-patch's height.
/// Nothing beyond the raster rises above the horizontal. The wall plane is not applied here (facade_sky_view
/// drops the azimuths behind it). One sweep with an upper convex hull per line: O(rows * cols + patches * log).
/// @throws invalid_input as facade_sky_view, or if the azimuth is not finite.
template <raster_input Dsm>
std::vector<double> facade_horizon(const Dsm& dsm, std::span<const facade_patch> patches, double cell_m,
                                   double azimuth_deg, const facade_sky_view_options& opt = {})
{
    constexpr const char* fn = "facade_horizon";
    detail::check_facade_sky_options(opt, cell_m, fn);
    detail::require(std::isfinite(azimuth_deg), fn, "azimuth_deg", "finite", azimuth_deg);
    detail::require_facade_cells(patches, dsm.rows(), dsm.cols(), fn);
    std::vector<double> tangent;
    detail::with_float_view(dsm, [&](raster_view<const float> z) {
        const std::span<const facade_patch> subs = patches;
        const detail::facade_observers obs = detail::make_facade_observers(z.rows(), z.cols(), subs);
        detail::facade_horizon_sweep(z, obs, subs, cell_m, azimuth_deg, tangent, opt.run.threads, fn);
    });
    detail::report(opt.run.progress, 1.0, fn);
    return tangent;
}

/// Sky view factor of every facade sub-patch, in [0, 1/2] (dissertation 3.2.4, Figure 78: a wall sees at most
/// half the sky). From facade_horizon's tangent tan(h_i) towards each azimuth A_i = i * 360 / directions, with
/// phi_i = A_i - facing azimuth; only azimuths in front of the wall plane (cos phi_i > 0) count:
///   source_share:    (sum over front A_i of #{e in 15, 20, ..., 85 deg: tan e >= tan h_i}) / (15 directions + 1),
///                    the dissertation's 1,081 sources for 72 azimuths; the zenith lies in the wall plane and
///                    does not count, so an open wall sees 525 / 1081 = 0.4857;
///   cosine_weighted: 1/2 * sum(cos phi_i * w(h_i)) / sum(cos phi_i), w(h) = 1 - (2 h + sin 2h) / pi: the view
///                    factor of a vertical plane, (1 / pi) * integral of cos(incidence) over the visible sky,
///                    with the azimuth sum normalized so that an open wall gets exactly 1/2.
/// Cost: `directions` sweeps, O(directions * (rows * cols + patches * log)). @throws invalid_input if cell_m is not
/// finite and > 0, directions < 4, run.threads < 0 or a sub-patch lies outside the DSM; cancelled if
/// run.progress returns false.
template <raster_input Dsm>
std::vector<double> facade_sky_view(const Dsm& dsm, std::span<const facade_patch> patches, double cell_m,
                                    const facade_sky_view_options& opt = {})
{
    constexpr const char* fn = "facade_sky_view";
    detail::check_facade_sky_options(opt, cell_m, fn);
    detail::require_facade_cells(patches, dsm.rows(), dsm.cols(), fn);
    const bool share = opt.method == sky_view_factor_method::source_share;
    std::vector<double> sum(patches.size(), 0.0), weight(patches.size(), 0.0);
    double tan_e[sky_source_elevations];
    for (int j = 0; j < sky_source_elevations; ++j) tan_e[j] = std::tan((15.0 + 5.0 * j) * (std::numbers::pi / 180.0));
    detail::with_float_view(dsm, [&](raster_view<const float> z) {
        const std::span<const facade_patch> subs = patches;
        const detail::facade_observers obs = detail::make_facade_observers(z.rows(), z.cols(), subs);
        std::vector<double> tangent;
        // Sub-patch p's share of the sky towards one azimuth, from its horizon tangent there.
        const auto add = [&](double azimuth, std::size_t p) {
            const double cos_phi = sincos_deg(azimuth - subs[p].facing_azimuth_deg)[1];
            if (cos_phi <= 1e-12) return;  // behind or in the wall plane (cos 90 deg rounds to ~1e-17)
            if (share) {
                int visible = 0;
                for (int j = 0; j < sky_source_elevations; ++j) visible += tan_e[j] >= tangent[p];
                sum[p] += visible;
            } else {
                const double h = std::atan(tangent[p]);
                sum[p] += cos_phi * (1.0 - (2.0 * h + std::sin(2.0 * h)) / std::numbers::pi);
                weight[p] += cos_phi;
            }
        };
        const int n = opt.directions;
        for (int i = 0; i < n; ++i) {
            const double azimuth = 360.0 * i / n;
            detail::facade_horizon_sweep(z, obs, subs, cell_m, azimuth, tangent, opt.run.threads, fn);
            // Each sub-patch adds its azimuths in order whichever block holds it: the same sums for any thread count.
            parallel_for_rows(static_cast<std::ptrdiff_t>(subs.size()), 8192, opt.run.threads,
                              [&](std::ptrdiff_t p0, std::ptrdiff_t p1) {
                                  for (auto p = static_cast<std::size_t>(p0); p < static_cast<std::size_t>(p1); ++p)
                                      add(azimuth, p);
                              });
            detail::report(opt.run.progress, static_cast<double>(i + 1) / n, fn);
        }
    });
    std::vector<double> svf(patches.size(), 0.0);
    for (std::size_t p = 0; p < svf.size(); ++p) {
        svf[p] = share ? sum[p] / (sky_source_elevations * opt.directions + 1.0)
                       : (weight[p] > 0.0 ? 0.5 * sum[p] / weight[p] : 0.0);
    }
    return svf;
}

}  // namespace lidarfx
