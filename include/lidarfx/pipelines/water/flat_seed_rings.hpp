// SPDX-License-Identifier: Apache-2.0
// measure_flat_seed_rings: the land around each component flat_water_seeds tests, and its sums.
#pragma once

#include <cmath>
#include <vector>

#include "lidarfx/core/parallel.hpp"
#include "lidarfx/pipelines/water/flat_seed_components.hpp"
#include "lidarfx/pipelines/water/flat_water_seeds_options.hpp"
#include "lidarfx/pipelines/water/water_rasters.hpp"

namespace lidarfx {

/// Sums over the ring of each component (the land flat_water_seeds compares it with). Vectors indexed by
/// label, count() + 1 entries (entry 0 unused, 0); 0 for components without free cells (not measured).
struct flat_seed_rings {
    std::vector<double> cells;          ///< ring cells of the component
    std::vector<double> count_sum;      ///< sum of in.count over them
    std::vector<double> intensity_sum;  ///< sum of in.mean_intensity over them
    std::vector<double> lower;          ///< ring cells whose min z lies more than opt.level_tolerance_m below
                                        ///< the component's lowest min z within opt.ring_cells of the ring cell
    std::vector<double> raised;         ///< ring cells whose min z lies more than opt.level_tolerance_m above it
                                        ///< (banks: water lies below the land around it)
    double land_intensity = NAN;        ///< the survey's land intensity the land tests of select_flat_seeds compare
                                        ///< with (survey_land_intensity); NaN (as measure_flat_seed_rings leaves
                                        ///< it): those tests are off
};

/// Third step of flat_water_seeds: the ring of each component of `comps` that has free cells: the cells
/// with a return (no dropout, finite min z, inside in.footprint) in no level component (label 0) within
/// Chebyshev distance opt.ring_cells of one of its cells; a ring cell near two components counts for each.
/// Sums are taken in row order whatever the thread count (run.threads; its progress is not called), so the
/// result never depends on it.
/// Method: per strip of rows, running maxima over rows of the labels (min_max_filter's max_filter_rows, on
/// [label | zeros | K + 1 − label] so one pass gives the smallest and largest label within reach) and a
/// running minimum of the components' min z; a cell with two labels within reach is read cell by cell.
/// O(cells · log ring_cells) plus (2 ring_cells + 1)² per ring cell near two components or more.
/// @throws invalid_input on rasters of different shapes, no in.count, or options or run out of range.
inline flat_seed_rings measure_flat_seed_rings(const water_rasters& in, const flat_seed_components& comps,
                                               const flat_water_seeds_options& opt = {}, const execution& run = {});

/// The survey's land intensity, for the land tests of select_flat_seeds: the opt.land_intensity_quantile
/// quantile of the mean intensity of the cells with a return (no dropout, finite min z and intensity, inside
/// in.footprint) outside every component that could be water by its shape: lowest (rings.lower <=
/// opt.max_lower_share · rings.cells, with a ring). Everything else is the survey's own land: vegetation,
/// roofs, roads, rough and sloping ground, level ground above its surroundings. From a histogram of the
/// intensities' float representations cut to 16 bits (bins 0.8 % of their value wide; the middle of the
/// bin is returned; negative intensities count as 0). NaN without such cells or with
/// opt.land_intensity_quantile < 0. One pass over the cells, in bands of rows on run.threads (the histogram's
/// counts add up exactly: the same result for any thread count): O(cells). Memory: 512 KiB of counts per band
/// (one band per thread).
/// @throws invalid_input on rasters of different shapes or rings or options that do not match.
inline double survey_land_intensity(const water_rasters& in, const flat_seed_components& comps,
                                    const flat_seed_rings& rings, const flat_water_seeds_options& opt = {},
                                    const execution& run = {});

}  // namespace lidarfx

#include "lidarfx/pipelines/water/detail/flat_seed_rings_impl.hpp"
