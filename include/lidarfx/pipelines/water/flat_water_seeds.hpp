// SPDX-License-Identifier: Apache-2.0
// flat_water_seeds: seeds of waterbodies from cells with returns: level, smooth, low, and sparser than the land around.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/kernels/filter/min_max_filter.hpp"
#include "lidarfx/kernels/label/connected_components.hpp"
#include "lidarfx/kernels/stats/ks_one_sided.hpp"
#include "lidarfx/pipelines/water/water_rasters.hpp"
#include "lidarfx/pipelines/water/water_surface_slope.hpp"

namespace lidarfx {

/// Options of flat_water_seeds. The defaults follow from the physics of the returns, not from one survey:
/// a water surface is level to the range noise of the scanner (2-3 cm per return), returns fewer pulses
/// than the land around it (specular reflection away from the sensor, absorption), and lies below its banks.
struct flat_water_seeds_options {
    int level_radius_cells = 1;          ///< the level test reads the (2 r + 1)² window around a cell (3 × 3: a
                                         ///< river a few cells wide still has level cells), >= 1. Default 1
    double level_tolerance_m = 0.10;     ///< the window's min z spans at most this, metres (≈ 4 σ of 2-3 cm range
                                         ///< noise on the lowest return), >= 0. Default 0.10
    double max_roughness_m = 0.2;        ///< a cell's max z − min z is at most this (several σ of range noise plus
                                         ///< waves; low vegetation and edges are rougher), metres, >= 0. Default 0.2
    std::size_t min_cells = 50;          ///< a seed keeps components of at least this many cells, >= 1. Default 50
    int ring_cells = 4;                  ///< the land a component is compared with lies within this Chebyshev
                                         ///< distance of it, cells, >= 1. Default 4
    double max_density_ratio = 0.85;     ///< sparse: a component's mean returns per cell is at most this share of its
                                         ///< ring's (water loses pulses; flat land, asphalt and roofs do not), in
                                         ///< (0, 1]. Default 0.85
    double dark_density_ratio = 0.97;    ///< dark and sparse: ... or at most this share when it is also dark (then
                                         ///< a few % fewer returns suffice: asphalt is dark but returns every
                                         ///< pulse), in (0, 1]. Default 0.97
    double max_intensity_ratio = 0.6;    ///< dark: its mean intensity is at most this share of its ring's (water
                                         ///< absorbs the near infrared), >= 0; 0 disables the dark path. Default 0.6
    double max_roughness_ratio = 0.6;    ///< smooth and sparse: ... or at most dark_density_ratio of it when its mean
                                         ///< max z − min z is at most this share of the median over all level cells
                                         ///< (calm water is smoother than grass, soil and asphalt with their
                                         ///< micro-relief), >= 0; 0 disables the smooth path. Default 0.6
    double max_lower_share = 0.1;        ///< lowest: at most this share of its ring lies more than level_tolerance_m
                                         ///< below the component's lowest cell within ring_cells of it (water fills
                                         ///< the lowest ground around it; roofs and lots on sloping ground have
                                         ///< lower ground next to them), in [0, 1].
                                         ///< Default 0.1
    double bright_density_ratio = 0.72;  ///< sparse and bright: at most this share of the ring's returns makes a
                                         ///< component sparse whatever its intensity (specular echoes near nadir
                                         ///< are brighter than a dark ring while the pulses around them are lost;
                                         ///< no flat land loses a quarter of its pulses), in [0, 1]; 0 disables.
                                         ///< Default 0.72
    double max_joint_ratio = 0.6;        ///< weak cues together: ... or at most dark_density_ratio of the ring's
                                         ///< returns when density ratio × intensity ratio × roughness ratio (as
                                         ///< above; roughness against the median of level cells) is at most this,
                                         ///< for a component of at least joint_min_cells (each cue a little
                                         ///< water-like; land fragments of a few dozen cells scatter too much to be
                                         ///< judged so), >= 0; 0 disables. Default 0.6
    std::size_t joint_min_cells = 150;   ///< see max_joint_ratio, cells. Default 150
    double max_surface_slope = 0.008;    ///< level: given a surface slope (water_surface_slope or its lazy form), a
                                         ///< component is a seed only when the median over its cells of the slope
                                         ///< of the plane fitted around them is at most this, and its cells where
                                         ///< the slope exceeds it are no seed cells, m/m (a water surface is level;
                                         ///< a river falls a few mm per metre; a beach rising 1-6 % has level 3 × 3
                                         ///< windows too, and joins the water's level cells); < 0 disables.
                                         ///< Default 0.008
    execution run = {};  ///< threads of the window filters and the labelling (same result for any count)
};

namespace detail {

inline void validate(const flat_water_seeds_options& o, const char* fn)
{
    require(o.level_radius_cells >= 1, fn, "level_radius_cells", ">= 1", o.level_radius_cells);
    require(o.level_tolerance_m >= 0, fn, "level_tolerance_m", ">= 0", o.level_tolerance_m);
    require(o.max_roughness_m >= 0, fn, "max_roughness_m", ">= 0", o.max_roughness_m);
    require(o.min_cells >= 1, fn, "min_cells", ">= 1", o.min_cells);
    require(o.ring_cells >= 1, fn, "ring_cells", ">= 1", o.ring_cells);
    require(o.max_density_ratio > 0 && o.max_density_ratio <= 1, fn, "max_density_ratio", "in (0, 1]",
            o.max_density_ratio);
    require(o.dark_density_ratio > 0 && o.dark_density_ratio <= 1, fn, "dark_density_ratio", "in (0, 1]",
            o.dark_density_ratio);
    require(o.max_intensity_ratio >= 0, fn, "max_intensity_ratio", ">= 0", o.max_intensity_ratio);
    require(o.max_roughness_ratio >= 0, fn, "max_roughness_ratio", ">= 0", o.max_roughness_ratio);
    require(o.max_lower_share >= 0 && o.max_lower_share <= 1, fn, "max_lower_share", "in [0, 1]", o.max_lower_share);
    require(o.bright_density_ratio >= 0 && o.bright_density_ratio <= 1, fn, "bright_density_ratio", "in [0, 1]",
            o.bright_density_ratio);
    require(o.max_joint_ratio >= 0, fn, "max_joint_ratio", ">= 0", o.max_joint_ratio);
    check_execution(o.run, fn);
}

/// One row of flat_water_seeds' level test: a return (no dropout, finite min z, inside the footprint), not
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

/// flat_water_seeds' level test for the window radii 1 and 2 (K), one output row per call, in two passes
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

/// One row of flat_water_seeds' ring test: a cell in no component (label 0) with a large one within reach
/// (highest label around it > 0) and a return (no dropout, finite min z, inside the footprint). Branch-free.
inline void ring_row(const std::int32_t* lab, const std::int32_t* highest, const std::uint8_t* drop, const float* z,
                     const std::uint8_t* inside, std::uint8_t* out, std::ptrdiff_t cols) noexcept
{
    for (std::ptrdiff_t c = 0; c < cols; ++c) {
        out[c] = static_cast<std::uint8_t>((lab[c] == 0) & (highest[c] != 0) & (drop[c] == 0) & std::isfinite(z[c]) &
                                           (inside[c] != 0));
    }
}

/// flat_water_seeds' slope test of the components: keep[l] = 0 for each kept component l (labels > 0 of
/// `labels`, sizes[l] cells) whose median surface slope over its cells (NaN counted as 0, level) exceeds
/// max_slope (m/m). Only the kept components' slopes are gathered (into one buffer, each in row order).
/// O(cells + kept cells).
inline void drop_sloping(raster_view<const std::int32_t> labels, const surface_slope_source& slope,
                         const std::vector<std::size_t>& sizes, double max_slope, std::vector<std::uint8_t>& keep)
{
    const std::ptrdiff_t rows = labels.rows(), cols = labels.cols();
    std::vector<std::size_t> offset(keep.size() + 1, 0);  // the slopes of label l: [offset[l], offset[l + 1])
    for (std::size_t l = 1; l < keep.size(); ++l) offset[l + 1] = offset[l] + (keep[l] ? sizes[l] : 0);
    if (offset.back() == 0) return;
    std::vector<float> all(offset.back());
    std::vector<std::size_t> next(offset.begin(), offset.end() - 1);
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for_each_run(labels.row(r), cols, [&](std::int32_t l, std::ptrdiff_t from, std::ptrdiff_t to) {
            if (!keep[static_cast<std::size_t>(l)]) return;
            float* out = all.data() + next[static_cast<std::size_t>(l)];
            for (std::ptrdiff_t i = from; i < to; ++i) {
                const float s = slope(r, i);
                *out++ = std::isnan(s) ? 0.0f : s;
            }
            next[static_cast<std::size_t>(l)] += static_cast<std::size_t>(to - from);
        });
    }
    for (std::size_t l = 1; l < keep.size(); ++l) {
        if (offset[l + 1] == offset[l]) continue;
        if (median(std::span<float>(all).subspan(offset[l], offset[l + 1] - offset[l])) > max_slope) keep[l] = 0;
    }
}

}  // namespace detail

