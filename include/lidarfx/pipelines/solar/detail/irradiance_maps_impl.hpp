// SPDX-License-Identifier: Apache-2.0
// Implementation of irradiance_maps (pipelines/solar/irradiance_maps.hpp): per-cell surfaces, the per-record
// terms, the accumulation of one daylight sun's lit-dependent light into a month, the month's sky terms summed once,
// and the month and annual outputs.
#pragma once
// Included at the end of its public header, which declares what is defined here.

#include <algorithm>
#include <array>
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
#include "lidarfx/kernels/solar/daylight_suns.hpp"
#include "lidarfx/kernels/solar/incidence.hpp"
#include "lidarfx/kernels/solar/irradiance_record.hpp"
#include "lidarfx/kernels/solar/perez_diffuse.hpp"
#include "lidarfx/kernels/solar/ray_lines.hpp"
#include "lidarfx/kernels/solar/raylines_shadow.hpp"
#include "lidarfx/kernels/solar/shadow_probes.hpp"
#include "lidarfx/kernels/solar/sky_options.hpp"
#include "lidarfx/kernels/solar/sky_view_factor.hpp"

namespace lidarfx::detail {

/// Per-cell incidence terms of a tilted surface: the normal vector as three float planes (read for every sun, so
/// kept small and contiguous), (1 + cos b) / 2, (1 - cos b) / 2 and, for the Perez sky only, sin b. Empty for
/// horizontal cells.
struct cell_surface {
    std::vector<float> east, north, up;
    std::vector<float> sky, ground, sin_tilt;
    bool tilted() const noexcept { return !sky.empty(); }
};

/// One record's terms, each already times DHI (or DNI, GHI) and the interval in kWh (W h / 1000). The isotropic
/// sky is the Perez sky with F1 = F2 = 0.
struct perez_record_terms {
    double dni = 0, beam_flat = 0;  ///< DNI, and DNI sin e for horizontal cells
    double isotropic = 0;           ///< DHI (1 - F1): times (1 + cos b) / 2 and SVF
    double horizon = 0;             ///< DHI F2: times sin b and SVF
    double circumsolar = 0;         ///< DHI F1 / max(cos 85, sin e): times max(0, cos theta) and lit
    double reflected = 0;           ///< GHI albedo: times (1 - cos b) / 2
    bool clamp = false;             ///< clamp the diffuse sum at 0 (components may be < 0)
};

/// Refuses a bad cell size, option or surface raster pair of irradiance_maps (before any sun is computed).
template <class In>
void check_irradiance_maps(const In& dsm, double cell_m, raster_view<const float> tilt,
                           raster_view<const float> azimuth, const irradiance_maps_options& opt, const char* fn)
{
    require_positive(cell_m, fn, "cell_m");
    check_execution(opt.run, fn);
    require_sky_options(opt.sky, fn);
    require(opt.shadow_line_phases >= 1 && opt.shadow_line_phases <= 64, fn, "shadow_line_phases", "in [1, 64]",
            opt.shadow_line_phases);
    const bool tilted = tilt.rows() > 0 || tilt.cols() > 0;
    const bool has_azimuth = azimuth.rows() > 0 || azimuth.cols() > 0;
    require(tilted == has_azimuth, fn,
            "surface_tilt_deg and surface_azimuth_deg must be given together (or neither, for horizontal)");
    if (tilted) {
        require_same_shape(dsm, tilt, fn, "dsm", "surface_tilt_deg");
        require_same_shape(dsm, azimuth, fn, "dsm", "surface_azimuth_deg");
    }
}

/// The GHI sums of every record (daylight or not), per month of UTC + utc_offset_h and in total, kWh/m^2.
inline void sum_ghi_by_month(std::span<const irradiance_record> records, double utc_offset_h,
                             irradiance_maps_result& res)
{
    for (const irradiance_record& r : records) {
        const int m = record_month(r, utc_offset_h);
        const double kwh = r.ghi_w_m2 * (static_cast<double>(r.interval.count()) / 3600.0) / 1000.0;
        res.month_ghi_kwh_m2[static_cast<std::size_t>(m)] += kwh;
        res.ghi_kwh_m2 += kwh;
    }
}

/// Per-cell surfaces of the tilt and azimuth rasters (empty when none are given); NaN tilts give NaN terms.
/// @throws invalid_input if a tilt is outside [0, 180] or an azimuth is infinite.
inline cell_surface make_cell_surfaces(raster_view<const float> tilt, raster_view<const float> azimuth, bool perez,
                                       const char* fn)
{
    cell_surface surf;
    const std::ptrdiff_t rows = tilt.rows(), cols = tilt.cols();
    const std::size_t n = static_cast<std::size_t>(rows * cols);
    if (n == 0) return surf;
    surf.east.resize(n);
    surf.north.resize(n);
    surf.up.resize(n);
    surf.sky.resize(n);
    surf.ground.resize(n);
    if (perez) surf.sin_tilt.resize(n);
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const double b = tilt(r, c), a = azimuth(r, c);
            const std::size_t k = static_cast<std::size_t>(r * cols + c);
            if (b != b) {
                const float nan = std::numeric_limits<float>::quiet_NaN();
                surf.east[k] = surf.north[k] = surf.up[k] = nan;
                surf.sky[k] = surf.ground[k] = nan;
                if (perez) surf.sin_tilt[k] = std::numeric_limits<float>::quiet_NaN();
                continue;
            }
            require(b >= 0.0 && b <= 180.0, fn, "surface_tilt_deg", "in [0, 180] degrees", b);
            const enu_vector normal = surface_normal(b, a == a ? a : 0.0);
            surf.east[k] = static_cast<float>(normal.east);
            surf.north[k] = static_cast<float>(normal.north);
            surf.up[k] = static_cast<float>(normal.up);
            const double cb = std::cos(b * (std::numbers::pi / 180.0));
            surf.sky[k] = static_cast<float>((1.0 + cb) / 2.0);
            surf.ground[k] = static_cast<float>((1.0 - cb) / 2.0);
            if (perez) surf.sin_tilt[k] = static_cast<float>(std::sin(b * (std::numbers::pi / 180.0)));
        }
    }
    return surf;
}

