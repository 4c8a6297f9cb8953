// SPDX-License-Identifier: Apache-2.0
// Implementation of kernels/filter/min_max_filter.hpp (included at its end; not meant to be included alone).
#pragma once

#include <algorithm>
#include <bit>
#include <cstddef>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// Buffers of min_max_rows, reused across the strips one thread runs (no allocation once grown).
template <class T>
class min_max_workspace {
public:
    std::vector<T> input, line, doubled, neutral_row, h, prefix, suffix;
};

namespace detail {

/// The two reductions: `neutral` is the value of cells outside the raster and of NaN cells, so padding
/// with it is exactly "ignored". For floating-point T the neutrals are ±infinity.
template <class T>
struct min_reduce {
    static constexpr T neutral =
        std::numeric_limits<T>::has_infinity ? std::numeric_limits<T>::infinity() : std::numeric_limits<T>::max();
    static constexpr T apply(T a, T b) noexcept { return b < a ? b : a; }
};
template <class T>
struct max_reduce {
    static constexpr T neutral =
        std::numeric_limits<T>::has_infinity ? -std::numeric_limits<T>::infinity() : std::numeric_limits<T>::lowest();
    static constexpr T apply(T a, T b) noexcept { return a < b ? b : a; }
};

/// Horizontal pass on one row: out[c] = Op over src[c - k .. c + k] clipped to [0, cols), NaN = neutral.
/// Doubling, as in morphology's rows: a_L(x) = Op over padded [x, x + L) for L = 1, 2, 4, ... up to the
/// largest power of two L <= 2k + 1, then out(c) = a_L(c) Op a_L(c + 2k + 1 - L): O(cols · log k), and
/// each step is a plain loop over the row that the compiler vectorizes.
template <class Op, class T>
void min_max_row(const T* src, T* out, std::ptrdiff_t cols, std::ptrdiff_t k, min_max_workspace<T>& s)
{
    const std::ptrdiff_t n = cols + 2 * k;
    s.line.resize(static_cast<std::size_t>(n));
    s.doubled.resize(static_cast<std::size_t>(n));
    T* a = s.line.data();
    T* b = s.doubled.data();
    std::fill(a, a + k, Op::neutral);
    for (std::ptrdiff_t c = 0; c < cols; ++c) {
        const T x = src[c];
        if constexpr (std::is_floating_point_v<T>)
            a[k + c] = x != x ? Op::neutral : x;
        else
            a[k + c] = x;
    }
    std::fill(a + k + cols, a + n, Op::neutral);
    if (k == 0) {
        std::copy(a, a + cols, out);
        return;
    }
    const auto top = static_cast<std::ptrdiff_t>(std::bit_floor(static_cast<std::size_t>(2 * k + 1)));
    std::ptrdiff_t valid = n;  // a[x] = Op over [x, x + len) for x < valid
    for (std::ptrdiff_t len = 1; len < top; len *= 2) {
        valid -= len;
        for (std::ptrdiff_t x = 0; x < valid; ++x) b[x] = Op::apply(a[x], a[x + len]);
        std::swap(a, b);
    }
    const std::ptrdiff_t shift = 2 * k + 1 - top;
    for (std::ptrdiff_t c = 0; c < cols; ++c) out[c] = Op::apply(a[c], a[c + shift]);
}

/// Computes output rows [r0, r1) of one reduction (Op) over a rows x cols raster whose row r the call
/// load(r, T* dst) writes (cols values; NaN = no data). Rows of `h` are the horizontal pass of input rows
/// r0 - k .. r1 + k (neutral outside the raster); vertical van Herk / Gil-Werman: those rows are cut into
/// blocks of 2k + 1, `prefix` = Op from the block start to a row and `suffix` = Op from a row to the block
/// end, and rows [i - k, i + k] combine as suffix(i) Op prefix(i + 2k): 3 ops per cell whatever k (for
/// k <= 2 the 2k + 1 rows are combined directly, which is as cheap and needs no prefix and suffix rows).
/// Writes output row r to out + (r - r0) * cols.
template <class Op, class T, class Load>
void min_max_rows(std::ptrdiff_t rows, std::ptrdiff_t cols, std::ptrdiff_t kx, std::ptrdiff_t ky, std::ptrdiff_t r0,
                  std::ptrdiff_t r1, Load& load, T* out, min_max_workspace<T>& s)
{
    const std::ptrdiff_t span = 2 * ky + 1, padded = (r1 - r0) + 2 * ky;
    const auto cells = static_cast<std::size_t>(padded * cols);
    s.h.resize(cells);
    s.neutral_row.assign(static_cast<std::size_t>(cols), Op::neutral);
    s.input.resize(static_cast<std::size_t>(cols));
    for (std::ptrdiff_t p = 0; p < padded; ++p) {
        const std::ptrdiff_t r = r0 - ky + p;
        T* h = s.h.data() + p * cols;
        if (r < 0 || r >= rows) {
            std::copy(s.neutral_row.begin(), s.neutral_row.end(), h);
            continue;
        }
        load(r, s.input.data());
        min_max_row<Op>(s.input.data(), h, cols, kx, s);
    }
    if (ky == 0) {
        std::copy(s.h.begin(), s.h.begin() + static_cast<std::ptrdiff_t>(cells), out);
        return;
    }
    if (ky <= 2) {  // short columns: the 2k + 1 rows directly (2k ops per cell, no prefix/suffix rows)
        for (std::ptrdiff_t i = 0; i < r1 - r0; ++i) {
            T* d = out + i * cols;
            const T* first = s.h.data() + i * cols;
            std::copy(first, first + cols, d);
            for (std::ptrdiff_t p = i + 1; p <= i + 2 * ky; ++p) {
                const T* x = s.h.data() + p * cols;
                for (std::ptrdiff_t c = 0; c < cols; ++c) d[c] = Op::apply(d[c], x[c]);
            }
        }
        return;
    }
    s.prefix.resize(cells);
    s.suffix.resize(cells);
    const auto row = [cols](std::vector<T>& v, std::ptrdiff_t p) { return v.data() + p * cols; };
    for (std::ptrdiff_t b0 = 0; b0 < padded; b0 += span) {
        const std::ptrdiff_t b1 = std::min(b0 + span, padded);
        std::copy(row(s.h, b0), row(s.h, b0) + cols, row(s.prefix, b0));
        for (std::ptrdiff_t p = b0 + 1; p < b1; ++p) {
            const T* x = row(s.h, p);
            const T* prev = row(s.prefix, p - 1);
            T* d = row(s.prefix, p);
            for (std::ptrdiff_t c = 0; c < cols; ++c) d[c] = Op::apply(prev[c], x[c]);
        }
        std::copy(row(s.h, b1 - 1), row(s.h, b1 - 1) + cols, row(s.suffix, b1 - 1));
        for (std::ptrdiff_t p = b1 - 2; p >= b0; --p) {
            const T* x = row(s.h, p);
            const T* next = row(s.suffix, p + 1);
            T* d = row(s.suffix, p);
            for (std::ptrdiff_t c = 0; c < cols; ++c) d[c] = Op::apply(next[c], x[c]);
        }
    }
    for (std::ptrdiff_t i = 0; i < r1 - r0; ++i) {
        const T* sfx = row(s.suffix, i);
        const T* pfx = row(s.prefix, i + 2 * ky);
        T* d = out + i * cols;
        for (std::ptrdiff_t c = 0; c < cols; ++c) d[c] = Op::apply(sfx[c], pfx[c]);
    }
}

/// One output row of min_max_filter from the strip's running minima and maxima: only a window without data
/// keeps both neutrals (else min <= max), and becomes NaN in both outputs.
template <class T>
void write_min_max_row(const T* mins, const T* maxs, T* lo, T* hi, std::ptrdiff_t cols) noexcept
{
    for (std::ptrdiff_t c = 0; c < cols; ++c) {
        T x = mins[c], y = maxs[c];
        if constexpr (std::is_floating_point_v<T>) {
            if (x == min_reduce<T>::neutral && y == max_reduce<T>::neutral) x = y = std::numeric_limits<T>::quiet_NaN();
        }
        lo[c] = x;
        hi[c] = y;
    }
}

}  // namespace detail

