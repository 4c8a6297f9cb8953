// SPDX-License-Identifier: Apache-2.0
// extract_waterbodies: waterbody maps from the rasters of an airborne LiDAR survey (dissertation ch. 2).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/kernels/points/rasterize.hpp"
#include "lidarfx/pipelines/water/assess_water_inputs.hpp"
#include "lidarfx/pipelines/water/channel_water_seeds.hpp"
#include "lidarfx/pipelines/water/cut_at_level_bands.hpp"
#include "lidarfx/pipelines/water/fill_small_islands.hpp"
#include "lidarfx/pipelines/water/flat_water_seeds.hpp"
#include "lidarfx/pipelines/water/grow_waterbodies.hpp"
#include "lidarfx/pipelines/water/grow_waterbody.hpp"
#include "lidarfx/pipelines/water/intensity_bins.hpp"
#include "lidarfx/pipelines/water/join_across_bridges.hpp"
#include "lidarfx/pipelines/water/join_adjacent_dropouts.hpp"
#include "lidarfx/pipelines/water/join_level_cells.hpp"
#include "lidarfx/pipelines/water/join_shore_cells.hpp"
#include "lidarfx/pipelines/water/measure_waterbodies.hpp"
#include "lidarfx/pipelines/water/seeds_beyond_bridges.hpp"
#include "lidarfx/pipelines/water/trim_raised_edge_cells.hpp"
#include "lidarfx/pipelines/water/water_angles.hpp"
#include "lidarfx/pipelines/water/water_rasters.hpp"
#include "lidarfx/pipelines/water/water_seeds.hpp"
#include "lidarfx/pipelines/water/water_surface_slope.hpp"
#include "lidarfx/pipelines/water/water_vegetation.hpp"

