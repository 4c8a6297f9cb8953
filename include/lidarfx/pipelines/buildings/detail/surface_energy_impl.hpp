// SPDX-License-Identifier: Apache-2.0
// Implementation of surface_energy (pipelines/buildings/surface_energy.hpp): the quarters' GHI, the sky views of
// roof patches and facade sub-patches, and per daylight sun one ray-line sweep shading both.
#pragma once
// Included at the end of its public header, which declares what is defined here.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <span>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/kernels/solar/daylight_suns.hpp"
#include "lidarfx/kernels/solar/incidence.hpp"
#include "lidarfx/kernels/solar/irradiance_record.hpp"
#include "lidarfx/kernels/solar/ray_lines.hpp"
#include "lidarfx/kernels/solar/raylines_shadow.hpp"
#include "lidarfx/kernels/solar/sky_options.hpp"
#include "lidarfx/kernels/solar/sky_view_factor.hpp"
#include "lidarfx/pipelines/buildings/facade_lit.hpp"
#include "lidarfx/pipelines/buildings/facade_observers.hpp"
#include "lidarfx/pipelines/buildings/facade_patches.hpp"
#include "lidarfx/pipelines/buildings/facade_sky_view.hpp"
#include "lidarfx/pipelines/buildings/surface_patches.hpp"

