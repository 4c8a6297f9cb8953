// SPDX-License-Identifier: Apache-2.0
// Implementation of pipelines/water/flat_seed_rings.hpp (included at its end; not meant to be included alone).
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/kernels/filter/min_max_filter.hpp"
#include "lidarfx/pipelines/water/flat_seed_components.hpp"
#include "lidarfx/pipelines/water/flat_water_seeds_options.hpp"
#include "lidarfx/pipelines/water/water_rasters.hpp"

namespace lidarfx {

namespace detail {

/// One row of the ring test: a cell in no component (label 0) with a large one within reach (highest label
/// around it > 0) and a return (no dropout, finite min z, inside the footprint). Branch-free.
inline void ring_row(const std::int32_t* lab, const std::int32_t* highest, const std::uint8_t* drop, const float* z,
                     const std::uint8_t* inside, std::uint8_t* out, std::ptrdiff_t cols) noexcept
{
    for (std::ptrdiff_t c = 0; c < cols; ++c) {
        out[c] = static_cast<std::uint8_t>((lab[c] == 0) & (highest[c] != 0) & (drop[c] == 0) & std::isfinite(z[c]) &
                                           (inside[c] != 0));
    }
}

/// A ring cell and one component within reach of it, with that component's lowest min z within reach.
struct ring_cell {
    std::ptrdiff_t r, c;
    std::int32_t label;
    float z;
};

/// What one strip of rows of measure_flat_seed_rings reads and writes; reused across the strips of a thread.
struct ring_strip_scratch {
    min_max_workspace<std::uint16_t> s16;
    min_max_workspace<std::uint32_t> s32;
    min_max_workspace<float> sf;
    std::vector<std::uint16_t> within16;
    std::vector<std::uint32_t> within32;
    std::vector<std::int32_t> lowest, highest;  // smallest and largest label within reach (0: none)
    std::vector<float> z_low;                   // lowest min z of component cells within reach
    std::vector<ring_cell> near;
    std::vector<std::uint8_t> candidate;
};

/// The geometry of measure_flat_seed_rings' windows: reach q, capped to the raster in each direction.
struct ring_reach {
    std::ptrdiff_t rows, cols, q, qx, qy;
};

/// True when a component with free cells lies within reach of rows [r0, r1) (only their rings matter).
inline bool strip_near_free_component(const flat_seed_components& comps, const ring_reach& g, std::ptrdiff_t r0,
                                      std::ptrdiff_t r1)
{
    bool any = false;
    for (std::ptrdiff_t r = std::max<std::ptrdiff_t>(0, r0 - g.qy); r < std::min(g.rows, r1 + g.qy) && !any; ++r) {
        for_each_run(comps.labels.view().row(r), g.cols, [&](std::int32_t l, std::ptrdiff_t, std::ptrdiff_t) {
            any = any || comps.free_cells[static_cast<std::size_t>(l)] > 0;
        });
    }
    return any;
}

/// Smallest and largest label of a component within reach of each cell of rows [r0, r1), into w.lowest and
/// w.highest (0 when none). Both from one running maximum over rows of twice the width, [label | qx zeros |
/// K_max + 1 − label] (0 where no large component; the zeros keep the halves apart), K_max + 1 − label
/// computed as K{0} − label modulo 2^bits; in K = 16 bits while the labels fit (twice the lanes of 32).
template <class K>
void ring_label_range(raster_view<const std::int32_t> labels, const ring_reach& g, std::ptrdiff_t r0, std::ptrdiff_t r1,
                      std::vector<K>& within, min_max_workspace<K>& s, ring_strip_scratch& w)
{
    const std::ptrdiff_t nc = g.cols, qx = g.qx;
    const std::ptrdiff_t wide = 2 * nc + qx;  // [label | qx zeros | K_max + 1 - label]
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
    max_filter_rows(g.rows, wide, qx, g.qy, r0, r1, load, within.data(), s);
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
}

/// The components within reach of ring cell (r, c) when more than one is, each with its own lowest min z
/// within reach, appended to `list` (in order of first appearance in the window).
inline void list_ring_cell_near_several(const water_rasters& in, raster_view<const std::int32_t> labels,
                                        const ring_reach& g, std::ptrdiff_t r, std::ptrdiff_t c,
                                        std::vector<ring_cell>& near, std::vector<ring_cell>& list)
{
    near.clear();
    for (std::ptrdiff_t rr = std::max<std::ptrdiff_t>(0, r - g.q); rr <= std::min(g.rows - 1, r + g.q); ++rr) {
        const std::int32_t* row = labels.row(rr);
        for (std::ptrdiff_t cc = std::max<std::ptrdiff_t>(0, c - g.q); cc <= std::min(g.cols - 1, c + g.q); ++cc) {
            if (row[cc] <= 0) continue;
            const auto it =
                std::find_if(near.begin(), near.end(), [&](const ring_cell& e) { return e.label == row[cc]; });
            if (it == near.end())
                near.push_back({r, c, row[cc], in.min_z(rr, cc)});
            else
                it->z = std::min(it->z, in.min_z(rr, cc));
        }
    }
    list.insert(list.end(), near.begin(), near.end());
}

/// The ring cells of rows [r0, r1), in row order, appended to `list`.
inline void list_ring_cells(const water_rasters& in, const flat_seed_components& comps, const ring_reach& g,
                            std::ptrdiff_t r0, std::ptrdiff_t r1, ring_strip_scratch& w, std::vector<ring_cell>& list)
{
    const std::ptrdiff_t nc = g.cols;
    const raster_view<const std::int32_t> labels = comps.labels.view();
    const auto cells = static_cast<std::size_t>((r1 - r0) * nc);
    w.lowest.resize(cells);
    w.highest.resize(cells);
    w.z_low.resize(cells);
    if (comps.count() < std::numeric_limits<std::uint16_t>::max())
        ring_label_range(labels, g, r0, r1, w.within16, w.s16, w);
    else
        ring_label_range(labels, g, r0, r1, w.within32, w.s32, w);
    const auto load_z = [&](std::ptrdiff_t r, float* dst) {
        const std::int32_t* lab = labels.row(r);
        const float* z = in.min_z.row(r);
        for (std::ptrdiff_t c = 0; c < nc; ++c) dst[c] = lab[c] > 0 ? z[c] : std::numeric_limits<float>::quiet_NaN();
    };
    min_filter_rows(g.rows, nc, g.qx, g.qy, r0, r1, load_z, w.z_low.data(), w.sf);
    const std::vector<std::uint8_t> ones(in.footprint.empty() ? static_cast<std::size_t>(nc) : 0, 1);
    w.candidate.resize(static_cast<std::size_t>(nc));
    std::uint8_t* candidate = w.candidate.data();
    for (std::ptrdiff_t r = r0; r < r1; ++r) {
        const std::int32_t* lowest = w.lowest.data() + (r - r0) * nc;
        const std::int32_t* highest = w.highest.data() + (r - r0) * nc;
        const float* z_low = w.z_low.data() + (r - r0) * nc;
        ring_row(labels.row(r), highest, in.dropout.row(r), in.min_z.row(r),
                 in.footprint.empty() ? ones.data() : in.footprint.row(r), candidate, nc);
        for (std::ptrdiff_t c = next_positive(candidate, 0, nc); c < nc; c = next_positive(candidate, c + 1, nc)) {
            if (lowest[c] == highest[c])
                list.push_back({r, c, highest[c], z_low[c]});
            else
                list_ring_cell_near_several(in, labels, g, r, c, w.near, list);
        }
    }
}

}  // namespace detail

inline flat_seed_rings measure_flat_seed_rings(const water_rasters& in, const flat_seed_components& comps,
                                               const flat_water_seeds_options& opt, const execution& run)
{
    constexpr const char* fn = "measure_flat_seed_rings";
    detail::validate(in, fn);
    detail::validate(opt, fn);
    detail::check_execution(run, fn);
    detail::require(!in.count.empty(), fn, "in.count is required (the densities of the rings need it)");
    detail::require_same_shape(in.min_z, comps.labels, fn, "min_z", "comps.labels");
    const std::ptrdiff_t rows = in.min_z.rows(), cols = in.min_z.cols();
    const std::ptrdiff_t q = opt.ring_cells;
    const detail::ring_reach g{rows, cols, q, std::min<std::ptrdiff_t>(q, cols - 1),
                               std::min<std::ptrdiff_t>(q, rows - 1)};
    // Strips list their ring cells; the sums below read the lists in row order (as one pass over the raster
    // would), whatever the thread count.
    const std::ptrdiff_t strip = min_max_strip_rows(rows, cols, g.qy);
    std::vector<std::vector<detail::ring_cell>> found(static_cast<std::size_t>((rows + strip - 1) / strip));
    for_each_row_strip<detail::ring_strip_scratch>(
        rows, strip, run.threads,
        [&](std::ptrdiff_t r0, std::ptrdiff_t r1, detail::ring_strip_scratch& w) {
            if (!detail::strip_near_free_component(comps, g, r0, r1)) return;
            detail::list_ring_cells(in, comps, g, r0, r1, w, found[static_cast<std::size_t>(r0 / strip)]);
        },
        {}, fn);
    const std::size_t nb = comps.count();
    flat_seed_rings rings{std::vector<double>(nb + 1, 0), std::vector<double>(nb + 1, 0),
                          std::vector<double>(nb + 1, 0), std::vector<double>(nb + 1, 0),
                          std::vector<double>(nb + 1, 0)};
    for (const auto& list : found) {
        for (const auto& e : list) {
            const auto m = static_cast<std::size_t>(e.label);
            rings.count_sum[m] += in.count(e.r, e.c);
            rings.cells[m] += 1;
            rings.intensity_sum[m] += in.mean_intensity(e.r, e.c);
            rings.lower[m] += in.min_z(e.r, e.c) < e.z - opt.level_tolerance_m;
            rings.raised[m] += in.min_z(e.r, e.c) > e.z + opt.level_tolerance_m;
        }
    }
    return rings;
}

namespace detail {

/// Whether component l is lowest: it has a ring, and at most opt.max_lower_share of it lies lower.
inline bool lowest(const flat_seed_rings& rings, std::size_t l, const flat_water_seeds_options& opt) noexcept
{
    return rings.cells[l] > 0 && rings.lower[l] <= opt.max_lower_share * rings.cells[l];
}

}  // namespace detail

namespace detail {

/// survey_land_intensity's histogram of the land cells of rows [r0, r1) added into `histogram` (1 << 15 bins, see
/// survey_land_intensity): columns c go to 4 interleaved sub-histograms by c mod 4, so that a run of cells of one
/// bin does not wait on its own increments (most land cells of a row share a few bins), summed at the end.
inline void land_intensity_histogram(const water_rasters& in, raster_view<const std::int32_t> labels,
                                     const std::vector<std::uint8_t>& land_of, std::ptrdiff_t r0, std::ptrdiff_t r1,
                                     std::vector<std::uint64_t>& histogram)
{
    constexpr std::size_t bins = std::size_t{1} << 15, ways = 4;
    const std::ptrdiff_t cols = in.min_z.cols();
    std::vector<std::uint32_t> part(ways * bins, 0);
    // A sub-histogram gains at most ceil(cols / 4) a row: flushed before it could pass 2^32 - 1.
    const auto per_row = static_cast<std::uint64_t>((cols + 3) / 4);
    const std::uint64_t rows_per_flush = std::max<std::uint64_t>(1, UINT32_MAX / std::max<std::uint64_t>(1, per_row));
    const std::vector<std::uint8_t> ones(in.footprint.empty() ? static_cast<std::size_t>(cols) : 0, 1);
    for (std::ptrdiff_t r = r0; r < r1; ++r) {
        const std::int32_t* lab = labels.row(r);
        const std::uint8_t* drop = in.dropout.row(r);
        const float* z = in.min_z.row(r);
        const float* v = in.mean_intensity.row(r);
        const std::uint8_t* inside = in.footprint.empty() ? ones.data() : in.footprint.row(r);
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const bool keep = land_of[static_cast<std::size_t>(lab[c] + 1)] & (drop[c] == 0) & (inside[c] != 0) &
                              std::isfinite(z[c]) & std::isfinite(v[c]);
            const float value = keep ? std::max(v[c], 0.0f) : 0.0f;
            part[static_cast<std::size_t>(c & 3) * bins + (std::bit_cast<std::uint32_t>(value) >> 16)] += keep;
        }
        if (static_cast<std::uint64_t>(r - r0 + 1) % rows_per_flush == 0 || r + 1 == r1) {
            for (std::size_t w = 0; w < ways; ++w)
                for (std::size_t b = 0; b < bins; ++b) histogram[b] += std::exchange(part[w * bins + b], 0u);
        }
    }
}

}  // namespace detail

