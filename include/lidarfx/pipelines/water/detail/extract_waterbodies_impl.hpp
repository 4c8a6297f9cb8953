// SPDX-License-Identifier: Apache-2.0
// Implementation of extract_waterbodies (included at the end of pipelines/water/extract_waterbodies.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/mask_ops.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/kernels/label/connected_components.hpp"

namespace lidarfx {

inline extract_waterbodies_options previous_water_method()
{
    extract_waterbodies_options o;
    o.seeds = {.opening_size_cells = 5, .min_cells = 100};
    o.grow.level_gate_m = 0;
    o.grow.level_ks_exempt_m = -1;
    o.grow.level_rise_m = -1;
    o.grow.level_follow_max_slope = -1;
    o.grow.test_first_step = false;
    o.flat_seeds = false;
    o.bridge_seed_rounds = 0;
    o.flat.bright_density_ratio = 0;
    o.flat.max_joint_ratio = 0;
    o.bridges.join_touching = false;
    o.flat_seed_dropouts = false;
    o.growing.min_free_seed_share = 1;
    o.shore_cells = false;
    o.trim_edges = false;
    return o;
}

inline extract_waterbodies_options flat_seed_water_method()
{
    extract_waterbodies_options o;
    o.flat_seeds = true;
    o.grow.level_follow_max_slope = o.flat.max_surface_slope;
    // With the cue a level follows min z only on level ground, so it may follow a steeper river (0.5 %
    // at 2 m cells) without climbing a beach; and a single walk over a deck (4 cells) may seed beyond it.
    o.grow.level_drift_m = 0.01;
    o.bridge_seed_min_cells = 4;
    // A river narrower than the angular window sees a bank from every cell: at its level it joins anyway.
    o.grow.level_any_angle_m = 0.03;
    // A narrow river that returns as many pulses as the land is seeded by its level, dark strip between two banks.
    o.channel_seeds = true;
    return o;
}

namespace detail {

/// The one validation of extract_waterbodies' options: each step's options by that step's own rules, the
/// steps left out not at all.
inline void validate(const extract_waterbodies_options& o, double cell_m, const char* fn)
{
    require_positive(cell_m, fn, "cell_m");
    validate(o.inputs, fn);
    validate(o.vegetation, fn);
    require(o.angles.radius_cells >= 1, fn, "angles.radius_cells", ">= 1", o.angles.radius_cells);
    validate(o.intensity, fn);
    validate(o.seeds, fn);
    if (o.flat_seeds) validate(o.flat, fn);
    if (o.flat_seeds && o.channel_seeds) validate(o.channel, fn);
    validate(o.grow, fn);
    validate(o.level, fn);
    require(o.growing.min_free_seed_share > 0 && o.growing.min_free_seed_share <= 1, fn, "min_free_seed_share",
            "in (0, 1]", o.growing.min_free_seed_share);
    require(o.bridge_seed_rounds >= 0, fn, "bridge_seed_rounds", ">= 0", o.bridge_seed_rounds);
    if (o.bridge_seed_rounds > 0) {
        validate(o.bridge_seeds, fn);
        require(o.bridge_seed_min_cells >= 1, fn, "bridge_seed_min_cells", ">= 1", o.bridge_seed_min_cells);
    }
    if (o.join_bridges) validate(o.bridges, fn);
    if (o.trim_edges) validate(o.trim, fn);
    if (o.shore_cells) validate(o.shore, fn);
    require(o.islands.island_min_area_m2 >= 0, fn, "island_min_area_m2", ">= 0", o.islands.island_min_area_m2);
    check_execution(o.run, fn);
}

/// The growing field of extract_waterbodies: angles, intensity bins and min z of `in`; eligible = not
/// vegetation and inside the footprint.
inline water_field water_field_of(const water_rasters& in, double cell_m, raster_view<const std::uint8_t> vegetation,
                                  const extract_waterbodies_options& opt)
{
    const std::ptrdiff_t rows = in.min_z.rows(), cols = in.min_z.cols();
    auto bins = intensity_bins(in.mean_intensity, in.dropout, opt.intensity, {.threads = opt.run.threads});
    water_field field{water_angles(in, cell_m, opt.angles, {.threads = opt.run.threads}),
                      raster<std::uint8_t>(rows, cols, uninitialized),
                      std::move(bins.bin),
                      bins.bins,
                      in.min_z,
                      {},
                      in.mean_intensity};
    mask_not(vegetation, field.eligible);
    if (!in.footprint.empty()) clear_outside(field.eligible.view(), in.footprint);
    return field;
}

/// grow_waterbodies' run in extract_waterbodies: the run's threads (floods grown ahead of their turn), and its
/// progress from `from` over `share` of the run's (cancelling throws in extract_waterbodies' name).
inline execution growing_run(const extract_waterbodies_options& opt, double from, double share, const char* fn)
{
    return {.threads = opt.run.threads, .progress = [&progress = opt.run.progress, from, share, fn](double f) {
                report(progress, from + share * f, fn);
                return true;
            }};
}

/// Grows further seeds into the cells of `field` still eligible: their bodies are numbered after those in
/// `grown`, their seeds after res.seeds_found in res.seeds (the new seeds are few: land is passed over).
inline void grow_more_seeds(water_field& field, const components& more, const water_rasters& in,
                            grow_waterbodies_result& grown, extract_waterbodies_result& res,
                            const extract_waterbodies_options& opt, double from, double share, const char* fn)
{
    const auto k = static_cast<std::int32_t>(res.seeds_found);
    grow_waterbodies(field, more, in.min_z, in.max_z, grown, opt.grow, opt.level, opt.growing, k,
                     growing_run(opt, from, share, fn));
    for (std::ptrdiff_t r = 0, cols = res.seeds.cols(); r < res.seeds.rows(); ++r) {
        std::int32_t* seed = res.seeds.view().row(r);
        for_each_run(more.labels.view().row(r), cols, [&](std::int32_t l, std::ptrdiff_t c0, std::ptrdiff_t c1) {
            std::fill(seed + c0, seed + c1, k + l);
        });
    }
    res.seeds_found += more.count();
}

/// The flat seed mask of extract_waterbodies: flat_water_seeds outside the bodies grown so far, with the
/// dropouts next to them (flat_seed_dropouts) and cut at level bands of 2 level gates (with the gate). Empty
/// when no flat seed cell is found. `labels` is reused memory (a new raster costs its first touch).
inline raster<std::uint8_t> flat_seed_mask(const water_rasters& in, const water_field& field,
                                           raster_view<const std::uint8_t> vegetation,
                                           raster_view<const std::uint8_t> dropouts,
                                           raster_view<const std::int32_t> taken, raster<std::int32_t>& labels,
                                           double& land_intensity, const extract_waterbodies_options& opt)
{
    const int threads = opt.run.threads;
    flat_water_seeds_workspace workspace{std::move(labels)};
    auto mask = flat_water_seeds(in, vegetation, opt.flat, field.surface_slope, taken, workspace, {.threads = threads});
    labels = std::move(workspace.labels);
    land_intensity = workspace.land_intensity;
    if (!mask_any(mask)) return {};
    if (opt.flat_seed_dropouts) mask = join_adjacent_dropouts(mask, dropouts, field.eligible, {.threads = threads});
    if (opt.grow.level_gate_m > 0) {
        ensure_shape(labels, mask.rows(), mask.cols());  // (flat_water_seeds without counts leaves it as it was)
        const auto parts = connected_components(
            mask, labels, connected_components_options{.conn = connectivity::eight, .run = {.threads = threads}});
        cut_at_level_bands(mask, labels, parts.empty() ? 0 : parts.size() - 1, in.min_z, 2 * opt.grow.level_gate_m);
    }
    return mask;
}

/// Takes back the bodies grown from `first` on (grown.bodies[first..], labels first + 1..) whose mean intensity over
/// their cells with a return exceeds `limit`: their cells become land and eligible again, the later bodies take
/// their labels in order. A flood from a seed that only its shape vouches for (channel_water_seeds) that spread
/// over land of land intensity is not water. The bodies grown after a dropped one keep what they took while its
/// cells were taken (they are not grown again). O(cells).
inline void drop_bright_bodies(grow_waterbodies_result& grown, std::size_t first, const water_rasters& in, double limit,
                               raster<std::uint8_t>& eligible)
{
    const std::size_t n = grown.bodies.size();
    if (n <= first) return;
    const auto lowest = static_cast<std::int32_t>(first);  // labels above it are the new bodies
    std::vector<double> sum(n - first, 0.0);
    std::vector<std::size_t> measured(n - first, 0);
    const std::ptrdiff_t rows = grown.labels.rows(), cols = grown.labels.cols();
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        const std::int32_t* label = grown.labels.view().row(r);
        const float* light = in.mean_intensity.row(r);
        const std::uint8_t* dropout = in.dropout.row(r);
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            if (label[c] <= lowest || dropout[c] || !std::isfinite(light[c])) continue;
            const auto k = static_cast<std::size_t>(label[c] - lowest - 1);
            sum[k] += light[c];
            ++measured[k];
        }
    }
    std::vector<std::int32_t> relabel(n - first, 0);  // 0: dropped
    std::size_t kept = first;
    for (std::size_t k = 0; k < n - first; ++k) {
        if (measured[k] > 0 && sum[k] / static_cast<double>(measured[k]) > limit) continue;
        grown.bodies[kept] = grown.bodies[first + k];
        relabel[k] = static_cast<std::int32_t>(kept + 1);
        grown.bodies[kept].label = relabel[k];
        ++kept;
    }
    if (kept == n) return;
    grown.seeds_grown -= n - kept;
    grown.bodies.resize(kept);
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        std::int32_t* label = grown.labels.view().row(r);
        std::uint8_t* open = eligible.view().row(r);
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            if (label[c] <= lowest) continue;
            label[c] = relabel[static_cast<std::size_t>(label[c] - lowest - 1)];
            if (label[c] == 0) open[c] = 1;
        }
    }
}