namespace lidarfx::detail {

/// Per-patch sums of one quarter each, turned into patch_energy.
inline std::vector<patch_energy> to_patch_energy(const std::vector<std::array<double, 4>>& sums,
                                                 const std::array<double, 4>& days)
{
    std::vector<patch_energy> out(sums.size());
    for (std::size_t i = 0; i < sums.size(); ++i) {
        for (std::size_t q = 0; q < 4; ++q) {
            out[i].annual_kwh_m2 += sums[i][q];
            out[i].quarter_kwh_m2_day[q] = days[q] > 0.0 ? sums[i][q] / days[q] : 0.0;
        }
    }
    return out;
}

/// Days and GHI of every record (daylight or not) per quarter of UTC + utc_offset_h, and the total GHI.
inline void sum_quarters(std::span<const irradiance_record> records, double utc_offset_h, surface_energy_result& res)
{
    for (const irradiance_record& r : records) {
        const auto q = static_cast<std::size_t>(record_month(r, utc_offset_h) / 3);
        const double hours = static_cast<double>(r.interval.count()) / 3600.0;
        res.quarter_days[q] += hours / 24.0;
        res.quarter_ghi_kwh_m2_day[q] += r.ghi_w_m2 * hours / 1000.0;
        res.ghi_kwh_m2 += r.ghi_w_m2 * hours / 1000.0;
    }
    for (std::size_t q = 0; q < 4; ++q) {
        if (res.quarter_days[q] > 0.0) res.quarter_ghi_kwh_m2_day[q] /= res.quarter_days[q];
    }
}

/// The sky views of the roof patches (mean SVF of their 4 cells times (1 + cos b) / 2) and facade sub-patches.
inline void surface_sky_views(raster_view<const float> z, double cell_m, const surface_energy_options& opt,
                              double sky_share, surface_energy_result& res)
{
    const raster<float> svf = sky_view_factor(
        z, cell_m,
        {.method = opt.sky.svf_method,
         .directions = opt.sky.svf_directions,
         .run = {.threads = opt.run.threads, .progress = progress_phase(opt.run.progress, 0.0, sky_share / 2)}});
    res.facade_sky_view = facade_sky_view(
        z, std::span<const facade_patch>(res.facades), cell_m,
        {.method = opt.sky.svf_method,
         .directions = opt.sky.svf_directions,
         .run = {.threads = opt.run.threads, .progress = progress_phase(opt.run.progress, sky_share / 2, sky_share)}});
    res.roof_sky_view.resize(res.roofs.size());
    for (std::size_t i = 0; i < res.roofs.size(); ++i) {
        const surface_patch& p = res.roofs[i];
        const double mean = 0.25 * (static_cast<double>(svf(p.row, p.col)) + svf(p.row, p.col + 1) +
                                    svf(p.row + 1, p.col) + svf(p.row + 1, p.col + 1));
        res.roof_sky_view[i] = mean * (1.0 + p.normal.up) / 2.0;
    }
}

/// One daylight sun's sweep for surface_energy: its ray lines' shadow lifts, the cells' lit state and the observers'
/// shadow limits.
struct surface_sun_sweep {
    shadow_lifts lift;
    raster<std::uint8_t> lit;
    std::vector<double> limit;
    bool zenith = false;  ///< the sun at the zenith: nothing casts a shadow, walls get no beam
};

/// Sweeps one daylight sun over the DSM on one thread (the suns of a batch are swept side by side).
inline void sweep_surface_sun(raster_view<const float> z, double cell_m, const daylight_sun& day,
                              const facade_observers& obs, surface_sun_sweep& s, const char* fn)
{
    s.zenith = day.elevation_deg >= 90.0;
    const ray_lines l = make_ray_lines(day.azimuth_deg, z.rows(), z.cols());
    s.lift = make_shadow_lifts(l, cell_m, s.zenith ? 0.0 : std::tan(day.elevation_deg * (std::numbers::pi / 180.0)));
    if (s.lit.rows() != z.rows() || s.lit.cols() != z.cols()) s.lit = raster<std::uint8_t>(z.rows(), z.cols());
    if (!s.zenith) facade_shadow_sweep(z, obs, l, s.lift, s.limit, s.lit.view(), 1, fn);
}

/// Adds a batch of swept daylight suns, in order, to the quarter sums of every roof patch and facade sub-patch.
inline void add_surface_suns(std::span<const daylight_sun* const> days, std::span<const surface_sun_sweep> sweeps,
                             const facade_observers& obs, const surface_energy_result& res,
                             std::vector<std::array<double, 4>>& roof_sum,
                             std::vector<std::array<double, 4>>& facade_sum, int threads)
{
    std::vector<facade_cos_table> cos_theta;
    for (const daylight_sun* d : days) cos_theta.emplace_back(d->azimuth_deg, d->elevation_deg);
    parallel_for_rows(
        static_cast<std::ptrdiff_t>(res.roofs.size()), 4096, threads, [&](std::ptrdiff_t i0, std::ptrdiff_t i1) {
            for (std::ptrdiff_t i = i0; i < i1; ++i) {
                const surface_patch& p = res.roofs[static_cast<std::size_t>(i)];
                for (std::size_t k = 0; k < days.size(); ++k) {
                    const daylight_sun& day = *days[k];
                    const raster<std::uint8_t>& lit = sweeps[k].lit;
                    const double share = sweeps[k].zenith ? 1.0
                                                          : 0.25 * (lit(p.row, p.col) + lit(p.row, p.col + 1) +
                                                                    lit(p.row + 1, p.col) + lit(p.row + 1, p.col + 1));
                    const double dni = day.dni_w_m2 * day.kwh_per_w_m2, dhi = day.dhi_w_m2 * day.kwh_per_w_m2;
                    const double cos_t = enu_dot(day.sun, p.normal);
                    roof_sum[static_cast<std::size_t>(i)][static_cast<std::size_t>(day.month / 3)] +=
                        (cos_t > 0.0 ? dni * cos_t * share : 0.0) +
                        dhi * res.roof_sky_view[static_cast<std::size_t>(i)];
                }
            }
        });
    parallel_for_rows(
        static_cast<std::ptrdiff_t>(res.facades.size()), 4096, threads, [&](std::ptrdiff_t i0, std::ptrdiff_t i1) {
            for (std::ptrdiff_t i = i0; i < i1; ++i) {
                const facade_patch& p = res.facades[static_cast<std::size_t>(i)];
                const auto o = static_cast<std::size_t>(obs.index(p.front_row, p.front_col));
                for (std::size_t k = 0; k < days.size(); ++k) {
                    const daylight_sun& day = *days[k];
                    const double dni = day.dni_w_m2 * day.kwh_per_w_m2, dhi = day.dhi_w_m2 * day.kwh_per_w_m2;
                    double beam = 0.0;
                    if (!sweeps[k].zenith) {
                        const double cos_t = cos_theta[k](p.facing_azimuth_deg);
                        if (facade_patch_lit(p, cos_t, sweeps[k].limit[o], sweeps[k].lift) == 1) beam = dni * cos_t;
                    }
                    facade_sum[static_cast<std::size_t>(i)][static_cast<std::size_t>(day.month / 3)] +=
                        beam + dhi * res.facade_sky_view[static_cast<std::size_t>(i)];
                }
            }
        });
}

}  // namespace lidarfx::detail

