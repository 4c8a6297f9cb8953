// SPDX-License-Identifier: Apache-2.0
// Implementation of water_surface_slope and lazy_water_surface_slope (included at the end of
// pipelines/water/water_surface_slope.hpp).
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>
#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

namespace detail {

/// One offset (x, y) of water_surface_slope's window over `count` cells of a row: the sums of the
/// neighbours nb[c] within ±band of the cell's own z0[c] (NaN on either side: left out). Branch-free over
/// separate arrays, so it vectorizes.
inline void slope_sums(const float* __restrict nb, const float* __restrict z0, std::ptrdiff_t count, float x, float y,
                       float band, float* __restrict n, float* __restrict sx, float* __restrict sy,
                       float* __restrict sxx, float* __restrict syy, float* __restrict sxy, float* __restrict sz,
                       float* __restrict sxz, float* __restrict syz) noexcept
{
    const float xx = x * x, yy = y * y, xy = x * y;
    for (std::ptrdiff_t c = 0; c < count; ++c) {
        const float d = nb[c] - z0[c];
        const bool in = std::fabs(d) <= band;
        // Bit-mask selects: a plain `in ? d : 0` keeps the loop scalar on AVX2 (no masked arithmetic).
        const float m = select_bits(in, 1.0f, 0.0f), dz = select_bits(in, d, 0.0f);
        n[c] += m;
        sx[c] += m * x;
        sy[c] += m * y;
        sxx[c] += m * xx;
        syy[c] += m * yy;
        sxy[c] += m * xy;
        sz[c] += dz;
        sxz[c] += dz * x;
        syz[c] += dz * y;
    }
}

/// water_surface_slope's sums for the cells [c0, c1) of row `z0` whose whole (2R+1)² window lies inside the
/// raster, R known at compile time: the window is unrolled and the sums stay in registers (the per-offset
/// passes of slope_sums read and write nine row arrays per offset). Same sums bit for bit: the six sums of
/// the mask times x, y, x², y², xy are small integers, exact in float in any order, and are taken per window
/// row; sz, sxz and syz add in the passes' order (row by row, column by column).
template <int R>
[[gnu::noinline, LIDARFX_VECTORIZE]] void slope_sums_window(
    const float* z0, std::ptrdiff_t row_stride, std::ptrdiff_t c0, std::ptrdiff_t c1, float band, float* __restrict n,
    float* __restrict sx, float* __restrict sy, float* __restrict sxx, float* __restrict syy, float* __restrict sxy,
    float* __restrict sz, float* __restrict sxz, float* __restrict syz) noexcept
{
    LIDARFX_IVDEP
    for (std::ptrdiff_t c = c0; c < c1; ++c) {
        const float p = z0[c];
        float a_n = 0, a_sx = 0, a_sy = 0, a_sxx = 0, a_syy = 0, a_sxy = 0, a_sz = 0, a_sxz = 0, a_syz = 0;
#pragma GCC unroll 16
        for (int dr = -R; dr <= R; ++dr) {
            const auto y = static_cast<float>(dr);
            float row_n = 0, row_sx = 0, row_sxx = 0;
#pragma GCC unroll 16
            for (int dc = -R; dc <= R; ++dc) {
                const auto x = static_cast<float>(dc);
                const float d = z0[dr * row_stride + c + dc] - p;
                const bool in = std::fabs(d) <= band;
                const float m = select_bits(in, 1.0f, 0.0f), dz = select_bits(in, d, 0.0f);
                row_n += m;
                row_sx += m * x;
                row_sxx += m * (x * x);
                a_sz += dz;
                a_sxz += dz * x;
                a_syz += dz * y;
            }
            a_n += row_n;
            a_sy += row_n * y;
            a_syy += row_n * (y * y);
            a_sx += row_sx;
            a_sxy += row_sx * y;
            a_sxx += row_sxx;
        }
        n[c] = a_n;
        sx[c] = a_sx;
        sy[c] = a_sy;
        sxx[c] = a_sxx;
        syy[c] = a_syy;
        sxy[c] = a_sxy;
        sz[c] = a_sz;
        sxz[c] = a_sxz;
        syz[c] = a_syz;
    }
}

inline void validate(const water_surface_slope_options& opt, double cell_m, const char* fn)
{
    require_positive(cell_m, fn, "cell_m");
    require(opt.radius_cells >= 1, fn, "radius_cells", ">= 1", opt.radius_cells);
    require(opt.min_cells >= 3, fn, "min_cells", ">= 3", opt.min_cells);
    require(opt.band_m > 0, fn, "band_m", "> 0", opt.band_m);
}

/// Row buffers of surface_slope_block: the nine window sums and the squared slope of up to `width` cells.
class slope_scratch {
public:
    explicit slope_scratch(std::ptrdiff_t width) : cells_(static_cast<std::size_t>(width)), sums_(10 * cells_) {}
    float* sum(int k) noexcept { return sums_.data() + static_cast<std::size_t>(k) * cells_; }  // k in [0, 9]

private:
    std::size_t cells_;
    std::vector<float> sums_;
};

/// water_surface_slope of the cells [c0, c1) of the rows [r0, r1) into `out`, the block's shape (cell (r, c)
/// at out(r − r0, c − c0)); `scratch` holds at least c1 − c0 cells. Each cell's sums take the same operations in the
/// same order whatever the block, so any tiling gives the values of the whole raster bit for bit.
inline void surface_slope_block(raster_view<const float> min_z, double cell_m, const water_surface_slope_options& opt,
                                std::ptrdiff_t r0, std::ptrdiff_t r1, std::ptrdiff_t c0, std::ptrdiff_t c1,
                                raster_view<float> out, slope_scratch& scratch)
{
    const std::ptrdiff_t rows = min_z.rows(), cols = min_z.cols(), k = opt.radius_cells, width = c1 - c0;
    const float band = static_cast<float>(opt.band_m);
    const auto need = static_cast<float>(opt.min_cells);
    // The window's sums are accumulated offset by offset along the block's row (contiguous, so the loops
    // vectorize), in float: heights enter relative to the cell's own, within ±band_m. Index i = c − c0.
    float* n = scratch.sum(0);
    float* sx = scratch.sum(1);
    float* sy = scratch.sum(2);
    float* sxx = scratch.sum(3);
    float* syy = scratch.sum(4);
    float* sxy = scratch.sum(5);
    float* sz = scratch.sum(6);
    float* sxz = scratch.sum(7);
    float* syz = scratch.sum(8);
    float* squared = scratch.sum(9);  // the squared slope per cell, NaN where unknown
    for (std::ptrdiff_t r = r0; r < r1; ++r) {
        const float* z0 = min_z.row(r);
        // Columns whose window lies inside, [w0, w1): the unrolled window (radii 1-4); the rest, and every
        // cell for larger radii or rows near the border, by passes per offset, which add to sums that start at 0.
        const bool inside = k <= 4 && r >= k && r + k < rows && cols > 2 * k;
        const std::ptrdiff_t w0 = inside ? std::clamp(k, c0, c1) : c1, w1 = inside ? std::clamp(cols - k, w0, c1) : c1;
        for (float* s : {n, sx, sy, sxx, syy, sxy, sz, sxz, syz}) {
            std::fill(s, s + (w0 - c0), 0.0f);
            std::fill(s + (w1 - c0), s + width, 0.0f);
        }
        if (w1 > w0) {
            const auto stride = min_z.row_stride();
            const float* z = z0 + c0;  // the kernels index from the block's first column
            const std::ptrdiff_t a = w0 - c0, b = w1 - c0;
            if (k == 1) slope_sums_window<1>(z, stride, a, b, band, n, sx, sy, sxx, syy, sxy, sz, sxz, syz);
            if (k == 2) slope_sums_window<2>(z, stride, a, b, band, n, sx, sy, sxx, syy, sxy, sz, sxz, syz);
            if (k == 3) slope_sums_window<3>(z, stride, a, b, band, n, sx, sy, sxx, syy, sxy, sz, sxz, syz);
            if (k == 4) slope_sums_window<4>(z, stride, a, b, band, n, sx, sy, sxx, syy, sxy, sz, sxz, syz);
        }
        for (std::ptrdiff_t dr = -k; dr <= k; ++dr) {
            if (r + dr < 0 || r + dr >= rows) continue;
            const float* zr = min_z.row(r + dr);
            const auto y = static_cast<float>(dr);
            for (std::ptrdiff_t dc = -k; dc <= k; ++dc) {
                const auto x = static_cast<float>(dc);
                // Cells whose neighbour at this offset exists, outside the window's columns.
                const std::ptrdiff_t lo = std::max({c0, -dc}), hi = std::min(c1, cols - dc);
                for (const auto& [from, to] : {std::pair{lo, std::min(hi, w0)}, std::pair{std::max(lo, w1), hi}}) {
                    if (to <= from) continue;
                    const std::ptrdiff_t i = from - c0;
                    slope_sums(zr + from + dc, z0 + from, to - from, x, y, band, n + i, sx + i, sy + i, sxx + i,
                               syy + i, sxy + i, sz + i, sxz + i, syz + i);
                }
            }
        }
        // Centre the sums on the mean position: the slopes solve the 2 × 2 system of the covariances. Every
        // cell is computed and the unknown ones masked to NaN, so that the loop vectorizes; the square root
        // (a libm call that compilers keep scalar for errno) runs in a loop of its own.
        for (std::ptrdiff_t i = 0; i < width; ++i) {
            const double w = 1.0 / n[i];  // one division per cell, not five
            const double mx = sx[i] * w, my = sy[i] * w;
            const double cxx = sxx[i] - mx * sx[i];
            const double cyy = syy[i] - my * sy[i];
            const double cxy = sxy[i] - mx * sy[i];
            const double cxz = sxz[i] - mx * sz[i];
            const double cyz = syz[i] - my * sz[i];
            const double det = cxx * cyy - cxy * cxy;
            const bool known = (n[i] >= need) & (det > 1e-6 * (cxx * cyy + 1));  // & not &&: no branch
            const double inv = 1.0 / det;
            const double b = (cxz * cyy - cyz * cxy) * inv, g = (cyz * cxx - cxz * cxy) * inv;
            const double nan = std::numeric_limits<double>::quiet_NaN();
            squared[i] = static_cast<float>(select_bits(known, b * b + g * g, nan));
        }
        sqrt_span(squared, out.row(r - r0), width, static_cast<float>(1 / cell_m));
    }
}

}  // namespace detail