/// Clears the cells of `mask` whose intensity is at least `limit` (land-like: a seed beyond a bridge that lands
/// on a level lawn of land intensity would flood it); NaN limit: none. O(cells).
inline void clear_at_least(raster<std::uint8_t>& mask, raster_view<const float> intensity, double limit)
{
    if (std::isnan(limit)) return;
    const auto at_least = static_cast<float>(limit);
    for (std::ptrdiff_t r = 0; r < mask.rows(); ++r) {
        std::uint8_t* m = mask.view().row(r);
        const float* v = intensity.row(r);
        for (std::ptrdiff_t c = 0, n = mask.cols(); c < n; ++c) m[c] = m[c] && !(v[c] >= at_least);
    }
}

/// The refinements of the grown bodies, in order: join_across_bridges, trim_raised_edge_cells,
/// join_shore_cells, fill_small_islands, then the labels cleared outside the footprint.
inline void refine_waterbodies(raster<std::int32_t>& labels, std::size_t bodies, const water_rasters& in, double cell_m,
                               raster_view<const std::uint8_t> vegetation, const extract_waterbodies_options& opt)
{
    const execution run{.threads = opt.run.threads};
    if (opt.join_bridges && bodies > 1) join_across_bridges(labels, in.min_z, cell_m, opt.bridges, run);
    if (opt.trim_edges) trim_raised_edge_cells(labels, in.min_z, opt.trim, run);
    if (opt.shore_cells && !in.count.empty())
        join_shore_cells(labels, in.count, vegetation, in.footprint, opt.shore, run);
    fill_small_islands(labels, cell_m, opt.islands, {.threads = opt.run.threads});
    if (!in.footprint.empty()) clear_outside(labels.view(), in.footprint);
}

}  // namespace detail