/// The terms of one daylight sun under the chosen sky.
inline perez_record_terms record_terms(const daylight_sun& d, const sky_options& sky)
{
    const double hours_k = d.kwh_per_w_m2;
    const double dhi = d.dhi_w_m2 * hours_k;
    const bool perez = sky.diffuse == diffuse_model::perez;
    // Perez sky of this record (unused by the isotropic sky): per-cell factors of DHI * hours_k.
    const perez_sky p =
        perez ? perez_sky_coefficients(d.dhi_w_m2, d.dni_w_m2, d.elevation_deg, d.day_of_year, sky.perez) : perez_sky{};
    return {.dni = d.dni_w_m2 * hours_k,
            .beam_flat = d.dni_w_m2 * (d.sun.up > 0.0 ? d.sun.up : 0.0) * hours_k,
            .isotropic = perez ? dhi * (1.0 - p.f1) : dhi,
            .horizon = dhi * p.f2,
            .circumsolar = dhi * p.f1 / std::max(perez_cos_85, d.sun.up),
            .reflected = d.ghi_w_m2 * sky.albedo * hours_k,
            .clamp = perez && !sky.perez.nonnegative};  // the isotropic sky is never negative
}

/// The sky terms of a month that do not depend on the shadows, summed over its records (they multiply per-cell
/// factors that do not change from hour to hour): the isotropic part (times the SVF and (1 + cos b) / 2), the
/// Perez horizon band (times the SVF and sin b) and the reflected part (times (1 - cos b) / 2). Under the clamped
/// Perez sky the diffuse sum is not separable, so only the reflected part is summed here.
struct month_sky_sums {
    double isotropic = 0, horizon = 0, reflected = 0;
    void add(const perez_record_terms& t) noexcept
    {
        if (!t.clamp) {
            isotropic += t.isotropic;
            horizon += t.horizon;
        }
        reflected += t.reflected;
    }
};

