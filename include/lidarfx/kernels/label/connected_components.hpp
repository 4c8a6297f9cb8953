// SPDX-License-Identifier: Apache-2.0
// Connected components of a mask (run-based union-find), and helpers: rank and renumber by size, drop small
// components, fill small holes, bounding boxes.
#pragma once

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numeric>
#include <type_traits>
#include <utility>
#include <vector>

#include "lidarfx/core/bit_mask.hpp"
#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/grid.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// Which neighbours join cells into one component: the 4 edge neighbours, or those plus the 4 diagonals.
enum class connectivity { four, eight };

/// Labelled components of a mask. labels(r, c) = 0 for background, else 1..count(); labels are numbered
/// in raster-scan order of each component's first cell (its top row, leftmost cell there).
/// sizes[label] = number of cells with that label; sizes[0] = number of background cells.
struct components {
    raster<std::int32_t> labels;
    std::vector<std::size_t> sizes;

    /// Number of components (labels 1..count()).
    std::size_t count() const noexcept { return sizes.empty() ? 0 : sizes.size() - 1; }
};

/// Settings of connected_components.
struct connected_components_options {
    connectivity conn = connectivity::eight;  ///< neighbourhood of foreground cells; default eight
    execution run = {};                       ///< threads, progress, cancellation (core/parallel.hpp); same result
};

/// Connected components of a mask (nonzero = foreground) under 4- or 8-connectivity, into `labels`
/// (same shape; 0 = background, 1..n in raster-scan order of each component's first cell); returns
/// sizes (sizes[label] = cells, sizes[0] = background cells).
/// Method: run-based two-pass union-find: runs of each row are linked to touching runs of the row
/// above (bands of rows in parallel, then joined along their edges), provisional labels are written,
/// and a second pass maps them to final labels. Identical for any thread count; progress is reported
/// between bands of rows. O(rows * cols) time; O(number of runs) extra memory.
/// @throws invalid_input if the shapes differ, run.threads < 0, m is wider than 2^24 columns, or the mask
/// has more runs than int32 labels can number; cancelled if run.progress returns false.
template <raster_input In, class Out>
requires raster_output_of<Out, std::int32_t> std::vector<std::size_t> connected_components(
    const In& m, Out&& labels, const connected_components_options& opt = {});

/// Returning form: labels and sizes of the components of m (see the into form above).
template <raster_input In>
components connected_components(const In& m, const connected_components_options& opt);

/// connected_components with the given connectivity on one thread.
template <raster_input In>
components connected_components(const In& m, connectivity c = connectivity::eight);

/// The rank of each label by decreasing size: given sizes[label] for labels 1..n (sizes[0], the
/// background, is not ranked), returns rank with rank[label] in 1..n (1 = largest; equal sizes keep label
/// order, so raster-scan order for connected_components' labels) and rank[0] = 0. Pass it to
/// relabel_components to renumber. O(n log n); no throws beyond allocation.
inline std::vector<std::int32_t> rank_components_by_size(const std::vector<std::size_t>& sizes);

/// Renumbers labels in place: labels(r, c) = to[labels(r, c)] for every label > 0; labels 0 and below are
/// left as they are (to[0] is not read). Each run of one label costs one lookup, and background is passed
/// over 64 cells at a time. Every label > 0 must be < to.size() (unchecked). O(rows * cols); no throws.
inline void relabel_components(raster_view<std::int32_t> labels, const std::vector<std::int32_t>& to);

/// Renumbers the components by decreasing size: label 1 becomes the largest; equal sizes keep their
/// raster-scan order (the earlier first cell first). Updates labels and sizes (sizes[0] stays the
/// background). O(rows * cols + n log n) for n components.
inline void rank_by_size(components& comps);

/// Bounding box of every label: result[label] for label 0 (background) .. count(); a label without
/// cells gets the empty box {0, 0, -1, -1}. O(rows * cols).
inline std::vector<cell_box> component_bounds(const components& comps);

/// The mask (as 0/1) keeping only its components of at least `min_cells` cells (inclusive), under
/// connectivity `c`. min_cells 0 or 1 keeps every component. O(rows * cols).
template <raster_input In>
raster<std::uint8_t> remove_small_components(const In& m, std::size_t min_cells, connectivity c = connectivity::eight);

/// The mask (as 0/1) with its small holes filled. A hole is a connected component of background cells
/// that touches no raster edge; background is connected with the complement of `c` (four when the
/// foreground uses eight, and the reverse), so that holes and objects never cross each other. Holes of
/// at most `max_hole_cells` cells become 1 (inclusive: 0 fills nothing); larger holes and background
/// reaching the border stay 0. O(rows * cols).
template <raster_input In>
raster<std::uint8_t> fill_holes(const In& m, std::size_t max_hole_cells, connectivity c = connectivity::eight);

}  // namespace lidarfx

#include "lidarfx/kernels/label/detail/connected_components_impl.hpp"
