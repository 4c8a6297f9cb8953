// SPDX-License-Identifier: Apache-2.0
// extract_waterbodies: waterbody maps from the rasters of an airborne LiDAR survey (dissertation ch. 2).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/kernels/filter/morphology.hpp"
#include "lidarfx/kernels/label/connected_components.hpp"
#include "lidarfx/kernels/points/rasterize.hpp"
#include "lidarfx/pipelines/water/assess_water_inputs.hpp"
#include "lidarfx/pipelines/water/bridge_seeds.hpp"
#include "lidarfx/pipelines/water/join_across_bridges.hpp"
#include "lidarfx/pipelines/water/flat_water_seeds.hpp"
#include "lidarfx/pipelines/water/grow_waterbodies.hpp"
#include "lidarfx/pipelines/water/grow_waterbody.hpp"
#include "lidarfx/pipelines/water/intensity_bins.hpp"
#include "lidarfx/pipelines/water/fill_small_islands.hpp"
#include "lidarfx/pipelines/water/join_level_cells.hpp"
#include "lidarfx/pipelines/water/measure_waterbodies.hpp"
#include "lidarfx/pipelines/water/join_shore_cells.hpp"
#include "lidarfx/pipelines/water/trim_raised_edge_cells.hpp"
#include "lidarfx/pipelines/water/water_angles.hpp"
#include "lidarfx/pipelines/water/water_rasters.hpp"
#include "lidarfx/pipelines/water/water_seeds.hpp"
#include "lidarfx/pipelines/water/water_surface_slope.hpp"
#include "lidarfx/pipelines/water/water_vegetation.hpp"

