// SPDX-License-Identifier: Apache-2.0
// irradiance_maps: hourly weather records summed into annual and monthly irradiation maps of a surface model,
// with cast shadows for the beam and the sky view factor for the diffuse part (dissertation 3.2.5, 3.3).
#pragma once

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
#include <span>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/kernels/solar/incidence.hpp"
#include "lidarfx/kernels/solar/irradiance_record.hpp"
#include "lidarfx/kernels/solar/perez_diffuse.hpp"
#include "lidarfx/kernels/solar/raylines_shadow.hpp"
#include "lidarfx/kernels/solar/sky_view_factor.hpp"
#include "lidarfx/kernels/solar/sun_position.hpp"

namespace lidarfx {

/// Sky model of the diffuse part of irradiance_maps.
enum class diffuse_model {
    isotropic,  ///< DHI * SVF * (1 + cos b) / 2: a uniform sky (the dissertation's)
    perez,      ///< Perez et al. (1990) anisotropic sky: circumsolar part times lit, the rest times SVF
};

/// Settings of irradiance_maps.
struct irradiance_maps_options {
    /// Surface tilt of every cell, degrees from horizontal in [0, 180] (e.g. slope_aspect's slope_deg); empty (the
    /// default) = every cell horizontal. Same shape as the DSM when given; NaN -> NaN output.
    raster_view<const float> surface_tilt_deg = {};
    /// Azimuth each cell faces, degrees clockwise from north (e.g. slope_aspect's aspect_deg); used with
    /// surface_tilt_deg, which it must accompany; NaN (a flat cell's aspect) counts as 0.
    raster_view<const float> surface_azimuth_deg = {};
    sun_position_options sun = {};  ///< sun model (default NREL SPA with refraction at sea level)
    sky_view_factor_method svf_method = sky_view_factor_method::source_share;  ///< the dissertation's by default
    int svf_directions = 72;  ///< azimuths of the sky view factor sweep, >= 4
    /// Line families of the hourly shadows (raylines_shadow_options::line_phases), in [1, 64]: 4 (default) puts
    /// every cell's ray within 1/8 cell of its own centre; 1 is the dissertation's single family, up to 3 times
    /// faster for azimuths off the axes and diagonals.
    int shadow_line_phases = 4;
    /// Ground reflectance (albedo) in [0, 1] for ground-reflected irradiance GHI * albedo * (1 - cos b) / 2 on
    /// tilted cells; 0 (the default, the dissertation's) leaves it out. Horizontal cells never get any.
    double albedo = 0.0;
    /// Sky model of the diffuse part: isotropic (the default, the dissertation's) or perez (perez_diffuse).
    diffuse_model diffuse = diffuse_model::isotropic;
    perez_diffuse_options perez = {};  ///< settings of the Perez sky (used with diffuse_model::perez)
    /// Months are those of local standard time UTC + this many hours (TMY3's zone), in [-14, 14]; 0 = UTC months.
    double month_utc_offset_h = 0.0;
    /// Meridian convergence at the DSM, degrees in [-90, 90]: the angle from true north to the grid's north (up,
    /// row 0), positive when grid north lies east (clockwise) of true north, as east of the central meridian of a
    /// transverse Mercator zone in the northern hemisphere. Sun azimuths (from true north) are turned to grid
    /// azimuths a_grid = a_true - meridian_convergence_deg before shadows and incidence, so surface_azimuth_deg
    /// is taken clockwise from grid north too. 0 (the default): grid north is true north.
    double meridian_convergence_deg = 0.0;
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

namespace detail {

/// Per-cell incidence terms of a tilted surface: normal vector, (1 + cos b) / 2, (1 - cos b) / 2 and, for the
/// Perez sky only, sin b.
struct cell_surface {
    std::vector<enu_vector> normal;
    std::vector<float> sky, ground, sin_tilt;
};

/// One record's Perez-sky terms, each already times DHI (or DNI, GHI) and the interval in kWh (W h / 1000).
struct perez_record_terms {
    double dni = 0, beam_flat = 0;  ///< DNI, and DNI sin e for horizontal cells
    double isotropic = 0;           ///< DHI (1 - F1): times (1 + cos b) / 2 and SVF
    double horizon = 0;             ///< DHI F2: times sin b and SVF
    double circumsolar = 0;         ///< DHI F1 / max(cos 85, sin e): times max(0, cos theta) and lit
    double reflected = 0;           ///< GHI albedo: times (1 - cos b) / 2
    bool clamp = false;             ///< clamp the diffuse sum at 0 (components may be < 0)
};

/// Adds one record's beam, Perez diffuse and reflected irradiation to one row (acc) of cols cells: lit and svf
/// the row's shadow and sky view factor, surf the per-cell surfaces (nullptr: horizontal) from cell index k0.
inline void add_perez_row(double* acc, const std::uint8_t* lit, const float* svf, std::ptrdiff_t cols,
                          const cell_surface* surf, std::size_t k0, const enu_vector& sun,
                          const perez_record_terms& t) noexcept
{
    if (surf == nullptr) {
        const double circumsolar = t.circumsolar * sun.up;
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            double diffuse = t.isotropic * static_cast<double>(svf[c]) + (lit[c] == 1 ? circumsolar : 0.0);
            if (t.clamp) diffuse = std::max(0.0, diffuse);
            acc[c] += (lit[c] == 1 ? t.beam_flat : 0.0) + diffuse;
        }
        return;
    }
    for (std::ptrdiff_t c = 0; c < cols; ++c) {
        const std::size_t k = k0 + static_cast<std::size_t>(c);
        const double cos_t = enu_dot(sun, surf->normal[k]);
        const bool sunny = lit[c] == 1 && cos_t > 0.0;
        const double sky =
            t.isotropic * static_cast<double>(surf->sky[k]) + t.horizon * static_cast<double>(surf->sin_tilt[k]);
        double diffuse = sky * static_cast<double>(svf[c]) + (sunny ? t.circumsolar * cos_t : 0.0);
        if (t.clamp) diffuse = std::max(0.0, diffuse);
        acc[c] += (sunny ? t.dni * cos_t : 0.0) + diffuse + t.reflected * static_cast<double>(surf->ground[k]);
    }
}

/// Day of the year 1..366 of a record's middle, UTC (for the extraterrestrial irradiance of the Perez sky).
inline int record_day_of_year(const irradiance_record& rec)
{
    namespace chr = std::chrono;
    const chr::sys_days day = chr::floor<chr::days>(rec.middle_utc());
    const chr::year_month_day ymd{day};
    return static_cast<int>((day - chr::sys_days{ymd.year() / chr::January / 1}).count()) + 1;
}

}  // namespace detail

/// Annual and monthly irradiation maps (kWh/m^2) of a surface model from irradiance records (dissertation 3.3).
/// For every record with the sun above the horizon at the middle of its interval (sun_position with opt.sun,
/// elevation e > 0), each cell gets, times the interval in hours / 1000:
///   beam    = DNI * max(0, cos theta) * lit    (cos theta from cos_incidence; lit from raylines_shadow for that
///                                               sun position: 1 lit, 0 shadow)
///   diffuse = DHI * SVF * (1 + cos b) / 2      (isotropic sky; SVF = sky_view_factor of the DSM, computed once)
///   ground  = GHI * albedo * (1 - cos b) / 2   (only when opt.albedo > 0)
/// with b the cell's tilt (0 by default: horizontal, cos theta = sin e), and the sun's azimuth turned from true to
/// grid north by opt.meridian_convergence_deg (a_grid = a_true - convergence). Records with the sun down add nothing.
/// With opt.diffuse = diffuse_model::perez the diffuse line is instead the Perez et al. (1990) sky (perez_diffuse
/// with opt.perez; the record's DHI, DNI, sun elevation and UTC day of year):
///   diffuse = (isotropic + horizon) * SVF + circumsolar * lit
///           = DHI [(1 - F1) (1 + cos b) / 2 + F2 sin b] SVF + DHI F1 max(0, cos theta) / max(cos 85, sin e) lit
/// (the circumsolar part comes from around the sun's disc, so the cell's shadow hides it; the horizon band takes
/// the SVF as the isotropic part does; with opt.perez.nonnegative = false the sum is clamped at 0).
/// On open horizontal ground a record adds DNI sin e + DHI (either sky model, for e >= 5 deg), which is GHI for
/// consistent records, so the annual map equals ghi_kwh_m2 there. Records may come in any order; each goes to the month
/// of its middle (in UTC + month_utc_offset_h). dsm heights and cell_m in metres; latitude/longitude in degrees (north,
/// east). Cost per daylight record O(rows * cols) (one raylines_shadow pass and one accumulation pass) plus one sky
/// view factor (svf_directions sweeps). Memory per cell: 2 doubles, 14 floats and a byte (plus 32 bytes with per-cell
/// surfaces, 36 with the Perez sky). Results are the same for any thread count.
/// @throws invalid_input if cell_m is not finite and > 0, a record has a non-positive interval or a negative or
/// non-finite irradiance, the surface rasters' shapes differ from the DSM's or only one is given, an option is
/// out of range, or sun_position refuses the place or a time; cancelled if run.progress returns false.
template <raster_input In>
irradiance_maps_result irradiance_maps(const In& dsm, double cell_m, double latitude_deg, double longitude_deg,
                                       std::span<const irradiance_record> records,
                                       const irradiance_maps_options& opt = {})
{
    constexpr const char* fn = "irradiance_maps";
    detail::require_positive(cell_m, fn, "cell_m");
    detail::check_execution(opt.run, fn);
    detail::require(opt.svf_directions >= 4, fn, "svf_directions", ">= 4", opt.svf_directions);
    detail::require(opt.shadow_line_phases >= 1 && opt.shadow_line_phases <= 64, fn, "shadow_line_phases", "in [1, 64]",
                    opt.shadow_line_phases);
    detail::require(opt.albedo >= 0.0 && opt.albedo <= 1.0, fn, "albedo", "in [0, 1]", opt.albedo);
    detail::require(opt.diffuse == diffuse_model::isotropic || opt.diffuse == diffuse_model::perez, fn, "diffuse",
                    "isotropic or perez", static_cast<int>(opt.diffuse));
    detail::require_positive(opt.perez.solar_constant_w_m2, fn, "perez.solar_constant_w_m2");
    detail::require(opt.month_utc_offset_h >= -14.0 && opt.month_utc_offset_h <= 14.0, fn, "month_utc_offset_h",
                    "in [-14, 14] hours", opt.month_utc_offset_h);
    detail::require(opt.meridian_convergence_deg >= -90.0 && opt.meridian_convergence_deg <= 90.0, fn,
                    "meridian_convergence_deg", "in [-90, 90] degrees", opt.meridian_convergence_deg);
    const bool tilted = opt.surface_tilt_deg.rows() > 0 || opt.surface_tilt_deg.cols() > 0;
    const bool has_azimuth = opt.surface_azimuth_deg.rows() > 0 || opt.surface_azimuth_deg.cols() > 0;
    detail::require(tilted == has_azimuth, fn,
                    "surface_tilt_deg and surface_azimuth_deg must be given together (or neither, for horizontal)");
    if (tilted) {
        detail::require_same_shape(dsm, opt.surface_tilt_deg, fn, "dsm", "surface_tilt_deg");
        detail::require_same_shape(dsm, opt.surface_azimuth_deg, fn, "dsm", "surface_azimuth_deg");
    }
    detail::require_records(records, fn);
    // Sun positions first: they validate the place and every time before any long work.
    struct daylight {
        std::size_t record;
        double azimuth_deg, elevation_deg;
        int day_of_year;
    };
    std::array<std::vector<daylight>, 12> by_month;
    irradiance_maps_result res;
    for (std::size_t i = 0; i < records.size(); ++i) {
        const irradiance_record& r = records[i];
        const int m = detail::record_month(r, opt.month_utc_offset_h);
        const double kwh = r.ghi_w_m2 * (static_cast<double>(r.interval.count()) / 3600.0) / 1000.0;
        res.month_ghi_kwh_m2[static_cast<std::size_t>(m)] += kwh;
        res.ghi_kwh_m2 += kwh;
        const sun_position_result sun = sun_position(r.middle_utc(), latitude_deg, longitude_deg, opt.sun);
        if (sun.elevation_deg > 0.0) {
            const double grid_azimuth = to_grid_azimuth_deg(sun.azimuth_deg, opt.meridian_convergence_deg);
            by_month[static_cast<std::size_t>(m)].push_back(
                {i, grid_azimuth, sun.elevation_deg, detail::record_day_of_year(r)});
        }
    }

    const std::ptrdiff_t rows = dsm.rows(), cols = dsm.cols();
    const std::size_t n = static_cast<std::size_t>(rows * cols);
    // Per-cell surface terms (horizontal: normal up, sky factor 1, ground factor 0).
    const bool perez = opt.diffuse == diffuse_model::perez;
    detail::cell_surface surf;
    if (tilted) {
        surf.normal.resize(n);
        surf.sky.resize(n);
        surf.ground.resize(n);
        if (perez) surf.sin_tilt.resize(n);
        for (std::ptrdiff_t r = 0; r < rows; ++r) {
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                const double b = opt.surface_tilt_deg(r, c), a = opt.surface_azimuth_deg(r, c);
                const std::size_t k = static_cast<std::size_t>(r * cols + c);
                if (b != b) {
                    const double nan = std::numeric_limits<double>::quiet_NaN();
                    surf.normal[k] = {nan, nan, nan};
                    surf.sky[k] = surf.ground[k] = std::numeric_limits<float>::quiet_NaN();
                    if (perez) surf.sin_tilt[k] = std::numeric_limits<float>::quiet_NaN();
                    continue;
                }
                detail::require(b >= 0.0 && b <= 180.0, fn, "surface_tilt_deg", "in [0, 180] degrees", b);
                surf.normal[k] = detail::surface_normal_unchecked(b, a == a ? a : 0.0);
                const double cb = std::cos(b * (std::numbers::pi / 180.0));
                surf.sky[k] = static_cast<float>((1.0 + cb) / 2.0);
                surf.ground[k] = static_cast<float>((1.0 - cb) / 2.0);
                if (perez) surf.sin_tilt[k] = static_cast<float>(std::sin(b * (std::numbers::pi / 180.0)));
            }
        }
    }

