// SPDX-License-Identifier: Apache-2.0
// Implementation of kernels/filter/vegetation_mask.hpp: the height-spread threshold per cell, then the closing.
// Included at the end of vegetation_mask.hpp, after the declarations it defines; not a public header.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/kernels/filter/morphology.hpp"

namespace lidarfx {

template <raster_input MinZ, raster_input MaxZ, class Out>
requires raster_output_of<Out, std::uint8_t> && std::is_arithmetic_v<typename MinZ::value_type> &&
    std::is_arithmetic_v<typename MaxZ::value_type>
void vegetation_mask(const MinZ& min_z, const MaxZ& max_z, Out&& out, const vegetation_mask_options& opt)
{
    constexpr const char* function = "vegetation_mask";
    detail::require_same_shape(min_z, max_z, function, "min_z", "max_z");
    detail::require_same_shape(min_z, out, function, "min_z", "out");
    detail::require(opt.height_m >= 0 && opt.height_m <= 1.0e300, function, "height_m", "finite and >= 0",
                    opt.height_m);
    detail::require(opt.closing_size_cells >= 1 && opt.closing_size_cells % 2 == 1, function, "closing_size_cells",
                    "odd and >= 1", opt.closing_size_cells);
    detail::check_execution(opt.run, function);
    const detail::readable<MinZ> lo(min_z);
    const detail::readable<MaxZ> hi(max_z);
    detail::write_through<std::uint8_t>(std::forward<Out>(out), [&](raster_view<std::uint8_t> o) {
        const auto a = lo.view();
        const auto b = hi.view();
        const bool close = opt.closing_size_cells > 1;
        // The threshold goes to scratch when a closing follows: closing in place would run as one strip
        // (morph_* reads every row before writing when out is m), with neither threads nor progress.
        raster<std::uint8_t> spread_mask =
            close ? raster<std::uint8_t>(o.rows(), o.cols(), uninitialized) : raster<std::uint8_t>();
        const raster_view<std::uint8_t> t = close ? spread_mask.view() : o;
        parallel_for_rows(
            o.rows(), 64, opt.run.threads,
            [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
                // Row pointers and the threshold in locals: a byte store may alias the views' own fields, which
                // would be reloaded per cell and keep the loop scalar.
                const std::ptrdiff_t cols = o.cols();
                const double height = opt.height_m;
                for (std::ptrdiff_t r = r0; r < r1; ++r) {
                    const auto* low = a.row(r);
                    const auto* high = b.row(r);
                    std::uint8_t* mask = t.row(r);
                    for (std::ptrdiff_t c = 0; c < cols; ++c) {
                        // A NaN on either side makes the comparison false: no return, no vegetation.
                        const double spread = static_cast<double>(high[c]) - static_cast<double>(low[c]);
                        mask[c] = static_cast<std::uint8_t>(spread > height);
                    }
                }
            },
            detail::progress_phase(opt.run.progress, 0.0, close ? 0.2 : 1.0), function);
        if (close) {  // morph_close under this function's name (for a cancellation's message)
            const morphology_options closing{
                .size_cells = opt.closing_size_cells,
                .run = {.threads = opt.run.threads, .progress = detail::progress_phase(opt.run.progress, 0.2, 1.0)}};
            detail::morph_into(t, o, closing, {detail::morph_step::dilate, detail::morph_step::erode}, function);
        }
    });
}

template <raster_input MinZ, raster_input MaxZ>
requires std::is_arithmetic_v<typename MinZ::value_type> && std::is_arithmetic_v<typename MaxZ::value_type>
    raster<std::uint8_t> vegetation_mask(const MinZ& min_z, const MaxZ& max_z, const vegetation_mask_options& opt)
{
    raster<std::uint8_t> out(min_z.rows(), min_z.cols(), uninitialized);  // every cell is written
    vegetation_mask(min_z, max_z, out, opt);
    return out;
}

}  // namespace lidarfx
