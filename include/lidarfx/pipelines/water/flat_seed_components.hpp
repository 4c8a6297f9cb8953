// SPDX-License-Identifier: Apache-2.0
// flat_seed_components: the components of level cells that flat_water_seeds tests, and their sums.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/pipelines/water/flat_water_seeds_options.hpp"
#include "lidarfx/pipelines/water/water_rasters.hpp"

namespace lidarfx {

/// The components of level cells flat_water_seeds tests, and what it sums over them. Per-label vectors
/// have count() + 1 entries (entry 0 unused, 0).
struct flat_seed_components {
    raster<std::int32_t> labels;          ///< 1..count(): a component of >= min_cells level cells (8-connected),
                                          ///< numbered in raster-scan order of its first cell; -1: a cell of a
                                          ///< smaller component; 0: no level cell
    std::vector<std::size_t> sizes;       ///< cells of each label
    std::vector<std::size_t> free_cells;  ///< cells of each label not `taken`; a label without any is no seed
    std::vector<double> count_sum;        ///< sum of in.count over the label's cells (row order), only for
                                          ///< labels with free cells (else 0)
    std::vector<double> intensity_sum;    ///< sum of in.mean_intensity, likewise
    std::vector<double> roughness_sum;    ///< sum of max z − min z (metres), likewise
    std::vector<float> level_roughness;   ///< max z − min z of every level cell, in row order (metres): the
                                          ///< survey's typical roughness is its median

    /// Number of components (labels 1..count()).
    std::size_t count() const noexcept { return sizes.empty() ? 0 : sizes.size() - 1; }
};

/// Second step of flat_water_seeds: labels the 8-connected components of `level` (nonzero = level cell,
/// flat_level_cells), keeps those of at least opt.min_cells cells as labels 1..n (renumbered in label
/// order, so raster-scan order) and marks the cells of smaller ones -1; then sums in.count,
/// in.mean_intensity and max z − min z over each kept component that has a cell outside `taken`
/// (optional, same shape; > 0 = a cell of a body grown before), in row order, and lists the roughness of
/// every level cell. `storage`: memory for the labels (any shape; replaced when the shape differs; its
/// contents are overwritten), so a caller that labels again reuses pages already touched. Needs in.count.
/// O(cells); labelling on run.threads (its progress is not called), the same result for any count.
/// @throws invalid_input on rasters of different shapes, no in.count, or options or run out of range.
inline flat_seed_components label_flat_seed_components(const water_rasters& in, raster_view<const std::uint8_t> level,
                                                       raster_view<const std::int32_t> taken = {},
                                                       const flat_water_seeds_options& opt = {},
                                                       raster<std::int32_t> storage = {}, const execution& run = {});

}  // namespace lidarfx

#include "lidarfx/pipelines/water/detail/flat_seed_components_impl.hpp"