    return detail::with_float_view(dsm, [&](raster_view<const float> z) {
        std::size_t total = 0;
        for (const auto& v : by_month) total += v.size();
        res.sun_up_records = total;
        const double svf_share = 0.1;  // share of the progress taken by the sky view factor
        res.sky_view_factor = raster<float>(rows, cols);
        sky_view_factor(z, res.sky_view_factor, cell_m,
                        {.method = opt.svf_method,
                         .directions = opt.svf_directions,
                         .run = {.threads = opt.run.threads,
                                 .progress = detail::progress_phase(opt.run.progress, 0.0, svf_share)}});

        raster<double> annual(rows, cols, 0.0), month(rows, cols, 0.0);
        raster<std::uint8_t> lit(rows, cols);
        const float nan_f = std::numeric_limits<float>::quiet_NaN();
        std::size_t done = 0;
        for (std::size_t m = 0; m < 12; ++m) {
            for (std::ptrdiff_t r = 0; r < rows; ++r)
                for (std::ptrdiff_t c = 0; c < cols; ++c) month(r, c) = 0.0;
            for (const daylight& d : by_month[m]) {
                const irradiance_record& rec = records[d.record];
                const double hours_k = static_cast<double>(rec.interval.count()) / 3600.0 / 1000.0;
                raylines_shadow(
                    z, lit, cell_m, d.azimuth_deg, d.elevation_deg,
                    {.nan_cell = 0, .line_phases = opt.shadow_line_phases, .run = {.threads = opt.run.threads}});
                const enu_vector sun = detail::sun_vector_unchecked(d.azimuth_deg, d.elevation_deg);
                const double beam_flat = rec.dni_w_m2 * (sun.up > 0.0 ? sun.up : 0.0) * hours_k;
                const double dni = rec.dni_w_m2 * hours_k, dhi = rec.dhi_w_m2 * hours_k;
                const double reflected = rec.ghi_w_m2 * opt.albedo * hours_k;
                // Perez sky of this record (unused by the isotropic sky): per-cell factors of DHI * hours_k.
                const perez_sky sky = perez ? detail::perez_sky_unchecked(rec.dhi_w_m2, rec.dni_w_m2, d.elevation_deg,
                                                                          d.day_of_year, opt.perez)
                                            : perez_sky{};
                const detail::perez_record_terms terms{
                    .dni = dni,
                    .beam_flat = beam_flat,
                    .isotropic = dhi * (1.0 - sky.f1),
                    .horizon = dhi * sky.f2,
                    .circumsolar = dhi * sky.f1 / std::max(detail::perez_cos_85, sun.up),
                    .reflected = reflected,
                    .clamp = !opt.perez.nonnegative};
                parallel_for_rows(rows, 64, opt.run.threads, [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
                    for (std::ptrdiff_t r = r0; r < r1; ++r) {
                        if (perez) {
                            detail::add_perez_row(month.view().row(r), lit.view().row(r),
                                                  res.sky_view_factor.view().row(r), cols, tilted ? &surf : nullptr,
                                                  static_cast<std::size_t>(r * cols), sun, terms);
                            continue;
                        }
                        double* acc = month.view().row(r);
                        const std::uint8_t* l = lit.view().row(r);
                        const float* svf = res.sky_view_factor.view().row(r);
                        if (!tilted) {
                            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                                acc[c] += (l[c] == 1 ? beam_flat : 0.0) + dhi * static_cast<double>(svf[c]);
                            }
                            continue;
                        }
                        const std::size_t k0 = static_cast<std::size_t>(r * cols);
                        for (std::ptrdiff_t c = 0; c < cols; ++c) {
                            const std::size_t k = k0 + static_cast<std::size_t>(c);
                            const double cos_t = detail::enu_dot(sun, surf.normal[k]);
                            const double beam = l[c] == 1 && cos_t > 0.0 ? dni * cos_t : 0.0;
                            acc[c] +=
                                beam + dhi * static_cast<double>(svf[c]) * surf.sky[k] + reflected * surf.ground[k];
                        }
                    }
                });
                const double fraction = static_cast<double>(++done) / static_cast<double>(total + 1);
                detail::report(opt.run.progress, svf_share + (1.0 - svf_share) * fraction, fn);
            }
            res.month_kwh_m2[m] = raster<float>(rows, cols);
            for (std::ptrdiff_t r = 0; r < rows; ++r) {
                for (std::ptrdiff_t c = 0; c < cols; ++c) {
                    const std::size_t k = static_cast<std::size_t>(r * cols + c);
                    const bool nodata = z(r, c) != z(r, c) || (tilted && surf.sky[k] != surf.sky[k]);
                    annual(r, c) += month(r, c);
                    res.month_kwh_m2[m](r, c) = nodata ? nan_f : static_cast<float>(month(r, c));
                }
            }
        }
        res.annual_kwh_m2 = raster<float>(rows, cols);
        for (std::ptrdiff_t r = 0; r < rows; ++r) {
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                const float m0 = res.month_kwh_m2[0](r, c);
                res.annual_kwh_m2(r, c) = m0 != m0 ? nan_f : static_cast<float>(annual(r, c));
            }
        }
        detail::report(opt.run.progress, 1.0, fn);
        return std::move(res);
    });
}

}  // namespace lidarfx
