// SPDX-License-Identifier: Apache-2.0
// Binary morphology on masks: dilate, erode, open and close with a rectangle, on bit-packed rows.
// morph_dilate, morph_erode, morph_open and morph_close are function objects (constants of one class template,
// as the std::ranges algorithms are), each callable in three forms; the implementation is in
// detail/morphology_impl.hpp.
#pragma once

#include <cstdint>

#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// Structuring element and execution of the binary morphology functions.
struct morphology_options {
    int size_cells = 5;    ///< width of the rectangle in cells (columns); odd, >= 1. Default 5.
    int height_cells = 0;  ///< height of the rectangle in cells (rows); odd, >= 1, or 0 for a square (= size_cells)
    execution run = {};    ///< threads, progress and cancellation (core/parallel.hpp); never changes the result
};

namespace detail {

/// One step of a morphology operation: a dilation or an erosion by the options' rectangle.
enum class morph_step { dilate, erode };

/// The type of morph_dilate, morph_erode, morph_open and morph_close: a function object (like the
/// std::ranges algorithms, a "niebloid") that runs `Steps` in order. It is called exactly like a function
/// template with three overloads; being an object, it can also be passed to other functions whole.
template <morph_step... Steps>
struct morphology_operation {
    const char* function;  ///< the public name, used in error messages

    /// Into form: writes 0/1 to `out`, of m's shape (`out` may be `m` itself).
    template <raster_input In, class Out>
    requires raster_output_of<Out, std::uint8_t>
    void operator()(const In& m, Out&& out, const morphology_options& opt = {}) const;

    /// Returning form: a new 0/1 raster of m's shape.
    template <raster_input In>
    raster<std::uint8_t> operator()(const In& m, const morphology_options& opt) const;

    /// Returning form with a size_cells x size_cells square on the caller's thread (morph_open(m, 5)).
    template <raster_input In>
    raster<std::uint8_t> operator()(const In& m, int size_cells) const;
};

}  // namespace detail

/// Binary dilation: out(r, c) = 1 if any mask cell in the size_cells x height_cells rectangle centred on
/// (r, c) is nonzero, else 0. The rectangle is clipped at the raster border (cells outside are ignored), so
/// an all-zero mask stays all zero. Bit-packed 64-cell words: O(rows * cols / 64 * log(size_cells)) plus one
/// pass to pack and one to unpack; `out` may be `m` itself. Progress is reported between strips of rows.
/// Forms: morph_dilate(m, out, opt = {}), morph_dilate(m, opt) and morph_dilate(m, size_cells) -> raster.
/// @throws invalid_input if size_cells or height_cells is even or < 1 (height_cells 0 = square),
/// run.threads < 0, or the shapes of m and out differ; cancelled if run.progress returns false.
inline constexpr detail::morphology_operation<detail::morph_step::dilate> morph_dilate{"morph_dilate"};

/// Binary erosion: out(r, c) = 1 if every mask cell of the size_cells x height_cells rectangle centred on
/// (r, c) that lies inside the raster is nonzero, else 0. Clipped at the border (an all-one mask stays all
/// one). Forms and cost as morph_dilate. @throws as morph_dilate.
inline constexpr detail::morphology_operation<detail::morph_step::erode> morph_erode{"morph_erode"};

/// Binary opening: dilate(erode(m)) with the same clipped rectangle. Removes features that the
/// rectangle does not fit in (isolated dropout cells, thin lines); anti-extensive and idempotent.
/// Forms as morph_dilate; cost as two dilations, with one pack and one unpack. @throws as morph_dilate.
inline constexpr detail::morphology_operation<detail::morph_step::erode, detail::morph_step::dilate> morph_open{
    "morph_open"};

/// Binary closing: erode(dilate(m)) with the same clipped rectangle. Fills gaps and holes narrower than
/// the rectangle; extensive and idempotent. Forms and cost as morph_open. @throws as morph_dilate.
inline constexpr detail::morphology_operation<detail::morph_step::dilate, detail::morph_step::erode> morph_close{
    "morph_close"};

}  // namespace lidarfx

#include "lidarfx/kernels/filter/detail/morphology_impl.hpp"
