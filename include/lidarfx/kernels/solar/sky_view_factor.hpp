// SPDX-License-Identifier: Apache-2.0
// sky_view_factor: the share of the sky a horizontal cell sees, from one horizon sweep per azimuth: the
// dissertation's count of visible sky sources (3.2.4) or the standard cosine-weighted view factor.
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/kernels/solar/horizon_map.hpp"

namespace lidarfx {

/// Which sky view factor sky_view_factor computes.
enum class sky_view_factor_method {
    /// The dissertation's (3.2.4): the share of point sources visible from the cell, one at each elevation
    /// 15, 20, ..., 85 degrees of each of the `directions` azimuths, plus the zenith (1,081 for 72
    /// azimuths). A source is visible when raylines_shadow with the sun there would light the cell.
    source_share,
    /// The standard view factor of a horizontal surface under an isotropic sky (cosine-weighted):
    /// SVF = mean over the azimuths of cos^2(horizon angle) (Dozier & Marks 1987; Zaksek et al. 2011).
    cosine_weighted,
};

/// Settings of sky_view_factor.
struct sky_view_factor_options {
    sky_view_factor_method method = sky_view_factor_method::source_share;  ///< definition; default the dissertation's
    int directions = 72;  ///< azimuths i * 360 / directions, clockwise from north; >= 4 (72 = 5 degree steps)
    execution run = {};   ///< threads, progress and cancellation (core/parallel.hpp); never changes the result
};

/// Number of source elevations per azimuth of sky_view_factor_method::source_share: 15, 20, ..., 85 degrees,
/// i.e. 15 + 5 j for j = 0 .. 14 (the zenith is counted apart).
inline constexpr int sky_source_elevations = 15;

/// Sky view factor of every cell (into form), in [0, 1], 1 on open flat ground; NaN for NaN cells. One
/// horizon sweep per azimuth (horizon_map, upper convex hull, O(rows * cols)) gives the horizon tangent
/// tan(h) of each cell; then source_share = (1 + sum over azimuths of #{e in 15..85 step 5: tan e >= tan h})
/// / (15 * directions + 1), and cosine_weighted = mean of 1 / (1 + tan^2 h) = mean cos^2 h. Beyond the raster
/// border the horizon is flat (horizon_map). Cost O(directions * rows * cols); 72 sweeps replace the
/// dissertation's 1,081 shadow passes. @throws invalid_input if shapes differ, cell_m is not finite and > 0,
/// directions < 4 or run.threads < 0; cancelled if run.progress returns false.
template <raster_input In, class Out>
requires raster_output_of<Out, float>
void sky_view_factor(const In& dsm, Out&& svf, double cell_m, const sky_view_factor_options& opt = {})
{
    constexpr const char* fn = "sky_view_factor";
    detail::require_positive(cell_m, fn, "cell_m");
    detail::require(opt.directions >= 4, fn, "directions", ">= 4", opt.directions);
    detail::check_execution(opt.run, fn);
    detail::require_same_shape(dsm, svf, fn, "dsm", "svf");
    detail::with_float_view(dsm, [&](raster_view<const float> z) {
        detail::write_through<float>(std::forward<Out>(svf), [&](raster_view<float> out) {
            detail::require(!detail::overlaps(z, out), fn, "svf must not overlap dsm");
            const std::ptrdiff_t rows = z.rows(), cols = z.cols();
            double tan_e[sky_source_elevations];
            for (int j = 0; j < sky_source_elevations; ++j) {
                tan_e[j] = std::tan((15.0 + 5.0 * j) * (std::numbers::pi / 180.0));
            }
            const bool share = opt.method == sky_view_factor_method::source_share;
            raster<double> tangent(rows, cols), sum(rows, cols, 0.0);
            const int n = opt.directions;
            for (int i = 0; i < n; ++i) {
                const double from = static_cast<double>(i) / n, to = static_cast<double>(i + 1) / n;
                horizon_map_options sweep{
                    .run = {.threads = opt.run.threads,
                            .progress = detail::progress_phase(opt.run.progress, from, from + 0.9 * (to - from))}};
                detail::horizon_map_view(z, tangent.view(), cell_m, 360.0 * i / n, sweep, fn);
                parallel_for_rows(
                    rows, 64, opt.run.threads,
                    [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
                        for (std::ptrdiff_t r = r0; r < r1; ++r) {
                            const double* t = tangent.view().row(r);
                            double* s = sum.view().row(r);
                            if (share) {
                                for (std::ptrdiff_t c = 0; c < cols; ++c) {
                                    int visible = 0;
                                    for (int j = 0; j < sky_source_elevations; ++j) visible += tan_e[j] >= t[c];
                                    s[c] += visible;
                                }
                            } else {
                                for (std::ptrdiff_t c = 0; c < cols; ++c) s[c] += 1.0 / (1.0 + t[c] * t[c]);
                            }
                        }
                    },
                    detail::progress_phase(opt.run.progress, from + 0.9 * (to - from), to), fn);
            }
            const double scale = share ? 1.0 / (sky_source_elevations * n + 1.0) : 1.0 / n;
            const double offset = share ? 1.0 : 0.0;  // the zenith, always visible
            const float nan = std::numeric_limits<float>::quiet_NaN();
            for (std::ptrdiff_t r = 0; r < rows; ++r) {
                for (std::ptrdiff_t c = 0; c < cols; ++c) {
                    out(r, c) = z(r, c) != z(r, c) ? nan : static_cast<float>((sum(r, c) + offset) * scale);
                }
            }
        });
    });
}

/// Sky view factor of every cell (returning form); see the into form. dsm and cell_m in metres; result in
/// [0, 1], NaN on NaN cells.
template <raster_input In>
raster<float> sky_view_factor(const In& dsm, double cell_m, const sky_view_factor_options& opt = {})
{
    raster<float> out(dsm.rows(), dsm.cols());
    sky_view_factor(dsm, out, cell_m, opt);
    return out;
}

}  // namespace lidarfx
