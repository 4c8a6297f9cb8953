// SPDX-License-Identifier: Apache-2.0
// Implementation of kernels/filter/morphology.hpp: bit-packed horizontal doubling, vertical van Herk/Gil-Werman
// passes, strips of rows run in parallel. Included at the end of morphology.hpp, after the declarations it
// defines; not a public header.
#pragma once

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <type_traits>
#include <utility>
#include <vector>

#include "lidarfx/core/bit_mask.hpp"
#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

namespace detail {

/// Dilation combines with OR (neutral 0, the value of cells outside the raster), erosion with AND
/// (neutral 1): padding with the neutral element is exactly "cells outside are ignored".
struct morph_or {
    static constexpr mask_word neutral = 0;
    static constexpr mask_word apply(mask_word a, mask_word b) noexcept { return a | b; }
};
struct morph_and {
    static constexpr mask_word neutral = ~mask_word{0};
    static constexpr mask_word apply(mask_word a, mask_word b) noexcept { return a & b; }
};

/// Horizontal pass on one row: out bit c = Op over in bits [c - k, c + k] clipped to [0, cols).
/// Doubling: a_L(x) = Op over [x, x + L) is built in place for L = 1, 2, 4, ... up to the largest power
/// of two L <= 2k + 1, then out(c) = a_L(c - k) Op a_L(c + k + 1 - L): O(words * log k). The row is
/// padded with neutral words (`buf` is scratch reused across rows).
template <class Op>
void morph_row(const mask_word* in, mask_word* out, std::ptrdiff_t cols, std::ptrdiff_t k, std::vector<mask_word>& buf)
{
    const std::ptrdiff_t words = mask_words(cols);
    if (k == 0) {
        std::copy(in, in + words, out);
        return;
    }
    const std::ptrdiff_t pad = k / 64 + 1;         // neutral words left of the data: position -k exists
    const std::ptrdiff_t n = words + 2 * pad + 1;  // and right of it, plus one for bits_from's a[q + 1]
    buf.resize(static_cast<std::size_t>(n));
    mask_word* a = buf.data();
    std::fill(a, a + pad, Op::neutral);
    std::copy(in, in + words, a + pad);
    std::fill(a + pad + words, a + n, Op::neutral);
    if (cols % 64 != 0) {
        const mask_word tail = ~mask_word{0} << (cols % 64);  // bits past the last column
        a[pad + words - 1] = (a[pad + words - 1] & ~tail) | (Op::neutral & tail);
    }
    const std::ptrdiff_t top = static_cast<std::ptrdiff_t>(std::bit_floor(static_cast<std::size_t>(2 * k + 1)));
    for (std::ptrdiff_t len = 1; len < top; len *= 2) {
        // In increasing order, word j reads words j + len / 64 and the next, not yet overwritten; words
        // past the end are neutral, so the last ones keep their value.
        const std::ptrdiff_t q = len / 64;
        const int s = static_cast<int>(len % 64);
        for (std::ptrdiff_t j = 0; j + q + 1 < n; ++j) a[j] = Op::apply(a[j], bits_from(a, j + q, s));
    }
    const std::ptrdiff_t left = pad * 64 - k, right = pad * 64 + k + 1 - top;  // both in [0, 64 * pad]
    const int sl = static_cast<int>(left % 64), sr = static_cast<int>(right % 64);
    const mask_word* al = a + left / 64;
    const mask_word* ar = a + right / 64;
    for (std::ptrdiff_t i = 0; i < words; ++i) out[i] = Op::apply(bits_from(al, i, sl), bits_from(ar, i, sr));
}

/// Vertical pass (van Herk / Gil-Werman) over the rows of `in`, rows outside it being neutral: padded
/// rows p (= row p - k of `in`) are cut into blocks of 2k + 1; `prefix` = Op from the block start to p,
/// `suffix` = Op from p to the block end. Rows [i - k, i + k] of `in` then combine as
/// suffix(i) Op prefix(i + 2k): 3 ops per word whatever k.
template <class Op>
void van_herk_scan(const bit_rows& in, std::ptrdiff_t k, bit_rows& prefix, bit_rows& suffix,
                   const std::vector<mask_word>& neutral_row)
{
    const std::ptrdiff_t span = 2 * k + 1, padded = in.rows + 2 * k, words = in.words;
    prefix.resize(padded, words);
    suffix.resize(padded, words);
    const auto source = [&](std::ptrdiff_t p) {
        const std::ptrdiff_t r = p - k;
        return r >= 0 && r < in.rows ? in.row(r) : neutral_row.data();
    };
    for (std::ptrdiff_t b0 = 0; b0 < padded; b0 += span) {
        const std::ptrdiff_t b1 = std::min(b0 + span, padded);
        std::copy(source(b0), source(b0) + words, prefix.row(b0));
        for (std::ptrdiff_t p = b0 + 1; p < b1; ++p) {
            const mask_word* s = source(p);
            const mask_word* prev = prefix.row(p - 1);
            mask_word* d = prefix.row(p);
            for (std::ptrdiff_t i = 0; i < words; ++i) d[i] = Op::apply(prev[i], s[i]);
        }
        std::copy(source(b1 - 1), source(b1 - 1) + words, suffix.row(b1 - 1));
        for (std::ptrdiff_t p = b1 - 2; p >= b0; --p) {
            const mask_word* s = source(p);
            const mask_word* next = suffix.row(p + 1);
            mask_word* d = suffix.row(p);
            for (std::ptrdiff_t i = 0; i < words; ++i) d[i] = Op::apply(next[i], s[i]);
        }
    }
}

/// Runs `steps` (each a dilation or erosion by the same rectangle) on mask `in` and writes 0/1 to `out`.
/// Strips of output rows are independent tasks: each packs the input rows it needs (its rows plus
/// `ky` per step above and below, clipped to the raster), runs every step on bits (horizontal doubling
/// per row, vertical van Herk) and unpacks its own rows; scratch stays small and cache-resident. Every
/// output bit is a function of the input alone, so results never depend on strips or threads.
/// `out` may alias `in` only when the whole raster is one strip (see morph_into).
template <class T>
void morph_run(raster_view<const T> in, raster_view<std::uint8_t> out, const morphology_options& opt,
               std::initializer_list<morph_step> steps, std::ptrdiff_t strip_rows, const char* function)
{
    const std::ptrdiff_t rows = in.rows(), cols = in.cols(), words = mask_words(cols);
    const int height = opt.height_cells == 0 ? opt.size_cells : opt.height_cells;
    // Windows reaching past the whole raster clip to it: cap the radii (keeps scratch small).
    const std::ptrdiff_t kx = std::min<std::ptrdiff_t>(opt.size_cells / 2, std::max<std::ptrdiff_t>(cols - 1, 0));
    const std::ptrdiff_t ky = std::min<std::ptrdiff_t>(height / 2, std::max<std::ptrdiff_t>(rows - 1, 0));
    const auto depth = static_cast<std::ptrdiff_t>(steps.size());

    parallel_for_rows(
        rows, strip_rows, opt.run.threads,
        [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
            const auto first_row = [&](std::ptrdiff_t j) { return std::max<std::ptrdiff_t>(0, r0 - (depth - j) * ky); };
            const auto end_row = [&](std::ptrdiff_t j) { return std::min(rows, r1 + (depth - j) * ky); };
            const auto horizontal = [&](morph_step step, const mask_word* src, mask_word* dst,
                                        std::vector<mask_word>& buf) {
                if (step == morph_step::erode)
                    morph_row<morph_and>(src, dst, cols, kx, buf);
                else
                    morph_row<morph_or>(src, dst, cols, kx, buf);
            };
            std::vector<mask_word> buf, packed(static_cast<std::size_t>(words)), v(static_cast<std::size_t>(words));
            std::vector<mask_word> neutral(static_cast<std::size_t>(words));
            bit_rows h, next, prefix, suffix;

            // h holds rows [first_row(j), end_row(j)) after j steps' horizontal parts.
            h.resize(end_row(0) - first_row(0), words);
            for (std::ptrdiff_t r = first_row(0); r < end_row(0); ++r) {
                pack_mask_row(in.row(r), cols, packed.data());
                horizontal(*steps.begin(), packed.data(), h.row(r - first_row(0)), buf);
            }
            for (std::ptrdiff_t j = 1; j <= depth; ++j) {
                const morph_step step = *(steps.begin() + (j - 1));
                const bool erode = step == morph_step::erode;
                if (ky > 0) {
                    std::fill(neutral.begin(), neutral.end(), erode ? morph_and::neutral : morph_or::neutral);
                    if (erode)
                        van_herk_scan<morph_and>(h, ky, prefix, suffix, neutral);
                    else
                        van_herk_scan<morph_or>(h, ky, prefix, suffix, neutral);
                }
                if (j < depth) next.resize(end_row(j) - first_row(j), words);
                for (std::ptrdiff_t r = first_row(j); r < end_row(j); ++r) {
                    const std::ptrdiff_t i = r - first_row(j - 1);  // r as a row of h
                    const mask_word* col = h.row(i);
                    if (ky > 0) {
                        const mask_word* s = suffix.row(i);
                        const mask_word* p = prefix.row(i + 2 * ky);
                        if (erode)
                            for (std::ptrdiff_t w = 0; w < words; ++w) v[w] = s[w] & p[w];
                        else
                            for (std::ptrdiff_t w = 0; w < words; ++w) v[w] = s[w] | p[w];
                        col = v.data();
                    }
                    if (j < depth)
                        horizontal(*(steps.begin() + j), col, next.row(r - first_row(j)), buf);
                    else
                        unpack_mask_row(col, cols, out.row(r));
                }
                if (j < depth) std::swap(h, next);
            }
        },
        opt.run.progress, function);
}

/// Rows per strip: small enough for cache-resident scratch and for load balance, large enough that
/// the rows recomputed around each strip (`ky` per step on each side) stay a small share.
inline std::ptrdiff_t morph_strip_rows(std::ptrdiff_t rows, const morphology_options& opt, std::size_t steps)
{
    const int height = opt.height_cells == 0 ? opt.size_cells : opt.height_cells;
    const std::ptrdiff_t halo = static_cast<std::ptrdiff_t>(steps) * (height / 2);
    return std::min(std::max<std::ptrdiff_t>(rows, 1), std::max<std::ptrdiff_t>(256, 8 * halo));
}

/// Validates the arguments shared by the four morphology functions.
template <class A, class B>
void morph_check(const A& in, const B& out, const morphology_options& opt, const char* function)
{
    require(opt.size_cells >= 1 && opt.size_cells % 2 == 1, function, "size_cells", "odd and >= 1", opt.size_cells);
    require(opt.height_cells == 0 || (opt.height_cells >= 1 && opt.height_cells % 2 == 1), function, "height_cells",
            "0 (square) or odd and >= 1", opt.height_cells);
    require_same_shape(in, out, function, "m", "out");
    check_execution(opt.run, function);
}

/// Into form shared by the four functions: validation, then the bit-packed pipeline.
template <raster_input In, class Out>
void morph_into(const In& m, Out&& out, const morphology_options& opt, std::initializer_list<morph_step> steps,
                const char* function)
{
    static_assert(std::is_arithmetic_v<typename In::value_type>, "a mask holds numbers (nonzero = 1)");
    morph_check(m, out, opt, function);
    if (m.rows() == 0 || m.cols() == 0) {
        report(opt.run.progress, 1.0, function);
        return;
    }
    const readable<In> in(m);
    std::ptrdiff_t strip = morph_strip_rows(m.rows(), opt, steps.size());
    write_through<std::uint8_t>(std::forward<Out>(out), [&](raster_view<std::uint8_t> o) {
        // A strip reads input rows beyond its own: if `out` shares memory with `m`, one strip (all rows)
        // reads everything before writing anything.
        if (overlaps(in.view(), o)) strip = m.rows();
        morph_run(in.view(), o, opt, steps, strip, function);
    });
}

/// Returning form shared by the four functions.
template <raster_input In>
raster<std::uint8_t> morph_new(const In& m, const morphology_options& opt, std::initializer_list<morph_step> steps,
                               const char* function)
{
    raster<std::uint8_t> out(m.rows(), m.cols(), uninitialized);  // every cell is written
    morph_into(m, out, opt, steps, function);
    return out;
}

template <morph_step... Steps>
template <raster_input In, class Out>
requires raster_output_of<Out, std::uint8_t>
void morphology_operation<Steps...>::operator()(const In& m, Out&& out, const morphology_options& opt) const
{
    morph_into(m, std::forward<Out>(out), opt, {Steps...}, function);
}

template <morph_step... Steps>
template <raster_input In>
raster<std::uint8_t> morphology_operation<Steps...>::operator()(const In& m, const morphology_options& opt) const
{
    return morph_new(m, opt, {Steps...}, function);
}

template <morph_step... Steps>
template <raster_input In>
raster<std::uint8_t> morphology_operation<Steps...>::operator()(const In& m, int size_cells) const
{
    return morph_new(m, morphology_options{.size_cells = size_cells}, {Steps...}, function);
}

}  // namespace detail

}  // namespace lidarfx