/// One daylight sun as the accumulation needs it: its terms, and what a lit cell gets from it besides the sky
/// terms: DNI sin e plus the circumsolar part times sin e on horizontal cells, (DNI + the circumsolar factor)
/// times max(0, cos theta) on tilted ones.
struct lit_sun {
    const daylight_sun* day = nullptr;  ///< the sun itself (its position and vector)
    perez_record_terms terms = {};
    double flat = 0, tilted = 0;
    /// True if the sun's light depends on the shadows at all (no beam and no circumsolar light: it does not).
    bool casts_shadows() const noexcept { return flat != 0.0 || tilted != 0.0 || terms.clamp; }
};

inline lit_sun make_lit_sun(const daylight_sun& d, const sky_options& sky)
{
    lit_sun s{.day = &d, .terms = record_terms(d, sky)};
    s.flat = s.terms.beam_flat + s.terms.circumsolar * d.sun.up;
    s.tilted = s.terms.dni + s.terms.circumsolar;
    return s;
}

/// One row of cells as the accumulation reads it: its shadows (1 lit), its SVF, and the per-cell surfaces from cell
/// index k0 (null when every cell is horizontal).
struct lit_row {
    const std::uint8_t* lit;
    const float* svf;
    std::ptrdiff_t cols;
    const cell_surface* surf;
    std::size_t k0;
};

/// The factor of tilted cell k's diffuse sky before the SVF: isotropic (1 + cos b) / 2 + horizon sin b (the horizon
/// band exists under the Perez sky only, whose surfaces carry sin b).
inline double cell_sky_factor(const cell_surface& surf, std::size_t k, double isotropic, double horizon) noexcept
{
    const double band = surf.sin_tilt.empty() ? 0.0 : horizon * static_cast<double>(surf.sin_tilt[k]);
    return isotropic * static_cast<double>(surf.sky[k]) + band;
}

/// cos theta of cell k's surface under sun s, in float from the float normal planes (both accumulations use it).
inline float cell_cos_incidence(const cell_surface& surf, std::size_t k, const enu_vector& s) noexcept
{
    return static_cast<float>(s.east) * surf.east[k] + static_cast<float>(s.north) * surf.north[k] +
           static_cast<float>(s.up) * surf.up[k];
}

/// Adds one sun's shadow-dependent light to one row of month sums (acc, kWh/m^2): its beam and circumsolar light
/// where the cell is lit and faces the sun. The plain loops vectorize.
inline void add_lit_row(double* acc, const lit_row& row, const lit_sun& s) noexcept
{
    const std::uint8_t* lit = row.lit;
    const double flat = s.flat, tilted = s.tilted;  // locals: acc cannot alias them, so the loops vectorize
    if (row.surf == nullptr) {
        for (std::ptrdiff_t c = 0; c < row.cols; ++c) acc[c] += lit[c] == 1 ? flat : 0.0;
        return;
    }
    const cell_surface& surf = *row.surf;
    const enu_vector sun = s.day->sun;
    for (std::ptrdiff_t c = 0; c < row.cols; ++c) {
        const float cos_t = cell_cos_incidence(surf, row.k0 + static_cast<std::size_t>(c), sun);
        acc[c] += lit[c] == 1 && cos_t > 0.0f ? tilted * static_cast<double>(cos_t) : 0.0;
    }
}

