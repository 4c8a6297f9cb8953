// SPDX-License-Identifier: Apache-2.0
// Implementation of hydro_flatten (included at the end of pipelines/water/hydro_flatten.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/grid.hpp"
#include "lidarfx/kernels/label/connected_components.hpp"
#include "lidarfx/pipelines/water/fill_small_islands.hpp"

namespace lidarfx {

namespace detail {

inline void validate(const hydro_flatten_options& o, const char* fn)
{
    const auto at_least = [fn](double v, double low, const char* name) {
        require(std::isfinite(v) && v >= low, fn, name, low == 0 ? "finite and >= 0" : "finite and >= 1", v);
    };
    at_least(o.min_lake_area_m2, 0, "min_lake_area_m2");
    at_least(o.min_river_width_m, 0, "min_river_width_m");
    at_least(o.min_island_area_m2, 0, "min_island_area_m2");
    at_least(o.min_river_elongation, 1, "min_river_elongation");
    at_least(o.flat_tolerance_m, 0, "flat_tolerance_m");
    check_execution(o.run, fn);
    validate(o.lake, fn);
    validate(o.river, fn);
    validate(o.join, fn);
    validate(o.decks, fn);
}

/// Land cells 8-adjacent to body `id` (inside `box` grown by one cell) whose value in `after` exceeds `before`.
inline std::size_t cells_lifted_beside(raster_view<const std::int32_t> body, raster_view<const float> before,
                                       raster_view<const float> after, std::int32_t id, const cell_box& box)
{
    std::size_t lifted = 0;
    for_each_shore_cell(body, id, box,
                        [&](std::ptrdiff_t r, std::ptrdiff_t c) { lifted += after(r, c) > before(r, c); });
    return lifted;
}

/// The bounding box of every label 1..top of `labels` (box[0] unused).
inline std::vector<cell_box> label_boxes(raster_view<const std::int32_t> labels, std::int32_t top)
{
    std::vector<cell_box> box(static_cast<std::size_t>(top) + 1);
    for (std::ptrdiff_t r = 0; r < labels.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < labels.cols(); ++c)
            if (const std::int32_t l = labels(r, c); l > 0) box[static_cast<std::size_t>(l)].extend(r, c);
    return box;
}

/// Splits every body of `labels` made of several 8-connected parts: the largest part keeps its label, the
/// others (by decreasing size, then raster order of their first cell) take new labels after the last one, and
/// `box` grows with their boxes. Bodies are visited in label order, so the numbering is fixed.
inline void split_into_parts(raster_view<std::int32_t> labels, std::vector<cell_box>& box)
{
    const std::size_t bodies = box.size();
    for (std::size_t l = 1; l < bodies; ++l) {
        const cell_box bx = box[l];
        if (bx.empty()) continue;
        components parts = connected_components(body_mask(labels, static_cast<std::int32_t>(l), bx));
        if (parts.count() < 2) continue;
        rank_by_size(parts);
        std::vector<cell_box> part_box(parts.count() + 1);
        for (std::ptrdiff_t r = 0; r < bx.rows(); ++r)
            for (std::ptrdiff_t c = 0; c < bx.cols(); ++c) {
                const std::int32_t k = parts.labels(r, c);
                if (k < 2) continue;
                const auto id = static_cast<std::int32_t>(box.size()) + k - 2;
                labels(bx.row_min + r, bx.col_min + c) = id;
                part_box[static_cast<std::size_t>(k)].extend(bx.row_min + r, bx.col_min + c);
            }
        box[l] = {};
        for (std::ptrdiff_t r = 0; r < bx.rows(); ++r)
            for (std::ptrdiff_t c = 0; c < bx.cols(); ++c)
                if (parts.labels(r, c) == 1) box[l].extend(bx.row_min + r, bx.col_min + c);
        box.insert(box.end(), part_box.begin() + 2, part_box.end());
    }
}

/// hydro_flatten's step 4b: water_under_decks on the flattened rivers of `out`; the DEM takes the new water and
/// the bodies' boxes grow with it.
inline void continue_under_decks(hydro_flatten_result& out, raster_view<const float> min_z, double cell_m,
                                 const water_under_decks_options& opt)
{
    std::vector<std::int32_t> rivers;
    std::vector<std::size_t> index;  // per id: its position in out.bodies
    for (std::size_t i = 0; i < out.bodies.size(); ++i) {
        const hydro_body& b = out.bodies[i];
        if (!b.flattened || b.type != hydro_body_type::river) continue;
        rivers.push_back(b.id);
        if (index.size() <= static_cast<std::size_t>(b.id)) index.resize(static_cast<std::size_t>(b.id) + 1);
        index[static_cast<std::size_t>(b.id)] = i;
    }
    if (rivers.empty()) return;
    const raster<std::int32_t> before(out.body);
    out.decks = water_under_decks(out.body, out.water_surface, min_z, rivers, cell_m, opt);
    if (out.decks.level_cells + out.decks.deck_cells == 0) return;
    for (std::ptrdiff_t r = 0; r < before.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < before.cols(); ++c) {
            const std::int32_t id = out.body(r, c);
            if (id == before(r, c)) continue;
            out.dem(r, c) = out.water_surface(r, c);
            out.bodies[index[static_cast<std::size_t>(id)]].box.extend(r, c);
        }
}

}  // namespace detail

inline hydro_flatten_result hydro_flatten(raster_view<const float> dem, raster_view<const std::int32_t> labels,
                                          raster_view<const float> min_z, raster_view<const float> max_z, double cell_m,
                                          const hydro_flatten_options& opt)
{
    constexpr const char* fn = "hydro_flatten";
    detail::require_same_shape(dem, labels, fn, "dem", "labels");
    detail::require_same_shape(dem, min_z, fn, "dem", "min_z");
    detail::require_same_shape(dem, max_z, fn, "dem", "max_z");
    detail::require_positive(cell_m, fn, "cell_m");
    detail::validate(opt, fn);
    detail::report(opt.run.progress, 0, fn);

    for (std::ptrdiff_t r = 0; r < labels.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < labels.cols(); ++c)
            detail::require(labels(r, c) >= 0, fn, "labels", ">= 0", labels(r, c));

    // 1. Islands under the minimum flatten with their body (the first tenth of the progress).
    raster<std::int32_t> filled(labels);
    hydro_flatten_result out;
    execution fill_run{.threads = opt.run.threads};
    if (opt.run.progress) fill_run.progress = [&](double f) { return opt.run.progress(0.1 * f); };
    out.island_cells_flattened =
        fill_small_islands(filled, cell_m, {.island_min_area_m2 = opt.min_island_area_m2}, fill_run);
    std::int32_t top = 0;
    for (const std::int32_t l : filled) top = std::max(top, l);
    std::vector<cell_box> box = detail::label_boxes(filled, top);
    detail::split_into_parts(filled, box);
    if (opt.join_channels) out.joins = join_channel_parts(filled, box, min_z, cell_m, opt.join);
    top = static_cast<std::int32_t>(box.size()) - 1;
    const raster<float> water_z = water_heights(filled, min_z, max_z);

    out.dem = raster<float>(dem);
    out.water_surface = raster<float>(dem.rows(), dem.cols(), NAN);
    out.body = raster<std::int32_t>(dem.rows(), dem.cols(), 0);
    std::vector<hydro_qa_body> checked;
    for (std::int32_t id = 1; id <= top; ++id) {
        const cell_box& bx = box[static_cast<std::size_t>(id)];
        if (bx.empty()) continue;
        // 2. Its shape and type, 3. its levels.
        hydro_body b;
        b.id = id;
        b.box = bx;
        b.shape = measure_hydro_body_shape(filled, id, bx, cell_m);
        const bool river = b.shape.elongation() >= opt.min_river_elongation;
        b.type = river ? hydro_body_type::river : hydro_body_type::lake;
        b.flattened = river ? b.shape.width_m >= opt.min_river_width_m : b.shape.area_m2 >= opt.min_lake_area_m2;
        if (b.flattened && river) {
            b.river = trace_river_profile(filled, id, bx, b.shape, water_z, cell_m, opt.river);
            if (opt.to_banks) b.banks = lower_to_banks(b.river, filled, id, dem, opt.river, opt.banks);
            const auto [low, high] = std::minmax_element(b.river.level_m.begin(), b.river.level_m.end());
            b.level_min_m = *low;
            b.level_max_m = *high;
        } else if (b.flattened) {
            b.lake = lake_level(filled, id, bx, water_z, dem, opt.lake);
            b.level_min_m = b.level_max_m = b.lake.level_m;
        }
        b.flattened = b.flattened && std::isfinite(b.level_min_m);  // a body without a return or a shore stays
        // 4. The water surface over the body.
        if (b.flattened) {
            for (std::ptrdiff_t r = bx.row_min; r <= bx.row_max; ++r)
                for (std::ptrdiff_t c = bx.col_min; c <= bx.col_max; ++c) {
                    if (filled(r, c) != id) continue;
                    double level = b.level_min_m;
                    if (river) {
                        const std::int32_t k = b.river.section(r - bx.row_min, c - bx.col_min);
                        if (k < 0) continue;  // a cell the profile could not reach stays as it was
                        level = b.river.level_m[static_cast<std::size_t>(k)];
                    }
                    out.water_surface(r, c) = static_cast<float>(level);
                    out.dem(r, c) = static_cast<float>(level);
                    out.body(r, c) = id;
                }
        }
        out.bodies.push_back(std::move(b));
        detail::report(opt.run.progress, 0.1 + 0.9 * static_cast<double>(id) / (top + 1.0), fn);
    }
    // 4b. The water under bridge decks.
    if (opt.under_decks) detail::continue_under_decks(out, min_z, cell_m, opt.decks);
    // 5. Shores, 6. the checks.
    const raster<float> before = opt.shoreline == shoreline_rule::lift ? out.dem : raster<float>();
    out.shorelines = enforce_shorelines(out.dem, out.water_surface, opt.shoreline);
    if (opt.shoreline == shoreline_rule::lift)
        for (hydro_body& b : out.bodies)
            if (b.flattened) b.shore_cells_lifted = detail::cells_lifted_beside(out.body, before, out.dem, b.id, b.box);
    for (const hydro_body& b : out.bodies) {
        if (!b.flattened) continue;
        const bool river = b.type == hydro_body_type::river;
        checked.push_back({b.id, river, river ? b.shape.width_m : b.shape.area_m2,
                           river ? opt.min_river_width_m : opt.min_lake_area_m2, river ? &b.river : nullptr});
    }
    out.qa = hydro_qa(out.dem, out.water_surface, out.body, checked, opt.flat_tolerance_m);
    detail::report(opt.run.progress, 1, fn);
    return out;
}

}  // namespace lidarfx
