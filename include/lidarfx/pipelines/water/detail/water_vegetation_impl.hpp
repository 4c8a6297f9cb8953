// SPDX-License-Identifier: Apache-2.0
// Implementation of water_vegetation (included at the end of pipelines/water/water_vegetation.hpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/kernels/filter/vegetation_mask.hpp"
#include "lidarfx/pipelines/water/water_rasters.hpp"

namespace lidarfx {

namespace detail {

inline void validate(const water_vegetation_options& o, const char* fn)
{
    require(o.height_m > 0, fn, "height_m", "> 0", o.height_m);
    require(o.closing_size_cells >= 1 && o.closing_size_cells % 2 == 1, fn, "closing_size_cells", "odd and >= 1",
            o.closing_size_cells);
}

}  // namespace detail

inline raster<std::uint8_t> water_vegetation(const water_rasters& in, const water_vegetation_options& opt,
                                             const execution& run)
{
    constexpr const char* fn = "water_vegetation";
    detail::validate(in, fn);
    detail::validate(opt, fn);
    detail::check_execution(run, fn);
    detail::report(run.progress, 0.0, fn);
    auto vegetation = vegetation_mask(
        in.min_z, in.max_z,
        vegetation_mask_options{
            .height_m = opt.height_m, .closing_size_cells = opt.closing_size_cells, .run = {.threads = run.threads}});
    if (opt.from_multiple_returns && !in.multiple_returns.empty()) {
        const std::ptrdiff_t rows = vegetation.rows(), cols = vegetation.cols();  // locals: see vegetation_mask
        for (std::ptrdiff_t r = 0; r < rows; ++r) {
            const std::uint8_t* multiple = in.multiple_returns.row(r);
            const std::uint8_t* dropout = in.dropout.row(r);
            std::uint8_t* v = vegetation.row(r);
            for (std::ptrdiff_t c = 0; c < cols; ++c)
                v[c] = static_cast<std::uint8_t>(v[c] | ((multiple[c] != 0) & (dropout[c] == 0)));
        }
    }
    detail::report(run.progress, 1.0, fn);
    return vegetation;
}

}  // namespace lidarfx
