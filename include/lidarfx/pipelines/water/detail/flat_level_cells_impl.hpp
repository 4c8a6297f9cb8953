// SPDX-License-Identifier: Apache-2.0
// Implementation of pipelines/water/flat_level_cells.hpp (included at its end; not meant to be included alone).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/kernels/filter/min_max_filter.hpp"
#include "lidarfx/pipelines/water/flat_water_seeds_options.hpp"
#include "lidarfx/pipelines/water/water_rasters.hpp"

namespace lidarfx {

namespace detail {

/// One row of flat_level_cells' test: a return (no dropout, finite min z, inside the footprint), not
/// excluded, smooth (max z − min z <= max_rough) and level (window max − min of min z <= tolerance).
/// Branch-free (& rather than &&) so that it vectorizes. One cell: level_cell; the window's min z span is
/// hi − lo.
inline std::uint8_t level_cell(float z0, float z1, float lo, float hi, std::uint8_t drop, std::uint8_t inside,
                               std::uint8_t ex, float max_rough, float tolerance) noexcept
{
    return static_cast<std::uint8_t>((drop == 0) & std::isfinite(z0) & (inside != 0) & (ex == 0) &
                                     (z1 - z0 <= max_rough) & (hi - lo <= tolerance));
}

inline void level_row(const float* z0, const float* z1, const float* lo, const float* hi, const std::uint8_t* drop,
                      const std::uint8_t* inside, const std::uint8_t* ex, std::uint8_t* out, std::ptrdiff_t cols,
                      float max_rough, float tolerance) noexcept
{
    for (std::ptrdiff_t c = 0; c < cols; ++c) {
        out[c] = level_cell(z0[c], z1[c], lo[c], hi[c], drop[c], inside[c], ex[c], max_rough, tolerance);
    }
}

/// flat_level_cells' test for the window radii 1 and 2 (K), one output row per call, in two passes
/// that read the rows of min z in place: the column minimum and maximum of the finite min z over the
/// 2K + 1 rows `rows` (a row of NaN for those outside the raster) into `low` and `high`, padded by K cells
/// of ±inf on each side; then level_row's test with the window's minimum and maximum taken from K columns
/// on either side. The same minima and maxima as the running filters (up to the sign of a zero, which
/// high − low does not see), without their strips of rows in memory.
template <int K>
void level_window_row(const float* const* rows, float* low, float* high, const float* z0, const float* z1,
                      const std::uint8_t* drop, const std::uint8_t* inside, const std::uint8_t* ex, std::uint8_t* out,
                      std::ptrdiff_t cols, float max_rough, float tolerance) noexcept
{
    constexpr float inf = std::numeric_limits<float>::infinity();
    std::fill(low, low + K, inf);
    std::fill(high, high + K, -inf);
    float* lo = low + K;
    float* hi = high + K;
    for (std::ptrdiff_t c = 0; c < cols; ++c) {
        float l = inf, h = -inf;
#pragma GCC unroll 5
        for (int d = 0; d <= 2 * K; ++d) {
            const float x = rows[d][c];
            const bool finite = std::isfinite(x);
            l = (finite & (x < l)) ? x : l;
            h = (finite & (x > h)) ? x : h;
        }
        lo[c] = l;
        hi[c] = h;
    }
    std::fill(lo + cols, lo + cols + K, inf);
    std::fill(hi + cols, hi + cols + K, -inf);
    for (std::ptrdiff_t c = 0; c < cols; ++c) {
        float l = low[c], h = high[c];
#pragma GCC unroll 4
        for (int d = 1; d <= 2 * K; ++d) {
            l = low[c + d] < l ? low[c + d] : l;
            h = high[c + d] > h ? high[c + d] : h;
        }
        out[c] = level_cell(z0[c], z1[c], l, h, drop[c], inside[c], ex[c], max_rough, tolerance);
    }
}

/// The per-row inputs of the level test that may be absent: a row of ones for a missing footprint, of
/// zeros for a missing exclusion mask, of NaN for the rows above and below the raster.
struct level_test_rows {
    std::vector<std::uint8_t> ones, zeros;
    std::vector<float> nan_row;
    explicit level_test_rows(std::ptrdiff_t cols)
        : ones(static_cast<std::size_t>(cols), 1),
          zeros(static_cast<std::size_t>(cols), 0),
          nan_row(static_cast<std::size_t>(cols), std::numeric_limits<float>::quiet_NaN())
    {
    }
};

/// flat_level_cells for radii 1 and 2, row by row in place (level_window_row); rows outside the raster
/// read as NaN.
inline void level_cells_small_window(const water_rasters& in, raster_view<const std::uint8_t> excluded, int k,
                                     float max_rough, float tolerance, int threads, raster_view<std::uint8_t> level,
                                     const char* fn)
{
    const std::ptrdiff_t rows = in.min_z.rows(), cols = in.min_z.cols();
    const level_test_rows fixed(cols);
    parallel_for_rows(
        rows, 256, threads,
        [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
            std::vector<float> low(static_cast<std::size_t>(cols + 2 * k)), high(low.size());
            const float* window[5];
            for (std::ptrdiff_t r = r0; r < r1; ++r) {
                for (std::ptrdiff_t d = -k; d <= k; ++d)
                    window[d + k] = r + d >= 0 && r + d < rows ? in.min_z.row(r + d) : fixed.nan_row.data();
                const auto test = k == 1 ? level_window_row<1> : level_window_row<2>;
                test(window, low.data(), high.data(), in.min_z.row(r), in.max_z.row(r), in.dropout.row(r),
                     in.footprint.empty() ? fixed.ones.data() : in.footprint.row(r),
                     excluded.empty() ? fixed.zeros.data() : excluded.row(r), level.row(r), cols, max_rough, tolerance);
            }
        },
        {}, fn);
}

/// flat_level_cells for radii from 3: the window's lowest and highest finite min z from running min/max
/// filters over strips of rows (non-finite min z is no data).
inline void level_cells_large_window(const water_rasters& in, raster_view<const std::uint8_t> excluded, int k,
                                     float max_rough, float tolerance, int threads, raster_view<std::uint8_t> level,
                                     const char* fn)
{
    const std::ptrdiff_t rows = in.min_z.rows(), cols = in.min_z.cols();
    const std::ptrdiff_t kx = std::min<std::ptrdiff_t>(k, cols - 1), ky = std::min<std::ptrdiff_t>(k, rows - 1);
    const level_test_rows fixed(cols);
    struct scratch {
        min_max_workspace<float> s;
        std::vector<float> lows, highs;
    };
    for_each_row_strip<scratch>(
        rows, min_max_strip_rows(rows, cols, ky), threads,
        [&](std::ptrdiff_t r0, std::ptrdiff_t r1, scratch& w) {
            const std::ptrdiff_t nc = cols;
            w.lows.resize(static_cast<std::size_t>((r1 - r0) * nc));
            w.highs.resize(w.lows.size());
            const auto load = [&](std::ptrdiff_t r, float* dst) {
                const float* z = in.min_z.row(r);
                for (std::ptrdiff_t c = 0; c < nc; ++c)
                    dst[c] = std::isfinite(z[c]) ? z[c] : std::numeric_limits<float>::quiet_NaN();
            };
            min_filter_rows(rows, nc, kx, ky, r0, r1, load, w.lows.data(), w.s);
            max_filter_rows(rows, nc, kx, ky, r0, r1, load, w.highs.data(), w.s);
            for (std::ptrdiff_t r = r0; r < r1; ++r) {
                level_row(
                    in.min_z.row(r), in.max_z.row(r), w.lows.data() + (r - r0) * nc, w.highs.data() + (r - r0) * nc,
                    in.dropout.row(r), in.footprint.empty() ? fixed.ones.data() : in.footprint.row(r),
                    excluded.empty() ? fixed.zeros.data() : excluded.row(r), level.row(r), nc, max_rough, tolerance);
            }
        },
        {}, fn);
}

}  // namespace detail

inline void flat_level_cells(const water_rasters& in, raster_view<const std::uint8_t> excluded,
                             const flat_water_seeds_options& opt, raster_view<std::uint8_t> level, const execution& run)
{
    constexpr const char* fn = "flat_level_cells";
    detail::validate(in, fn);
    detail::validate(opt, fn);
    detail::check_execution(run, fn);
    if (!excluded.empty()) detail::require_same_shape(in.min_z, excluded, fn, "min_z", "excluded");
    detail::require_same_shape(in.min_z, level, fn, "min_z", "level");
    const float max_rough = detail::float_at_most(opt.max_roughness_m);
    const float tolerance = detail::float_at_most(opt.level_tolerance_m);
    if (opt.level_radius_cells <= 2)
        detail::level_cells_small_window(in, excluded, opt.level_radius_cells, max_rough, tolerance, run.threads, level,
                                         fn);
    else
        detail::level_cells_large_window(in, excluded, opt.level_radius_cells, max_rough, tolerance, run.threads, level,
                                         fn);
}

inline raster<std::uint8_t> flat_level_cells(const water_rasters& in, raster_view<const std::uint8_t> excluded,
                                             const flat_water_seeds_options& opt, const execution& run)
{
    detail::validate(in, "flat_level_cells");
    raster<std::uint8_t> level(in.min_z.rows(), in.min_z.cols(), uninitialized);  // every cell is written
    flat_level_cells(in, excluded, opt, level, run);
    return level;
}

}  // namespace lidarfx
