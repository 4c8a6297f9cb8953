// SPDX-License-Identifier: Apache-2.0
// intensity_bins: intensities as ranks of their distinct rounded values, the samples of the KS stop.
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
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// Options of intensity_bins.
struct intensity_bins_options {
    double resolution = 1.0;  ///< intensity quantum: values are rounded to multiples of it (nearest, ties to
                              ///< even), in intensity units; finite, > 0. Default 1 (LAS integer intensities).
};

/// Intensity bins of a survey, the form grow_waterbody reads (water_field::intensity_bin and bins).
struct intensity_bins_result {
    raster<std::int32_t> bin;  ///< rank of the cell's rounded intensity among the distinct values, 0-based;
                               ///< -1 for dropouts and non-finite intensities
    int bins = 1;              ///< number of distinct rounded values (ranks 0 .. bins - 1), >= 1
};

namespace detail {

inline void validate(const intensity_bins_options& o, const char* fn)
{
    require_positive(o.resolution, fn, "resolution");
}

}  // namespace detail

/// Rounds the mean intensity of every cell with returns to q = nearbyint(intensity / resolution) and
/// replaces q by its rank among the distinct q of the raster, so that a KS histogram has one bin per
/// distinct value: the one-sided KS statistic depends only on the order of the values, so ranks give the
/// same test as the values. Cells with dropout != 0 or a non-finite intensity get -1.
/// O(cells + range of q) when that range is below 2^24 (LAS intensities), else O(cells log cells). The passes over
/// the cells run on blocks of rows on `run.threads` threads (the same ranks for every thread count).
/// @throws invalid_input if the shapes differ, resolution is not finite and > 0, or run.threads < 0.
inline intensity_bins_result intensity_bins(raster_view<const float> mean_intensity,
                                            raster_view<const std::uint8_t> dropout,
                                            const intensity_bins_options& opt = {}, const execution& run = {})
{
    constexpr const char* fn = "intensity_bins";
    detail::require_same_shape(mean_intensity, dropout, fn, "mean_intensity", "dropout");
    detail::validate(opt, fn);
    detail::check_execution(run, fn);
    const std::ptrdiff_t rows = mean_intensity.rows(), cols = mean_intensity.cols();
    constexpr std::int32_t none = std::numeric_limits<std::int32_t>::min();
    intensity_bins_result result{raster<std::int32_t>(rows, cols, uninitialized), 1};  // pass 1 writes every cell
    raster<std::int32_t>& out = result.bin;
    // Pass 1, in integer masks rather than selects so that GCC vectorizes it (FP compares and selects
    // feeding the min / max reductions keep it scalar): rounded values as integers, clamped to
    // +-(1e9 + 1) (a clamped value shows as lo < -1e9 or hi > 1e9 below), none = no sample; lo, hi over
    // the samples.
    constexpr double limit = 1.0e9 + 1.0;
    constexpr std::int32_t most = std::numeric_limits<std::int32_t>::max();
    // Presence is marked while the row is in L1, in a table over the window [0, window) of values (LAS
    // intensities at resolution 1); values outside it, and none, land in the extra slot seen[window]. Stores
    // are what costs here (a byte store per cell, or an AVX-512 scatter, takes ~3 cycles a cell on Zen 4;
    // loads ~0.3), and the values of a survey repeat: each row is first checked against the table with loads
    // only, and only a row holding a value not yet seen is marked. When all samples fall in the
    // window (lo >= 0, hi < window), no presence pass over the raster follows.
    constexpr std::uint32_t window = std::uint32_t{1} << 16;
    const auto slot = [](std::int32_t v) {
        const auto u = static_cast<std::uint32_t>(v);
        return u < window ? u : window;
    };
    const double inverse = 1.0 / opt.resolution;
    const std::ptrdiff_t width = cols;
    // At most 16 blocks of rows, each with its own presence table, merged after.
    const std::ptrdiff_t block_rows = std::max<std::ptrdiff_t>(64, (rows + 15) / 16);
    const auto blocks = static_cast<std::size_t>(std::max<std::ptrdiff_t>(1, (rows + block_rows - 1) / block_rows));
    std::vector<std::int32_t> block_lo(blocks, most), block_hi(blocks, none);
    std::vector<std::vector<std::uint32_t>> block_seen(blocks);
    parallel_for_rows(rows, block_rows, run.threads, [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
        const auto b = static_cast<std::size_t>(r0 / block_rows);
        block_seen[b].assign(std::size_t{window} + 1, 0);
        std::uint32_t* mark = block_seen[b].data();
        // Captured values in locals: read through the closure, they would be reloaded after every store.
        const double scale = inverse;
        const std::ptrdiff_t n_cols = width;
        std::int32_t lo = most, hi = none;
        for (std::ptrdiff_t r = r0; r < r1; ++r) {
            std::int32_t* o = out.row(r);
            const std::uint8_t* d = dropout.row(r);
            const float* mean = mean_intensity.row(r);
            for (std::ptrdiff_t c = 0; c < n_cols; ++c) {
                const auto bits = std::bit_cast<std::int32_t>(mean[c]);
                const bool finite = (bits & 0x7f800000) != 0x7f800000;
                const std::int32_t sample = -static_cast<std::int32_t>(finite & (d[c] == 0));  // all ones or 0
                double x = static_cast<double>(std::bit_cast<float>(bits & sample)) * scale;   // 0 without sample
                x = x < -limit ? -limit : x;  // clamping before rounding gives the same integer as after
                x = x > limit ? limit : x;
                const auto q =
                    static_cast<std::int32_t>(std::rint(x));  // rint, not nearbyint: GCC inlines and vectorizes it
                o[c] = (q & sample) | (none & ~sample);
                lo = std::min(lo, (q & sample) | (most & ~sample));
                hi = std::max(hi, (q & sample) | (none & ~sample));
            }
            std::uint32_t missing = 0;
            for (std::ptrdiff_t c = 0; c < n_cols; ++c) missing |= mark[slot(o[c])] ^ 1u;
            if (missing) {
                for (std::ptrdiff_t c = 0; c < n_cols; ++c) mark[slot(o[c])] = 1;
            }
        }
        block_lo[b] = lo;
        block_hi[b] = hi;
    });
    const std::int32_t lo = *std::min_element(block_lo.begin(), block_lo.end());
    const std::int32_t hi = *std::max_element(block_hi.begin(), block_hi.end());
    std::vector<std::uint32_t> seen = std::move(block_seen[0]);
    seen.resize(std::size_t{window} + 1, 0);  // rows = 0: no block ran
    for (std::size_t b = 1; b < blocks; ++b)
        for (std::size_t v = 0; v <= window; ++v) seen[v] |= block_seen[b][v];
    if (hi == none) {
        out.fill(-1);
        return result;
    }
    std::int32_t* cell = out.data();
    const std::ptrdiff_t n = out.size();
    if (std::int64_t{hi} - lo < (std::int64_t{1} << 24) && lo >= -1'000'000'000 && hi <= 1'000'000'000) {
        // Ranks from a presence table over the range of values. Offsets are unsigned 32-bit differences
        // capped at span: none wraps to a huge offset and lands in the extra slot rank[span], which holds
        // -1 in the end; no branch, so the marking scatters in vectors (a value met twice in one vector only
        // stores 1 twice) and pass 2 gathers in vectors.
        const auto base = static_cast<std::uint32_t>(lo);
        const auto span = static_cast<std::uint32_t>(hi - lo) + 1;
        const auto offset = [&](std::int32_t v) {
            return static_cast<std::int32_t>(std::min(static_cast<std::uint32_t>(v) - base, span));
        };
        std::vector<std::int32_t> rank(std::size_t{span} + 1, 0);
        if (lo >= 0 && static_cast<std::uint32_t>(hi) < window) {  // presence known from pass 1
            std::copy_n(seen.begin() + base, span, rank.begin());
        } else {
            std::int32_t* present = rank.data();  // through a pointer, as pass 2 reads it: the loop vectorizes
            LIDARFX_IVDEP
            for (std::ptrdiff_t i = 0; i < n; ++i) present[offset(cell[i])] = 1;
        }
        rank[span] = 0;
        std::int32_t next = 0;
        for (auto& k : rank) k = k ? next++ : -1;
        result.bins = std::max(1, static_cast<int>(next));
        const std::int32_t* ranks = rank.data();
        parallel_for_rows(rows, block_rows, run.threads, [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
            std::int32_t* row = out.row(r0);  // contiguous: rows r0 .. r1 - 1 follow one another
            LIDARFX_IVDEP
            for (std::ptrdiff_t i = 0, m = (r1 - r0) * cols; i < m; ++i) row[i] = ranks[offset(row[i])];
        });
        return result;
    }
    // Wide ranges: ranks from the sorted distinct values, recomputed exactly.
    std::vector<double> distinct;
    const auto value = [&](std::ptrdiff_t i) {
        return std::nearbyint(static_cast<double>(mean_intensity(i / cols, i % cols)) * inverse);
    };
    for (std::ptrdiff_t i = 0; i < n; ++i)
        if (cell[i] != none) distinct.push_back(value(i));
    std::sort(distinct.begin(), distinct.end());
    distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
    result.bins = std::max(1, static_cast<int>(distinct.size()));
    for (std::ptrdiff_t i = 0; i < n; ++i)
        cell[i] = cell[i] == none
                      ? -1
                      : static_cast<std::int32_t>(std::lower_bound(distinct.begin(), distinct.end(), value(i)) -
                                                  distinct.begin());
    return result;
}

}  // namespace lidarfx
