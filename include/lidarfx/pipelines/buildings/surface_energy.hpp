// SPDX-License-Identifier: Apache-2.0
// surface_energy: annual and quarterly irradiation of every roof patch and facade sub-patch of a surface model
// from hourly weather records, beam with cast shadows and diffuse with the sky view (dissertation 3.3).
#pragma once

#include <array>
#include <chrono>
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
#include "lidarfx/kernels/solar/incidence.hpp"
#include "lidarfx/kernels/solar/irradiance_record.hpp"
#include "lidarfx/kernels/solar/ray_lines.hpp"
#include "lidarfx/kernels/solar/raylines_shadow.hpp"
#include "lidarfx/kernels/solar/sky_view_factor.hpp"
#include "lidarfx/kernels/solar/sun_position.hpp"
#include "lidarfx/pipelines/buildings/facade_patches.hpp"
#include "lidarfx/pipelines/buildings/facade_rays.hpp"
#include "lidarfx/pipelines/buildings/facade_shading.hpp"
#include "lidarfx/pipelines/buildings/facade_sky.hpp"
#include "lidarfx/pipelines/buildings/patches.hpp"

namespace lidarfx {

/// Settings of surface_energy.
struct surface_energy_options {
    facade_patches_options facades = {};  ///< how walls are found and split (8 levels, walls > 1 m)
    /// Sky view factor for the diffuse part: source_share (the dissertation's 1,081 sources, default) or
    /// cosine_weighted; roofs use sky_view_factor of their cells, facades facade_sky_view.
    sky_view_factor_method svf_method = sky_view_factor_method::source_share;
    int svf_directions = 72;        ///< azimuths of the sky view sweeps, >= 4
    sun_position_options sun = {};  ///< sun model (default NREL SPA with refraction at sea level)
    /// Quarters are those of local standard time UTC + this many hours (TMY3's zone), in [-14, 14]; 0 = UTC.
    double month_utc_offset_h = 0.0;
    /// Meridian convergence of the grid at the site, degrees (> 0: grid north east of true north): sun azimuths
    /// are turned to grid north, a_grid = a_true - convergence (to_grid_azimuth_deg), in [-90, 90]; 0 = none.
    double meridian_convergence_deg = 0.0;
    execution run = {};  ///< threads, progress and cancellation (core/parallel.hpp); never changes the result
};

/// Irradiation received by one patch per square metre of its surface.
struct patch_energy {
    double annual_kwh_m2 = 0;                    ///< sum over all records, kWh/m^2
    std::array<double, 4> quarter_kwh_m2_day{};  ///< Jan-Mar, Apr-Jun, Jul-Sep, Oct-Dec: sum / days of the quarter
};

/// The patches of a surface model and what each receives.
struct surface_energy_result {
    std::vector<surface_patch> roofs;                ///< roof quad patches (surface_patches, ground left out)
    std::vector<double> roof_sky_view;               ///< per roof patch: mean SVF of its 4 cells * (1 + cos tilt) / 2
    std::vector<patch_energy> roof_energy;           ///< per roof patch
    std::vector<facade_patch> facades;               ///< facade sub-patches (facade_patches)
    std::vector<double> facade_sky_view;             ///< per sub-patch: facade_sky_view
    std::vector<patch_energy> facade_energy;         ///< per sub-patch
    double ghi_kwh_m2 = 0;                           ///< sum of GHI * interval over all records (open flat ground)
    std::array<double, 4> quarter_ghi_kwh_m2_day{};  ///< the same per quarter, per day
    std::array<double, 4> quarter_days{};            ///< days of records in each quarter (sum of intervals / 86400)
    std::size_t sun_up_records = 0;                  ///< records with the sun above the horizon at their middle
};

namespace detail {

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

}  // namespace detail

/// Annual and quarterly irradiation (kWh/m^2) of every roof patch and facade sub-patch of a DSM with a
/// building-id raster (dissertation 3.3, Tables 1-2 come from surface_class_table). For every record with the sun
/// above the horizon at the middle of its interval (sun_position with opt.sun, 0 < e), times the interval in
/// hours / 1000:
///   roof patch:  DNI * max(0, n . s) * lit + DHI * SVF * (1 + cos b) / 2, with n the patch normal, s the sun
///                vector, lit the share of the patch's 4 cells that raylines_shadow lights and SVF the mean
///                sky_view_factor (opt.svf_method) of its 4 cells;
///   sub-patch:   DNI * max(0, cos theta) * lit + DHI * SVF_facade, cos theta = cos e cos(A_sun - A_facing),
///                lit from facade_lit and SVF_facade from facade_sky_view (it already holds the wall's tilt).
/// A flat open roof thus receives DNI sin e + DHI = GHI per record. Each record goes to the quarter of its middle
/// in UTC + month_utc_offset_h; quarter_kwh_m2_day = the quarter's sum / its days of records. Cost: one sky view
/// factor of the raster and facade_sky_view (2 svf_directions sweeps), then per daylight record one ray-line
/// sweep of the raster (shadows of the cells and of every sub-patch at once) and O(patches):
/// O(records * rows * cols + records * patches). Results are the same for any thread count. dsm and cell_m in
/// metres, latitude and longitude in degrees (north, east). @throws invalid_input if shapes differ, cell_m is not
/// finite and > 0, a record is invalid, an option is out of range or sun_position refuses the place or a time;
/// cancelled if run.progress returns false.
template <raster_input Dsm, raster_input Ids>
surface_energy_result surface_energy(const Dsm& dsm, const Ids& building_id, double cell_m, double latitude_deg,
                                     double longitude_deg, std::span<const irradiance_record> records,
                                     const surface_energy_options& opt = {})
{
    constexpr const char* fn = "surface_energy";
    detail::require_positive(cell_m, fn, "cell_m");
    detail::check_execution(opt.run, fn);
    detail::require(opt.svf_directions >= 4, fn, "svf_directions", ">= 4", opt.svf_directions);
    detail::require(opt.meridian_convergence_deg >= -90.0 && opt.meridian_convergence_deg <= 90.0, fn,
                    "meridian_convergence_deg", "in [-90, 90] degrees", opt.meridian_convergence_deg);
    detail::require(opt.month_utc_offset_h >= -14.0 && opt.month_utc_offset_h <= 14.0, fn, "month_utc_offset_h",
                    "in [-14, 14] hours", opt.month_utc_offset_h);
    detail::require_same_shape(dsm, building_id, fn, "dsm", "building_id");
    detail::require_records(records, fn);
    surface_energy_result res;
    // Sun positions first: they validate the place and every time before any long work.
    struct daylight {
        std::size_t record, quarter;
        double azimuth_deg, elevation_deg;
    };
    std::vector<daylight> days;
    for (std::size_t i = 0; i < records.size(); ++i) {
        const irradiance_record& r = records[i];
        const auto q = static_cast<std::size_t>(detail::record_month(r, opt.month_utc_offset_h) / 3);
        const double hours = static_cast<double>(r.interval.count()) / 3600.0;
        res.quarter_days[q] += hours / 24.0;
        res.quarter_ghi_kwh_m2_day[q] += r.ghi_w_m2 * hours / 1000.0;
        res.ghi_kwh_m2 += r.ghi_w_m2 * hours / 1000.0;
        const sun_position_result sun = sun_position(r.middle_utc(), latitude_deg, longitude_deg, opt.sun);
        if (sun.elevation_deg > 0.0)
            days.push_back(
                {i, q, to_grid_azimuth_deg(sun.azimuth_deg, opt.meridian_convergence_deg), sun.elevation_deg});
    }
    for (std::size_t q = 0; q < 4; ++q) {
        if (res.quarter_days[q] > 0.0) res.quarter_ghi_kwh_m2_day[q] /= res.quarter_days[q];
    }
    res.sun_up_records = days.size();
    res.roofs = surface_patches(dsm, building_id, cell_m, {.ground = false});
    res.facades = facade_patches(dsm, building_id, cell_m, opt.facades);

    detail::with_float_view(dsm, [&](raster_view<const float> z) {
        const std::ptrdiff_t rows = z.rows(), cols = z.cols();
        const double sky_share = 0.1;  // share of the progress taken by the two sky views
        const raster<float> svf =
            sky_view_factor(z, cell_m,
                            {.method = opt.svf_method,
                             .directions = opt.svf_directions,
                             .run = {.threads = opt.run.threads,
                                     .progress = detail::progress_phase(opt.run.progress, 0.0, sky_share / 2)}});
        res.facade_sky_view =
            facade_sky_view(z, std::span<const facade_patch>(res.facades), cell_m,
                            {.method = opt.svf_method,
                             .directions = opt.svf_directions,
                             .run = {.threads = opt.run.threads,
                                     .progress = detail::progress_phase(opt.run.progress, sky_share / 2, sky_share)}});
        res.roof_sky_view.resize(res.roofs.size());
        for (std::size_t i = 0; i < res.roofs.size(); ++i) {
            const surface_patch& p = res.roofs[i];
            const double mean = 0.25 * (static_cast<double>(svf(p.row, p.col)) + svf(p.row, p.col + 1) +
                                        svf(p.row + 1, p.col) + svf(p.row + 1, p.col + 1));
            res.roof_sky_view[i] = mean * (1.0 + p.normal.up) / 2.0;
        }

        const detail::facade_observers obs = detail::make_facade_observers(rows, cols, res.facades);
        std::vector<std::array<double, 4>> roof_sum(res.roofs.size()), facade_sum(res.facades.size());
        raster<std::uint8_t> lit(rows, cols);
        std::vector<double> limit;
        const std::ptrdiff_t nroof = static_cast<std::ptrdiff_t>(res.roofs.size());
        const std::ptrdiff_t nfacade = static_cast<std::ptrdiff_t>(res.facades.size());
        for (std::size_t d = 0; d < days.size(); ++d) {
            const daylight& day = days[d];
            const irradiance_record& rec = records[day.record];
            const double hours_k = static_cast<double>(rec.interval.count()) / 3600.0 / 1000.0;
            const double dni = rec.dni_w_m2 * hours_k, dhi = rec.dhi_w_m2 * hours_k;
            const enu_vector sun = detail::sun_vector_unchecked(day.azimuth_deg, day.elevation_deg);
            const bool zenith = day.elevation_deg >= 90.0;  // nothing casts a shadow; walls get no beam
            const detail::ray_lines l = detail::make_ray_lines(day.azimuth_deg, rows, cols);
            const detail::shadow_lifts lift = detail::make_shadow_lifts(
                l, cell_m, zenith ? 0.0 : std::tan(day.elevation_deg * (std::numbers::pi / 180.0)));
            if (!zenith) detail::facade_shadow_sweep(z, obs, l, lift, limit, lit.view(), opt.run.threads, fn);
            const std::size_t q = day.quarter;
            const detail::facade_cos_table cos_theta(day.azimuth_deg, day.elevation_deg);
            parallel_for_rows(nroof, 4096, opt.run.threads, [&](std::ptrdiff_t i0, std::ptrdiff_t i1) {
                for (std::ptrdiff_t i = i0; i < i1; ++i) {
                    const surface_patch& p = res.roofs[static_cast<std::size_t>(i)];
                    const double share = zenith ? 1.0
                                                : 0.25 * (lit(p.row, p.col) + lit(p.row, p.col + 1) +
                                                          lit(p.row + 1, p.col) + lit(p.row + 1, p.col + 1));
                    const double cos_t = detail::enu_dot(sun, p.normal);
                    roof_sum[static_cast<std::size_t>(i)][q] += (cos_t > 0.0 ? dni * cos_t * share : 0.0) +
                                                                dhi * res.roof_sky_view[static_cast<std::size_t>(i)];
                }
            });
            parallel_for_rows(nfacade, 4096, opt.run.threads, [&](std::ptrdiff_t i0, std::ptrdiff_t i1) {
                for (std::ptrdiff_t i = i0; i < i1; ++i) {
                    const facade_patch& p = res.facades[static_cast<std::size_t>(i)];
                    double beam = 0.0;
                    if (!zenith) {
                        const auto o = static_cast<std::size_t>(obs.index(p.front_row, p.front_col));
                        const double cos_t = cos_theta(p.facing_azimuth_deg);
                        if (detail::facade_patch_lit(p, cos_t, limit[o], lift) == 1) beam = dni * cos_t;
                    }
                    facade_sum[static_cast<std::size_t>(i)][q] +=
                        beam + dhi * res.facade_sky_view[static_cast<std::size_t>(i)];
                }
            });
            detail::report(
                opt.run.progress,
                sky_share + (1.0 - sky_share) * static_cast<double>(d + 1) / static_cast<double>(days.size() + 1), fn);
        }
        res.roof_energy = detail::to_patch_energy(roof_sum, res.quarter_days);
        res.facade_energy = detail::to_patch_energy(facade_sum, res.quarter_days);
    });
    detail::report(opt.run.progress, 1.0, fn);
    return res;
}

}  // namespace lidarfx