namespace lidarfx {

/// Options of extract_waterbodies; defaults follow the dissertation where it gives a value. Each group
/// is passed to one step (see that step's options for the details).
struct extract_waterbodies_options {
    double vegetation_height_m = 2.0;       ///< water_vegetation: max z − min z above this is vegetation, metres
    int vegetation_closing_size_cells = 5;  ///< water_vegetation: closing of the vegetation mask, cells (odd)
    bool vegetation_from_multiple_returns = true;  ///< water_vegetation: multiple-return cells are vegetation too
    int angular_radius_cells = 2;                  ///< water_angles: angular filter window radius, cells ("two tiers")
    angular_input angular_on = angular_input::returns_only;  ///< water_angles: elevation read by the filter
    bool dropouts_join_any_threshold = true;  ///< water_angles: dropout cells join a region at any θ (their
                                              ///< angle is unknown); false = the dissertation's literal behaviour
    int seed_opening_size_cells = 3;          ///< water_seeds: opening of the dropout mask before seeding, cells (odd)
    std::size_t min_seed_cells = 50;          ///< water_seeds: smallest seed component kept, cells (>= it is kept)
    bool flat_seeds = false;                  ///< flat_water_seeds: also seed from level, low cells with fewer returns
                                              ///< than the land around them (or a few % fewer and dark or smooth):
                                              ///< water without dropouts (turbid, specular, dense surveys). These
                                              ///< seeds (their cells outside the bodies of the dropout seeds; same
                                              ///< opening and min_seed_cells) grow after the dropout seeds. Off by
                                              ///< default: on the water family, with grow.level_follow_max_slope =
                                              ///< 0.008, they lift sensitivity (lakes 77 -> 98 %, rivers 76 -> 96 %)
                                              ///< and accuracy (lakes 97.1 -> 99.6 %, rivers 97.8 -> 99.2 %) but take
                                              ///< about 1.4x the time (docs/waterbodies.md, seventh reporting run;
                                              ///< docs/performance.md)
    bool flat_seed_dropouts = true;           ///< flat seeds: the dropout cells next to a seed cell (8-neighbours,
                                              ///< eligible, in no body) join the seed mask before its opening: water
                                              ///< with scattered dropouts keeps its seeds whole; their level ignores
                                              ///< them (no return). Default true (water family, rivers of seeds
                                              ///< 500-599: see docs/waterbodies.md, eighth session)
    flat_water_seeds_options flat = {};       ///< flat_water_seeds: its thresholds (run is ignored)
    grow_waterbody_options grow = {};         ///< grow_waterbody: θ schedule, KS test, min_ks_samples, level gate
    double min_free_seed_share = 0.5;         ///< grow_waterbodies: a seed partly inside the bodies grown before it
                                              ///< grows from its cells outside them when they are at least this share
                                              ///< of it, else it is skipped; in (0, 1]. Default 0.5
    water_surface_slope_options surface_slope = {};  ///< the surface slope (a lazy_water_surface_slope: tiles
                                                     ///< computed where read), used when grow.level_follow_max_slope >=
                                                     ///< 0 (run is ignored)
    double intensity_resolution = 1.0;      ///< intensity_bins: intensity quantum of the KS samples (rounded to
                                            ///< nearest, ties to even), > 0
    double level_tolerance_m = 0.15;        ///< join_level_cells: land cells next to a body whose min z is within
                                            ///< this of the adjacent water level join it; 0 disables. Also
                                            ///< join_across_bridges' water_tolerance_m
    double level_max_rise_m = 0.5;          ///< join_level_cells: ... and whose highest return is at most this
                                            ///< above that level (a cell mostly on the bank is not water), metres
    int level_join_depth_cells = 2;         ///< join_level_cells: how far (cells) from the grown region it reaches
    double island_min_area_m2 = 200.0;      ///< fill_small_islands: holes in a body at least this large stay
                                            ///< land; smaller ones become water, m²
    double bridge_max_span_m = 30.0;        ///< join_across_bridges: gaps up to this long between two bodies at
                                            ///< one water level are bridged (decks become water, bodies merge),
                                            ///< metres; 0 disables
    double bridge_level_tolerance_m = 1.0;  ///< join_across_bridges: water levels on both sides differ by at most this
    double bridge_min_clearance_m = 2.0;    ///< join_across_bridges: a deck cell's lowest return stands at least
                                            ///< this high above the water on both sides, metres
    int bridge_seed_rounds = 3;             ///< seeds_beyond_bridges: rounds of seeds beyond the decks that end
                                            ///< bodies (a river's stretches one bridge further per round), each
                                            ///< grown like the flat seeds; 0 disables. Default 3 (water family,
                                            ///< rivers of seeds 500-599 with flat seeds: 92.9 -> 95.2 % mean
                                            ///< sensitivity, 99.49 -> 99.48 % specificity; docs/waterbodies.md)
    seeds_beyond_bridges_options bridge_seeds = {};  ///< seeds_beyond_bridges: deck and level tests
    std::size_t bridge_seed_min_cells = 8;           ///< seeds_beyond_bridges: smallest seed component kept, cells
    bool bridge_join_touching = true;                ///< join_across_bridges: bodies that touch, at levels within
                                                     ///< bridge_level_tolerance_m, merge (one surface grown from
                                                     ///< several seeds); needs bridge_max_span_m > 0. Default true
    bool trim_edges = true;                    ///< trim_raised_edge_cells: edge cells standing 0.05-0.5 m above the
                                               ///< local level become land, after the bridges. Default true (water
                                               ///< family, seeds 500-599: see docs/waterbodies.md)
    trim_raised_edge_cells_options trim = {};  ///< trim_raised_edge_cells: window, rise range
    bool shore_cells = true;                   ///< join_shore_cells (needs in.count): edge cells whose count says
                                               ///< they are mostly water join their body, after the bridges. Default
                                               ///< true (water family, seeds 500-599: see docs/waterbodies.md)
    join_shore_cells_options shore = {};       ///< join_shore_cells: window, contrast, water share, neighbours
    double min_points_per_cell = 2.0;          ///< assess_water_inputs: below this mean density the inputs are refused
    bool check_inputs = true;                  ///< refuse inputs that cannot support the method (see diagnostics)
    execution run = {};                        ///< threads of the raster kernels (0 = all cores; same result for any
                                               ///< count); progress over seeds, returning false cancels
};

/// The options of the method before the water family (issue 17): no level gate (grow.level_gate_m = 0),
/// no KS exemption of cells at the level, seeds from a 5-cell opening and >= 100 cells, dropouts only
/// (no flat_seeds). Kept so that its accuracy stays printable for comparison.
inline extract_waterbodies_options previous_water_method()
{
    extract_waterbodies_options o;
    o.seed_opening_size_cells = 5;
    o.min_seed_cells = 100;
    o.grow.level_gate_m = 0;
    o.grow.level_ks_exempt_m = -1;
    o.grow.level_rise_m = -1;
    o.grow.level_follow_max_slope = -1;
    o.grow.test_first_step = false;
    o.flat_seeds = false;
    o.bridge_seed_rounds = 0;
    o.flat.bright_density_ratio = 0;
    o.flat.max_joint_ratio = 0;
    o.bridge_join_touching = false;
    o.flat_seed_dropouts = false;
    o.min_free_seed_share = 1;
    o.shore_cells = false;
    o.trim_edges = false;
    return o;
}

/// The options of the best configuration on the water family: the defaults with flat_seeds on, the
/// level-surface cue (grow.level_follow_max_slope = 0.008 m/m, flat_water_seeds' max_surface_slope), which
/// makes a faster level drift safe (grow.level_drift_m = 0.01 m per cell), and bridge seeds from a single
/// walk over a deck (bridge_seed_min_cells = 4). It also finds water without dropouts (turbid, specular,
/// dense surveys) and is what `lidarfx water` runs unless told --dropout-seeds-only; it takes about 1.4x
/// the defaults' time on rasters (docs/performance.md).
inline extract_waterbodies_options flat_seed_water_method()
{
    extract_waterbodies_options o;
    o.flat_seeds = true;
    o.grow.level_follow_max_slope = o.flat.max_surface_slope;
    // With the cue a level follows min z only on level ground, so it may follow a steeper river (0.5 %
    // at 2 m cells) without climbing a beach; and a single walk over a deck (4 cells) may seed beyond it.
    o.grow.level_drift_m = 0.01;
    o.bridge_seed_min_cells = 4;
    return o;
}

/// Result of extract_waterbodies, with the intermediate rasters for inspection.
struct extract_waterbodies_result {
    raster<std::int32_t> labels;    ///< 0 land, 1..n waterbodies by decreasing area
    raster<std::uint8_t> water;     ///< 1 water, 0 land
    std::vector<waterbody> bodies;  ///< bodies[i].label == i + 1
    water_diagnostics diagnostics;
    raster<std::uint8_t> vegetation;  ///< vegetation mask used
    raster<float> angle_deg;          ///< angular filter output as growing saw it (NaN: joins at any θ)
    raster<std::int32_t> seeds;       ///< seed components, 1 = largest
    std::size_t seeds_found = 0, seeds_grown = 0;
    bool ran = false;  ///< false when check_inputs refused the data
};

namespace detail {

/// Whether a mask has a nonzero cell (each row passed over 64 cells at a time, as next_positive does).
inline bool any_set(raster_view<const std::uint8_t> mask) noexcept
{
    for (std::ptrdiff_t r = 0; r < mask.rows(); ++r)
        if (next_positive(mask.row(r), 0, mask.cols()) < mask.cols()) return true;
    return false;
}

inline void validate(const extract_waterbodies_options& o, double cell_m, const char* fn)
{
    require_positive(cell_m, fn, "cell_m");
    require(o.vegetation_height_m > 0, fn, "vegetation_height_m", "> 0", o.vegetation_height_m);
    require(o.vegetation_closing_size_cells >= 1 && o.vegetation_closing_size_cells % 2 == 1, fn,
            "vegetation_closing_size_cells", "odd and >= 1", o.vegetation_closing_size_cells);
    require(o.angular_radius_cells >= 1, fn, "angular_radius_cells", ">= 1", o.angular_radius_cells);
    require(o.seed_opening_size_cells >= 1 && o.seed_opening_size_cells % 2 == 1, fn, "seed_opening_size_cells",
            "odd and >= 1", o.seed_opening_size_cells);
    require(o.min_seed_cells >= 1, fn, "min_seed_cells", ">= 1", o.min_seed_cells);
    require(o.min_free_seed_share > 0 && o.min_free_seed_share <= 1, fn, "min_free_seed_share", "in (0, 1]",
            o.min_free_seed_share);
    require_positive(o.intensity_resolution, fn, "intensity_resolution");
    require(o.level_tolerance_m >= 0, fn, "level_tolerance_m", ">= 0", o.level_tolerance_m);
    require(o.level_max_rise_m >= 0, fn, "level_max_rise_m", ">= 0", o.level_max_rise_m);
    require(o.level_join_depth_cells >= 0, fn, "level_join_depth_cells", ">= 0", o.level_join_depth_cells);
    require(o.island_min_area_m2 >= 0, fn, "island_min_area_m2", ">= 0", o.island_min_area_m2);
    require(o.bridge_max_span_m >= 0, fn, "bridge_max_span_m", ">= 0", o.bridge_max_span_m);
    require(o.bridge_min_clearance_m >= 0, fn, "bridge_min_clearance_m", ">= 0", o.bridge_min_clearance_m);
    require(o.bridge_level_tolerance_m >= 0, fn, "bridge_level_tolerance_m", ">= 0", o.bridge_level_tolerance_m);
    require(o.min_points_per_cell >= 0, fn, "min_points_per_cell", ">= 0", o.min_points_per_cell);
    require(o.bridge_seed_rounds >= 0, fn, "bridge_seed_rounds", ">= 0", o.bridge_seed_rounds);
    require(o.bridge_seed_min_cells >= 1, fn, "bridge_seed_min_cells", ">= 1", o.bridge_seed_min_cells);
    if (o.bridge_seed_rounds > 0) validate(o.bridge_seeds, fn);
    if (o.shore_cells) validate(o.shore, fn);
    if (o.trim_edges) validate(o.trim, fn);
    check_execution(o.run, fn);
    validate(o.grow, fn);
}

/// extract_waterbodies' cut of the flat seed mask at level bands: `parts` labels the 8-connected parts of
/// `mask` (1..count, 0 off the mask; as connected_components gives them). A mask cell with a return has the
/// band index floor((min z − mean) / band + 0.5) in double, mean = its part's mean min z over the cells with
/// a return (0 when none); one without a return has none. A mask cell (r, c) with c + 1 < cols and r + 1 <
/// rows becomes 0 when its right or lower neighbour is on the mask and both have a band index and they
/// differ (uncut neighbours: each cell reads the mask as it was); the other cells keep their value. band in
/// metres, > 0. Only the runs of the
/// mask are visited (stretches of 64 cells off it are passed over at once): O(cells / 64 + mask cells).
inline void cut_at_level_bands(raster_view<std::uint8_t> mask, raster_view<const std::int32_t> parts, std::size_t count,
                               raster_view<const float> min_z, double band)
{
    const std::ptrdiff_t rows = mask.rows(), cols = mask.cols();
    std::vector<double> mean(count + 1, 0.0), finite(count + 1, 0.0);  // over returns
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        const std::int32_t* part = parts.row(r);
        const float* z = min_z.row(r);
        for_each_run(part, cols, [&](std::int32_t label, std::ptrdiff_t from, std::ptrdiff_t to) {
            const auto l = static_cast<std::size_t>(label);
            double sum = mean[l], n = finite[l];  // along the run in registers, the same additions in order
            for (std::ptrdiff_t c = from; c < to; ++c) {
                if (std::isfinite(z[c])) {
                    sum += z[c];
                    n += 1;
                }
            }
            mean[l] = sum;
            finite[l] = n;
        });
    }
    for (std::size_t l = 1; l < mean.size(); ++l) mean[l] = finite[l] > 0 ? mean[l] / finite[l] : 0.0;
    // Row by row, with the band index of each mask cell of this row and the next (NaN without a return; cells
    // off the mask are not written and not read); a cell's cut reads the uncut mask to its right and below,
    // which `parts` still shows, so row r is cut in place.
    std::vector<double> here(static_cast<std::size_t>(cols)), below(here.size());
    const auto band_row = [&](std::ptrdiff_t r, double* out) {
        const std::int32_t* part = parts.row(r);
        const float* z = min_z.row(r);
        for_each_run(part, cols, [&](std::int32_t l, std::ptrdiff_t from, std::ptrdiff_t to) {
            const double m = mean[static_cast<std::size_t>(l)];
            for (std::ptrdiff_t c = from; c < to; ++c) out[c] = std::floor((z[c] - m) / band + 0.5);
        });
    };
    if (rows > 1) band_row(0, here.data());
    for (std::ptrdiff_t r = 0; r + 1 < rows; ++r) {
        band_row(r + 1, below.data());
        const std::int32_t* part = parts.row(r);
        const std::int32_t* part_below = parts.row(r + 1);
        std::uint8_t* m = mask.row(r);
        for (std::ptrdiff_t c = next_positive(part, 0, cols - 1); c < cols - 1; c = next_positive(part, c, cols - 1)) {
            for (; c < cols - 1 && part[c] > 0; ++c) {
                // A dropout in the mask has no band (NaN): nothing is cut next to it.
                const double h = here[static_cast<std::size_t>(c)];
                if (std::isnan(h)) continue;
                const double right = here[static_cast<std::size_t>(c + 1)], down = below[static_cast<std::size_t>(c)];
                const bool cut_right = part[c + 1] > 0 && !std::isnan(right) && right != h;
                const bool cut_down = part_below[c] > 0 && !std::isnan(down) && down != h;
                if (cut_right || cut_down) m[c] = 0;
            }
        }
        here.swap(below);
    }
}

}  // namespace detail

