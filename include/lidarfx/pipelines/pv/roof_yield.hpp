// SPDX-License-Identifier: Apache-2.0
// roof_yield: the annual irradiation on the plane of every roof patch of roof_suitability, with cast shadows
// and sky view from the solar kernels, and the energy a PV system of the patch's size gives from it.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/kernels/solar/incidence.hpp"
#include "lidarfx/kernels/solar/irradiance_record.hpp"
#include "lidarfx/kernels/solar/raylines_shadow.hpp"
#include "lidarfx/kernels/solar/sky_view_factor.hpp"
#include "lidarfx/kernels/solar/sun_position.hpp"
#include "lidarfx/pipelines/pv/roof_suitability.hpp"

namespace lidarfx {

/// Settings of roof_yield.
struct roof_yield_options {
    sun_position_options sun = {};          ///< sun model (default NREL SPA with refraction at sea level)
    double meridian_convergence_deg = 0.0;  ///< sun azimuths turned to grid north (to_grid_azimuth_deg), [-90, 90]
    sky_view_factor_method svf_method = sky_view_factor_method::source_share;  ///< as irradiance_maps
    int svf_directions = 72;         ///< azimuths of the sky view factor sweep, >= 4
    double performance_ratio = 0.8;  ///< system losses: energy = H_plane * kWp * ratio / (1 kW/m^2), (0, 1]
    execution run = {};              ///< threads, progress and cancellation; never changes the result
};

/// Irradiation and energy of one roof patch.
struct roof_patch_yield {
    std::int32_t patch_id = 0;
    double annual_kwh_m2 = 0;  ///< mean over the patch's cells of the irradiation on the patch's plane, kWh/m^2
    double annual_kwh = 0;     ///< annual_kwh_m2 * kwp * performance_ratio (kWh per kWp at 1 kW/m^2)
};

/// Annual irradiation on the plane of every patch of `roofs` (roof_suitability on the same DSM and grid), as
/// irradiance_maps computes it for a tilted cell: for every record with the sun above the horizon at its middle,
///   beam    = DNI * max(0, cos theta) * lit   (theta between the sun and the patch's plane; lit from
///                                              raylines_shadow of the DSM: neighbours and trees shade the patch)
///   diffuse = DHI * SVF * (1 + cos tilt) / 2   (isotropic sky; SVF = sky_view_factor of the DSM)
/// times the record's interval, averaged over the patch's cells, in kWh/m^2; energy = irradiation * kWp * ratio.
/// A patch's plane is its tilt and azimuth (flat roofs: their reported tilt, 0 unless racks are modelled).
/// O(records * rows * cols + records * patch cells). dsm and cell_m in metres, latitude and longitude in degrees.
/// @throws invalid_input if shapes differ, cell_m is not finite and > 0, a record is invalid or an option is out
/// of range; cancelled if run.progress returns false.
template <raster_input Dsm>
std::vector<roof_patch_yield> roof_yield(const Dsm& dsm, double cell_m, const roof_suitability_result& roofs,
                                         double latitude_deg, double longitude_deg,
                                         std::span<const irradiance_record> records, const roof_yield_options& opt = {})
{
    constexpr const char* fn = "roof_yield";
    detail::require_positive(cell_m, fn, "cell_m");
    detail::check_execution(opt.run, fn);
    detail::require_same_shape(dsm, roofs.patch_id, fn, "dsm", "roofs.patch_id");
    detail::require(opt.svf_directions >= 4, fn, "svf_directions", ">= 4", opt.svf_directions);
    detail::require(opt.performance_ratio > 0.0 && opt.performance_ratio <= 1.0, fn, "performance_ratio", "in (0, 1]",
                    opt.performance_ratio);
    detail::require(opt.meridian_convergence_deg >= -90.0 && opt.meridian_convergence_deg <= 90.0, fn,
                    "meridian_convergence_deg", "in [-90, 90] degrees", opt.meridian_convergence_deg);
    detail::require_records(records, fn);
    const std::ptrdiff_t rows = dsm.rows(), cols = dsm.cols();
    // Cells of each patch (by position in roofs.patches), in raster order.
    std::vector<std::size_t> index_of;
    for (std::size_t i = 0; i < roofs.patches.size(); ++i) {
        const auto id = static_cast<std::size_t>(roofs.patches[i].patch_id);
        if (index_of.size() <= id) index_of.resize(id + 1, roofs.patches.size());
        index_of[id] = i;
    }
    std::vector<std::vector<std::ptrdiff_t>> cells(roofs.patches.size());
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const auto id = static_cast<std::size_t>(std::max(0, roofs.patch_id(r, c)));
            if (id > 0 && id < index_of.size() && index_of[id] < cells.size())
                cells[index_of[id]].push_back(r * cols + c);
        }
    struct daylight {
        std::size_t record;
        double azimuth_deg, elevation_deg;
    };
    std::vector<daylight> days;
    for (std::size_t i = 0; i < records.size(); ++i) {
        const sun_position_result s = sun_position(records[i].middle_utc(), latitude_deg, longitude_deg, opt.sun);
        if (s.elevation_deg > 0.0)
            days.push_back({i, to_grid_azimuth_deg(s.azimuth_deg, opt.meridian_convergence_deg), s.elevation_deg});
    }
    std::vector<roof_patch_yield> out(roofs.patches.size());
    return detail::with_float_view(dsm, [&](raster_view<const float> z) {
        const raster<float> svf = sky_view_factor(
            z, cell_m,
            {.method = opt.svf_method, .directions = opt.svf_directions, .run = {.threads = opt.run.threads}});
        // Per patch: sky factor sum over its cells (constant over the year) and the plane's normal.
        std::vector<double> sky(roofs.patches.size(), 0.0), beam(roofs.patches.size(), 0.0);
        double dhi_kwh = 0.0;  // the year's DHI sum, kWh/m^2: the same for every patch
        std::vector<enu_vector> normal(roofs.patches.size());
        for (std::size_t i = 0; i < roofs.patches.size(); ++i) {
            const roof_patch& p = roofs.patches[i];
            normal[i] = detail::surface_normal_unchecked(p.tilt_deg, p.azimuth_deg);
            const double view = (1.0 + std::cos(p.tilt_deg * detail::incidence_rad_per_deg)) / 2.0;
            for (const std::ptrdiff_t k : cells[i]) sky[i] += static_cast<double>(svf.data()[k]) * view;
        }
        raster<std::uint8_t> lit(rows, cols);
        for (std::size_t d = 0; d < days.size(); ++d) {
            const irradiance_record& rec = records[days[d].record];
            const double hours_k = static_cast<double>(rec.interval.count()) / 3600.0 / 1000.0;
            raylines_shadow(z, lit, cell_m, days[d].azimuth_deg, days[d].elevation_deg,
                            {.nan_cell = 0, .run = {.threads = opt.run.threads}});
            const enu_vector sun = detail::sun_vector_unchecked(days[d].azimuth_deg, days[d].elevation_deg);
            dhi_kwh += rec.dhi_w_m2 * hours_k;
            for (std::size_t i = 0; i < cells.size(); ++i) {
                const double cos_t = detail::enu_dot(sun, normal[i]);
                if (!(cos_t > 0.0)) continue;
                std::size_t lit_cells = 0;
                for (const std::ptrdiff_t k : cells[i]) lit_cells += lit.data()[k] == 1 ? 1 : 0;
                beam[i] += rec.dni_w_m2 * hours_k * cos_t * static_cast<double>(lit_cells);
            }
            detail::report(opt.run.progress, static_cast<double>(d + 1) / static_cast<double>(days.size()), fn);
        }
        for (std::size_t i = 0; i < out.size(); ++i) {
            const double n = static_cast<double>(cells[i].size());
            out[i].patch_id = roofs.patches[i].patch_id;
            out[i].annual_kwh_m2 = n > 0 ? (beam[i] + dhi_kwh * sky[i]) / n : 0.0;
            out[i].annual_kwh = out[i].annual_kwh_m2 * roofs.patches[i].kwp * opt.performance_ratio;
        }
        return out;
    });
}

}  // namespace lidarfx
