// SPDX-License-Identifier: Apache-2.0
// Implementation of fill_small_islands (included at the end of pipelines/water/fill_small_islands.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>
#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/grid.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/kernels/label/connected_components.hpp"

namespace lidarfx {

namespace detail {

/// The holes of body `l` in its bounding box grown by one cell (`box`, a window of the labels): the cells of
/// other labels or land there, 4-connected (connected_components on one thread), form parts; a part touching no
/// edge of the box, holding only land and fewer than max_hole_cells cells is a hole. Appends the holes' cells
/// (r · cols + c of the raster, r0 and c0 the box's corner) to `holes`. `other` is the caller's scratch.
inline void holes_of_body(raster_view<const std::int32_t> box, std::int32_t l, std::size_t max_hole_cells,
                          std::ptrdiff_t r0, std::ptrdiff_t c0, std::ptrdiff_t cols, raster<std::uint8_t>& other,
                          std::vector<std::ptrdiff_t>& holes)
{
    const std::ptrdiff_t nr = box.rows(), nc = box.cols();
    ensure_shape(other, nr, nc);
    for (std::ptrdiff_t r = 0; r < nr; ++r) {
        const std::int32_t* in = box.row(r);
        std::uint8_t* out = other.row(r);
        for (std::ptrdiff_t c = 0; c < nc; ++c) out[c] = in[c] != l;
    }
    const auto parts = connected_components(other, connected_components_options{.conn = connectivity::four});
    std::vector<std::uint8_t> fill(parts.sizes.size(), 1);
    fill[0] = 0;
    for (std::size_t k = 1; k < parts.sizes.size(); ++k)
        if (parts.sizes[k] >= max_hole_cells) fill[k] = 0;
    // A part that stays a hole has all its cells listed: only they are visited again.
    const std::size_t first = holes.size();
    for (std::ptrdiff_t r = 0; r < nr; ++r) {
        const std::int32_t* part = parts.labels.row(r);
        const std::int32_t* in = box.row(r);
        for (std::ptrdiff_t c = 0; c < nc; ++c) {
            const auto k = static_cast<std::size_t>(part[c]);
            if (k == 0 || !fill[k]) continue;
            if (r == 0 || c == 0 || r == nr - 1 || c == nc - 1 || in[c] != 0)
                fill[k] = 0;
            else
                holes.push_back(r * nc + c);
        }
    }
    std::size_t kept = first;
    for (std::size_t k = first; k < holes.size(); ++k) {
        const std::ptrdiff_t r = holes[k] / nc, c = holes[k] % nc;
        if (fill[static_cast<std::size_t>(parts.labels(r, c))]) holes[kept++] = (r0 + r) * cols + c0 + c;
    }
    holes.resize(kept);
}

/// Holes of the bodies of `labels` (all labels in 1..bodies) by one pass per body over the body's bounding box
/// grown by one cell (holes_of_body). The bodies are searched on `threads` threads, all on the labels as they came
/// in, and their holes written after in label order: a hole of one body lies inside it, so its cells are in a part
/// of another body's box that holds the body's cells, no hole of the other's before or after the fill. The same
/// result for any thread count. O(sum of the grown boxes' areas). Returns the cells filled.
inline std::size_t fill_holes_per_body(raster_view<std::int32_t> labels, std::size_t max_hole_cells,
                                       const std::vector<cell_box>& boxes, int threads)
{
    const std::ptrdiff_t rows = labels.rows(), cols = labels.cols();
    // Blocks of bodies, each block's holes in a list of its own (with the label of each cell's body).
    constexpr std::ptrdiff_t block_bodies = 16;
    const auto bodies = static_cast<std::ptrdiff_t>(boxes.size());
    struct hole_cell {
        std::ptrdiff_t cell;
        std::int32_t label;
    };
    std::vector<std::vector<hole_cell>> found(static_cast<std::size_t>((bodies + block_bodies - 1) / block_bodies));
    const raster_view<const std::int32_t> in = labels;
    parallel_for_rows(bodies, block_bodies, threads, [&](std::ptrdiff_t b0, std::ptrdiff_t b1) {
        raster<std::uint8_t> other;
        std::vector<std::ptrdiff_t> holes;
        auto& out = found[static_cast<std::size_t>(b0 / block_bodies)];
        for (std::ptrdiff_t body = std::max<std::ptrdiff_t>(b0, 1); body < b1; ++body) {
            const auto& b = boxes[static_cast<std::size_t>(body)];
            if (b.empty()) continue;
            const std::ptrdiff_t r0 = std::max<std::ptrdiff_t>(0, b.row_min - 1),
                                 c0 = std::max<std::ptrdiff_t>(0, b.col_min - 1);
            const std::ptrdiff_t r1 = std::min(rows - 1, b.row_max + 1), c1 = std::min(cols - 1, b.col_max + 1);
            const std::ptrdiff_t nr = r1 - r0 + 1, nc = c1 - c0 + 1;
            if (nr < 3 || nc < 3) continue;
            holes.clear();
            const auto l = static_cast<std::int32_t>(body);
            holes_of_body(in.window(r0, c0, nr, nc), l, max_hole_cells, r0, c0, cols, other, holes);
            for (const auto cell : holes) out.push_back({cell, l});
        }
    });
    std::size_t filled = 0;
    for (const auto& block : found) {
        for (const auto& h : block) {
            labels(h.cell / cols, h.cell % cols) = h.label;
            ++filled;
        }
    }
    return filled;
}

/// Holes of the bodies of `labels` by one labelling of the land inside `bounds` (the bounding box of all
/// bodies grown by one cell): 4-connected land parts (connected_components) on the edge of that box or of
/// max_hole_cells cells or more are dropped (where the box's edge is not the raster's border, it is land
/// reaching the border outside the box); one pass finds each remaining part's neighbour bodies, and a part
/// next to exactly one body becomes it. O(area of bounds). Returns the cells filled.
inline std::size_t fill_holes_at_once(raster_view<std::int32_t> labels, std::size_t max_hole_cells, cell_box bounds,
                                      int threads)
{
    const std::ptrdiff_t nr = bounds.rows(), nc = bounds.cols();
    const auto box = labels.window(bounds.row_min, bounds.col_min, nr, nc);
    raster<std::uint8_t> land(nr, nc, uninitialized);
    for (std::ptrdiff_t r = 0; r < nr; ++r) {
        const std::int32_t* in = box.row(r);
        std::uint8_t* out = land.row(r);
        for (std::ptrdiff_t c = 0; c < nc; ++c) out[c] = in[c] == 0;
    }
    const auto parts = connected_components(
        land, connected_components_options{.conn = connectivity::four, .run = {.threads = threads}});
    // owner[k]: the body around part k while it may be a hole; 0 = none seen yet, -1 = not a hole (too
    // large, on the box's edge, or next to two bodies).
    std::vector<std::int32_t> owner(parts.sizes.size(), 0);
    owner[0] = -1;
    for (std::size_t k = 1; k < parts.sizes.size(); ++k)
        if (parts.sizes[k] >= max_hole_cells) owner[k] = -1;
    for (std::ptrdiff_t c = 0; c < nc; ++c)
        owner[static_cast<std::size_t>(parts.labels(0, c))] = owner[static_cast<std::size_t>(parts.labels(nr - 1, c))] =
            -1;
    for (std::ptrdiff_t r = 0; r < nr; ++r)
        owner[static_cast<std::size_t>(parts.labels(r, 0))] = owner[static_cast<std::size_t>(parts.labels(r, nc - 1))] =
            -1;
    const auto meet = [](std::int32_t& o, std::int32_t l) {
        if (l > 0 && o >= 0) o = o == 0 || o == l ? l : -1;
    };
    for (std::ptrdiff_t r = 1; r < nr - 1; ++r) {
        const std::int32_t* part = parts.labels.row(r);
        for (std::ptrdiff_t c = 1; c < nc - 1; ++c) {
            auto& o = owner[static_cast<std::size_t>(part[c])];
            if (o < 0) continue;
            meet(o, box(r - 1, c));
            meet(o, box(r + 1, c));
            meet(o, box(r, c - 1));
            meet(o, box(r, c + 1));
        }
    }
    std::size_t filled = 0;
    for (std::ptrdiff_t r = 1; r < nr - 1; ++r) {
        const std::int32_t* part = parts.labels.row(r);
        std::int32_t* out = box.row(r);
        for (std::ptrdiff_t c = 1; c < nc - 1; ++c) {
            const auto o = owner[static_cast<std::size_t>(part[c])];
            if (o <= 0) continue;
            out[c] = o;
            ++filled;
        }
    }
    return filled;
}

}  // namespace detail

inline std::size_t fill_small_islands(raster_view<std::int32_t> labels, double cell_m,
                                      const fill_small_islands_options& opt, const execution& run)
{
    constexpr const char* fn = "fill_small_islands";
    detail::require_positive(cell_m, fn, "cell_m");
    detail::require(opt.island_min_area_m2 >= 0, fn, "island_min_area_m2", ">= 0", opt.island_min_area_m2);
    detail::check_execution(run, fn);
    const std::ptrdiff_t rows = labels.rows(), cols = labels.cols();
    // Clamped so that any area converts; no raster holds 2^60 cells.
    const auto max_hole_cells =
        static_cast<std::size_t>(std::min(std::ceil(opt.island_min_area_m2 / (cell_m * cell_m)), 0x1p60));
    // One pass: the labels' range, the bounding box of all bodies (every hole lies inside it) and, while the
    // labels are few enough to keep a box each (at most cells / 8), every body's box. Per row a vectorized
    // min / max, then on a row that holds bodies its runs, land passed over in blocks: a run of one label
    // widens its box once.
    cell_box all{rows, cols, -1, -1};
    std::int32_t lowest = 0;
    std::vector<cell_box> boxes;
    bool boxed = max_hole_cells > 0;
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        const std::int32_t* row = labels.row(r);
        const auto [low, high] = detail::row_label_range(row, cols);
        lowest = std::min(lowest, low);
        if (high <= 0) continue;
        if (high > rows * cols / 8) boxed = false;
        if (boxed && boxes.size() <= static_cast<std::size_t>(high))
            boxes.resize(static_cast<std::size_t>(high) + 1, cell_box{rows, cols, -1, -1});
        std::ptrdiff_t first = cols, last = -1;
        for (std::ptrdiff_t c = detail::next_positive(row, 0, cols); c < cols;
             c = detail::next_positive(row, c, cols)) {
            const std::int32_t l = row[c];
            const std::ptrdiff_t start = c;
            while (c < cols && row[c] == l) ++c;
            first = std::min(first, start);
            last = c - 1;
            if (!boxed) continue;
            auto& b = boxes[static_cast<std::size_t>(l)];
            b = {std::min(b.row_min, r), std::min(b.col_min, start), r, std::max(b.col_max, c - 1)};
        }
        all = {std::min(all.row_min, r), std::min(all.col_min, first), r, std::max(all.col_max, last)};
    }
    detail::require(lowest >= 0, fn, "labels", ">= 0", lowest);
    detail::report(run.progress, 0.0, fn);
    std::size_t filled = 0;
    if (max_hole_cells > 0 && !all.empty()) {
        // What the boxes cover, when there are boxes.
        std::ptrdiff_t covered = rows * cols + 1;
        if (boxed) {
            covered = 0;
            for (const auto& b : boxes)
                if (!b.empty()) covered += (b.rows() + 2) * (b.cols() + 2);
        }
        if (covered <= rows * cols) {
            filled = detail::fill_holes_per_body(labels, max_hole_cells, boxes, run.threads);
        } else {
            const cell_box grown{std::max<std::ptrdiff_t>(0, all.row_min - 1),
                                 std::max<std::ptrdiff_t>(0, all.col_min - 1), std::min(rows - 1, all.row_max + 1),
                                 std::min(cols - 1, all.col_max + 1)};
            filled = detail::fill_holes_at_once(labels, max_hole_cells, grown, run.threads);
        }
    }
    detail::report(run.progress, 1.0, fn);
    return filled;
}

}  // namespace lidarfx
