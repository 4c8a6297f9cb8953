// SPDX-License-Identifier: Apache-2.0
// Implementation of tiling/stitch_labels.hpp: labelling tile by tile, a union-find over the tiles' pieces joined
// across tile borders, and the final numbering. Included at the end of stitch_labels.hpp, after the declarations it
// defines; not a public header.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numeric>
#include <type_traits>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/grid.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/kernels/label/connected_components.hpp"

namespace lidarfx {

namespace detail {

/// Union-find over the pieces (tile-local components) of all tiles; the root of a set is its smallest id.
class piece_forest {
public:
    explicit piece_forest(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), std::size_t{0}); }
    std::size_t find(std::size_t x) noexcept
    {
        while (parent_[x] != x) {
            parent_[x] = parent_[parent_[x]];  // path halving
            x = parent_[x];
        }
        return x;
    }
    void join(std::size_t a, std::size_t b) noexcept
    {
        a = find(a);
        b = find(b);
        if (a < b)
            parent_[b] = a;
        else if (b < a)
            parent_[a] = b;
    }

private:
    std::vector<std::size_t> parent_;
};

/// What a tile knows of one of its pieces (index 0: the tile's background cells).
struct piece_stats {
    std::size_t cells = 0;
    cell_box box;  ///< whole-raster cells
    std::int64_t sum = 0;
    std::ptrdiff_t first = std::numeric_limits<std::ptrdiff_t>::max();  ///< row-major index of its first cell
};

/// The tiling of a stitch: square tiles of `t` cells, row-major, and the global id of every piece (offset of
/// its tile + its local label; local 0 = that tile's background).
struct piece_tiling {
    std::ptrdiff_t t, tile_cols;
    std::vector<std::size_t> offset;  ///< per tile, its first piece id; offset[tiles] = all pieces

    std::size_t tile_of(std::ptrdiff_t r, std::ptrdiff_t c) const noexcept
    {
        return static_cast<std::size_t>(r / t * tile_cols + c / t);
    }
    std::size_t id(raster_view<const std::int32_t> labels, std::ptrdiff_t r, std::ptrdiff_t c) const noexcept
    {
        return offset[tile_of(r, c)] + static_cast<std::size_t>(labels(r, c));
    }
};

/// Stage 1, per tile and independent: local labels (1..n in the tile's raster-scan order) written into the tile's
/// cells of `labels`, and each piece's cells, box, sum and first cell. Progress 0 to 0.8.
template <class T, class V>
std::vector<std::vector<piece_stats>> label_tiles(raster_view<const T> m, const raster_view<const V>* values,
                                                  raster_view<std::int32_t> labels, std::ptrdiff_t t,
                                                  std::ptrdiff_t tile_cols, const stitch_labels_options& opt,
                                                  const char* function)
{
    const std::ptrdiff_t rows = m.rows(), cols = m.cols();
    const std::ptrdiff_t tiles = (rows + t - 1) / t * tile_cols;
    std::vector<std::vector<piece_stats>> pieces(static_cast<std::size_t>(tiles));
    parallel_for_rows(
        tiles, 1, opt.run.threads,
        [&](std::ptrdiff_t first, std::ptrdiff_t last) {
            for (std::ptrdiff_t i = first; i < last; ++i) {
                const std::ptrdiff_t r0 = i / tile_cols * t, c0 = i % tile_cols * t;
                const std::ptrdiff_t nr = std::min(t, rows - r0), nc = std::min(t, cols - c0);
                const raster_view<std::int32_t> local = labels.window(r0, c0, nr, nc);
                const std::vector<std::size_t> sizes =
                    connected_components(m.window(r0, c0, nr, nc), local, {.conn = opt.conn});
                std::vector<piece_stats>& p = pieces[static_cast<std::size_t>(i)];
                p.resize(sizes.size());
                for (std::ptrdiff_t r = 0; r < nr; ++r) {
                    for (std::ptrdiff_t c = 0; c < nc; ++c) {
                        piece_stats& s = p[static_cast<std::size_t>(local(r, c))];
                        if (s.cells == 0) s.first = (r0 + r) * cols + c0 + c;
                        ++s.cells;
                        s.box.extend(r0 + r, c0 + c);
                        if (values) s.sum += static_cast<std::int64_t>((*values)(r0 + r, c0 + c));
                    }
                }
            }
        },
        detail::progress_phase(opt.run.progress, 0.0, 0.8), function);
    return pieces;
}