/// Seed mask of waterbodies that need no dropouts: seed = components (8-connected, >= min_cells) of the
/// level cells {return, not excluded, max z − min z <= max_roughness_m, max − min of min z over the
/// (2 level_radius_cells + 1)² window <= level_tolerance_m} that are sparse (mean count <=
/// max_density_ratio · their ring's and not brighter, or <= bright_density_ratio · whatever the intensity),
/// or, on >= joint_min_cells, <= dark_density_ratio · with count ratio × intensity ratio × roughness ratio
/// <= max_joint_ratio, or dark and sparse (<= dark_density_ratio · and mean intensity <=
/// max_intensity_ratio · their ring's), or smooth and sparse (<= dark_density_ratio · and mean max z −
/// min z <= max_roughness_ratio · median over level cells) and lowest (<= max_lower_share of the ring more than
/// level_tolerance_m below the component's lowest min z within ring_cells of the ring cell); the ring:
/// cells with returns within ring_cells of the component, not in a component.
/// With `surface_slope` (optional, same shape: water_surface_slope of min z, m/m), a component whose median
/// slope exceeds max_surface_slope is no seed, nor is any cell where the slope exceeds it.
/// Needs in.count (without it the mask is empty). `excluded` (optional, same shape; nonzero = never a
/// seed, e.g. vegetation) and in.footprint keep cells out. Returns 1 = seed cell.
/// The windows are running min/max filters (min_max_filter's strips; the level window of radius 1 or 2 is
/// read in place, level_window_row): O(cells · log(level_radius_cells · ring_cells)), plus (2 ring_cells +
/// 1)² per ring cell within reach of two components or more.
/// The level cells' component labels are written into `labels` (given another shape, it is replaced by one
/// of min z's shape; its contents afterwards are unspecified): a caller that labels again reuses the memory
/// (a new raster's pages cost their first touch).
/// `taken` (optional, same shape; > 0 = a cell of a body grown before) clears those cells from the mask and
/// changes nothing else: they still count as level cells in the components, the rings and the slope
/// medians. A component entirely taken is not tested at all (its slope is not read). `taken` must not show
/// the cells of `labels` (they are overwritten before it is read).
/// @throws invalid_input on rasters of different shapes or options out of range.
inline raster<std::uint8_t> flat_water_seeds(const water_rasters& in, raster_view<const std::uint8_t> excluded,
                                             const flat_water_seeds_options& opt, surface_slope_source surface_slope,
                                             raster<std::int32_t>& labels, raster_view<const std::int32_t> taken = {})
{
    constexpr const char* fn = "flat_water_seeds";
    detail::validate(in, fn);
    detail::validate(opt, fn);
    if (!excluded.empty()) detail::require_same_shape(in.min_z, excluded, fn, "min_z", "excluded");
    if (!surface_slope.empty()) detail::require_same_shape(in.min_z, surface_slope, fn, "min_z", "surface_slope");
    if (!taken.empty()) detail::require_same_shape(in.min_z, taken, fn, "min_z", "taken");
    const std::ptrdiff_t rows = in.min_z.rows(), cols = in.min_z.cols();
    if (in.count.empty()) return raster<std::uint8_t>(rows, cols, 0);
    const std::vector<std::uint8_t> ones(static_cast<std::size_t>(cols), 1);  // the footprint when none is given
    constexpr float none = std::numeric_limits<float>::quiet_NaN();
    // Level cells: smooth, not excluded, and the lowest returns of the window around them within the tolerance.
    // The window's lowest and highest finite min z: read in place for radii 1 and 2 (level_window_row), else
    // from running min/max filters over strips of rows.
    raster<std::uint8_t> level(rows, cols, uninitialized);
    {
        const std::ptrdiff_t kx = std::min<std::ptrdiff_t>(opt.level_radius_cells, cols - 1);
        const std::ptrdiff_t ky = std::min<std::ptrdiff_t>(opt.level_radius_cells, rows - 1);
        const std::vector<std::uint8_t> zeros(static_cast<std::size_t>(cols), 0);
        const float max_rough = detail::float_at_most(opt.max_roughness_m);
        const float tolerance = detail::float_at_most(opt.level_tolerance_m);
        if (opt.level_radius_cells <= 2) {
            // Small windows row by row, in place (level_window_row); rows outside the raster read as NaN.
            const int k = opt.level_radius_cells;
            const std::vector<float> nan_row(static_cast<std::size_t>(cols), none);
            parallel_for_rows(
                rows, 256, opt.run.threads,
                [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
                    std::vector<float> low(static_cast<std::size_t>(cols + 2 * k)), high(low.size());
                    const float* window[5];
                    for (std::ptrdiff_t r = r0; r < r1; ++r) {
                        for (std::ptrdiff_t d = -k; d <= k; ++d)
                            window[d + k] = r + d >= 0 && r + d < rows ? in.min_z.row(r + d) : nan_row.data();
                        const auto test = k == 1 ? detail::level_window_row<1> : detail::level_window_row<2>;
                        test(window, low.data(), high.data(), in.min_z.row(r), in.max_z.row(r), in.dropout.row(r),
                             in.footprint.empty() ? ones.data() : in.footprint.row(r),
                             excluded.empty() ? zeros.data() : excluded.row(r), level.row(r), cols, max_rough,
                             tolerance);
                    }
                },
                {}, fn);
        } else {
            struct scratch {
                detail::min_max_scratch<float> s;
                std::vector<float> lows, highs;
            };
            detail::for_each_strip<scratch>(
                rows, detail::min_max_strip_rows(rows, cols, ky), opt.run.threads,
                [&](std::ptrdiff_t r0, std::ptrdiff_t r1, scratch& w) {
                    const std::ptrdiff_t nc = cols;
                    w.lows.resize(static_cast<std::size_t>((r1 - r0) * nc));
                    w.highs.resize(w.lows.size());
                    const auto load = [&](std::ptrdiff_t r, float* dst) {
                        const float* z = in.min_z.row(r);
                        for (std::ptrdiff_t c = 0; c < nc; ++c) dst[c] = std::isfinite(z[c]) ? z[c] : none;
                    };
                    detail::min_max_rows<detail::min_reduce<float>>(rows, nc, kx, ky, r0, r1, load, w.lows.data(), w.s);
                    detail::min_max_rows<detail::max_reduce<float>>(rows, nc, kx, ky, r0, r1, load, w.highs.data(),
                                                                    w.s);
                    for (std::ptrdiff_t r = r0; r < r1; ++r) {
                        detail::level_row(in.min_z.row(r), in.max_z.row(r), w.lows.data() + (r - r0) * nc,
                                          w.highs.data() + (r - r0) * nc, in.dropout.row(r),
                                          in.footprint.empty() ? ones.data() : in.footprint.row(r),
                                          excluded.empty() ? zeros.data() : excluded.row(r), level.row(r), nc,
                                          max_rough, tolerance);
                    }
                },
                {}, fn);
        }
    }
    detail::ensure_shape(labels, rows, cols);
    const auto level_sizes = connected_components(
        level, labels, connected_components_options{.conn = connectivity::eight, .run = {.threads = opt.run.threads}});
    const std::size_t n = level_sizes.size() - 1;
    if (n == 0) return level;  // all 0
    // From here on a label > 0 is a component large enough to be a seed, renumbered 1..nb in the order of
    // the labels (so the smallest and largest label within reach stay those components), and -1 marks the
    // cells of the smaller ones (level cells all the same): later passes test the sign, not a table.
    std::vector<std::int32_t> big(n + 1, 0);  // the new label of a large component, 0 for a small one
    std::vector<std::size_t> sizes(1, 0);     // cells per new label
    std::size_t level_cells = 0;
    for (std::size_t l = 1; l <= n; ++l) {
        if (level_sizes[l] >= opt.min_cells) {
            big[l] = static_cast<std::int32_t>(sizes.size());
            sizes.push_back(level_sizes[l]);
        }
        level_cells += level_sizes[l];
    }
    const std::size_t nb = sizes.size() - 1;
    // Per component: its count, intensity and roughness (summed in row order), needed only for those with a
    // cell not taken (the others are no seed); max z − min z of every level cell: the survey's typical
    // roughness. First the renumbering, the roughness of every level cell, the free cells and the rows of
    // each component; then the sums of the components with free cells, over their rows.
    std::vector<double> count_sum(nb + 1, 0), ring_count(nb + 1, 0), ring_cells(nb + 1, 0), light(nb + 1, 0),
        ring_light(nb + 1, 0), rough(nb + 1, 0), lower(nb + 1, 0);
    std::vector<float> level_rough(level_cells);
    std::vector<std::size_t> free_cells(nb + 1, 0);  // cells not taken
    const std::vector<std::int32_t> none_taken(static_cast<std::size_t>(cols), 0);
    const auto taken_row = [&](std::ptrdiff_t r) { return taken.empty() ? none_taken.data() : taken.row(r); };
    std::vector<std::ptrdiff_t> first_row(nb + 1, rows), last_row(nb + 1, -1);
    {
        float* rough_out = level_rough.data();
        for (std::ptrdiff_t r = 0; r < rows; ++r) {
            std::int32_t* lab = labels.row(r);
            const float* z0 = in.min_z.row(r);
            const float* z1 = in.max_z.row(r);
            const std::int32_t* body = taken_row(r);
            detail::for_each_run(lab, cols, [&](std::int32_t l, std::ptrdiff_t from, std::ptrdiff_t end) {
                const std::int32_t to = big[static_cast<std::size_t>(l)];
                if (to == 0) {
                    for (std::ptrdiff_t c = from; c < end; ++c) {
                        *rough_out++ = z1[c] - z0[c];
                        lab[c] = -1;
                    }
                    return;
                }
                std::size_t free = 0;
                for (std::ptrdiff_t c = from; c < end; ++c) {
                    *rough_out++ = z1[c] - z0[c];
                    free += body[c] <= 0;
                    lab[c] = to;
                }
                const auto m = static_cast<std::size_t>(to);
                free_cells[m] += free;
                first_row[m] = std::min(first_row[m], r);
                last_row[m] = r;
            });
        }
    }
    std::ptrdiff_t free_first = rows, free_last = -1;  // the rows of the components with free cells
    for (std::size_t m = 1; m <= nb; ++m) {
        if (free_cells[m] == 0) continue;
        free_first = std::min(free_first, first_row[m]);
        free_last = std::max(free_last, last_row[m]);
    }
    for (std::ptrdiff_t r = free_first; r <= free_last; ++r) {
        const std::int32_t* lab = labels.row(r);
        const float* z0 = in.min_z.row(r);
        const float* z1 = in.max_z.row(r);
        const std::uint32_t* pulses = in.count.row(r);
        const float* intensity = in.mean_intensity.row(r);
        // Along a run of one label the sums stay in registers (the same additions in the same order as cell
        // by cell, and as one pass over the raster in row order).
        detail::for_each_run(lab, cols, [&](std::int32_t l, std::ptrdiff_t from, std::ptrdiff_t end) {
            const auto m = static_cast<std::size_t>(l);
            if (free_cells[m] == 0) return;
            double pulse_sum = count_sum[m], light_sum = light[m], rough_sum = rough[m];
            for (std::ptrdiff_t c = from; c < end; ++c) {
                pulse_sum += pulses[c];
                light_sum += intensity[c];
                rough_sum += z1[c] - z0[c];
            }
            count_sum[m] = pulse_sum;
            light[m] = light_sum;
            rough[m] = rough_sum;
        });
    }
    // The ring: cells with returns, in no component, within ring_cells of a large one. Per strip of rows, running
    // filters over the labels of large components give the smallest and largest label within reach and the lowest min z
    // of their cells; where both labels agree that is the one component in reach, else the window is read cell by cell.
    // Both labels come from one running maximum over rows of twice the width, [label | ring_cells zeros | K_max + 1 −
    // label] (0 where no large component; the zeros keep the halves apart), in 16 bits while the labels fit (twice the
    // lanes of 32 bits). Strips list their ring cells; the sums below read the lists in row order (as one pass over the
    // raster would), whatever the thread count.
    struct ring_cell {
        std::ptrdiff_t r, c;
        std::int32_t label;
        float z;  // lowest min z of the component's cells within ring_cells
    };
    const std::ptrdiff_t q = opt.ring_cells;
    const std::ptrdiff_t qx = std::min<std::ptrdiff_t>(q, cols - 1), qy = std::min<std::ptrdiff_t>(q, rows - 1);
    const std::ptrdiff_t strip = detail::min_max_strip_rows(rows, cols, qy);
    std::vector<std::vector<ring_cell>> found(static_cast<std::size_t>((rows + strip - 1) / strip));
    struct scratch {
        detail::min_max_scratch<std::uint16_t> s16;
        detail::min_max_scratch<std::uint32_t> s32;
        detail::min_max_scratch<float> sf;
        std::vector<std::uint16_t> within16;
        std::vector<std::uint32_t> within32;
        std::vector<std::int32_t> lowest, highest;
        std::vector<float> z_low;
        std::vector<ring_cell> near;
        std::vector<std::uint8_t> candidate;
    };
    detail::for_each_strip<scratch>(
        rows, strip, opt.run.threads,
        [&](std::ptrdiff_t r0, std::ptrdiff_t r1, scratch& w) {
            const std::ptrdiff_t nc = cols;
            // Only rings of components with a cell not taken matter (the others are no seed whatever their ring).
            bool any = false;
            for (std::ptrdiff_t r = std::max<std::ptrdiff_t>(0, r0 - qy); r < std::min(rows, r1 + qy) && !any; ++r) {
                detail::for_each_run(labels.row(r), nc, [&](std::int32_t l, std::ptrdiff_t, std::ptrdiff_t) {
                    any = any || free_cells[static_cast<std::size_t>(l)] > 0;
                });
            }
            if (!any) return;
            const auto cells = static_cast<std::size_t>((r1 - r0) * nc);
            w.lowest.resize(cells);
            w.highest.resize(cells);
            w.z_low.resize(cells);
            const std::ptrdiff_t wide = 2 * nc + qx;  // [label | qx zeros | K_max + 1 - label]
            // K_max + 1 − label as K{0} − label, modulo 2^bits.
            const auto label_range = [&]<class K>(std::vector<K>& within, detail::min_max_scratch<K>& s) {
                const auto load = [&](std::ptrdiff_t r, K* dst) {
                    const std::int32_t* lab = labels.row(r);
                    K* mirrored = dst + nc + qx;
                    for (std::ptrdiff_t c = 0; c < nc; ++c) {
                        const K key = static_cast<K>(lab[c] > 0 ? lab[c] : 0);
                        dst[c] = key;
                        mirrored[c] = static_cast<K>(K{0} - key);  // 0 stays 0
                    }
                    std::fill(dst + nc, mirrored, K{0});
                };
                within.resize(static_cast<std::size_t>((r1 - r0) * wide));
                detail::min_max_rows<detail::max_reduce<K>>(rows, wide, qx, qy, r0, r1, load, within.data(), s);
                for (std::ptrdiff_t i = 0; i < r1 - r0; ++i) {
                    const K* high = within.data() + i * wide;
                    const K* mirrored = high + nc + qx;
                    std::int32_t* lowest = w.lowest.data() + i * nc;
                    std::int32_t* highest = w.highest.data() + i * nc;
                    for (std::ptrdiff_t c = 0; c < nc; ++c) {
                        highest[c] = static_cast<std::int32_t>(high[c]);
                        lowest[c] = static_cast<std::int32_t>(static_cast<K>(K{0} - mirrored[c]));  // 0 when none
                    }
                }
            };
            if (nb < std::numeric_limits<std::uint16_t>::max())
                label_range(w.within16, w.s16);
            else
                label_range(w.within32, w.s32);
            const auto load_z = [&](std::ptrdiff_t r, float* dst) {
                const std::int32_t* lab = labels.row(r);
                const float* z = in.min_z.row(r);
                for (std::ptrdiff_t c = 0; c < nc; ++c) dst[c] = lab[c] > 0 ? z[c] : none;
            };
            detail::min_max_rows<detail::min_reduce<float>>(rows, nc, qx, qy, r0, r1, load_z, w.z_low.data(), w.sf);
            auto& list = found[static_cast<std::size_t>(r0 / strip)];
            auto& near = w.near;
            w.candidate.resize(static_cast<std::size_t>(nc));
            std::uint8_t* candidate = w.candidate.data();
            for (std::ptrdiff_t r = r0; r < r1; ++r) {
                const std::int32_t* lab = labels.row(r);
                const std::int32_t* lowest = w.lowest.data() + (r - r0) * nc;
                const std::int32_t* highest = w.highest.data() + (r - r0) * nc;
                const float* z_low = w.z_low.data() + (r - r0) * nc;
                // Ring cells of this row: in no component, a large one within reach, a return.
                detail::ring_row(lab, highest, in.dropout.row(r), in.min_z.row(r),
                                 in.footprint.empty() ? ones.data() : in.footprint.row(r), candidate, nc);
                for (std::ptrdiff_t c = detail::next_positive(candidate, 0, nc); c < nc;
                     c = detail::next_positive(candidate, c + 1, nc)) {
                    if (lowest[c] == highest[c]) {
                        list.push_back({r, c, highest[c], z_low[c]});
                        continue;
                    }
                    near.clear();  // two components or more within reach: each with its own lowest min z
                    for (std::ptrdiff_t rr = std::max<std::ptrdiff_t>(0, r - q); rr <= std::min(rows - 1, r + q);
                         ++rr) {
                        const std::int32_t* row = labels.row(rr);
                        for (std::ptrdiff_t cc = std::max<std::ptrdiff_t>(0, c - q); cc <= std::min(nc - 1, c + q);
                             ++cc) {
                            if (row[cc] <= 0) continue;
                            const auto it = std::find_if(near.begin(), near.end(),
                                                         [&](const ring_cell& e) { return e.label == row[cc]; });
                            if (it == near.end())
                                near.push_back({r, c, row[cc], in.min_z(rr, cc)});
                            else
                                it->z = std::min(it->z, in.min_z(rr, cc));
                        }
                    }
                    list.insert(list.end(), near.begin(), near.end());
                }
            }
        },
        {}, fn);
    for (const auto& list : found) {
        for (const auto& e : list) {
            const auto m = static_cast<std::size_t>(e.label);
            ring_count[m] += in.count(e.r, e.c);
            ring_cells[m] += 1;
            ring_light[m] += in.mean_intensity(e.r, e.c);
            lower[m] += in.min_z(e.r, e.c) < e.z - opt.level_tolerance_m;
        }
    }
    // A component is a seed when sparse, or a few % sparser and dark, smooth or all three cues together
    // (the roughness, against the median over all level cells, is found when first needed), and lowest.
    std::vector<std::uint8_t> keep(nb + 1, 0);
    double typical_rough = NAN;
    bool typical_known = false;
    for (std::size_t l = 1; l <= nb; ++l) {
        // A component all taken leaves no seed cell. (Every renumbered component has >= min_cells cells.)
        if (free_cells[l] == 0 || ring_cells[l] == 0) continue;
        const double size = static_cast<double>(sizes[l]);
        const double density = count_sum[l] / size / (ring_count[l] / ring_cells[l]);
        const double intensity = light[l] / size / (ring_light[l] / ring_cells[l]);
        // Sparse counts only when not brighter than the ring: a bright (specular) echo is one that arrived.
        const bool sparse = (density <= opt.max_density_ratio && intensity <= 1) || density <= opt.bright_density_ratio;
        const bool dark = intensity <= opt.max_intensity_ratio;
        if (!sparse) {
            if (!(density <= opt.dark_density_ratio)) continue;
            if (!dark) {
                if (!typical_known) {
                    typical_rough = detail::median(level_rough);
                    typical_known = true;
                }
                // On perfectly smooth data (typical 0) a smooth component is 0, not 0 / 0.
                const double mean_rough = rough[l] / size;
                const double roughness = mean_rough <= 0 ? 0.0 : mean_rough / typical_rough;
                const bool smooth = roughness <= opt.max_roughness_ratio;
                const bool joint =
                    sizes[l] >= opt.joint_min_cells && density * intensity * roughness <= opt.max_joint_ratio;
                if (!smooth && !joint) continue;
            }
        }
        if (!(lower[l] <= opt.max_lower_share * ring_cells[l])) continue;
        keep[l] = 1;
    }
    // With a surface slope: a component kept so far whose median slope around its cells (NaN, unknown, as
    // level) exceeds max_surface_slope is no seed (only kept ones are read: most components are land).
    const bool slope_test = !surface_slope.empty() && opt.max_surface_slope >= 0;
    if (slope_test) detail::drop_sloping(labels, surface_slope, sizes, opt.max_surface_slope, keep);
    // The seed mask takes the level mask's place (connected_components has read it), run by run of one label;
    // with the slope test, no seed cell where the surface around it slopes (a beach joined to the water); no
    // taken cell (its slope is not read).
    const float max_slope = slope_test ? detail::float_at_most(opt.max_surface_slope) : 0.0f;  // x > it: x > max
    const std::ptrdiff_t nc = cols;
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        const std::int32_t* lab = labels.row(r);
        const std::int32_t* body = taken_row(r);
        std::uint8_t* d = level.row(r);
        std::fill(d, d + nc, std::uint8_t{0});
        detail::for_each_run(lab, nc, [&](std::int32_t l, std::ptrdiff_t from, std::ptrdiff_t to) {
            if (!keep[static_cast<std::size_t>(l)]) return;
            if (!slope_test)
                for (std::ptrdiff_t i = from; i < to; ++i) d[i] = static_cast<std::uint8_t>(body[i] <= 0);
            else
                for (std::ptrdiff_t i = from; i < to; ++i)
                    d[i] = static_cast<std::uint8_t>(body[i] <= 0 && !(surface_slope(r, i) > max_slope));
        });
    }
    return level;
}

/// flat_water_seeds (see above) with its component labels in a raster of its own.
inline raster<std::uint8_t> flat_water_seeds(const water_rasters& in, raster_view<const std::uint8_t> excluded = {},
                                             const flat_water_seeds_options& opt = {},
                                             surface_slope_source surface_slope = {})
{
    raster<std::int32_t> labels;
    return flat_water_seeds(in, excluded, opt, surface_slope, labels);
}

}  // namespace lidarfx
