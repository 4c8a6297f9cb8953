// SPDX-License-Identifier: Apache-2.0
// Implementation of pipelines/water/channel_water_seeds.hpp (included at its end; not meant to be included alone).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/kernels/label/connected_components.hpp"
#include "lidarfx/pipelines/water/detail/body_within.hpp"

namespace lidarfx {

namespace detail {

inline void validate(const channel_water_seeds_options& o, const char* fn)
{
    require(o.level_tolerance_m >= 0, fn, "level_tolerance_m", ">= 0", o.level_tolerance_m);
    require(o.along_cells >= 1, fn, "along_cells", ">= 1", o.along_cells);
    require(o.bank_rise_m > o.level_tolerance_m && std::isfinite(o.bank_rise_m), fn, "bank_rise_m",
            "finite and > level_tolerance_m", o.bank_rise_m);
    require_positive(o.max_width_m, fn, "max_width_m");
    require(o.max_intensity_ratio > 0, fn, "max_intensity_ratio", "> 0", o.max_intensity_ratio);
    require(o.min_cells >= 1, fn, "min_cells", ">= 1", o.min_cells);
    require(o.max_lower_share >= 0 && o.max_lower_share <= 1, fn, "max_lower_share", "in [0, 1]", o.max_lower_share);
    require(o.clear_cells >= 0, fn, "clear_cells", ">= 0", o.clear_cells);
}

/// Whether at most max_lower_share of the cells with a return within `reach` cells (Chebyshev distance) of
/// (r, c) lie more than bank_rise_m below z0.
inline bool bottom_of_surroundings(raster_view<const float> min_z, std::ptrdiff_t r, std::ptrdiff_t c, float z0,
                                   int reach, const channel_water_seeds_options& opt)
{
    const float below = z0 - static_cast<float>(opt.bank_rise_m);
    std::size_t measured = 0, lower = 0;
    for (std::ptrdiff_t y = std::max<std::ptrdiff_t>(0, r - reach); y <= std::min(min_z.rows() - 1, r + reach); ++y) {
        const float* row = min_z.row(y);
        for (std::ptrdiff_t x = std::max<std::ptrdiff_t>(0, c - reach); x <= std::min(min_z.cols() - 1, c + reach);
             ++x) {
            measured += !std::isnan(row[x]);
            lower += row[x] < below;
        }
    }
    return static_cast<double>(lower) <= opt.max_lower_share * static_cast<double>(measured);
}

/// Whether cell (r, c) of height z0 lies in a channel along the axis (dr, dc) (channel_water_seeds' rule).
inline bool channel_along(raster_view<const float> min_z, std::ptrdiff_t r, std::ptrdiff_t c, float z0, int dr, int dc,
                          double cell_m, const channel_water_seeds_options& opt)
{
    const std::ptrdiff_t rows = min_z.rows(), cols = min_z.cols();
    const auto inside = [&](std::ptrdiff_t y, std::ptrdiff_t x) { return y >= 0 && y < rows && x >= 0 && x < cols; };
    const auto tolerance = static_cast<float>(opt.level_tolerance_m);
    const auto along = static_cast<int>(std::min<std::ptrdiff_t>(opt.along_cells, rows + cols));  // beyond: outside
    for (const int way : {-1, 1}) {  // level along the channel, with a return each way
        bool measured = false;
        for (int k = 1; k <= along; ++k) {
            const std::ptrdiff_t y = r + way * k * dr, x = c + way * k * dc;
            if (!inside(y, x) || std::isnan(min_z(y, x))) continue;
            if (std::abs(min_z(y, x) - z0) > tolerance) return false;
            measured = true;
        }
        if (!measured) return false;
    }
    const double step = (dr != 0 && dc != 0) ? cell_m * std::sqrt(2.0) : cell_m;
    // Cells the strip may hold (a width of a whole number of steps is not lost to rounding; beyond the raster's
    // rows and columns a strip ends outside it anyway).
    const auto max_steps =
        static_cast<int>(std::min(std::floor(opt.max_width_m / step + 1e-9), static_cast<double>(rows + cols)));
    const auto bank = static_cast<float>(opt.bank_rise_m);
    int strip = 1;  // the cell and the level or empty cells across it
    for (const int side : {-1, 1}) {
        for (int j = 1;; ++j) {  // across: side · (dc, −dr)
            const std::ptrdiff_t y = r + side * j * dc, x = c - side * j * dr;
            if (!inside(y, x) || strip > max_steps) return false;
            const float z = min_z(y, x);
            if (z - z0 >= bank) break;
            if (z0 - z > tolerance) return false;  // passed: no return (NaN), or below a bank and not lower
            ++strip;
        }
    }
    return true;
}

}  // namespace detail

inline raster<std::uint8_t> channel_water_seeds(raster_view<const float> min_z, raster_view<const float> intensity,
                                                raster_view<const std::uint8_t> excluded,
                                                raster_view<const std::int32_t> taken, double cell_m,
                                                double land_intensity, const channel_water_seeds_options& opt,
                                                const execution& run)
{
    constexpr const char* fn = "channel_water_seeds";
    detail::require_same_shape(min_z, intensity, fn, "min_z", "intensity");
    if (!excluded.empty()) detail::require_same_shape(min_z, excluded, fn, "min_z", "excluded");
    if (!taken.empty()) detail::require_same_shape(min_z, taken, fn, "min_z", "taken");
    detail::require_positive(cell_m, fn, "cell_m");
    detail::validate(opt, fn);
    detail::check_execution(run, fn);
    const std::ptrdiff_t rows = min_z.rows(), cols = min_z.cols();
    raster<std::uint8_t> seeds(rows, cols, 0);
    if (std::isnan(land_intensity)) return seeds;
    const auto darkest_land = static_cast<float>(opt.max_intensity_ratio * land_intensity);
    constexpr int axes[4][2] = {{0, 1}, {1, 1}, {1, 0}, {1, -1}};
    const auto surroundings =
        static_cast<int>(std::min(std::ceil(opt.max_width_m / cell_m), static_cast<double>(rows + cols)));
    parallel_for_rows(
        rows, 16, run.threads,
        [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
            for (std::ptrdiff_t r = r0; r < r1; ++r) {
                std::uint8_t* out = seeds.view().row(r);
                for (std::ptrdiff_t c = 0; c < cols; ++c) {
                    const float z0 = min_z(r, c);
                    if (std::isnan(z0) || !(intensity(r, c) <= darkest_land)) continue;
                    if ((!excluded.empty() && excluded(r, c)) || (!taken.empty() && taken(r, c) > 0)) continue;
                    for (const auto& a : axes) {
                        if (detail::channel_along(min_z, r, c, z0, a[0], a[1], cell_m, opt)) {
                            // The cheaper test first: clear_cells is small, the surroundings reach max_width_m.
                            out[c] = !detail::body_within(taken, r, c, opt.clear_cells) &&
                                     detail::bottom_of_surroundings(min_z, r, c, z0, surroundings, opt);
                            break;
                        }
                    }
                }
            }
        },
        {}, fn);
    raster<std::int32_t> groups(rows, cols, uninitialized);
    const auto sizes = connected_components(
        seeds, groups, connected_components_options{.conn = connectivity::eight, .run = {.threads = run.threads}});
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        std::uint8_t* out = seeds.view().row(r);
        const std::int32_t* group = groups.view().row(r);
        for (std::ptrdiff_t c = 0; c < cols; ++c)
            out[c] = out[c] && sizes[static_cast<std::size_t>(group[c])] >= opt.min_cells;
    }
    return seeds;
}

}  // namespace lidarfx