template <class T, class Load>
void min_filter_rows(std::ptrdiff_t rows, std::ptrdiff_t cols, std::ptrdiff_t radius_x, std::ptrdiff_t radius_y,
                     std::ptrdiff_t r0, std::ptrdiff_t r1, Load&& load, T* out, min_max_workspace<T>& ws)
{
    detail::min_max_rows<detail::min_reduce<T>>(rows, cols, radius_x, radius_y, r0, r1, load, out, ws);
}

template <class T, class Load>
void max_filter_rows(std::ptrdiff_t rows, std::ptrdiff_t cols, std::ptrdiff_t radius_x, std::ptrdiff_t radius_y,
                     std::ptrdiff_t r0, std::ptrdiff_t r1, Load&& load, T* out, min_max_workspace<T>& ws)
{
    detail::min_max_rows<detail::max_reduce<T>>(rows, cols, radius_x, radius_y, r0, r1, load, out, ws);
}

inline std::ptrdiff_t min_max_strip_rows(std::ptrdiff_t rows, std::ptrdiff_t cols, std::ptrdiff_t radius)
{
    const std::ptrdiff_t fit =
        std::max<std::ptrdiff_t>(16, (std::ptrdiff_t{1} << 17) / std::max<std::ptrdiff_t>(cols, 1));
    return std::min(std::max<std::ptrdiff_t>(rows, 1), std::max(fit, 8 * radius));
}

