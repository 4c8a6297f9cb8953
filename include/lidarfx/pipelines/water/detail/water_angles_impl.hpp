// SPDX-License-Identifier: Apache-2.0
// Implementation of water_angles (included at the end of pipelines/water/water_angles.hpp).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/kernels/filter/angular_filter.hpp"
#include "lidarfx/kernels/interpolate/idw_fill.hpp"
#include "lidarfx/pipelines/water/water_rasters.hpp"

namespace lidarfx {

inline raster<float> water_angles(const water_rasters& in, double cell_m, const water_angles_options& opt,
                                  const execution& run)
{
    constexpr const char* fn = "water_angles";
    detail::validate(in, fn);
    detail::require_positive(cell_m, fn, "cell_m");
    detail::require(opt.radius_cells >= 1, fn, "radius_cells", ">= 1", opt.radius_cells);
    detail::check_execution(run, fn);
    detail::report(run.progress, 0.0, fn);
    const int threads = run.threads;
    const angular_filter_options af{.radius_cells = opt.radius_cells, .run = {.threads = threads}};
    raster<float> angle =
        opt.input == angular_input::idw_filled
            ? angular_filter(idw_fill(in.min_z, cell_m, idw_fill_options{.run = {.threads = threads}}).filled, cell_m,
                             af)
            : angular_filter(in.min_z, cell_m, af);
    for (std::ptrdiff_t r = 0; r < angle.rows(); ++r) {
        float* a = angle.row(r);
        const std::uint8_t* dropout = in.dropout.row(r);
        if (opt.dropouts_join_any_threshold) {
            for (std::ptrdiff_t c = 0; c < angle.cols(); ++c) a[c] = dropout[c] ? NAN : a[c];
        } else {
            for (std::ptrdiff_t c = 0; c < angle.cols(); ++c) a[c] = dropout[c] && std::isnan(a[c]) ? 90.0f : a[c];
        }
    }
    detail::report(run.progress, 1.0, fn);
    return angle;
}

}  // namespace lidarfx
