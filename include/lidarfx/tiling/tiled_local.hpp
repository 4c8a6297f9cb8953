// SPDX-License-Identifier: Apache-2.0
// tiled_local: runs a local raster step tile by tile on windows grown by the step's reach and keeps each core,
// so the result equals the whole-raster call (docs/scale.md).
#pragma once

#include <algorithm>
#include <concepts>
#include <cstddef>
#include <type_traits>
#include <utility>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/grid.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

namespace detail {

/// Calls step(window) or step(window, box): the second form lets a step window other rasters the same way.
template <class T, class Step>
decltype(auto) call_local_step(Step& step, raster_view<const T> window, const cell_box& box)
{
    if constexpr (std::is_invocable_v<Step&, raster_view<const T>, const cell_box&>) {
        return step(window, box);
    } else {
        return step(window);
    }
}

template <class T, class Step>
using local_step_result = std::remove_cvref_t<decltype(call_local_step<T>(
    std::declval<Step&>(), std::declval<raster_view<const T>>(), std::declval<const cell_box&>()))>;

}  // namespace detail

/// Runs a local step tile by tile: the raster is cut into tile_cells x tile_cells cores (row-major, the last
/// row and column smaller), each core grown by `reach` cells on every side and clipped to the raster is handed
/// to step(window) or step(window, box) (box = the window's cells in `in`), which returns a raster of the
/// window's shape; the core's cells of it go to the output. When `reach` is at least the step's reach
/// (tiling/halo.hpp) and the step treats cells beyond its input as the raster border does, the result equals
/// step(in) bit for bit: every cell of a core sees the same inputs in the window as in the whole raster. Peak
/// memory: the output plus, per thread, one window and the step's result. Tiles run on run.threads threads
/// (each tile writes only its core: the same result for any count), so `step` must be safe to call from
/// several threads at once (a lambda that only reads what it captures is); progress after each tile.
/// @throws invalid_input if reach < 0, tile_cells < 1 or run.threads < 0, or a step's result has not the
/// window's shape; whatever `step` throws; cancelled if run.progress returns false.
template <class T, class Step>
requires raster_input<detail::local_step_result<T, Step>>
auto tiled_local(raster_view<const T> in, std::ptrdiff_t reach, std::ptrdiff_t tile_cells, Step step,
                 execution run = {})
{
    using U = typename detail::local_step_result<T, Step>::value_type;
    constexpr const char* function = "tiled_local";
    detail::require(reach >= 0, function, "reach", ">= 0", reach);
    detail::require(tile_cells >= 1, function, "tile_cells", ">= 1", tile_cells);
    detail::check_execution(run, function);
    raster<U> out(in.rows(), in.cols(), uninitialized);
    if (in.rows() == 0 || in.cols() == 0) return out;
    const std::ptrdiff_t t = std::min(tile_cells, std::max(in.rows(), in.cols()));
    const std::ptrdiff_t tile_rows = (in.rows() + t - 1) / t, tile_cols = (in.cols() + t - 1) / t;
    raster_view<U> target = out.view();
    parallel_for_rows(
        tile_rows * tile_cols, 1, run.threads,
        [&](std::ptrdiff_t first, std::ptrdiff_t last) {
            for (std::ptrdiff_t i = first; i < last; ++i) {
                const std::ptrdiff_t r0 = i / tile_cols * t, c0 = i % tile_cols * t;
                const std::ptrdiff_t r1 = std::min(r0 + t, in.rows()), c1 = std::min(c0 + t, in.cols());
                // Clip before adding, so a huge reach cannot overflow.
                const cell_box box{r0 - std::min(reach, r0), c0 - std::min(reach, c0),
                                   r1 - 1 + std::min(reach, in.rows() - r1), c1 - 1 + std::min(reach, in.cols() - c1)};
                const raster_view<const T> window = in.window(box.row_min, box.col_min, box.rows(), box.cols());
                const auto result = detail::call_local_step<T>(step, window, box);
                detail::require(result.rows() == box.rows() && result.cols() == box.cols(), function, [&] {
                    return detail::concat("the step returned ", result.rows(), "x", result.cols(),
                                          " cells for a window of ", box.rows(), "x", box.cols());
                });
                for (std::ptrdiff_t r = r0; r < r1; ++r) {
                    for (std::ptrdiff_t c = c0; c < c1; ++c) {
                        target(r, c) = static_cast<U>(result(r - box.row_min, c - box.col_min));
                    }
                }
            }
        },
        run.progress, function);
    return out;
}

/// tiled_local on an owned raster (viewed as raster_view<const T>).
template <class T, class Step>
auto tiled_local(const raster<T>& in, std::ptrdiff_t reach, std::ptrdiff_t tile_cells, Step step, execution run = {})
{
    return tiled_local(raster_view<const T>(in.view()), reach, tile_cells, std::move(step), std::move(run));
}

}  // namespace lidarfx
