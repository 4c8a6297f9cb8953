// SPDX-License-Identifier: Apache-2.0
// line_opening: the cells of a mask that lie on a straight run of mask cells along a row, a column or a diagonal.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// Opening by line segments: out(r, c) = 1 when (r, c) lies on a run of at least length_cells consecutive
/// nonzero cells of `m` along its row, its column or one of its two diagonals, else 0 — the union of the
/// openings of `m` by the four segments of length_cells cells. Unlike morph_open with a square, it keeps
/// thin elongated features (a band one cell wide, a diagonal band) and removes what is short in every
/// direction (scattered cells, small blobs). Runs end at the raster border. length_cells 1 keeps every
/// nonzero cell. Anti-extensive and idempotent. Each opening is an erosion then a dilation by the segment,
/// byte-wise over rows of length_cells shifted copies: O(cells * length_cells) simple vector operations, on
/// blocks of max(64, 4 * length_cells) rows (`run.threads` threads; the same result for every thread count;
/// progress per block and cancellation), with scratch of about three blocks of rows per running block.
/// @throws invalid_input if length_cells < 1 or > 255 or run.threads < 0; cancelled.
template <raster_input Mask>
raster<std::uint8_t> line_opening(const Mask& m, int length_cells, const execution& run = {});

// ---- implementation ----

namespace detail {

/// line_opening of the output rows [r0, r1): the mask rows they depend on are copied as 0/1 bytes into a
/// scratch buffer with zero rows and columns around them (the raster's border ends runs), then each direction's
/// segment erosion and dilation run on whole rows.
template <class Mask>
void line_opening_rows(const Mask& m, int length, std::ptrdiff_t r0, std::ptrdiff_t r1, raster_view<std::uint8_t> out)
{
    const std::ptrdiff_t rows = m.rows(), cols = m.cols(), reach = length - 1;
    // Columns: a diagonal erosion at column c reads c ± reach, its dilation c ± reach more.
    const std::ptrdiff_t pad = 2 * reach, width = cols + 2 * pad;
    // Mask rows [r0 - reach, r1 + reach), erosion rows [r0 - reach, r1) (one per dilation input row).
    const std::ptrdiff_t mask_rows = r1 - r0 + 2 * reach, eroded_rows = r1 - r0 + reach;
    std::vector<std::uint8_t> scratch(static_cast<std::size_t>((mask_rows + eroded_rows + 1) * width), 0);
    std::uint8_t* const mask = scratch.data();  // mask row i: raster row r0 - reach + i, column c at pad + c
    std::uint8_t* const eroded = mask + mask_rows * width;
    std::uint8_t* const line = eroded + eroded_rows * width;
    for (std::ptrdiff_t i = 0; i < mask_rows; ++i) {
        const std::ptrdiff_t r = r0 - reach + i;
        if (r < 0 || r >= rows) continue;
        std::uint8_t* row = mask + i * width + pad;
        for (std::ptrdiff_t c = 0; c < cols; ++c) row[c] = m(r, c) ? 1 : 0;
    }
    // Along the row: a cell is eroded when the `length` cells from it to the right are set, kept when one of
    // the `length` cells from it to the left is eroded.
    for (std::ptrdiff_t r = r0; r < r1; ++r) {
        const std::uint8_t* here = mask + (r - r0 + reach) * width;
        std::copy_n(here, width, line);
        for (std::ptrdiff_t k = 1; k <= reach; ++k)
            for (std::ptrdiff_t j = 0; j + k < width; ++j) line[j] &= here[j + k];
        std::uint8_t* o = out.row(r);
        for (std::ptrdiff_t c = 0; c < cols; ++c) o[c] = line[pad + c];
        for (std::ptrdiff_t t = 1; t <= reach; ++t)
            for (std::ptrdiff_t c = 0; c < cols; ++c) o[c] |= line[pad + c - t];
    }
    // Down columns and diagonals, direction (1, dc): eroded(q, c) = AND over k of mask(q + k, c + k dc),
    // kept(r, c) = OR over t of eroded(r − t, c − t dc).
    for (const std::ptrdiff_t dc : {std::ptrdiff_t{0}, std::ptrdiff_t{1}, std::ptrdiff_t{-1}}) {
        for (std::ptrdiff_t q = 0; q < eroded_rows; ++q) {  // eroded row q: raster row r0 - reach + q
            std::uint8_t* e = eroded + q * width;
            std::copy_n(mask + q * width, width, e);
            for (std::ptrdiff_t k = 1; k <= reach; ++k) {
                const std::uint8_t* below = mask + (q + k) * width + k * dc;  // column j + k dc of row q + k
                const std::ptrdiff_t from = std::max<std::ptrdiff_t>(0, -k * dc);
                const std::ptrdiff_t to = std::min(width, width - k * dc);
                for (std::ptrdiff_t j = from; j < to; ++j) e[j] &= below[j];
            }
        }
        for (std::ptrdiff_t r = r0; r < r1; ++r) {
            std::uint8_t* o = out.row(r);
            for (std::ptrdiff_t t = 0; t <= reach; ++t) {
                const std::uint8_t* e = eroded + (r - r0 + reach - t) * width + pad - t * dc;  // column c - t dc
                for (std::ptrdiff_t c = 0; c < cols; ++c) o[c] |= e[c];
            }
        }
    }
}

}  // namespace detail

template <raster_input Mask>
raster<std::uint8_t> line_opening(const Mask& m, int length_cells, const execution& run)
{
    constexpr const char* fn = "line_opening";
    detail::require(length_cells >= 1 && length_cells <= 255, fn, "length_cells", "in [1, 255]", length_cells);
    detail::check_execution(run, fn);
    const std::ptrdiff_t rows = m.rows(), cols = m.cols();
    raster<std::uint8_t> out(rows, cols, uninitialized);  // every cell is written
    if (cols == 0) return out;
    // Each block recomputes 2 (length - 1) rows around it: blocks of at least 4 lengths keep that within half.
    const std::ptrdiff_t block_rows = std::max<std::ptrdiff_t>(64, 4 * std::ptrdiff_t{length_cells});
    parallel_for_rows(
        rows, block_rows, run.threads,
        [&](std::ptrdiff_t r0, std::ptrdiff_t r1) { detail::line_opening_rows(m, length_cells, r0, r1, out.view()); },
        run.progress, fn);
    return out;
}

}  // namespace lidarfx
