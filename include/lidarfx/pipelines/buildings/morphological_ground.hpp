// SPDX-License-Identifier: Apache-2.0
// morphological_ground: the ground cells of an unclassified surface model by a progressive morphological
// filter (Zhang et al. 2003): openings by growing windows remove objects narrower than the window; a cell that
// an opening lowers by more than the terrain could drop over the window's growth is not ground.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/kernels/filter/min_max_filter.hpp"

namespace lidarfx {

/// Settings of morphological_ground.
struct morphological_ground_options {
    /// The largest window's side, metres; > 0. Objects that hold no square of this side are removed: it must
    /// exceed the narrow side of the widest building block (40 m: city blocks round a courtyard).
    double max_window_m = 40.0;
    double slope = 0.3;             ///< the steepest terrain kept as ground, metres per metre; finite and >= 0
    double initial_height_m = 0.3;  ///< the height above the first opening that is still ground, metres; > 0
    /// The threshold never exceeds this, metres; >= initial_height_m. Below the 2.5 m of a building
    /// (building_candidates' min_height_m), so that a low shop or garage is not left as ground.
    double max_height_m = 2.0;
};

/// Ground cells of a surface model and the terrain they give.
struct morphological_ground_result {
    raster<float> ground;            ///< the surface on ground cells, NaN elsewhere (and where the surface is), metres
    raster<std::uint8_t> is_ground;  ///< 1 = ground
    std::size_t ground_cells = 0;
};

/// Progressive morphological filter on a surface model `z` (metres, NaN = no data; cells of cell_m metres):
/// windows of half-side r_k = 1, 2, 4, ... cells, the last one round(max_window_m / (2 cell_m)) (so the side
/// 2 r + 1 reaches max_window_m); z_k = opening of z_(k-1) by the (2 r_k + 1)^2 square (min_max_filter's
/// minimum then maximum, clipped at the border, NaN ignored). A cell is not ground when z_(k-1) - z_k > t_k
/// for some k, with t_1 = initial_height_m and t_k = min(max_height_m, initial_height_m + slope x 2 (r_k -
/// r_(k-1)) x cell_m). O(cells x log r x number of windows). Same bits for any run.threads.
/// @throws invalid_input on options out of range, cell_m not finite and > 0, or run.threads < 0; cancelled if
/// run.progress returns false.
template <raster_input In>
morphological_ground_result morphological_ground(const In& z, double cell_m,
                                                 const morphological_ground_options& opt = {},
                                                 const execution& run = {});

// ---- implementation ----

namespace detail {

/// The half-sides of morphological_ground's windows: 1, 2, 4, ... up to the last (at least 1).
inline std::vector<int> morphological_window_radii(double max_window_m, double cell_m)
{
    const int last = std::max(1, static_cast<int>(std::lround(max_window_m / (2.0 * cell_m))));
    std::vector<int> radii;
    for (int r = 1; r < last; r *= 2) radii.push_back(r);
    radii.push_back(last);
    return radii;
}

}  // namespace detail

template <raster_input In>
morphological_ground_result morphological_ground(const In& z, double cell_m, const morphological_ground_options& opt,
                                                 const execution& run)
{
    constexpr const char* function = "morphological_ground";
    detail::require_positive(cell_m, function, "cell_m");
    detail::require_positive(opt.max_window_m, function, "max_window_m");
    detail::require(opt.slope >= 0 && std::isfinite(opt.slope), function, "slope", "finite and >= 0", opt.slope);
    detail::require_positive(opt.initial_height_m, function, "initial_height_m");
    detail::require(opt.max_height_m >= opt.initial_height_m && std::isfinite(opt.max_height_m), function,
                    "max_height_m", "finite and >= initial_height_m", opt.max_height_m);
    detail::check_execution(run, function);
    const std::ptrdiff_t rows = z.rows(), cols = z.cols();
    morphological_ground_result out{raster<float>(rows, cols), raster<std::uint8_t>(rows, cols, 1), 0};
    raster<float> surface(rows, cols);
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c) surface(r, c) = static_cast<float>(z(r, c));
    const std::vector<int> radii = detail::morphological_window_radii(opt.max_window_m, cell_m);
    int previous = 0;
    for (std::size_t k = 0; k < radii.size(); ++k) {
        const execution inner{run.threads, {}};
        const raster<float> eroded = min_max_filter(surface, {.radius_cells = radii[k], .run = inner}).min;
        raster<float> opened = min_max_filter(eroded, {.radius_cells = radii[k], .run = inner}).max;
        const double threshold =
            k == 0
                ? opt.initial_height_m
                : std::min(opt.max_height_m, opt.initial_height_m + opt.slope * 2.0 * (radii[k] - previous) * cell_m);
        for (std::ptrdiff_t r = 0; r < rows; ++r) {
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                if (static_cast<double>(surface(r, c)) - static_cast<double>(opened(r, c)) > threshold)
                    out.is_ground(r, c) = 0;
                if (std::isnan(surface(r, c))) opened(r, c) = surface(r, c);  // no data stays no data
            }
        }
        surface = std::move(opened);
        previous = radii[k];
        detail::report(run.progress, static_cast<double>(k + 1) / static_cast<double>(radii.size()), function);
    }
    constexpr float nan = std::numeric_limits<float>::quiet_NaN();
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const auto v = static_cast<float>(z(r, c));
            if (std::isnan(v)) out.is_ground(r, c) = 0;
            out.ground(r, c) = out.is_ground(r, c) ? v : nan;
            out.ground_cells += out.is_ground(r, c);
        }
    }
    return out;
}

}  // namespace lidarfx