/// Stage 2: joins the pieces that touch across the seams between tiles.
inline void join_across_seams(raster_view<const std::int32_t> labels, const piece_tiling& tiling, connectivity conn,
                              piece_forest& forest)
{
    const std::ptrdiff_t rows = labels.rows(), cols = labels.cols(), t = tiling.t;
    const std::ptrdiff_t diag = conn == connectivity::eight ? 1 : 0;
    // Vertical seams: cell (r, c - 1) and the cells (r + d, c) of the next tile, |d| <= diag. The diagonal pairs
    // that also cross a horizontal seam (tile corners) are among them.
    for (std::ptrdiff_t c = t; c < cols; c += t) {
        for (std::ptrdiff_t r = 0; r < rows; ++r) {
            if (labels(r, c - 1) == 0) continue;
            for (std::ptrdiff_t d = -diag; d <= diag; ++d) {
                if (r + d < 0 || r + d >= rows || labels(r + d, c) == 0) continue;
                forest.join(tiling.id(labels, r, c - 1), tiling.id(labels, r + d, c));
            }
        }
    }
    // Horizontal seams: cell (r - 1, c) and the cells (r, c + d) below it.
    for (std::ptrdiff_t r = t; r < rows; r += t) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            if (labels(r - 1, c) == 0) continue;
            for (std::ptrdiff_t d = -diag; d <= diag; ++d) {
                if (c + d < 0 || c + d >= cols || labels(r, c + d) == 0) continue;
                forest.join(tiling.id(labels, r - 1, c), tiling.id(labels, r, c + d));
            }
        }
    }
}

/// Stage 3: merges the statistics of every set (exact: counts, boxes and integer sums), orders the sets by their
/// first cell in raster-scan order, as connected_components numbers them, fills out's sizes, boxes and sums
/// (sums only with values) and returns each piece's final label.
inline std::vector<std::int32_t> number_sets(const std::vector<std::vector<piece_stats>>& pieces,
                                             const piece_tiling& tiling, piece_forest& forest, bool with_values,
                                             stitched_components& out, const char* function)
{
    const std::vector<std::size_t>& offset = tiling.offset;
    const std::size_t tiles = pieces.size();
    std::vector<piece_stats> merged(offset[tiles]);
    piece_stats background;
    for (std::size_t i = 0; i < tiles; ++i) {
        for (std::size_t l = 0; l < pieces[i].size(); ++l) {
            const piece_stats& s = pieces[i][l];
            piece_stats& into = l == 0 ? background : merged[forest.find(offset[i] + l)];
            if (s.cells == 0) continue;
            into.cells += s.cells;
            into.sum += s.sum;
            into.first = std::min(into.first, s.first);
            into.box.extend(s.box.row_min, s.box.col_min);
            into.box.extend(s.box.row_max, s.box.col_max);
        }
    }
    std::vector<std::size_t> roots;
    for (std::size_t i = 0; i < tiles; ++i) {
        for (std::size_t l = 1; l < pieces[i].size(); ++l) {
            if (forest.find(offset[i] + l) == offset[i] + l) roots.push_back(offset[i] + l);
        }
    }
    std::sort(roots.begin(), roots.end(),
              [&](std::size_t a, std::size_t b) { return merged[a].first < merged[b].first; });
    detail::require(roots.size() <= static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()), function,
                    "the mask has more components than int32 labels can number");
    std::vector<std::int32_t> final_label(offset[tiles], 0);
    out.sizes.assign(roots.size() + 1, 0);
    out.boxes.assign(roots.size() + 1, cell_box{});
    if (with_values) out.sums.assign(roots.size() + 1, 0);
    out.sizes[0] = background.cells;
    out.boxes[0] = background.box;
    if (with_values) out.sums[0] = background.sum;
    for (std::size_t k = 0; k < roots.size(); ++k) {
        const piece_stats& s = merged[roots[k]];
        final_label[roots[k]] = static_cast<std::int32_t>(k + 1);
        out.sizes[k + 1] = s.cells;
        out.boxes[k + 1] = s.box;
        if (with_values) out.sums[k + 1] = s.sum;
    }
    for (std::size_t i = 0; i < tiles; ++i) {
        for (std::size_t l = 1; l < pieces[i].size(); ++l) {
            final_label[offset[i] + l] = final_label[forest.find(offset[i] + l)];
        }
    }
    return final_label;
}

