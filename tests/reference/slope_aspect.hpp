// SPDX-License-Identifier: Apache-2.0
// Reference slope/aspect: Horn's weighted differences cell by cell in double, with std::atan2 and std::hypot.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>

#include <lidarfx/core/raster.hpp>
#include <lidarfx/core/raster_view.hpp>

namespace reference {

struct slope_aspect_rasters {
    lidarfx::raster<float> slope_deg, aspect_deg;
    lidarfx::raster<std::uint8_t> flat;
};

/// One gradient component at (r, c): the 1-2-1 weighted mean over the three lines across the axis of each
/// line's difference (centred if both ends exist, else one-sided against the line's middle cell, else left
/// out), per metre. Lines run along `step` = (0, 1) for east or (-1, 0) for north; `across` picks the line.
inline double horn_component(lidarfx::raster_view<const float> z, std::ptrdiff_t r, std::ptrdiff_t c,
                             std::ptrdiff_t step_r, std::ptrdiff_t step_c, double cell)
{
    const auto at = [&](std::ptrdiff_t rr, std::ptrdiff_t cc) {
        const bool inside = rr >= 0 && rr < z.rows() && cc >= 0 && cc < z.cols();
        return inside ? static_cast<double>(z(rr, cc)) : std::numeric_limits<double>::quiet_NaN();
    };
    double sum = 0, weight = 0;
    for (std::ptrdiff_t k = -1; k <= 1; ++k) {
        // The line's middle cell is offset from (r, c) perpendicular to the step.
        const std::ptrdiff_t mr = r + k * step_c, mc = c + k * (-step_r);
        const double back = at(mr - step_r, mc - step_c), mid = at(mr, mc), ahead = at(mr + step_r, mc + step_c);
        double slope_per_m;
        if (!std::isnan(back) && !std::isnan(ahead)) {
            slope_per_m = (ahead - back) / (2 * cell);
        } else if (!std::isnan(ahead) && !std::isnan(mid)) {
            slope_per_m = (ahead - mid) / cell;
        } else if (!std::isnan(back) && !std::isnan(mid)) {
            slope_per_m = (mid - back) / cell;
        } else {
            continue;
        }
        const double w = k == 0 ? 2 : 1;
        sum += w * slope_per_m;
        weight += w;
    }
    return weight > 0 ? sum / weight : std::numeric_limits<double>::quiet_NaN();
}

/// Slope (atan |grad|), aspect (atan2 of the down-slope direction, clockwise from north) and flat flag.
inline slope_aspect_rasters slope_aspect(lidarfx::raster_view<const float> z, double cell, double flat_slope_deg)
{
    const float nan = std::numeric_limits<float>::quiet_NaN();
    slope_aspect_rasters out{lidarfx::raster<float>(z.rows(), z.cols(), nan),
                             lidarfx::raster<float>(z.rows(), z.cols(), nan),
                             lidarfx::raster<std::uint8_t>(z.rows(), z.cols(), 0)};
    for (std::ptrdiff_t r = 0; r < z.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < z.cols(); ++c) {
            if (std::isnan(z(r, c))) continue;
            const double east = horn_component(z, r, c, 0, 1, cell);
            const double north = horn_component(z, r, c, -1, 0, cell);
            if (std::isnan(east) || std::isnan(north)) continue;
            const auto slope = static_cast<float>(std::atan(std::hypot(east, north)) * 180 / std::numbers::pi);
            out.slope_deg(r, c) = slope;
            if (slope <= flat_slope_deg) {
                out.flat(r, c) = 1;
                continue;
            }
            double aspect = std::atan2(-east, -north) * 180 / std::numbers::pi;
            if (aspect < 0) aspect += 360;
            const auto aspect_f = static_cast<float>(aspect);
            out.aspect_deg(r, c) = aspect_f >= 360.0f ? 0.0f : aspect_f;
        }
    }
    return out;
}

}  // namespace reference