inline raster<float> water_surface_slope(raster_view<const float> min_z, double cell_m,
                                         const water_surface_slope_options& opt, const execution& run)
{
    constexpr const char* fn = "water_surface_slope";
    detail::validate(opt, cell_m, fn);
    detail::check_execution(run, fn);
    const std::ptrdiff_t rows = min_z.rows(), cols = min_z.cols();
    raster<float> out(rows, cols, uninitialized);  // every cell is written
    parallel_for_rows(
        rows, 16, run.threads,
        [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
            detail::slope_scratch scratch(cols);
            detail::surface_slope_block(min_z, cell_m, opt, r0, r1, 0, cols, out.view().window(r0, 0, r1 - r0, cols),
                                        scratch);
        },
        {}, fn);
    return out;
}

inline lazy_water_surface_slope::lazy_water_surface_slope(raster_view<const float> min_z, double cell_m,
                                                          const water_surface_slope_options& opt)
    : min_z_(min_z),
      cell_m_(cell_m),
      opt_(opt),
      tiles_across_((min_z.cols() + tile_cols - 1) / tile_cols),
      tile_(static_cast<std::size_t>((min_z.rows() + tile_rows - 1) / tile_rows * tiles_across_)),
      chunks_((tile_.size() + chunk_tiles - 1) / chunk_tiles)
{
    detail::validate(opt, cell_m, "lazy_water_surface_slope");
    for (auto& slot : tile_) slot.store(unread, std::memory_order_relaxed);
}

