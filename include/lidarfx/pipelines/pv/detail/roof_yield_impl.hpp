// SPDX-License-Identifier: Apache-2.0
// Implementation of roof_yield (pipelines/pv/roof_yield.hpp): the cells of each patch, then per daylight sun one
// cast-shadow pass and the beam of every patch; the diffuse part is the year's DHI times each patch's sky view.
#pragma once
// Included at the end of its public header, which declares what is defined here.

#include <algorithm>
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
#include "lidarfx/kernels/solar/raylines_shadow.hpp"
#include "lidarfx/kernels/solar/sky_options.hpp"
#include "lidarfx/kernels/solar/sky_view_factor.hpp"
#include "lidarfx/pipelines/pv/roof_suitability.hpp"

namespace lidarfx::detail {

/// The cell indices (r * cols + c) of each patch, by position in roofs.patches, in raster order.
inline std::vector<std::vector<std::ptrdiff_t>> roof_patch_cells(const roof_suitability_result& roofs)
{
    const std::ptrdiff_t rows = roofs.patch_id.rows(), cols = roofs.patch_id.cols();
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
    return cells;
}

}  // namespace lidarfx::detail

namespace lidarfx {

template <raster_input Dsm>
std::vector<roof_patch_yield> roof_yield(const Dsm& dsm, double cell_m, const roof_suitability_result& roofs,
                                         const solar_site& site, std::span<const irradiance_record> records,
                                         const roof_yield_options& opt)
{
    constexpr const char* fn = "roof_yield";
    detail::require_positive(cell_m, fn, "cell_m");
    detail::check_execution(opt.run, fn);
    detail::require_same_shape(dsm, roofs.patch_id, fn, "dsm", "roofs.patch_id");
    require_sky_options(opt.sky, fn, true);
    detail::require(opt.performance_ratio > 0.0 && opt.performance_ratio <= 1.0, fn, "performance_ratio", "in (0, 1]",
                    opt.performance_ratio);
    const std::vector<daylight_sun> suns = daylight_suns(records, site);
    const std::ptrdiff_t rows = dsm.rows(), cols = dsm.cols();
    const std::vector<std::vector<std::ptrdiff_t>> cells = detail::roof_patch_cells(roofs);
    std::vector<roof_patch_yield> out(roofs.patches.size());
    return detail::with_float_view(dsm, [&](raster_view<const float> z) {
        const raster<float> svf = sky_view_factor(
            z, cell_m,
            {.method = opt.sky.svf_method, .directions = opt.sky.svf_directions, .run = {.threads = opt.run.threads}});
        // Per patch: sky factor sum over its cells (constant over the year) and the plane's normal.
        std::vector<double> sky(roofs.patches.size(), 0.0), beam(roofs.patches.size(), 0.0);
        double dhi_kwh = 0.0;  // the year's DHI sum, kWh/m^2: the same for every patch
        std::vector<enu_vector> normal(roofs.patches.size());
        for (std::size_t i = 0; i < roofs.patches.size(); ++i) {
            const roof_patch& p = roofs.patches[i];
            normal[i] = surface_normal(p.tilt_deg, p.azimuth_deg);
            const double view = (1.0 + std::cos(p.tilt_deg * (std::numbers::pi / 180.0))) / 2.0;
            for (const std::ptrdiff_t k : cells[i]) sky[i] += static_cast<double>(svf.data()[k]) * view;
        }
        raster<std::uint8_t> lit(rows, cols);
        for (std::size_t d = 0; d < suns.size(); ++d) {
            const daylight_sun& s = suns[d];
            raylines_shadow(z, lit, cell_m, s.azimuth_deg, s.elevation_deg,
                            {.nan_cell = 0, .run = {.threads = opt.run.threads}});
            dhi_kwh += s.dhi_w_m2 * s.kwh_per_w_m2;
            for (std::size_t i = 0; i < cells.size(); ++i) {
                const double cos_t = enu_dot(s.sun, normal[i]);
                if (!(cos_t > 0.0)) continue;
                std::size_t lit_cells = 0;
                for (const std::ptrdiff_t k : cells[i]) lit_cells += lit.data()[k] == 1 ? 1 : 0;
                beam[i] += s.dni_w_m2 * s.kwh_per_w_m2 * cos_t * static_cast<double>(lit_cells);
            }
            detail::report(opt.run.progress, static_cast<double>(d + 1) / static_cast<double>(suns.size()), fn);
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