/// add_lit_row under the clamped Perez sky, whose diffuse sum max(0, sky + circumsolar) depends on the shadow:
/// the sun's whole beam and diffuse light, per cell (its reflected part is in the month's sums).
inline void add_lit_row_clamped(double* acc, const lit_row& row, const lit_sun& s) noexcept
{
    const perez_record_terms& t = s.terms;
    for (std::ptrdiff_t c = 0; c < row.cols; ++c) {
        const bool lit = row.lit[c] == 1;
        const double svf = row.svf[c];
        if (row.surf == nullptr) {
            acc[c] += (lit ? t.beam_flat : 0.0) +
                      std::max(0.0, t.isotropic * svf + (lit ? t.circumsolar * s.day->sun.up : 0.0));
            continue;
        }
        const std::size_t k = row.k0 + static_cast<std::size_t>(c);
        const double cos_t = cell_cos_incidence(*row.surf, k, s.day->sun);
        const bool sunny = lit && cos_t > 0.0;
        const double sky = cell_sky_factor(*row.surf, k, t.isotropic, t.horizon);
        acc[c] += (sunny ? t.dni * cos_t : 0.0) + std::max(0.0, sky * svf + (sunny ? t.circumsolar * cos_t : 0.0));
    }
}

/// Suns whose shadows are swept before their light is added, so that each row of month sums is read and written
/// once per batch rather than once per sun (the accumulation is bound by memory traffic).
constexpr std::size_t suns_per_batch = 8;

/// The shadows of a batch of suns and where each lies: suns whose lines are shallow are swept along the rows of the
/// transposed DSM (when it is kept: horizontal cells only), as fast as steep ones, and their lit rasters and light
/// stay transposed (cols x rows) until the month ends.
struct sun_shadows {
    raster_view<const float> z_transposed;         ///< empty: every sun in z's own layout
    shadow_probes no_probes;                       ///< raylines_shadow_probed's probes: none (z's shape)
    std::vector<raster<std::uint8_t>> lit, lit_t;  ///< per sun of a batch, in z's layout and transposed
    std::vector<std::uint8_t> transposed;          ///< per sun of the batch: its shadows are in lit_t
};

/// Adds a batch of daylight suns' shadow-dependent light to `month` (and to `month_t`, transposed, for the suns swept
/// transposed): each sun's cast shadows into its own lit raster (one thread per sun), then every row once, with
/// every sun of the batch in order.
inline void add_daylight_suns(raster_view<const float> z, double cell_m, std::span<const lit_sun> s,
                              const cell_surface& surf, const raster<float>& svf, sun_shadows& shadows,
                              raster<double>& month, raster<double>& month_t, const irradiance_maps_options& opt)
{
    const std::ptrdiff_t rows = z.rows(), cols = z.cols();
    shadows.transposed.assign(s.size(), 0);
    for (std::size_t k = 0; k < s.size(); ++k) {
        // Only the plain sums (no per-cell surface, no clamped sky) are added in the transposed layout.
        const bool plain = !shadows.z_transposed.empty() && !s[k].terms.clamp && s[k].day->elevation_deg < 90.0;
        shadows.transposed[k] = plain && !make_ray_lines(s[k].day->azimuth_deg, rows, cols).steep ? 1 : 0;
    }
    // The suns' shadows are independent: each is swept by one thread, all of them side by side.
    parallel_for_rows(
        static_cast<std::ptrdiff_t>(s.size()), 1, opt.run.threads, [&](std::ptrdiff_t i0, std::ptrdiff_t i1) {
            for (std::ptrdiff_t i = i0; i < i1; ++i) {
                const std::size_t k = static_cast<std::size_t>(i);
                const raylines_shadow_options shadow{
                    .nan_cell = 0, .line_phases = opt.shadow_line_phases, .run = {.threads = 1}};
                const double az = s[k].day->azimuth_deg, el = s[k].day->elevation_deg;
                if (!shadows.transposed[k]) {
                    raylines_shadow(z, shadows.lit[k], cell_m, az, el, shadow);
                    continue;
                }
                const ray_lines l = make_ray_lines(az, rows, cols);
                const shadow_lifts lift = make_shadow_lifts(l, cell_m, std::tan(el * (std::numbers::pi / 180.0)));
                std::vector<double> no_limits;
                raylines_shadow_probed(z, shadows.z_transposed, l, lift, shadows.no_probes, no_limits,
                                       shadows.lit_t[k].view(), shadow);
            }
        });
    const cell_surface* tilted = surf.tilted() ? &surf : nullptr;
    parallel_for_rows(rows, 16, opt.run.threads, [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
        for (std::ptrdiff_t r = r0; r < r1; ++r) {
            double* acc = month.view().row(r);
            for (std::size_t i = 0; i < s.size(); ++i) {
                if (shadows.transposed[i]) continue;
                const lit_row row{shadows.lit[i].view().row(r), svf.view().row(r), cols, tilted,
                                  static_cast<std::size_t>(r * cols)};
                if (s[i].terms.clamp) {
                    add_lit_row_clamped(acc, row, s[i]);
                } else {
                    add_lit_row(acc, row, s[i]);
                }
            }
        }
    });
    if (std::find(shadows.transposed.begin(), shadows.transposed.end(), 1) == shadows.transposed.end()) return;
    parallel_for_rows(cols, 16, opt.run.threads, [&](std::ptrdiff_t c0, std::ptrdiff_t c1) {
        for (std::ptrdiff_t c = c0; c < c1; ++c) {
            double* acc = month_t.view().row(c);
            for (std::size_t i = 0; i < s.size(); ++i) {
                if (!shadows.transposed[i]) continue;
                add_lit_row(acc, {shadows.lit_t[i].view().row(c), nullptr, rows, nullptr, 0}, s[i]);
            }
        }
    });
}

