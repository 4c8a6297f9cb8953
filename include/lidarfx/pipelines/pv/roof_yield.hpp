// SPDX-License-Identifier: Apache-2.0
// roof_yield: the annual irradiation on the plane of every roof patch of roof_suitability, with cast shadows
// and sky view from the solar kernels, and the energy a PV system of the patch's size gives from it.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/kernels/solar/daylight_suns.hpp"
#include "lidarfx/kernels/solar/irradiance_record.hpp"
#include "lidarfx/kernels/solar/sky_options.hpp"
#include "lidarfx/pipelines/pv/roof_suitability.hpp"

namespace lidarfx {

/// Settings of roof_yield. Fields in this order (designated initializers follow it).
struct roof_yield_options {
    /// Sky view factor sweep of the diffuse part (as irradiance_maps). Only the isotropic sky without reflected
    /// light is modelled: diffuse must be isotropic and albedo 0.
    sky_options sky = {};
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
/// irradiance_maps computes it for a tilted cell: for every daylight sun of the records at the site
/// (daylight_suns: sun above the horizon at the record's middle, azimuth turned to grid north by
/// site.meridian_convergence_deg),
///   beam    = DNI * max(0, cos theta) * lit   (theta between the sun and the patch's plane; lit from
///                                              raylines_shadow of the DSM: neighbours and trees shade the patch)
///   diffuse = DHI * SVF * (1 + cos tilt) / 2   (isotropic sky; SVF = sky_view_factor of the DSM)
/// times the record's interval, averaged over the patch's cells, in kWh/m^2; energy = irradiation * kWp * ratio.
/// A patch's plane is its tilt and azimuth (clockwise from grid north; flat roofs: their reported tilt, 0 unless
/// racks are modelled). O(records * rows * cols + records * patch cells). dsm and cell_m in metres.
/// @throws invalid_input if shapes differ, cell_m is not finite and > 0, an option is out of range (or asks for
/// the Perez sky or an albedo), or daylight_suns refuses a record, the site or a time; cancelled if run.progress
/// returns false.
template <raster_input Dsm>
std::vector<roof_patch_yield> roof_yield(const Dsm& dsm, double cell_m, const roof_suitability_result& roofs,
                                         const solar_site& site, std::span<const irradiance_record> records,
                                         const roof_yield_options& opt = {});

}  // namespace lidarfx

#include "lidarfx/pipelines/pv/detail/roof_yield_impl.hpp"
