// SPDX-License-Identifier: Apache-2.0
// water_surface_slope: the slope of the least-squares plane through the lowest returns around each cell.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// Options of water_surface_slope.
struct water_surface_slope_options {
    int radius_cells = 3;        ///< the plane is fitted to the (2 r + 1)² window around a cell (7 × 7: with 2-3 cm
                                 ///< range noise its slope is known to about 0.1 % at 2 m cells), >= 1. Default 3
    std::size_t min_cells = 12;  ///< fewer cells with a return in the window give NaN (unknown), >= 3. Default 12
    double band_m = 0.15;        ///< only returns within this of the cell's own min z are fitted (water next to a
                                 ///< bank sees the water, not the bank; on a beach rising 1-6 % the band still
                                 ///< spans several cells), metres, > 0. Default 0.15 (the level gate)
    execution run = {};          ///< threads (rows are independent; same result for any count)
};

/// Slope of the water surface test: per cell, the magnitude of the gradient of the least-squares plane
/// z = a + b·x + c·y through the min z of the (2·radius_cells + 1)² window (clipped at the raster border)
/// that lie within band_m of the cell's own, sqrt(b² + c²) in metres per metre (0 = level); NaN where the
/// cell has no return, the window holds fewer than min_cells such returns, or they lie on a line. A water surface is level to the range noise (a river falls a few mm per
/// metre at most); beaches, banks and meadows rising from the water are not. cell_m in metres.
/// O(cells · (2·radius_cells + 1)²).
/// @throws invalid_input on cell_m <= 0 or options out of range.
inline raster<float> water_surface_slope(raster_view<const float> min_z, double cell_m,
                                         const water_surface_slope_options& opt = {})
{
    constexpr const char* fn = "water_surface_slope";
    detail::require_positive(cell_m, fn, "cell_m");
    detail::require(opt.radius_cells >= 1, fn, "radius_cells", ">= 1", opt.radius_cells);
    detail::require(opt.min_cells >= 3, fn, "min_cells", ">= 3", opt.min_cells);
    detail::require(opt.band_m > 0, fn, "band_m", "> 0", opt.band_m);
    detail::check_execution(opt.run, fn);
    const std::ptrdiff_t rows = min_z.rows(), cols = min_z.cols(), k = opt.radius_cells;
    raster<float> out(rows, cols, NAN);
    parallel_for_rows(rows, 16, opt.run.threads, [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
        for (std::ptrdiff_t r = r0; r < r1; ++r) {
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                // Normal equations of the plane in window coordinates (cells), heights about the first return.
                double n = 0, sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0, sz = 0, sxz = 0, syz = 0;
                const float z0 = min_z(r, c);
                if (!std::isfinite(z0)) continue;
                for (std::ptrdiff_t rr = std::max<std::ptrdiff_t>(0, r - k); rr <= std::min(rows - 1, r + k); ++rr) {
                    for (std::ptrdiff_t cc = std::max<std::ptrdiff_t>(0, c - k); cc <= std::min(cols - 1, c + k); ++cc) {
                        const float zf = min_z(rr, cc);
                        const double z = static_cast<double>(zf) - z0;
                        if (!(std::abs(z) <= opt.band_m)) continue;  // also skips NaN
                        const double x = static_cast<double>(cc - c), y = static_cast<double>(rr - r);
                        n += 1, sx += x, sy += y, sxx += x * x, syy += y * y, sxy += x * y;
                        sz += z, sxz += x * z, syz += y * z;
                    }
                }
                if (n < static_cast<double>(opt.min_cells)) continue;
                // Centre the sums on the mean position: b, c solve the 2 × 2 system of the covariances.
                const double cxx = sxx - sx * sx / n, cyy = syy - sy * sy / n, cxy = sxy - sx * sy / n;
                const double cxz = sxz - sx * sz / n, cyz = syz - sy * sz / n;
                const double det = cxx * cyy - cxy * cxy;
                if (!(det > 1e-9 * (cxx * cyy + 1))) continue;
                const double b = (cxz * cyy - cyz * cxy) / det, g = (cyz * cxx - cxz * cxy) / det;
                out(r, c) = static_cast<float>(std::sqrt(b * b + g * g) / cell_m);
            }
        }
    }, {}, fn);
    return out;
}

}  // namespace lidarfx