/// Month m's map as floats: its shadow-dependent sums plus its sky terms (NaN on NaN cells and NaN surfaces); the
/// month is added to `annual`.
inline raster<float> finish_month(raster_view<const float> z, const cell_surface& surf, const month_sky_sums& sky,
                                  const raster<float>& svf, const raster<double>& month, raster<double>& annual,
                                  int threads)
{
    const std::ptrdiff_t rows = z.rows(), cols = z.cols();
    raster<float> out(rows, cols);
    parallel_for_rows(rows, 64, threads, [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
        for (std::ptrdiff_t r = r0; r < r1; ++r) {
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                const std::size_t k = static_cast<std::size_t>(r * cols + c);
                const double f = svf(r, c);
                double diffuse = sky.isotropic * f;  // horizontal cells: no horizon band, no reflected light
                if (surf.tilted()) {
                    diffuse = f * cell_sky_factor(surf, k, sky.isotropic, sky.horizon) +
                              sky.reflected * static_cast<double>(surf.ground[k]);
                }
                const double total = month(r, c) + diffuse;
                const bool nodata = z(r, c) != z(r, c) || (surf.tilted() && surf.sky[k] != surf.sky[k]);
                annual(r, c) += total;
                out(r, c) = nodata ? std::numeric_limits<float>::quiet_NaN() : static_cast<float>(total);
            }
        }
    });
    return out;
}

