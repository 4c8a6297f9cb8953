// SPDX-License-Identifier: Apache-2.0
// fill_small_islands: small land holes inside one waterbody become part of it; islands stay land.
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

/// Options of fill_small_islands.
struct fill_small_islands_options {
    double island_min_area_m2 = 200.0;  ///< holes of at least this area stay land (islands), smaller ones
                                        ///< become water, m²; >= 0, 0 keeps every hole. Default 200 m².
};

/// Fills the small holes of waterbodies. A hole is a 4-connected component of land cells (label 0) that
/// touches no raster edge and whose 4-neighbours all carry one body's label; it becomes part of that body
/// when its area, cells · cell_m², is below island_min_area_m2 (it holds fewer than
/// ceil(island_min_area_m2 / cell_m²) cells). Land next to two bodies, or reaching the border, stays land.
/// Built on the label kernels (connected_components, 4-connected) in one of two ways with the same result:
/// per body, over the body's bounding box grown by one cell, while the boxes' areas add up to at most the
/// raster's cells (the usual case, and the least memory: a few compact bodies); otherwise in one labelling
/// of the land inside the box of all bodies, so that nested boxes never cost more than O(cells).
/// O(cells). `run`: threads of the labelling, progress (0 on entry, 1 when done) and cancellation; never changes
/// the result. Returns the number of cells filled.
/// @throws invalid_input on cell_m <= 0, options or run out of range, negative labels; cancelled.
inline std::size_t fill_small_islands(raster_view<std::int32_t> labels, double cell_m,
                                      const fill_small_islands_options& opt = {}, const execution& run = {});

}  // namespace lidarfx

#include "lidarfx/pipelines/water/detail/fill_small_islands_impl.hpp"