inline float lazy_water_surface_slope::operator()(std::ptrdiff_t r, std::ptrdiff_t c)
{
    const std::ptrdiff_t tr = r / tile_rows, tc = c / tile_cols;
    std::atomic<std::int32_t>& tile = tile_[static_cast<std::size_t>(tr * tiles_across_ + tc)];
    // A tile's cells are written once, before its slot is published (release); a reader that sees the slot
    // (acquire) sees the cells.
    std::int32_t s = tile.load(std::memory_order_acquire);
    if (s < 0) [[unlikely]]
        s = publish(tile, tr, tc);
    return tile_cells(s)[(r - tr * tile_rows) * tile_cols + (c - tc * tile_cols)];
}

inline std::int32_t lazy_water_surface_slope::publish(std::atomic<std::int32_t>& tile, std::ptrdiff_t tr,
                                                      std::ptrdiff_t tc)
{
    // The first reader marks the tile computing; readers of that tile wait until its slot is published.
    for (std::int32_t s = tile.load(std::memory_order_acquire);; s = tile.load(std::memory_order_acquire)) {
        if (s >= 0) return s;
        if (s == computing) {
            tile.wait(computing, std::memory_order_acquire);
        } else if (tile.compare_exchange_strong(s, computing, std::memory_order_acquire)) {
            break;
        }
    }
    std::int32_t s = unread;
    try {
        s = compute(tr, tc);
    } catch (...) {
        tile.store(unread, std::memory_order_release);  // the next reader tries again
        tile.notify_all();
        throw;
    }
    tile.store(s, std::memory_order_release);
    tile.notify_all();
    return s;
}

inline float* lazy_water_surface_slope::tile_cells(std::int32_t slot) noexcept
{
    const auto s = static_cast<std::size_t>(slot);
    return chunks_[s / chunk_tiles].get() + (s % chunk_tiles) * tile_size;
}

inline std::int32_t lazy_water_surface_slope::compute(std::ptrdiff_t tr, std::ptrdiff_t tc)
{
    detail::slope_scratch scratch(tile_cols);  // first: once a slot is taken nothing throws
    std::int32_t slot = 0;
    {
        const std::lock_guard lock(reserve_);
        slot = static_cast<std::int32_t>(used_);
        if (static_cast<std::size_t>(slot) % chunk_tiles == 0)
            chunks_[static_cast<std::size_t>(slot) / chunk_tiles] =
                std::make_unique_for_overwrite<float[]>(chunk_tiles * tile_size);
        ++used_;  // only once its chunk is there: a failed allocation leaves the cache as it was
    }
    const std::ptrdiff_t r0 = tr * tile_rows, c0 = tc * tile_cols;
    const std::ptrdiff_t r1 = std::min(rows(), r0 + tile_rows), c1 = std::min(cols(), c0 + tile_cols);
    detail::surface_slope_block(min_z_, cell_m_, opt_, r0, r1, c0, c1,
                                raster_view<float>(tile_cells(slot), r1 - r0, c1 - c0, tile_cols), scratch);
    return slot;
}

}  // namespace lidarfx
