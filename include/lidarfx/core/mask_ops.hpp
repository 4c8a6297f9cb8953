// SPDX-License-Identifier: Apache-2.0
// mask_ops: cell-wise operations on 0/1 masks and label rasters (and, or, not, clear outside, any, labels to mask).
#pragma once

#include <cstddef>
#include <cstdint>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

// Masks are std::uint8_t rasters, 0 = off, any other value = on; the operations below write 0 or 1. All
// arguments of one call have the same shape; an output may be one of the inputs (each cell is read before it
// is written). One pass over the rows, O(cells), vectorized; no allocation.

/// out = 1 where `in` is 0, else 0.
/// @throws invalid_input if the shapes differ.
inline void mask_not(raster_view<const std::uint8_t> in, raster_view<std::uint8_t> out);

/// out = 1 where both `a` and `b` are nonzero, else 0.
/// @throws invalid_input if the shapes differ.
inline void mask_and(raster_view<const std::uint8_t> a, raster_view<const std::uint8_t> b,
                     raster_view<std::uint8_t> out);

/// out = 1 where `a` or `b` is nonzero, else 0.
/// @throws invalid_input if the shapes differ.
inline void mask_or(raster_view<const std::uint8_t> a, raster_view<const std::uint8_t> b,
                    raster_view<std::uint8_t> out);

/// Cells of `mask` where `inside` is 0 become 0; the others keep their value.
/// @throws invalid_input if the shapes differ.
inline void clear_outside(raster_view<std::uint8_t> mask, raster_view<const std::uint8_t> inside);

/// Cells of `labels` where `inside` is 0 become 0 (land, background); the others keep their label.
/// @throws invalid_input if the shapes differ.
inline void clear_outside(raster_view<std::int32_t> labels, raster_view<const std::uint8_t> inside);

/// out = 1 where labels > 0 (a labelled part), else 0.
/// @throws invalid_input if the shapes differ.
inline void mask_of_labels(raster_view<const std::int32_t> labels, raster_view<std::uint8_t> out);

/// Whether any cell of `mask` is nonzero. Rows are passed over 64 cells at a time and the search stops at the
/// first nonzero cell: O(cells / 64) on an empty mask.
inline bool mask_any(raster_view<const std::uint8_t> mask) noexcept;

// ---- implementation ----

namespace detail {

/// out(r, c) = f(a(r, c), b(r, c)) row by row, with the row pointers and width in locals: byte stores may
/// alias anything, so loops bounded by members would reload them and not vectorize.
template <class A, class B, class Out, class F>
void mask_cellwise(raster_view<A> a, raster_view<B> b, raster_view<Out> out, F f)
{
    const std::ptrdiff_t rows = out.rows(), width = out.cols();
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        const A* x = a.row(r);
        const B* y = b.row(r);
        Out* o = out.row(r);
        for (std::ptrdiff_t c = 0; c < width; ++c) o[c] = f(x[c], y[c]);
    }
}

}  // namespace detail

inline void mask_not(raster_view<const std::uint8_t> in, raster_view<std::uint8_t> out)
{
    detail::require_same_shape(in, out, "mask_not", "in", "out");
    detail::mask_cellwise(in, in, out, [](std::uint8_t x, std::uint8_t) { return static_cast<std::uint8_t>(!x); });
}

inline void mask_and(raster_view<const std::uint8_t> a, raster_view<const std::uint8_t> b,
                     raster_view<std::uint8_t> out)
{
    detail::require_same_shape(a, b, "mask_and", "a", "b");
    detail::require_same_shape(a, out, "mask_and", "a", "out");
    detail::mask_cellwise(
        a, b, out, [](std::uint8_t x, std::uint8_t y) { return static_cast<std::uint8_t>((x != 0) & (y != 0)); });
}

inline void mask_or(raster_view<const std::uint8_t> a, raster_view<const std::uint8_t> b, raster_view<std::uint8_t> out)
{
    detail::require_same_shape(a, b, "mask_or", "a", "b");
    detail::require_same_shape(a, out, "mask_or", "a", "out");
    detail::mask_cellwise(
        a, b, out, [](std::uint8_t x, std::uint8_t y) { return static_cast<std::uint8_t>((x != 0) | (y != 0)); });
}

inline void clear_outside(raster_view<std::uint8_t> mask, raster_view<const std::uint8_t> inside)
{
    detail::require_same_shape(mask, inside, "clear_outside", "mask", "inside");
    detail::mask_cellwise(raster_view<const std::uint8_t>(mask), inside, mask, [](std::uint8_t x, std::uint8_t in) {
        return static_cast<std::uint8_t>((x != 0) & (in != 0));
    });
}

inline void clear_outside(raster_view<std::int32_t> labels, raster_view<const std::uint8_t> inside)
{
    detail::require_same_shape(labels, inside, "clear_outside", "labels", "inside");
    detail::mask_cellwise(raster_view<const std::int32_t>(labels), inside, labels,
                          [](std::int32_t l, std::uint8_t in) { return in != 0 ? l : 0; });
}

inline void mask_of_labels(raster_view<const std::int32_t> labels, raster_view<std::uint8_t> out)
{
    detail::require_same_shape(labels, out, "mask_of_labels", "labels", "out");
    detail::mask_cellwise(labels, labels, out,
                          [](std::int32_t l, std::int32_t) { return static_cast<std::uint8_t>(l > 0); });
}

inline bool mask_any(raster_view<const std::uint8_t> mask) noexcept
{
    for (std::ptrdiff_t r = 0; r < mask.rows(); ++r)
        if (detail::next_positive(mask.row(r), 0, mask.cols()) < mask.cols()) return true;
    return false;
}

}  // namespace lidarfx
