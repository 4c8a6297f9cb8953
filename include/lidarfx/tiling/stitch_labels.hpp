// SPDX-License-Identifier: Apache-2.0
// stitch_labels: connected components computed tile by tile and joined across tile borders with union-find,
// numbered and measured exactly as connected_components over the whole mask (docs/scale.md).
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

/// Settings of stitch_labels.
struct stitch_labels_options {
    connectivity conn = connectivity::eight;  ///< neighbourhood of foreground cells, as connected_components
    std::ptrdiff_t tile_cells = 256;          ///< tile edge, cells, >= 1 (the last row / column of tiles smaller)
    execution run = {};                       ///< threads (tiles labelled at once), progress; never changes the result
};

/// Components of a mask with per-label statistics. labels and sizes are those of connected_components: 0 =
/// background, 1..count() in raster-scan order of each component's first cell; index 0 of every vector is the
/// background.
struct stitched_components {
    raster<std::int32_t> labels;
    std::vector<std::size_t> sizes;  ///< cells per label (sizes[0] = background cells)
    std::vector<cell_box> boxes;     ///< bounding box per label, as component_bounds (empty box if no cell)
    std::vector<std::int64_t> sums;  ///< sum of `values` over each label's cells (empty without values)

    std::size_t count() const noexcept { return sizes.empty() ? 0 : sizes.size() - 1; }
};

/// Connected components of a mask (nonzero = foreground) computed tile by tile: each tile of tile_cells x
/// tile_cells is labelled on its own (connected_components), pieces that touch across a tile border (edge
/// neighbours, and diagonal ones under 8-connectivity, tile corners included) are joined with union-find, and
/// the sets are numbered by their first cell in raster-scan order. labels and sizes equal
/// connected_components(m, conn) for every tile size and thread count; boxes equal component_bounds. The
/// statistics are merged per piece, exactly (counts and boxes), so a host holding only border rows and piece
/// tables could stitch the same way. O(rows * cols + pieces log pieces).
/// @throws invalid_input if tile_cells < 1, run.threads < 0, a tile is wider than 2^24 columns, or there are
/// more components than int32 labels; cancelled if run.progress returns false.
template <raster_input In>
stitched_components stitch_labels(const In& m, const stitch_labels_options& opt = {});

/// stitch_labels with sums: sums[label] = sum of values(r, c) over the label's cells, in int64 (exact, in any
/// order of tiles). values holds integers (e.g. intensity in fixed point, counts) and has m's shape.
/// @throws invalid_input as stitch_labels, or if the shapes differ.
template <raster_input In, raster_input Values>
requires std::is_integral_v<typename Values::value_type> stitched_components
stitch_labels(const In& m, const Values& values, const stitch_labels_options& opt = {});

}  // namespace lidarfx

#include "lidarfx/tiling/detail/stitch_labels_impl.hpp"
