// SPDX-License-Identifier: Apache-2.0
// Implementation of grow_waterbodies (included at the end of pipelines/water/grow_waterbodies.hpp): a seed's turn
// (the cells it grows from, the body it adds), and the turns in seed order, one after another or with floods
// grown ahead on other threads (detail/grow_waterbodies_ahead.hpp).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"

namespace lidarfx::detail {

/// The cells seed `cells` grows from, given the labels so far (> 0: a body): all of them when none is in a body,
/// else those outside the bodies (copied into `free_cells`) when they are at least min_free_seed_share of its cells.
/// False when the seed is skipped.
inline bool seed_cells_to_grow(std::span<const std::ptrdiff_t> cells, const std::int32_t* labels,
                               double min_free_seed_share, std::vector<std::ptrdiff_t>& free_cells,
                               std::span<const std::ptrdiff_t>& grow_from)
{
    const auto taken = static_cast<std::size_t>(
        std::count_if(cells.begin(), cells.end(), [&](std::ptrdiff_t i) { return labels[i] > 0; }));
    grow_from = cells;
    if (taken == 0) return true;
    const auto free = static_cast<double>(cells.size() - taken);
    if (taken == cells.size() || free < min_free_seed_share * static_cast<double>(cells.size())) return false;
    free_cells.clear();
    for (const auto i : cells)
        if (labels[i] <= 0) free_cells.push_back(i);
    grow_from = free_cells;
    return true;
}

/// Adds seed s's region as the next body of `out`: its cells take the body's label and leave the eligible cells,
/// then join_level_cells extends it (the body's label is its stamp: no cell holds it before). On return
/// region.cells holds every cell the body took. An empty region adds nothing.
inline void accept_body(grow_waterbody_result& region, std::size_t s, std::int32_t seed_offset,
                        raster_view<const float> min_z, raster_view<const float> max_z, std::uint8_t* eligible,
                        grow_waterbodies_result& out, const join_level_cells_options& level)
{
    if (region.cells.empty()) return;
    const auto label = static_cast<std::int32_t>(out.bodies.size() + 1);
    std::int32_t* labels = out.labels.data();  // in a local: the byte stores would reload it
    for (const auto i : region.cells) {
        labels[i] = label;
        eligible[i] = 0;
    }
    join_level_cells_stamped(region.cells, min_z, max_z, eligible, eligible, labels, label, level);
    auto& body = out.bodies.emplace_back();
    body.label = label;
    body.seed = static_cast<std::int32_t>(s) + seed_offset;
    body.theta_deg = region.theta_deg;
    body.stopped_by_ks = region.stopped_by_ks;
    ++out.seeds_grown;
}

}  // namespace lidarfx::detail

#include "lidarfx/pipelines/water/detail/grow_waterbodies_ahead.hpp"

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
    detail::check_execution(run, fn);
    const auto seed_lists = detail::seed_cells_flat(seeds, fn);
    const std::size_t n = seeds.count();
    if (n == 0) {
        detail::report(run.progress, 1.0, fn);
        return;
    }
    detail::validate(field, grow, fn);
    if (detail::resolve_threads(run.threads, fn) > 1 && n > 1) {
        detail::grow_waterbodies_ahead(field, seeds.labels.data(), seed_lists, n, min_z, max_z, into, grow, level, opt,
                                       seed_offset, run);
        return;
    }
    auto& out = into;
    // The label raster doubles as the floods' scratch: bodies are > 0, each flood marks the cells it visits
    // with its own negative stamp (cleared at the end).
    grow_waterbody_workspace workspace(out.labels.view());
    bool flooded = false;
    std::vector<std::ptrdiff_t> free_cells;
    for (std::size_t s = 1; s <= n; ++s) {
        detail::report(run.progress, static_cast<double>(s - 1) / static_cast<double>(n), fn);
        std::span<const std::ptrdiff_t> cells;
        if (!detail::seed_cells_to_grow(seed_lists.of(s), out.labels.data(), opt.min_free_seed_share, free_cells,
                                        cells))
            continue;
        const auto [marks, stamp] = workspace.next_flood(field.eligible.rows(), field.eligible.cols());
        auto region = detail::grow_waterbody_flood(field, field.eligible.data(), cells, grow, marks.data(), stamp,
                                                   [](std::ptrdiff_t) {});
        flooded = true;
        detail::accept_body(region, s, seed_offset, min_z, max_z, field.eligible.data(), out, level);
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