inline extract_waterbodies_result extract_waterbodies(const water_rasters& in, double cell_m,
                                                      const extract_waterbodies_options& opt)
{
    constexpr const char* fn = "extract_waterbodies";
    detail::validate(in, fn);
    detail::validate(opt, cell_m, fn);
    const std::ptrdiff_t rows = in.min_z.rows(), cols = in.min_z.cols();
    const int threads = opt.run.threads;  // the steps run silently; progress is reported per seed

    extract_waterbodies_result res;
    res.diagnostics = assess_water_inputs(in, cell_m, opt.inputs, {.threads = threads});
    res.water = raster<std::uint8_t>(rows, cols, 0);
    if (opt.check_inputs && !res.diagnostics.usable()) {
        res.labels = raster<std::int32_t>(rows, cols, 0);
        return res;
    }
    res.ran = true;
    detail::report(opt.run.progress, 0.0, fn);

    res.vegetation = water_vegetation(in, opt.vegetation, {.threads = threads});
    water_field field = detail::water_field_of(in, cell_m, res.vegetation, opt);
    // The level follows min z only where the surface is level; the slope is computed tile by tile where it
    // is read (around water), by the first thread that reads it.
    std::optional<lazy_water_surface_slope> lazy_slope;  // field.surface_slope reads it; empty: no slope
    if (opt.grow.level_follow_max_slope >= 0 && opt.grow.level_gate_m > 0)
        field.surface_slope = lazy_slope.emplace(in.min_z, cell_m, opt.surface_slope);
    // Outside the footprint nothing was flown: no seed starts there.
    raster<std::uint8_t> dropout_inside;
    if (!in.footprint.empty()) {
        dropout_inside = raster<std::uint8_t>(rows, cols, uninitialized);
        mask_and(in.dropout, in.footprint, dropout_inside);
    }
    const raster_view<const std::uint8_t> dropouts = in.footprint.empty() ? in.dropout : dropout_inside.view();
    const execution seed_run{.threads = threads};

    // Growing is the first 0.9 of the run's progress (0.8 for the dropout seeds when flat seeds follow).
    auto seeds = water_seeds(dropouts, opt.seeds, seed_run);
    auto grown = grow_waterbodies(field, seeds, in.min_z, in.max_z, opt.grow, opt.level, opt.growing,
                                  detail::growing_run(opt, 0.0, opt.flat_seeds ? 0.8 : 0.9, fn));
    res.seeds_found = seeds.count();
    res.seeds = std::move(seeds.labels);
    raster<std::int32_t> labels;  // reused by the labelling steps below
    // The floods of flat seeds and of the seeds beyond bridges after them: the level follows no cell of land
    // intensity (a flat seed has no lost pulses to vouch for it).
    extract_waterbodies_options later = opt;
    if (opt.flat_seeds) {
        double land_intensity = NAN;
        auto mask =
            detail::flat_seed_mask(in, field, res.vegetation, dropouts, grown.labels, labels, land_intensity, opt);
        if (std::isnan(later.grow.level_follow_max_intensity)) later.grow.level_follow_max_intensity = land_intensity;
        if (mask.empty()) {
            detail::report(opt.run.progress, 0.9, fn);  // no flat seed: the step is passed over
        } else {
            auto more = water_seeds(mask, opt.seeds, std::move(labels), seed_run);
            detail::grow_more_seeds(field, more, in, grown, res, later, 0.8, 0.1, fn);
            labels = std::move(more.labels);
        }
        if (opt.channel_seeds) {
            const auto channels = channel_water_seeds(in.min_z, in.mean_intensity, res.vegetation, grown.labels, cell_m,
                                                      land_intensity, opt.channel, seed_run);
            if (mask_any(channels)) {
                auto more = water_seeds(channels, {.opening_size_cells = 1, .min_cells = opt.channel.min_cells},
                                        std::move(labels), seed_run);
                const std::size_t before = grown.bodies.size();
                if (more.count() > 0) detail::grow_more_seeds(field, more, in, grown, res, later, 0.9, 0.0, fn);
                detail::drop_bright_bodies(grown, before, in, opt.channel.max_intensity_ratio * land_intensity,
                                           field.eligible);
                labels = std::move(more.labels);
            }
        }
    }
    for (int round = 0; round < opt.bridge_seed_rounds; ++round) {  // each round's bodies may end at a bridge
        auto mask = seeds_beyond_bridges(grown.labels, in.min_z, field.eligible, cell_m, opt.bridge_seeds,
                                         field.surface_slope, seed_run);
        detail::clear_at_least(mask, in.mean_intensity, later.grow.level_follow_max_intensity);
        if (!mask_any(mask)) break;  // none: no labelling
        auto more = water_seeds(mask, {.opening_size_cells = 1, .min_cells = opt.bridge_seed_min_cells},
                                std::move(labels), seed_run);
        if (more.count() == 0) break;
        detail::grow_more_seeds(field, more, in, grown, res, later, 0.9, 0.0, fn);
        labels = std::move(more.labels);
    }
    res.seeds_grown = grown.seeds_grown;
    res.labels = std::move(grown.labels);
    detail::refine_waterbodies(res.labels, grown.bodies.size(), in, cell_m, res.vegetation, opt);
    measure_waterbodies(res.labels, grown.bodies, in, cell_m, {.threads = threads});
    res.bodies = std::move(grown.bodies);
    mask_of_labels(res.labels, res.water);
    res.angle_deg = std::move(field.angle_deg);
    detail::report(opt.run.progress, 1.0, fn);
    return res;
}

inline extract_waterbodies_result extract_waterbodies(const rasterize_result& pr,
                                                      const extract_waterbodies_options& opt)
{
    return extract_waterbodies(to_water_rasters(pr), pr.g.cell, opt);
}

}  // namespace lidarfx