inline double survey_land_intensity(const water_rasters& in, const flat_seed_components& comps,
                                    const flat_seed_rings& rings, const flat_water_seeds_options& opt,
                                    const execution& run)
{
    constexpr const char* fn = "survey_land_intensity";
    detail::validate(in, fn);
    detail::validate(opt, fn);
    detail::check_execution(run, fn);
    detail::require_same_shape(in.min_z, comps.labels, fn, "min_z", "comps.labels");
    const std::size_t nb = comps.count();
    detail::require(rings.cells.size() == nb + 1 && rings.lower.size() == nb + 1, fn,
                    "rings must hold comps.count() + 1 entries per measure");
    const double quantile = opt.land_intensity_quantile;
    if (quantile < 0) return NAN;
    // land_of[label + 1]: 1 when a cell of that label (-1, 0 or a component) is land.
    std::vector<std::uint8_t> land_of(nb + 2, 1);
    for (std::size_t l = 1; l <= nb; ++l) land_of[l + 1] = !detail::lowest(rings, l, opt);
    // One pass: a histogram over the high 16 bits of the intensity's float representation (sign, exponent and
    // 7 bits of mantissa), which orders non-negative floats (positive floats have the sign bit 0); negative
    // intensities count as 0. One band of rows per thread, each with its own counts, added up after.
    const std::ptrdiff_t rows = in.min_z.rows();
    const auto threads = static_cast<std::ptrdiff_t>(detail::resolve_threads(run.threads, fn));
    const std::ptrdiff_t band = std::max<std::ptrdiff_t>(1, (rows + threads - 1) / threads);
    std::vector<std::vector<std::uint64_t>> counts(static_cast<std::size_t>((rows + band - 1) / band));
    parallel_for_rows(
        rows, band, run.threads,
        [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
            auto& histogram = counts[static_cast<std::size_t>(r0 / band)];
            histogram.assign(std::size_t{1} << 15, 0);
            detail::land_intensity_histogram(in, comps.labels.view(), land_of, r0, r1, histogram);
        },
        {}, fn);
    std::vector<std::uint64_t> histogram(std::size_t{1} << 15, 0);
    for (const auto& part : counts)
        for (std::size_t b = 0; b < part.size(); ++b) histogram[b] += part[b];
    std::uint64_t n = 0;
    for (const std::uint64_t h : histogram) n += h;
    if (n == 0) return NAN;
    const double target = quantile * static_cast<double>(n);
    std::uint64_t seen = 0;
    for (std::size_t b = 0; b < histogram.size(); ++b) {
        seen += histogram[b];
        if (static_cast<double>(seen) >= target && seen > 0) {
            // The middle of the bin's values: its 16 high bits, then 1 and 15 zeros.
            return std::bit_cast<float>(static_cast<std::uint32_t>((b << 16) | 0x8000u));
        }
    }
    return NAN;  // not reached: seen reaches n
}

}  // namespace lidarfx