namespace lidarfx {

/// Options of extract_waterbodies: each step's options once, in a member named after the step, in the order
/// the steps run; a step that may be left out has one `bool` (or a count of rounds) here, beside its options.
/// Defaults follow the dissertation where it gives a value. Threads and progress come from `run` alone: the
/// `run` member of a step's options is not read (the steps run with run.threads; progress is reported per
/// seed). A designated initializer of a nested member starts from that step's own defaults: `.seeds =
/// {.min_cells = 80}` also sets opening_size_cells to water_seeds' 5, not the 3 set here.
struct extract_waterbodies_options {
    bool check_inputs = true;                  ///< refuse inputs that cannot support the method (see diagnostics)
    assess_water_inputs_options inputs = {};   ///< assess_water_inputs: min_points_per_cell
    water_vegetation_options vegetation = {};  ///< water_vegetation: height, closing, multiple returns
    water_angles_options angles = {};          ///< water_angles: radius, elevation read, dropouts at any θ
    intensity_bins_options intensity = {};     ///< intensity_bins: intensity quantum of the KS samples
    water_seeds_options seeds = {.opening_size_cells = 3,
                                 .min_cells = 50,
                                 .line_length_cells = 4};  ///< water_seeds: opening, size and straight runs
                                                           ///< of the seeds from dropouts and of the flat seeds
                                                           ///< (3, 50 and 4 here: a river two cells wide seeds)
    bool flat_seeds = false;             ///< flat_water_seeds: also seed from level, low cells with fewer returns
                                         ///< than the land around them (or a few % fewer and dark or smooth):
                                         ///< water without dropouts (turbid, specular, dense surveys). These
                                         ///< seeds (their cells outside the bodies of the dropout seeds, cut at
                                         ///< level bands of 2 grow.level_gate_m, then water_seeds) grow after
                                         ///< the dropout seeds. Off by default: on the water family, with
                                         ///< grow.level_follow_max_slope = 0.008, they lift sensitivity and
                                         ///< accuracy but take about 1.4x the time (docs/waterbodies.md)
    flat_water_seeds_options flat = {};  ///< flat_water_seeds: its thresholds
    bool flat_seed_dropouts = true;      ///< join_adjacent_dropouts: the dropout cells next to a flat seed cell
                                         ///< (eligible, in no body) join the seed mask before its opening:
                                         ///< water with scattered dropouts keeps its seeds whole
    bool channel_seeds = false;          ///< channel_water_seeds (with flat_seeds, whose survey land intensity it
                                         ///< reads): seeds in level, dark strips between two banks, grown after
                                         ///< the flat seeds: narrow rivers that return as many pulses as the land;
                                         ///< a body of them brighter than the seeds may be is taken back. Off here
                                         ///< (as flat_seeds is), on in flat_seed_water_method()
    channel_water_seeds_options channel = {};  ///< channel_water_seeds: level, banks, width, darkness, size
    grow_waterbody_options grow = {};          ///< grow_waterbody: θ schedule, KS test, min_ks_samples, level gate
    join_level_cells_options level = {};       ///< join_level_cells: narrow water next to each grown region
    grow_waterbodies_options growing = {};     ///< grow_waterbodies: min_free_seed_share
    water_surface_slope_options surface_slope = {};  ///< the surface slope (a lazy_water_surface_slope: tiles
                                                     ///< computed where read), used when grow.level_gate_m > 0
                                                     ///< and grow.level_follow_max_slope >= 0
    int bridge_seed_rounds = 3;  ///< seeds_beyond_bridges: rounds of seeds beyond the decks that end
                                 ///< bodies (a river's stretches one bridge further per round), each
                                 ///< grown like the flat seeds; 0 leaves the step out. Default 3
    seeds_beyond_bridges_options bridge_seeds = {};  ///< seeds_beyond_bridges: deck and level tests
    std::size_t bridge_seed_min_cells = 8;     ///< water_seeds of the bridge seeds (no opening): smallest component
                                               ///< kept, cells, >= 1. Default 8
    bool join_bridges = true;                  ///< join_across_bridges: bodies at one level across a deck (or
                                               ///< touching) merge
    join_across_bridges_options bridges = {};  ///< join_across_bridges: span, levels, clearance, touching
    bool trim_edges = true;                    ///< trim_raised_edge_cells: edge cells standing 0.05-0.5 m above the
                                               ///< local level become land, after the bridges
    trim_raised_edge_cells_options trim = {};  ///< trim_raised_edge_cells: window, rise range
    bool shore_cells = true;                   ///< join_shore_cells (needs in.count): edge cells whose count says
                                               ///< they are mostly water join their body, after the trim
    join_shore_cells_options shore = {};       ///< join_shore_cells: window, contrast, water share, neighbours
    fill_small_islands_options islands = {};   ///< fill_small_islands: holes smaller than island_min_area_m2 fill
    execution run = {};                        ///< drives every step: threads of the raster kernels (0 = all cores;
                                               ///< same result for any count); progress over seeds, returning
                                               ///< false cancels
};

/// The options of the method before the water family: no level gate (grow.level_gate_m = 0), no KS exemption
/// of cells at the level, seeds from a 5-cell opening and >= 100 cells, dropouts only (no flat_seeds), no
/// seeds beyond bridges, no merge of touching bodies, no trim, no shore cells. Kept so that its accuracy stays
/// printable for comparison.
inline extract_waterbodies_options previous_water_method();

/// The options of the best configuration on the water family: the defaults with flat_seeds on, the
/// level-surface cue (grow.level_follow_max_slope = flat.max_surface_slope, 0.008 m/m), which makes a faster
/// level drift safe (grow.level_drift_m = 0.01 m per cell), bridge seeds from a single walk over a deck
/// (bridge_seed_min_cells = 4) and cells within 0.03 m of the level joining at any angle
/// (grow.level_any_angle_m: narrow rivers), and channel_seeds (narrow rivers that return as many pulses as the
/// land). It also finds water without dropouts (turbid, specular, dense surveys) and
/// is what `lidarfx water` runs unless told --dropout-seeds-only; it takes about 1.4x the defaults' time on rasters
/// (docs/performance.md).
inline extract_waterbodies_options flat_seed_water_method();

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

/// Extracts waterbodies from the rasters of a survey (dissertation ch. 2, with the refinements of
/// docs/waterbodies.md), as a composition of the public steps, in order:
///  1. assess_water_inputs; when check_inputs is set and it reports problems, nothing is extracted
///     (ran = false) and the diagnostics say why;
///  2. water_vegetation, water_angles and intensity_bins give the growing field (water_field); its eligible
///     cells are the cells off the vegetation (mask_not) and inside in.footprint (clear_outside);
///  3. water_seeds of the dropouts inside the footprint (largest first), grown by grow_waterbodies
///     (grow_waterbody, the KS-stopped bucket-queue flood, then join_level_cells per seed);
///  4. with flat_seeds: flat_water_seeds outside the bodies grown, join_adjacent_dropouts (flat_seed_dropouts),
///     cut_at_level_bands of 2 grow.level_gate_m (with the gate), water_seeds, grown into the cells still
///     eligible;
///  4b. with flat_seeds and channel_seeds: channel_water_seeds outside the bodies grown and the vegetation, with
///     the survey land intensity of the flat seeds, water_seeds without opening (channel.min_cells), grown the
///     same way;
///  5. bridge_seed_rounds rounds of seeds_beyond_bridges (water cut off by a deck from a body), grown the
///     same way;
///  6. join_across_bridges (join_bridges), trim_raised_edge_cells (trim_edges), join_shore_cells (shore_cells,
///     with in.count), fill_small_islands, clear_outside the footprint (neither a bridge nor a filled hole
///     reaches beyond what was flown) and measure_waterbodies (labels 1..n by decreasing area).
/// With in.footprint, cells outside it are no data: they neither seed nor join a body (survey_footprint tells
/// them apart). cell_m in metres. O(cells · angular radius + sum over seeds of cells reached). Progress: 0,
/// then per seed, then 1.
/// @throws invalid_input on rasters of different shapes, cell_m <= 0 or options out of range; cancelled.
inline extract_waterbodies_result extract_waterbodies(const water_rasters& in, double cell_m,
                                                      const extract_waterbodies_options& opt = {});

/// extract_waterbodies on the output of rasterize(), at its grid's cell size.
inline extract_waterbodies_result extract_waterbodies(const rasterize_result& pr,
                                                      const extract_waterbodies_options& opt = {});

}  // namespace lidarfx

#include "lidarfx/pipelines/water/detail/extract_waterbodies_impl.hpp"
