// SPDX-License-Identifier: Apache-2.0
// line_opening: the cells of a mask that lie on a straight run of mask cells along a row, a column or a diagonal.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// Opening by line segments: out(r, c) = 1 when (r, c) lies on a run of at least length_cells consecutive
/// nonzero cells of `m` along its row, its column or one of its two diagonals, else 0 — the union of the
/// openings of `m` by the four segments of length_cells cells. Unlike morph_open with a square, it keeps
/// thin elongated features (a band one cell wide, a diagonal band) and removes what is short in every
/// direction (scattered cells, small blobs). Runs end at the raster border. length_cells 1 keeps every
/// nonzero cell. Anti-extensive and idempotent. Two passes over the rows per direction: O(cells), one byte
/// per cell of scratch.
/// @throws invalid_input if length_cells < 1 or > 255.
template <raster_input Mask>
raster<std::uint8_t> line_opening(const Mask& m, int length_cells);

// ---- implementation ----

template <raster_input Mask>
raster<std::uint8_t> line_opening(const Mask& m, int length_cells)
{
    detail::require(length_cells >= 1 && length_cells <= 255, "line_opening", "length_cells", "in [1, 255]",
                    length_cells);
    const std::ptrdiff_t rows = m.rows(), cols = m.cols();
    raster<std::uint8_t> out(rows, cols, 0);
    if (rows == 0 || cols == 0) return out;
    const int cap = length_cells;
    const auto longer = [cap](std::uint8_t run) { return static_cast<std::uint8_t>(std::min(cap, run + 1)); };
    // Along rows: the run ending at each cell from the left, then from the right; a cell lies on a run of
    // at least `cap` cells when the two (each capped at cap) overlap by at least cap.
    std::vector<std::uint8_t> from_left(static_cast<std::size_t>(cols));
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        std::uint8_t* o = out.view().row(r);
        std::uint8_t run = 0;
        for (std::ptrdiff_t c = 0; c < cols; ++c) from_left[c] = run = m(r, c) ? longer(run) : 0;
        run = 0;
        for (std::ptrdiff_t c = cols - 1; c >= 0; --c) {
            run = m(r, c) ? longer(run) : 0;
            if (run && from_left[c] + run - 1 >= cap) o[c] = 1;
        }
    }
    // Down columns (dc = 0) and diagonals (dc = ±1): the run ending at (r, c) from above comes from
    // (r − 1, c − dc); it is kept for the whole raster, then the run from below is carried row by row.
    raster<std::uint8_t> from_above(rows, cols, uninitialized);
    std::vector<std::uint8_t> below(static_cast<std::size_t>(cols)), here(static_cast<std::size_t>(cols));
    for (const std::ptrdiff_t dc : {std::ptrdiff_t{0}, std::ptrdiff_t{1}, std::ptrdiff_t{-1}}) {
        const auto inside = [cols](std::ptrdiff_t c) { return c >= 0 && c < cols; };
        for (std::ptrdiff_t r = 0; r < rows; ++r) {
            std::uint8_t* a = from_above.view().row(r);
            const std::uint8_t* up = r > 0 ? from_above.view().row(r - 1) : nullptr;
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                const std::uint8_t prev = up && inside(c - dc) ? up[c - dc] : 0;
                a[c] = m(r, c) ? longer(prev) : 0;
            }
        }
        std::fill(below.begin(), below.end(), 0);
        for (std::ptrdiff_t r = rows - 1; r >= 0; --r) {
            const std::uint8_t* a = from_above.view().row(r);
            std::uint8_t* o = out.view().row(r);
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                const std::uint8_t next = r + 1 < rows && inside(c + dc) ? below[c + dc] : 0;
                here[c] = m(r, c) ? longer(next) : 0;
                if (here[c] && a[c] + here[c] - 1 >= cap) o[c] = 1;
            }
            std::swap(below, here);
        }
    }
    return out;
}

}  // namespace lidarfx