template <class T, class V>
stitched_components stitch_labels_view(raster_view<const T> m, const raster_view<const V>* values,
                                       const stitch_labels_options& opt, const char* function)
{
    const std::ptrdiff_t rows = m.rows(), cols = m.cols();
    stitched_components out{raster<std::int32_t>(rows, cols, uninitialized), {}, {}, {}};
    const std::ptrdiff_t t = std::min(opt.tile_cells, std::max<std::ptrdiff_t>({rows, cols, 1}));
    piece_tiling tiling{t, (cols + t - 1) / t, {}};
    const raster_view<std::int32_t> labels = out.labels.view();
    const std::vector<std::vector<piece_stats>> pieces =
        label_tiles(m, values, labels, t, tiling.tile_cols, opt, function);
    tiling.offset.assign(pieces.size() + 1, 0);
    for (std::size_t i = 0; i < pieces.size(); ++i) tiling.offset[i + 1] = tiling.offset[i] + pieces[i].size();
    piece_forest forest(tiling.offset.back());
    join_across_seams(labels, tiling, opt.conn, forest);
    const std::vector<std::int32_t> final_label = number_sets(pieces, tiling, forest, values != nullptr, out, function);
    parallel_for_rows(
        rows, 64, opt.run.threads,
        [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
            for (std::ptrdiff_t r = r0; r < r1; ++r) {
                for (std::ptrdiff_t c = 0; c < cols; ++c) {
                    if (labels(r, c) != 0) labels(r, c) = final_label[tiling.id(labels, r, c)];
                }
            }
        },
        detail::progress_phase(opt.run.progress, 0.8, 1.0), function);
    return out;
}

template <class In>
void check_stitch_labels(const In& m, const stitch_labels_options& opt, const char* function)
{
    static_assert(std::is_arithmetic_v<typename In::value_type>, "a mask holds numbers (nonzero = foreground)");
    detail::check_execution(opt.run, function);
    detail::require(opt.tile_cells >= 1, function, "tile_cells", ">= 1", opt.tile_cells);
    detail::require(m.rows() >= 0 && m.cols() >= 0, function, "the mask extents must be >= 0");
}

}  // namespace detail

template <raster_input In>
stitched_components stitch_labels(const In& m, const stitch_labels_options& opt)
{
    constexpr const char* function = "stitch_labels";
    detail::check_stitch_labels(m, opt, function);
    const detail::readable<In> in(m);
    return detail::stitch_labels_view<typename In::value_type, std::int64_t>(in.view(), nullptr, opt, function);
}

template <raster_input In, raster_input Values>
requires std::is_integral_v<typename Values::value_type> stitched_components
stitch_labels(const In& m, const Values& values, const stitch_labels_options& opt)
{
    constexpr const char* function = "stitch_labels";
    detail::check_stitch_labels(m, opt, function);
    detail::require_same_shape(m, values, function, "m", "values");
    const detail::readable<In> in(m);
    const detail::readable<Values> v(values);
    const auto view = v.view();
    return detail::stitch_labels_view<typename In::value_type, typename Values::value_type>(in.view(), &view, opt,
                                                                                            function);
}

}  // namespace lidarfx
