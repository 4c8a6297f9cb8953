// SPDX-License-Identifier: Apache-2.0
// irradiance_maps: hourly weather records summed into annual and monthly irradiation maps of a surface model,
// with cast shadows for the beam and the sky view factor for the diffuse part (dissertation 3.2.5, 3.3).
#pragma once

#include <array>
#include <cstddef>
#include <span>

#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/kernels/solar/daylight_suns.hpp"
#include "lidarfx/kernels/solar/irradiance_record.hpp"
#include "lidarfx/kernels/solar/sky_options.hpp"

namespace lidarfx {

/// Settings of irradiance_maps. Fields in this order (designated initializers follow it).
struct irradiance_maps_options {
    /// Sky view factor sweep, diffuse sky model (isotropic by default, or perez) and ground albedo (0 by default;
    /// horizontal cells never get reflected light).
    sky_options sky = {};
    /// Line families of the hourly shadows (raylines_shadow_options::line_phases), in [1, 64]: 4 (default) puts
    /// every cell's ray within 1/8 cell of its own centre; 1 is the dissertation's single family, up to 3 times
    /// faster for azimuths off the axes and diagonals.
    int shadow_line_phases = 4;
    execution run = {};  ///< threads, progress and cancellation (core/parallel.hpp); never changes the result
};

/// Irradiation maps of a surface model, kWh/m^2 per cell (NaN on NaN cells), with their ingredients.
struct irradiance_maps_result {
    raster<float> annual_kwh_m2;                   ///< sum over all records
    std::array<raster<float>, 12> month_kwh_m2;    ///< [0] January ... [11] December; they sum to annual_kwh_m2
    raster<float> sky_view_factor;                 ///< the SVF used for the diffuse part, [0, 1]
    double ghi_kwh_m2 = 0;                         ///< sum of GHI * interval over all records (open flat ground)
    std::array<double, 12> month_ghi_kwh_m2 = {};  ///< the same per month
    std::size_t sun_up_records = 0;                ///< records with the sun above the horizon at their middle
};

/// Annual and monthly irradiation maps (kWh/m^2) of a surface model from irradiance records (dissertation 3.3).
/// For every daylight sun of the records at the site (daylight_suns: sun above the horizon at the middle of the
/// record's interval, azimuth turned to grid north by site.meridian_convergence_deg), each cell gets, times the
/// interval in hours / 1000:
///   beam    = DNI * max(0, cos theta) * lit    (cos theta = enu_dot(sun, surface normal); lit from
///                                               raylines_shadow for that sun: 1 lit, 0 shadow)
///   diffuse = DHI * SVF * (1 + cos b) / 2      (isotropic sky; SVF = sky_view_factor of the DSM, computed once)
///   ground  = GHI * albedo * (1 - cos b) / 2   (only when opt.sky.albedo > 0)
/// with b the cell's tilt: surface_tilt_deg (degrees from horizontal in [0, 180], e.g. slope_aspect's slope_deg)
/// and surface_azimuth_deg (degrees clockwise from grid north, e.g. slope_aspect's aspect_deg; NaN counts as 0),
/// given together with the DSM's shape, or both empty (the default): every cell horizontal, cos theta = sin e.
/// A NaN tilt gives a NaN cell; an infinite azimuth is refused. Records with the sun down add nothing.
/// With opt.sky.diffuse = diffuse_model::perez the diffuse line is instead the Perez et al. (1990) sky
/// (perez_sky_coefficients with opt.sky.perez; the record's DHI, DNI, sun elevation and UTC day of year):
///   diffuse = (isotropic + horizon) * SVF + circumsolar * lit
///           = DHI [(1 - F1) (1 + cos b) / 2 + F2 sin b] SVF + DHI F1 max(0, cos theta) / max(cos 85, sin e) lit
/// (the circumsolar part comes from around the sun's disc, so the cell's shadow hides it; the horizon band takes
/// the SVF as the isotropic part does; with opt.sky.perez.nonnegative = false the sum is clamped at 0).
/// On open horizontal ground a record adds DNI sin e + DHI (either sky model, for e >= 5 deg), which is GHI for
/// consistent records, so the annual map equals ghi_kwh_m2 there. Records may come in any order; each goes to the
/// month of its middle in UTC + site.utc_offset_h. dsm heights and cell_m in metres. The terms that do not depend
/// on "lit" (isotropic sky, horizon band, reflected light) are summed per month first and meet each cell once per
/// month; a record without beam or circumsolar light casts no shadow to compute. The shadows of up to 8 records of
/// a month are swept side by side (one thread each), then added to the month in one pass. On horizontal cells the
/// suns whose ray lines are shallow (closer to east-west than the diagonals) are swept along the rows of a transposed
/// copy of the DSM (raylines_shadow_probed, the same shadows bit for bit) and summed transposed until the month
/// ends. Cost per daylight record with beam light O(rows * cols) (one raylines_shadow pass and part of an
/// accumulation pass) plus one sky view factor (svf_directions sweeps). Memory per cell: 2 doubles, 14 floats and
/// 8 bytes, plus on horizontal cells a double, a float and 8 bytes for the transposed suns (with per-cell surfaces
/// 20 bytes instead, 24 with the Perez sky). Results are the same for any thread count.
/// @throws invalid_input if cell_m is not finite and > 0, the surface rasters' shapes differ from the DSM's or
/// only one is given, a tilt is outside [0, 180], an option is out of range, or daylight_suns refuses a record,
/// the site or a time; cancelled if run.progress returns false.
template <raster_input In>
irradiance_maps_result irradiance_maps(const In& dsm, double cell_m, const solar_site& site,
                                       std::span<const irradiance_record> records,
                                       raster_view<const float> surface_tilt_deg = {},
                                       raster_view<const float> surface_azimuth_deg = {},
                                       const irradiance_maps_options& opt = {});

}  // namespace lidarfx

#include "lidarfx/pipelines/solar/detail/irradiance_maps_impl.hpp"
