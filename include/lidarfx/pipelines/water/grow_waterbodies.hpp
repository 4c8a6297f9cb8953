// SPDX-License-Identifier: Apache-2.0
// grow_waterbodies: every seed grown in turn, largest first, each body refined to its water level.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/kernels/label/connected_components.hpp"
#include "lidarfx/pipelines/water/grow_waterbody.hpp"
#include "lidarfx/pipelines/water/join_level_cells.hpp"
#include "lidarfx/pipelines/water/measure_waterbodies.hpp"
#include "lidarfx/pipelines/water/water_seeds.hpp"

namespace lidarfx {

/// Options of grow_waterbodies itself (each flood's options and the refinement's are passed beside them).
struct grow_waterbodies_options {
    double min_free_seed_share = 0.5;  ///< a seed partly inside the bodies grown before it grows from its cells
                                       ///< outside them when they are at least this share of its cells (a seed
                                       ///< that a body reached but stopped short of is still water beyond it),
                                       ///< else it is skipped; in (0, 1], 1 = skip a seed with any cell in a body.
                                       ///< Default 0.5
};

/// Bodies grown from the seeds, in growth order.
struct grow_waterbodies_result {
    raster<std::int32_t> labels;    ///< 0 land, k + 1 for bodies[k]
    std::vector<waterbody> bodies;  ///< growth records: seed, theta_deg, stopped_by_ks (measure_waterbodies
                                    ///< numbers and measures them)
    std::size_t seeds_grown = 0;    ///< seeds that gave a body (== bodies.size())
};

/// Grows the seeds into waterbodies (dissertation 2.3.3), largest seed first (seed label 1 first): a seed
/// with fewer than min_free_seed_share of its cells outside the accepted bodies is skipped; otherwise
/// grow_waterbody floods from its cells outside them (options `grow`), and a
/// non-empty region is extended by join_level_cells (options `level`; min_z, max_z in metres) and accepted as the next
/// body; its cells stop being eligible in `field` for the seeds that follow. This form adds to `into`: its labels (the
/// field's shape; 0 land, k + 1 for into.bodies[k]) and bodies are kept, new bodies are numbered after them and record
/// seed label + seed_offset (so that several rounds of seeds grow into one raster without a merge); their cells must
/// not be eligible in `field` (as an earlier call leaves them). `field` must have the shape of the seeds; its eligible
/// raster is updated. O(cells + sum over seeds of cells reached). `run`:
/// progress (the fraction of seeds done, 0 before the first, 1 at the end) and cancellation, and threads: the seeds
/// take their turns in order (the order decides who owns a cell), and with threads > 1 their floods are grown ahead
/// on other threads, each kept when no body accepted before its turn touched a cell it read and grown again
/// otherwise. The result is the same bit for bit for any thread count. Threads > 1 cost 1 byte a cell for a copy of
/// the eligible cells and 1 byte a cell per thread, and 16 bytes per cell reached by each of at most 2 floods per
/// thread grown ahead. A lazy field.surface_slope is read by every thread.
/// @throws invalid_input on shapes that differ or options out of range; cancelled.
inline void grow_waterbodies(water_field& field, const components& seeds, raster_view<const float> min_z,
                             raster_view<const float> max_z, grow_waterbodies_result& into,
                             const grow_waterbody_options& grow = {}, const join_level_cells_options& level = {},
                             const grow_waterbodies_options& opt = {}, std::int32_t seed_offset = 0,
                             const execution& run = {});
/// Grows the seeds into waterbodies on a raster of land: the form above into an empty result.
inline grow_waterbodies_result grow_waterbodies(water_field& field, const components& seeds,
                                                raster_view<const float> min_z, raster_view<const float> max_z,
                                                const grow_waterbody_options& grow = {},
                                                const join_level_cells_options& level = {},
                                                const grow_waterbodies_options& opt = {}, const execution& run = {});

}  // namespace lidarfx

#include "lidarfx/pipelines/water/detail/grow_waterbodies_impl.hpp"
