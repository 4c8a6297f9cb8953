// SPDX-License-Identifier: Apache-2.0
// Implementation of grow_waterbodies (included at the end of pipelines/water/grow_waterbodies.hpp).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"

namespace lidarfx {

inline void grow_waterbodies(water_field& field, const components& seeds, raster_view<const float> min_z,
                             raster_view<const float> max_z, grow_waterbodies_result& into,
                             const grow_waterbody_options& grow, const join_level_cells_options& level,
                             const grow_waterbodies_options& opt, std::int32_t seed_offset, const execution& run)
{
    constexpr const char* fn = "grow_waterbodies";
    detail::require_same_shape(field.eligible, seeds.labels, fn, "field.eligible", "seeds.labels");
    detail::require_same_shape(field.eligible, min_z, fn, "field.eligible", "min_z");
    detail::require_same_shape(field.eligible, max_z, fn, "field.eligible", "max_z");
    detail::require_same_shape(field.eligible, into.labels, fn, "field.eligible", "into.labels");
    detail::validate(grow, fn);
    detail::validate(level, fn);
    detail::require(opt.min_free_seed_share > 0 && opt.min_free_seed_share <= 1, fn, "min_free_seed_share", "in (0, 1]",
                    opt.min_free_seed_share);
    const auto seed_lists = detail::seed_cells_flat(seeds, fn);
    const std::size_t n = seeds.count();
    auto& out = into;
    // The label raster doubles as the floods' scratch: bodies are > 0, each flood marks the cells it visits
    // with its own negative stamp (cleared at the end), and each refinement uses its body's new label as its
    // stamp (no cell holds it before: the labels so far are 1 .. bodies.size(), as documented).
    grow_waterbody_workspace workspace(out.labels.view());
    bool flooded = false;
    std::vector<std::ptrdiff_t> free_cells;
    for (std::size_t s = 1; s <= n; ++s) {
        detail::report(run.progress, static_cast<double>(s - 1) / static_cast<double>(n), fn);
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
        auto region = grow_waterbody(field, cells, grow, workspace);
        flooded = true;
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
        detail::join_level_cells_stamped(region.cells, min_z, max_z, eligible, eligible, labels, label, level);
        auto& body = out.bodies.emplace_back();
        body.label = label;
        body.seed = static_cast<std::int32_t>(s) + seed_offset;
        body.theta_deg = region.theta_deg;
        body.stopped_by_ks = region.stopped_by_ks;
        ++out.seeds_grown;
    }
    if (flooded) workspace.clear_marks();
    detail::report(run.progress, 1.0, fn);
}

inline grow_waterbodies_result grow_waterbodies(water_field& field, const components& seeds,
                                                raster_view<const float> min_z, raster_view<const float> max_z,
                                                const grow_waterbody_options& grow,
                                                const join_level_cells_options& level,
                                                const grow_waterbodies_options& opt, const execution& run)
{
    grow_waterbodies_result out{raster<std::int32_t>(seeds.labels.rows(), seeds.labels.cols(), 0), {}, 0};
    grow_waterbodies(field, seeds, min_z, max_z, out, grow, level, opt, 0, run);
    return out;
}

}  // namespace lidarfx
