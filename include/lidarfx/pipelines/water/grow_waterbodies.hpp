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

/// Options of grow_waterbodies.
struct grow_waterbodies_options {
    grow_waterbody_options grow = {};     ///< θ schedule and KS stop of each flood
    join_level_cells_options level = {};  ///< narrow-water refinement of each grown region
    double min_free_seed_share = 0.5;     ///< a seed partly inside the bodies grown before it grows from its
                                          ///< cells outside them when they are at least this share of its
                                          ///< cells (a seed that a body reached but stopped short of is still
                                          ///< water beyond it), else it is skipped; in (0, 1], 1 = skip a seed
                                          ///< with any cell in a body (before issue 17's eighth session). Default 0.5
    execution run = {};                   ///< progress per seed (fraction of seeds done); threads are not used:
                                          ///< seeds grow one after another (the order decides who owns a cell)
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
/// grow_waterbody floods from its cells outside them, and a
/// non-empty region is extended by join_level_cells (min_z, max_z in metres) and accepted as the next body;
/// its cells stop being eligible in `field` for the seeds that follow. This form adds to `into`: its
/// labels (the field's shape; 0 land, k + 1 for into.bodies[k]) and bodies are kept, new bodies are
/// numbered after them and record seed label + seed_offset (so that several rounds of seeds grow into one
/// raster without a merge). `field` must have the shape of the seeds; its eligible raster is updated.
/// O(cells + sum over seeds of cells reached). Progress: the fraction of seeds done, 0 before the first,
/// 1 at the end.
/// @throws invalid_input on shapes that differ or options out of range; cancelled.
inline void grow_waterbodies(water_field& field, const components& seeds, raster_view<const float> min_z,
                             raster_view<const float> max_z, grow_waterbodies_result& into,
                             const grow_waterbodies_options& opt = {}, std::int32_t seed_offset = 0)
{
    constexpr const char* fn = "grow_waterbodies";
    detail::require_same_shape(field.eligible, seeds.labels, fn, "field.eligible", "seeds.labels");
    detail::require_same_shape(field.eligible, min_z, fn, "field.eligible", "min_z");
    detail::require_same_shape(field.eligible, max_z, fn, "field.eligible", "max_z");
    detail::require_same_shape(field.eligible, into.labels, fn, "field.eligible", "into.labels");
    detail::validate(opt.grow, fn);
    detail::validate(opt.level, fn);
    detail::require(opt.min_free_seed_share > 0 && opt.min_free_seed_share <= 1, fn, "min_free_seed_share", "in (0, 1]",
                    opt.min_free_seed_share);
    const auto seed_lists = detail::seed_cells_flat(seeds, fn);
    const std::size_t n = seeds.count();
    auto& out = into;
    // The label raster doubles as the floods' scratch: bodies are > 0, each flood marks the cells it visits
    // with its own negative stamp (cleared at the end), and each refinement uses its body's new label as its
    // stamp (no cell holds it before: the labels so far are 1 .. bodies.size(), as documented).
    std::int32_t stamp = 0;
    std::vector<std::ptrdiff_t> free_cells;
    for (std::size_t s = 1; s <= n; ++s) {
        detail::report(opt.run.progress, static_cast<double>(s - 1) / static_cast<double>(n), fn);
        // The seed's cells outside the bodies so far (all of them, mostly: then the seed's own list).
        std::span<const std::ptrdiff_t> cells = seed_lists.of(s);
        const auto taken = static_cast<std::size_t>(
            std::count_if(cells.begin(), cells.end(), [&](std::ptrdiff_t i) { return out.labels.data()[i] > 0; }));
        if (taken > 0) {
            const auto free = static_cast<double>(cells.size() - taken);
            if (taken == cells.size() || free < opt.min_free_seed_share * static_cast<double>(cells.size())) continue;
            free_cells.clear();
            for (const auto i : cells)
                if (out.labels.data()[i] <= 0) free_cells.push_back(i);
            cells = free_cells;
        }
        auto region = grow_waterbody(field, cells, opt.grow, out.labels, --stamp);
        if (region.cells.empty()) continue;
        // The body's label is join_level_cells' stamp: the region is labelled and taken first, and the cells
        // the refinement joins get the label and leave the eligible cells as they join.
        const auto label = static_cast<std::int32_t>(out.bodies.size() + 1);
        std::int32_t* labels = out.labels.data();  // in locals: the byte stores would reload them
        std::uint8_t* eligible = field.eligible.data();
        for (const auto i : region.cells) {
            labels[i] = label;
            eligible[i] = 0;
        }
        detail::join_level_cells_stamped(region.cells, min_z, max_z, eligible, eligible, labels, label, opt.level);
        auto& body = out.bodies.emplace_back();
        body.label = label;
        body.seed = static_cast<std::int32_t>(s) + seed_offset;
        body.theta_deg = region.theta_deg;
        body.stopped_by_ks = region.stopped_by_ks;
        ++out.seeds_grown;
    }
    if (stamp < 0)
        for (auto& l : out.labels) l = std::max(l, 0);
    detail::report(opt.run.progress, 1.0, fn);
}

/// Grows the seeds into waterbodies on a raster of land: the form above into an empty result.
inline grow_waterbodies_result grow_waterbodies(water_field& field, const components& seeds,
                                                raster_view<const float> min_z, raster_view<const float> max_z,
                                                const grow_waterbodies_options& opt = {})
{
    grow_waterbodies_result out{raster<std::int32_t>(seeds.labels.rows(), seeds.labels.cols(), 0), {}, 0};
    grow_waterbodies(field, seeds, min_z, max_z, out, opt);
    return out;
}

}  // namespace lidarfx