template <class Scratch, class Strip>
void for_each_row_strip(std::ptrdiff_t rows, std::ptrdiff_t strip_rows, int threads, Strip&& strip,
                        const progress_callback& progress, const char* function)
{
    const std::ptrdiff_t strips = (rows + strip_rows - 1) / strip_rows;
    const std::ptrdiff_t run = std::clamp<std::ptrdiff_t>(strips / 8, 1, 16);
    parallel_for_rows(
        rows, run * strip_rows, threads,
        [&](std::ptrdiff_t b0, std::ptrdiff_t b1) {
            Scratch scratch;
            for (std::ptrdiff_t r0 = b0; r0 < b1; r0 += strip_rows) strip(r0, std::min(b1, r0 + strip_rows), scratch);
        },
        progress, function);
}

template <raster_input In, class OutMin, class OutMax>
requires raster_output_of<OutMin, typename In::value_type> && raster_output_of<OutMax, typename In::value_type>
void min_max_filter(const In& in, OutMin&& out_min, OutMax&& out_max, const min_max_filter_options& opt)
{
    using T = typename In::value_type;
    static_assert(std::is_arithmetic_v<T>, "min_max_filter: the raster holds numbers");
    constexpr const char* fn = "min_max_filter";
    detail::require(opt.radius_cells >= 0, fn, "radius_cells", ">= 0", opt.radius_cells);
    detail::require_same_shape(in, out_min, fn, "in", "out_min");
    detail::require_same_shape(in, out_max, fn, "in", "out_max");
    detail::check_execution(opt.run, fn);
    const std::ptrdiff_t rows = in.rows(), cols = in.cols();
    if (rows == 0 || cols == 0) {
        detail::report(opt.run.progress, 1.0, fn);
        return;
    }
    const detail::readable<In> readable_in(in);
    const raster_view<const T> src = readable_in.view();
    // Windows reaching past the whole raster clip to it: cap the radii (keeps scratch small).
    const std::ptrdiff_t kx = std::min<std::ptrdiff_t>(opt.radius_cells, cols - 1);
    const std::ptrdiff_t ky = std::min<std::ptrdiff_t>(opt.radius_cells, rows - 1);
    detail::write_through<T>(std::forward<OutMin>(out_min), [&](raster_view<T> lo) {
        detail::write_through<T>(std::forward<OutMax>(out_max), [&](raster_view<T> hi) {
            detail::require(!detail::overlaps(src, lo) && !detail::overlaps(src, hi) && !detail::overlaps(lo, hi), fn,
                            "out_min, out_max and in must not share memory");
            struct scratch {
                min_max_workspace<T> s;
                std::vector<T> mins, maxs;
            };
            for_each_row_strip<scratch>(
                rows, min_max_strip_rows(rows, cols, std::max(kx, ky)), opt.run.threads,
                [&](std::ptrdiff_t r0, std::ptrdiff_t r1, scratch& w) {
                    w.mins.resize(static_cast<std::size_t>((r1 - r0) * cols));
                    w.maxs.resize(w.mins.size());
                    auto load = [&](std::ptrdiff_t r, T* dst) { std::copy(src.row(r), src.row(r) + cols, dst); };
                    min_filter_rows(rows, cols, kx, ky, r0, r1, load, w.mins.data(), w.s);
                    max_filter_rows(rows, cols, kx, ky, r0, r1, load, w.maxs.data(), w.s);
                    for (std::ptrdiff_t r = r0; r < r1; ++r)
                        detail::write_min_max_row(w.mins.data() + (r - r0) * cols, w.maxs.data() + (r - r0) * cols,
                                                  lo.row(r), hi.row(r), cols);
                },
                opt.run.progress, fn);
        });
    });
}

template <raster_input In>
min_max_filter_result<typename In::value_type> min_max_filter(const In& in, const min_max_filter_options& opt)
{
    using T = typename In::value_type;
    min_max_filter_result<T> res{raster<T>(in.rows(), in.cols(), uninitialized),
                                 raster<T>(in.rows(), in.cols(), uninitialized)};
    min_max_filter(in, res.min, res.max, opt);
    return res;
}

}  // namespace lidarfx
