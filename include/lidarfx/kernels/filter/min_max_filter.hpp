// SPDX-License-Identifier: Apache-2.0
// min_max_filter: running minimum and maximum of a raster over a square window, NaN cells ignored.
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

/// Settings of min_max_filter.
struct min_max_filter_options {
    int radius_cells = 1;  ///< the window of a cell: the cells within this Chebyshev distance of it, a
                           ///< (2 r + 1)² square clipped at the raster border, in cells, >= 0. Default 1
    execution run = {};    ///< threads, progress, cancellation (core/parallel.hpp); never changes the result
};

/// Both outputs of the returning form of min_max_filter.
template <class T>
struct min_max_filter_result {
    raster<T> min;  ///< lowest value of each cell's window
    raster<T> max;  ///< highest value of each cell's window
};

/// Running minimum and maximum over a square window: out_min(r, c) and out_max(r, c) are the lowest and
/// highest values of `in` among the cells within Chebyshev distance radius_cells of (r, c), the window
/// clipped at the raster border (cells outside are ignored). Units are those of `in`. NaN cells are no
/// data and are ignored; a window without any other cell gives NaN in both outputs (±inf are values).
/// Separable: rows by doubling (O(log r), vectorized), columns by van Herk / Gil-Werman (3 ops per cell
/// whatever r), in strips of rows with cache-sized scratch: O(cells · log r). Any arithmetic T.
/// @throws invalid_input if radius_cells < 0, run.threads < 0, the shapes differ or an output overlaps
/// `in`; cancelled if run.progress returns false.
template <raster_input In, class OutMin, class OutMax>
requires raster_output_of<OutMin, typename In::value_type> && raster_output_of<OutMax, typename In::value_type>
void min_max_filter(const In& in, OutMin&& out_min, OutMax&& out_max, const min_max_filter_options& opt = {});

/// Returning form: new min and max rasters of in's shape (see the into form).
template <raster_input In>
min_max_filter_result<typename In::value_type> min_max_filter(const In& in, const min_max_filter_options& opt = {});

// ---- Row-streaming form, for callers whose input rows are computed on the fly ----------------------------
//
// min_max_filter reads a raster. A caller that filters a value it derives per cell (a label made a key, a
// height masked by another raster) and consumes the result row by row calls the same running filters on
// strips of rows, with no raster of the input or the output: for_each_row_strip runs the strips (in
// parallel), min_filter_rows / max_filter_rows fill one strip's rows of output from a row loader.

/// Reusable scratch memory of min_filter_rows and max_filter_rows (buffers of a few strip-sized rows of T).
/// One per thread: it grows on first use and later calls reuse it without allocating. Default-constructed
/// empty; its contents are no part of the interface.
template <class T>
class min_max_workspace;

/// Running minimum over a (2 radius_x + 1) × (2 radius_y + 1) window of output rows [r0, r1) of a virtual
/// rows × cols raster whose row r the call load(r, T* dst) writes (cols values). Writes output row r to
/// out + (r − r0) · cols (contiguous). Cells outside the raster and NaN cells are ignored: a window without
/// data gives +inf for floating T, numeric_limits<T>::max() otherwise (min_max_filter turns that into NaN).
/// The same values as min_max_filter for every cell of the strip. Loads input rows r0 − radius_y ..
/// r1 + radius_y (clipped), each once. O((r1 − r0 + 2 radius_y) · cols · log radius_x); no throws (the
/// caller validates: radii >= 0, 0 <= r0 <= r1 <= rows).
template <class T, class Load>
void min_filter_rows(std::ptrdiff_t rows, std::ptrdiff_t cols, std::ptrdiff_t radius_x, std::ptrdiff_t radius_y,
                     std::ptrdiff_t r0, std::ptrdiff_t r1, Load&& load, T* out, min_max_workspace<T>& ws);

/// Running maximum: as min_filter_rows, a window without data giving −inf for floating T,
/// numeric_limits<T>::lowest() otherwise.
template <class T, class Load>
void max_filter_rows(std::ptrdiff_t rows, std::ptrdiff_t cols, std::ptrdiff_t radius_x, std::ptrdiff_t radius_y,
                     std::ptrdiff_t r0, std::ptrdiff_t r1, Load&& load, T* out, min_max_workspace<T>& ws);

/// Rows per strip for min_filter_rows / max_filter_rows on a rows × cols raster with a window of the given
/// radius (cells): a strip's scratch (its rows plus 2 radius, a few arrays of them) stays near cache size,
/// and the rows loaded twice around a strip stay a small share. In [1, max(rows, 1)].
inline std::ptrdiff_t min_max_strip_rows(std::ptrdiff_t rows, std::ptrdiff_t cols, std::ptrdiff_t radius);

/// Runs strip(r0, r1, scratch) over [0, rows) in strips of `strip_rows` rows (the last one shorter), on
/// `threads` threads (parallel_for_rows) that each take runs of up to 16 consecutive strips sharing one
/// default-constructed Scratch, so buffers are allocated once per run, not per strip. Which strips share a
/// Scratch depends on the thread count, so a result must not depend on Scratch's contents on entry.
/// Progress is reported between runs, under `function`'s name.
/// @throws cancelled if progress returns false; what strip throws.
template <class Scratch, class Strip>
void for_each_row_strip(std::ptrdiff_t rows, std::ptrdiff_t strip_rows, int threads, Strip&& strip,
                        const progress_callback& progress, const char* function);

}  // namespace lidarfx

#include "lidarfx/kernels/filter/detail/min_max_filter_impl.hpp"