namespace lidarfx {

template <raster_input Dsm, raster_input Ids>
surface_energy_result surface_energy(const Dsm& dsm, const Ids& building_id, double cell_m, const solar_site& site,
                                     std::span<const irradiance_record> records, const surface_energy_options& opt)
{
    constexpr const char* fn = "surface_energy";
    detail::require_positive(cell_m, fn, "cell_m");
    detail::check_execution(opt.run, fn);
    require_sky_options(opt.sky, fn, true);
    detail::require_same_shape(dsm, building_id, fn, "dsm", "building_id");
    // Sun positions first: they validate the site and every time before any long work.
    const std::vector<daylight_sun> suns = daylight_suns(records, site);
    surface_energy_result res;
    detail::sum_quarters(records, site.utc_offset_h, res);
    res.sun_up_records = suns.size();
    res.roofs = surface_patches(dsm, building_id, cell_m, {.ground = false});
    res.facades = facade_patches(dsm, building_id, cell_m, opt.facades);

    detail::with_float_view(dsm, [&](raster_view<const float> z) {
        const double sky_share = 0.1;  // share of the progress taken by the two sky views
        detail::surface_sky_views(z, cell_m, opt, sky_share, res);
        const detail::facade_observers obs = detail::make_facade_observers(z.rows(), z.cols(), res.facades);
        std::vector<std::array<double, 4>> roof_sum(res.roofs.size()), facade_sum(res.facades.size());
        // Batches of suns: each sun of a batch swept on its own thread, then the batch added to every patch in
        // sun order (so the sums are the same for any thread count).
        const std::size_t batch = 8;
        std::vector<detail::surface_sun_sweep> sweeps(std::min(batch, suns.size()));
        std::vector<const daylight_sun*> days;
        for (std::size_t d0 = 0; d0 < suns.size(); d0 += batch) {
            const std::size_t n = std::min(batch, suns.size() - d0);
            days.clear();
            for (std::size_t k = 0; k < n; ++k) days.push_back(&suns[d0 + k]);
            parallel_for_rows(static_cast<std::ptrdiff_t>(n), 1, opt.run.threads,
                              [&](std::ptrdiff_t k0, std::ptrdiff_t k1) {
                                  for (std::ptrdiff_t k = k0; k < k1; ++k) {
                                      const auto u = static_cast<std::size_t>(k);
                                      detail::sweep_surface_sun(z, cell_m, *days[u], obs, sweeps[u], fn);
                                  }
                              });
            detail::add_surface_suns(days, std::span<const detail::surface_sun_sweep>(sweeps.data(), n), obs, res,
                                     roof_sum, facade_sum, opt.run.threads);
            detail::report(
                opt.run.progress,
                sky_share + (1.0 - sky_share) * static_cast<double>(d0 + n) / static_cast<double>(suns.size() + 1), fn);
        }
        res.roof_energy = detail::to_patch_energy(roof_sum, res.quarter_days);
        res.facade_energy = detail::to_patch_energy(facade_sum, res.quarter_days);
    });
    detail::report(opt.run.progress, 1.0, fn);
    return res;
}

}  // namespace lidarfx