/// Extracts waterbodies from the rasters of a survey (dissertation ch. 2, with DESIGN.md §5's refinements),
/// as a composition of the public steps: assess_water_inputs, water_vegetation, intensity_bins,
/// water_angles, water_seeds (>= min_seed_cells, largest first), grow_waterbodies (per seed not yet inside
/// a body: grow_waterbody, the KS-stopped bucket-queue flood, then join_level_cells), join_across_bridges,
/// trim_raised_edge_cells (edge cells standing above the local level), join_shore_cells (edge cells that
/// are mostly water by their count), fill_small_islands and
/// measure_waterbodies (labels 1..n by decreasing area). With flat_seeds, after the
/// dropout seeds: flat_water_seeds outside the bodies grown, water_seeds on them, grow_waterbodies again. Then,
/// for bridge_seed_rounds rounds, seeds_beyond_bridges (water cut off by a deck from a body), grown the same
/// way. With in.footprint, cells outside it are no data: they neither seed nor join a body (survey_footprint
/// tells them apart).
/// When check_inputs is set and assess_water_inputs()
/// reports problems, nothing is extracted (ran = false) and the diagnostics say why. cell_m in metres.
/// O(cells · angular radius + sum over seeds of cells reached). Progress: 0, then per seed, then 1.
/// @throws invalid_input on rasters of different shapes, cell_m <= 0 or options out of range; cancelled.
inline extract_waterbodies_result extract_waterbodies(const water_rasters& in, double cell_m,
                                                      const extract_waterbodies_options& opt = {})
{
    constexpr const char* fn = "extract_waterbodies";
    detail::validate(in, fn);
    detail::validate(opt, cell_m, fn);
    const std::ptrdiff_t rows = in.min_z.rows(), cols = in.min_z.cols();
    const execution kernels{.threads = opt.run.threads};  // steps run silently; progress is reported per seed

    extract_waterbodies_result res;
    res.diagnostics = assess_water_inputs(in, cell_m, {.min_points_per_cell = opt.min_points_per_cell});
    res.water = raster<std::uint8_t>(rows, cols, 0);
    if (opt.check_inputs && !res.diagnostics.usable()) {
        res.labels = raster<std::int32_t>(rows, cols, 0);
        return res;
    }
    res.ran = true;
    detail::report(opt.run.progress, 0.0, fn);

    res.vegetation = water_vegetation(in, {.height_m = opt.vegetation_height_m,
                                           .closing_size_cells = opt.vegetation_closing_size_cells,
                                           .from_multiple_returns = opt.vegetation_from_multiple_returns,
                                           .run = kernels});
    auto bins = intensity_bins(in.mean_intensity, in.dropout, {.resolution = opt.intensity_resolution});
    water_field field{water_angles(in, cell_m,
                                   {.radius_cells = opt.angular_radius_cells,
                                    .input = opt.angular_on,
                                    .dropouts_join_any_threshold = opt.dropouts_join_any_threshold,
                                    .run = kernels}),
                      raster<std::uint8_t>(rows, cols), std::move(bins.bin), bins.bins, in.min_z};
    {  // byte stores may alias anything: with the pointers in locals the loop vectorizes
        std::uint8_t* eligible = field.eligible.data();
        const std::uint8_t* vegetation = res.vegetation.data();
        for (std::ptrdiff_t i = 0, n = field.eligible.size(); i < n; ++i) eligible[i] = !vegetation[i];
    }
    // The level follows min z only where the surface is level. The slope is read around water only: it is
    // computed tile by tile where it is read.
    std::optional<lazy_water_surface_slope> lazy_slope;  // field.surface_slope reads it; empty: no slope
    if (opt.grow.level_follow_max_slope >= 0 && opt.grow.level_gate_m > 0) {
        auto so = opt.surface_slope;
        so.run = {};  // ignored, as documented: tiles are computed by the one thread that reads them
        field.surface_slope = lazy_slope.emplace(in.min_z, cell_m, so);
    }
    // Outside the footprint nothing was flown: no seed starts there and no body grows there.
    raster<std::uint8_t> dropout_inside;
    if (!in.footprint.empty()) {
        dropout_inside = raster<std::uint8_t>(rows, cols, uninitialized);
        const std::ptrdiff_t width = cols;  // (see the flat seeds' dropouts below)
        for (std::ptrdiff_t r = 0; r < rows; ++r) {
            const std::uint8_t* inside = in.footprint.row(r);
            const std::uint8_t* dropout = in.dropout.row(r);
            std::uint8_t* dropout_in = dropout_inside.view().row(r);
            std::uint8_t* eligible = field.eligible.view().row(r);
            for (std::ptrdiff_t c = 0; c < width; ++c) {
                dropout_in[c] = static_cast<std::uint8_t>((dropout[c] != 0) & (inside[c] != 0));
                eligible[c] = static_cast<std::uint8_t>((eligible[c] != 0) & (inside[c] != 0));
            }
        }
    }
    const raster_view<const std::uint8_t> dropouts =
        in.footprint.empty() ? in.dropout : raster_view<const std::uint8_t>(dropout_inside);
    auto seeds = water_seeds(
        dropouts, {.opening_size_cells = opt.seed_opening_size_cells, .min_cells = opt.min_seed_cells, .run = kernels});
    // Growing is the first 0.9 of the run's progress (0.8 for the dropout seeds when flat seeds follow);
    // cancelling there throws in this function's name.
    const double share = opt.flat_seeds ? 0.8 : 0.9;
    const progress_callback seed_progress = [&](double f) {
        detail::report(opt.run.progress, share * f, fn);
        return true;
    };
    const grow_waterbodies_options grow_opt{.grow = opt.grow,
                                            .level = {.tolerance_m = opt.level_tolerance_m,
                                                      .max_rise_m = opt.level_max_rise_m,
                                                      .depth_cells = opt.level_join_depth_cells},
                                            .min_free_seed_share = opt.min_free_seed_share,
                                            .run = {.progress = seed_progress}};
    auto grown = grow_waterbodies(field, seeds, in.min_z, in.max_z, grow_opt);
    res.seeds_found = seeds.count();
    res.seeds = std::move(seeds.labels);
    // Grows further seeds into the cells still eligible: their bodies are numbered after those so far (in
    // the same label raster), their seeds after the seeds so far.
    const auto grow_more = [&](const components& more, double progress_from, double progress_share) {
        auto more_opt = grow_opt;
        more_opt.run.progress = [&](double f) {
            detail::report(opt.run.progress, progress_from + progress_share * f, fn);
            return true;
        };
        const auto k = static_cast<std::int32_t>(res.seeds_found);
        grow_waterbodies(field, more, in.min_z, in.max_z, grown, more_opt, k);
        for (std::ptrdiff_t r = 0; r < rows; ++r) {  // (the new seeds are few: land is passed over)
            std::int32_t* seed = res.seeds.view().row(r);
            const auto copy = [&](std::int32_t l, std::ptrdiff_t from, std::ptrdiff_t to) {
                std::fill(seed + from, seed + to, k + l);
            };
            detail::for_each_run(more.labels.view().row(r), cols, copy);
        }
        res.seeds_found += more.count();
    };
    raster<std::int32_t> labels;  // reused by the labelling steps below (a new raster costs its first touch)
    if (opt.flat_seeds) {
        // Then seeds from level, sparse cells (flat_water_seeds), for the water no dropout seed reached:
        // their cells outside the bodies grown so far, opened and sized like the dropout seeds, largest
        // first (labels k + 1.. in res.seeds), grown into the cells still eligible.
        auto flat = opt.flat;
        flat.run = kernels;
        auto mask = flat_water_seeds(in, res.vegetation, flat, field.surface_slope, labels, grown.labels);
        // Without a flat seed cell (all water found already, or none without dropouts) the steps below find
        // no seed: they are passed over, and their progress reported as done.
        const bool any_flat = detail::any_set(mask);
        if (!any_flat) detail::report(opt.run.progress, 0.9, fn);
        if (any_flat && opt.flat_seed_dropouts) {
            // The dropouts next to the seed cells (3 x 3 dilation) join them: water with scattered dropouts
            // has level cells between them that the opening would otherwise break apart. Eligible: not
            // vegetation, in no body yet.
            auto near = morph_dilate(mask, morphology_options{.size_cells = 3, .run = kernels});
            // The width in a local of this block: `cols` is captured by reference (grow_more), so as far as
            // the compiler knows a byte store might change it, and a loop bounded by it would not vectorize
            // (19 against 2 ms here at 4096²).
            const std::ptrdiff_t width = cols;
            for (std::ptrdiff_t r = 0; r < rows; ++r) {
                std::uint8_t* out = near.view().row(r);
                const std::uint8_t* seed_cell = mask.view().row(r);
                const std::uint8_t* dropout = dropouts.row(r);
                const std::uint8_t* free = field.eligible.view().row(r);
                for (std::ptrdiff_t c = 0; c < width; ++c)
                    out[c] = static_cast<std::uint8_t>((seed_cell[c] != 0) |
                                                       ((out[c] != 0) & (dropout[c] != 0) & (free[c] != 0)));
            }
            mask = std::move(near);
        }
        // A seed holds one level: cut the mask where min z crosses a band of 2 level gates (a seed along a
        // falling river would otherwise take the level of its low end and gate out its high end). The bands
        // are centred on each connected part's mean min z, band index round((min z − mean) / band): a lake
        // whose level happens to lie on a fixed band boundary (a multiple of the band) stays whole.
        if (any_flat && opt.grow.level_gate_m > 0) {
            detail::ensure_shape(labels, rows, cols);  // (flat_water_seeds without counts left it as it was)
            const auto parts = connected_components(
                mask, labels, connected_components_options{.conn = connectivity::eight, .run = kernels});
            detail::cut_at_level_bands(mask, labels, parts.empty() ? 0 : parts.size() - 1, in.min_z,
                                       2 * opt.grow.level_gate_m);
        }
        if (any_flat) {
            auto more = water_seeds(
                mask,
                {.opening_size_cells = opt.seed_opening_size_cells, .min_cells = opt.min_seed_cells, .run = kernels},
                std::move(labels));
            grow_more(more, 0.8, 0.1);
            labels = std::move(more.labels);
        }
    }
    // Seeds beyond bridge decks, round by round: each round's bodies may end at the next bridge.
    for (int round = 0; round < opt.bridge_seed_rounds; ++round) {
        const auto mask =
            seeds_beyond_bridges(grown.labels, in.min_z, field.eligible, cell_m, opt.bridge_seeds, field.surface_slope);
        if (!detail::any_set(mask)) break;  // none: no labelling
        auto more = water_seeds(mask, {.opening_size_cells = 1, .min_cells = opt.bridge_seed_min_cells, .run = kernels},
                                std::move(labels));
        if (more.count() == 0) break;
        grow_more(more, 0.9, 0.0);
        labels = std::move(more.labels);
    }
    res.seeds_grown = grown.seeds_grown;
    res.labels = std::move(grown.labels);
    auto& bodies = grown.bodies;

    if (opt.bridge_max_span_m > 0 && bodies.size() > 1) {
        join_across_bridges(res.labels, in.min_z, cell_m,
                            {.max_span_m = opt.bridge_max_span_m,
                             .level_tolerance_m = opt.bridge_level_tolerance_m,
                             .min_clearance_m = opt.bridge_min_clearance_m,
                             .water_tolerance_m = opt.level_tolerance_m,
                             .join_touching = opt.bridge_join_touching});
    }
    if (opt.trim_edges) trim_raised_edge_cells(res.labels, in.min_z, opt.trim);
    if (opt.shore_cells && !in.count.empty())
        join_shore_cells(res.labels, in.count, res.vegetation, in.footprint, opt.shore);
    fill_small_islands(res.labels, cell_m, {.island_min_area_m2 = opt.island_min_area_m2, .run = kernels});
    if (!in.footprint.empty()) {  // neither a bridge nor a filled hole reaches beyond what was flown
        const std::ptrdiff_t width = cols;
        for (std::ptrdiff_t r = 0; r < rows; ++r) {
            const std::uint8_t* inside = in.footprint.row(r);
            std::int32_t* label = res.labels.view().row(r);
            for (std::ptrdiff_t c = 0; c < width; ++c) label[c] = inside[c] != 0 ? label[c] : 0;
        }
    }
    measure_waterbodies(res.labels, bodies, in, cell_m);
    res.bodies = std::move(bodies);
    std::uint8_t* water = res.water.data();
    const std::int32_t* label = res.labels.data();
    for (std::ptrdiff_t i = 0, n = res.water.size(); i < n; ++i) water[i] = label[i] > 0;
    res.angle_deg = std::move(field.angle_deg);
    detail::report(opt.run.progress, 1.0, fn);
    return res;
}

/// extract_waterbodies on the output of rasterize(), at its grid's cell size.
inline extract_waterbodies_result extract_waterbodies(const rasterize_result& pr,
                                                      const extract_waterbodies_options& opt = {})
{
    return extract_waterbodies(to_water_rasters(pr), pr.g.cell, opt);
}

}  // namespace lidarfx
