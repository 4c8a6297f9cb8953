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
#include "lidarfx/kernels/solar/daylight_suns.hpp"
#include "lidarfx/kernels/solar/incidence.hpp"
#include "lidarfx/kernels/solar/irradiance_record.hpp"
#include "lidarfx/kernels/solar/ray_lines.hpp"
#include "lidarfx/kernels/solar/raylines_shadow.hpp"
#include "lidarfx/kernels/solar/sky_options.hpp"
#include "lidarfx/kernels/solar/sky_view_factor.hpp"
#include "lidarfx/kernels/solar/sun_position.hpp"
#include "lidarfx/pipelines/buildings/facade_lit.hpp"
#include "lidarfx/pipelines/buildings/facade_observers.hpp"
#include "lidarfx/pipelines/buildings/facade_patches.hpp"
#include "lidarfx/pipelines/buildings/facade_sky_view.hpp"
#include "lidarfx/pipelines/buildings/surface_patches.hpp"

namespace lidarfx {

/// Settings of surface_energy. Fields in this order (designated initializers follow it).
struct surface_energy_options {
    facade_patches_options facades = {};  ///< how walls are found and split (8 levels, walls > 1 m)
    /// Sky view factor for the diffuse part (svf_method, svf_directions): roofs use sky_view_factor of their
    /// cells, facades facade_sky_view. Only the isotropic sky without reflected light is modelled: diffuse must be
    /// isotropic and albedo 0.
    sky_options sky = {};
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

/// Annual and quarterly irradiation (kWh/m^2) of every roof patch and facade sub-patch of a DSM with a
/// building-id raster (dissertation 3.3, Tables 1-2 come from surface_class_table). For every daylight sun of the
/// records at the site (daylight_suns: sun above the horizon at the middle of the record's interval, azimuth
/// turned to grid north by site.meridian_convergence_deg), times the interval in hours / 1000:
///   roof patch:  DNI * max(0, n . s) * lit + DHI * SVF * (1 + cos b) / 2, with n the patch normal, s the sun
///                vector, lit the share of the patch's 4 cells that raylines_shadow lights and SVF the mean
///                sky_view_factor (opt.sky.svf_method) of its 4 cells;
///   sub-patch:   DNI * max(0, cos theta) * lit + DHI * SVF_facade, cos theta = cos e cos(A_sun - A_facing),
///                lit from facade_lit and SVF_facade from facade_sky_view (it already holds the wall's tilt).
/// A flat open roof thus receives DNI sin e + DHI = GHI per record. Each record goes to the quarter of its middle
/// in UTC + site.utc_offset_h; quarter_kwh_m2_day = the quarter's sum / its days of records. Cost: one sky view
/// factor of the raster and facade_sky_view (2 svf_directions sweeps), then per daylight record with DNI > 0 one
/// ray-line sweep of the raster (shadows of the cells and of every sub-patch at once; shallow lines along the rows
/// of a transposed copy) and O(roof patches + walls): O(records * rows * cols + records * patches). A wall's lit
/// sub-patches are those above a height, so a record's beam is added once per wall and summed upwards at the
/// end; the diffuse part, DHI * sky view, is added once per quarter. Records are taken 32 at a time: their
/// sweeps run side by side, then they are added to every patch in record order, so results are the same for any
/// thread count. Memory: the DSM twice (three times when it is not float), two bytes per cell per thread and, per
/// record of a batch, a byte per roof patch and 8 bytes per observer cell. dsm and cell_m in metres. @throws
/// invalid_input if shapes differ, cell_m is not finite and > 0, an option is out of range (or asks for the Perez sky
/// or an albedo), or daylight_suns refuses a record, the site or a time; cancelled if run.progress returns false.
template <raster_input Dsm, raster_input Ids>
surface_energy_result surface_energy(const Dsm& dsm, const Ids& building_id, double cell_m, const solar_site& site,
                                     std::span<const irradiance_record> records,
                                     const surface_energy_options& opt = {});

}  // namespace lidarfx

#include "lidarfx/pipelines/buildings/detail/surface_energy_impl.hpp"