/// The month and annual maps of the daylight suns, grouped by month; res.sky_view_factor is already set.
inline void accumulate_months(raster_view<const float> z, double cell_m, std::span<const daylight_sun> suns,
                              const cell_surface& surf, const irradiance_maps_options& opt, double progress_from,
                              irradiance_maps_result& res, const char* fn)
{
    const std::ptrdiff_t rows = z.rows(), cols = z.cols();
    std::array<std::vector<const daylight_sun*>, 12> by_month;
    for (const daylight_sun& d : suns) by_month[static_cast<std::size_t>(d.month)].push_back(&d);
    raster<double> annual(rows, cols, 0.0), month(rows, cols, 0.0);
    // Horizontal cells: shallow suns are swept along the rows of the transposed DSM and summed transposed.
    raster<float> z_transposed;
    raster<double> month_t;
    if (!surf.tilted()) {
        z_transposed = transposed_dsm(z, opt.run.threads);
        month_t = raster<double>(cols, rows, 0.0);
    }
    sun_shadows shadows{z_transposed.view(), make_shadow_probes(rows, cols, {}, {}), {}, {}, {}};
    std::size_t done = 0;
    std::vector<lit_sun> batch;
    const auto flush = [&] {
        if (batch.empty()) return;
        if (shadows.lit.size() < batch.size()) {
            shadows.lit.resize(batch.size(), raster<std::uint8_t>(rows, cols));
            if (!shadows.z_transposed.empty()) shadows.lit_t.resize(batch.size(), raster<std::uint8_t>(cols, rows));
        }
        add_daylight_suns(z, cell_m, batch, surf, res.sky_view_factor, shadows, month, month_t, opt);
        done += batch.size();
        report(opt.run.progress,
               progress_from + (1.0 - progress_from) * static_cast<double>(done) / static_cast<double>(suns.size() + 1),
               fn);
        batch.clear();
    };
    for (std::size_t m = 0; m < 12; ++m) {
        for (std::ptrdiff_t r = 0; r < rows; ++r)
            for (std::ptrdiff_t c = 0; c < cols; ++c) month(r, c) = 0.0;
        month_sky_sums sky;
        for (const daylight_sun* d : by_month[m]) {
            const lit_sun s = make_lit_sun(*d, opt.sky);
            sky.add(s.terms);
            if (!s.casts_shadows()) {
                ++done;
                continue;
            }
            batch.push_back(s);
            if (batch.size() == suns_per_batch) flush();
        }
        flush();
        if (!month_t.empty()) {
            // The transposed suns' sums join the month's, then start again from 0.
            parallel_for_rows(rows, 64, opt.run.threads, [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
                for (std::ptrdiff_t r = r0; r < r1; ++r) {
                    for (std::ptrdiff_t c = 0; c < cols; ++c) {
                        month(r, c) += month_t(c, r);
                        month_t(c, r) = 0.0;
                    }
                }
            });
        }
        res.month_kwh_m2[m] = finish_month(z, surf, sky, res.sky_view_factor, month, annual, opt.run.threads);
    }
    res.annual_kwh_m2 = raster<float>(rows, cols);
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const float m0 = res.month_kwh_m2[0](r, c);
            res.annual_kwh_m2(r, c) =
                m0 != m0 ? std::numeric_limits<float>::quiet_NaN() : static_cast<float>(annual(r, c));
        }
    }
}

}  // namespace lidarfx::detail

namespace lidarfx {

template <raster_input In>
irradiance_maps_result irradiance_maps(const In& dsm, double cell_m, const solar_site& site,
                                       std::span<const irradiance_record> records,
                                       raster_view<const float> surface_tilt_deg,
                                       raster_view<const float> surface_azimuth_deg, const irradiance_maps_options& opt)
{
    constexpr const char* fn = "irradiance_maps";
    detail::check_irradiance_maps(dsm, cell_m, surface_tilt_deg, surface_azimuth_deg, opt, fn);
    // Sun positions first: they validate the site and every time before any long work.
    const std::vector<daylight_sun> suns = daylight_suns(records, site);
    irradiance_maps_result res;
    detail::sum_ghi_by_month(records, site.utc_offset_h, res);
    res.sun_up_records = suns.size();
    const detail::cell_surface surf =
        detail::make_cell_surfaces(surface_tilt_deg, surface_azimuth_deg, opt.sky.diffuse == diffuse_model::perez, fn);
    return detail::with_float_view(dsm, [&](raster_view<const float> z) {
        const double svf_share = 0.1;  // share of the progress taken by the sky view factor
        res.sky_view_factor = raster<float>(z.rows(), z.cols());
        sky_view_factor(z, res.sky_view_factor, cell_m,
                        {.method = opt.sky.svf_method,
                         .directions = opt.sky.svf_directions,
                         .run = {.threads = opt.run.threads,
                                 .progress = detail::progress_phase(opt.run.progress, 0.0, svf_share)}});
        detail::accumulate_months(z, cell_m, suns, surf, opt, svf_share, res, fn);
        detail::report(opt.run.progress, 1.0, fn);
        return std::move(res);
    });
}

}  // namespace lidarfx
