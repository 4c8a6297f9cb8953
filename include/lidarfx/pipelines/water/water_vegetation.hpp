// SPDX-License-Identifier: Apache-2.0
// water_vegetation: the cells that never join a waterbody (canopy by height spread, multiple returns).
#pragma once

#include <cstddef>
#include <cstdint>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/kernels/filter/vegetation_mask.hpp"
#include "lidarfx/pipelines/water/water_rasters.hpp"

namespace lidarfx {

/// Options of water_vegetation.
struct water_vegetation_options {
    double height_m = 2.0;              ///< h: max z − min z > h is vegetation, metres; > 0. Default 2 m.
    int closing_size_cells = 5;         ///< side of the square closing the height mask, cells; odd, >= 1
                                        ///< (1 = no closing). Default 5.
    bool from_multiple_returns = true;  ///< cells with returns and a multiple-return pulse are vegetation too
                                        ///< (needs the multiple_returns raster). Default true.
    execution run = {};                 ///< threads of the kernels (same result for any count), progress
};

namespace detail {

inline void validate(const water_vegetation_options& o, const char* fn)
{
    require(o.height_m > 0, fn, "height_m", "> 0", o.height_m);
    require(o.closing_size_cells >= 1 && o.closing_size_cells % 2 == 1, fn, "closing_size_cells", "odd and >= 1",
            o.closing_size_cells);
    check_execution(o.run, fn);
}

}  // namespace detail

/// Vegetation mask of the waterbody method (dissertation 2.3.1): vegetation_mask (1 where max z − min z >
/// height_m, closed by a closing_size_cells square), then OR cells with a return (dropout == 0) whose
/// multiple_returns is set, when from_multiple_returns and that raster is given. 1 = vegetation.
/// O(cells). Progress: 0 on entry, 1 when done.
/// @throws invalid_input on rasters of different shapes or empty, options out of range; cancelled.
inline raster<std::uint8_t> water_vegetation(const water_rasters& in, const water_vegetation_options& opt = {})
{
    constexpr const char* fn = "water_vegetation";
    detail::validate(in, fn);
    detail::validate(opt, fn);
    detail::report(opt.run.progress, 0.0, fn);
    auto vegetation = vegetation_mask(in.min_z, in.max_z,
                                      vegetation_mask_options{.height_m = opt.height_m,
                                                              .closing_size_cells = opt.closing_size_cells,
                                                              .run = {.threads = opt.run.threads}});
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
    detail::report(opt.run.progress, 1.0, fn);
    return vegetation;
}

}  // namespace lidarfx
