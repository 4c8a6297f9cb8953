// SPDX-License-Identifier: Apache-2.0
// Implementation of pipelines/water/flat_seed_components.hpp (included at its end; not meant to be included
// alone).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/kernels/label/connected_components.hpp"
#include "lidarfx/pipelines/water/flat_water_seeds_options.hpp"
#include "lidarfx/pipelines/water/water_rasters.hpp"

namespace lidarfx {

namespace detail {

/// Renumbers the labels of the components of >= min_cells cells (level_sizes[l]) to 1..n in label order and
/// those of smaller ones to -1, row by row; lists max z − min z of every level cell in row order, counts
/// each kept component's cells outside `taken` and records the first and last row of each.
inline void renumber_flat_components(const water_rasters& in, raster_view<const std::int32_t> taken,
                                     const std::vector<std::size_t>& level_sizes, std::size_t min_cells,
                                     flat_seed_components& comps, std::vector<std::ptrdiff_t>& first_row,
                                     std::vector<std::ptrdiff_t>& last_row)
{
    const std::ptrdiff_t rows = in.min_z.rows(), cols = in.min_z.cols();
    const std::size_t n = level_sizes.size() - 1;
    std::vector<std::int32_t> big(n + 1, 0);  // the new label of a large component, 0 for a small one
    comps.sizes.assign(1, 0);
    std::size_t level_cells = 0;
    for (std::size_t l = 1; l <= n; ++l) {
        if (level_sizes[l] >= min_cells) {
            big[l] = static_cast<std::int32_t>(comps.sizes.size());
            comps.sizes.push_back(level_sizes[l]);
        }
        level_cells += level_sizes[l];
    }
    const std::size_t nb = comps.count();
    comps.free_cells.assign(nb + 1, 0);
    comps.level_roughness.resize(level_cells);
    first_row.assign(nb + 1, rows);
    last_row.assign(nb + 1, -1);
    const std::vector<std::int32_t> none_taken(static_cast<std::size_t>(cols), 0);
    float* rough_out = comps.level_roughness.data();
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        std::int32_t* lab = comps.labels.view().row(r);
        const float* z0 = in.min_z.row(r);
        const float* z1 = in.max_z.row(r);
        const std::int32_t* body = taken.empty() ? none_taken.data() : taken.row(r);
        for_each_run(lab, cols, [&](std::int32_t l, std::ptrdiff_t from, std::ptrdiff_t end) {
            const std::int32_t to = big[static_cast<std::size_t>(l)];
            if (to == 0) {
                for (std::ptrdiff_t c = from; c < end; ++c) {
                    *rough_out++ = z1[c] - z0[c];
                    lab[c] = -1;
                }
                return;
            }
            std::size_t free = 0;
            for (std::ptrdiff_t c = from; c < end; ++c) {
                *rough_out++ = z1[c] - z0[c];
                free += body[c] <= 0;
                lab[c] = to;
            }
            const auto m = static_cast<std::size_t>(to);
            comps.free_cells[m] += free;
            first_row[m] = std::min(first_row[m], r);
            last_row[m] = r;
        });
    }
}

/// Sums in.count, in.mean_intensity and max z − min z over the components with free cells, over the rows
/// those components span.
inline void sum_flat_components(const water_rasters& in, const std::vector<std::ptrdiff_t>& first_row,
                                const std::vector<std::ptrdiff_t>& last_row, flat_seed_components& comps)
{
    const std::ptrdiff_t rows = in.min_z.rows(), cols = in.min_z.cols();
    const std::size_t nb = comps.count();
    comps.count_sum.assign(nb + 1, 0);
    comps.intensity_sum.assign(nb + 1, 0);
    comps.roughness_sum.assign(nb + 1, 0);
    std::ptrdiff_t free_first = rows, free_last = -1;  // the rows of the components with free cells
    for (std::size_t m = 1; m <= nb; ++m) {
        if (comps.free_cells[m] == 0) continue;
        free_first = std::min(free_first, first_row[m]);
        free_last = std::max(free_last, last_row[m]);
    }
    for (std::ptrdiff_t r = free_first; r <= free_last; ++r) {
        const std::int32_t* lab = comps.labels.view().row(r);
        const float* z0 = in.min_z.row(r);
        const float* z1 = in.max_z.row(r);
        const std::uint32_t* pulses = in.count.row(r);
        const float* intensity = in.mean_intensity.row(r);
        // Along a run of one label the sums stay in registers (the same additions in the same order as cell
        // by cell, and as one pass over the raster in row order).
        for_each_run(lab, cols, [&](std::int32_t l, std::ptrdiff_t from, std::ptrdiff_t end) {
            const auto m = static_cast<std::size_t>(l);
            if (comps.free_cells[m] == 0) return;
            double pulse_sum = comps.count_sum[m], light_sum = comps.intensity_sum[m],
                   rough_sum = comps.roughness_sum[m];
            for (std::ptrdiff_t c = from; c < end; ++c) {
                pulse_sum += pulses[c];
                light_sum += intensity[c];
                rough_sum += z1[c] - z0[c];
            }
            comps.count_sum[m] = pulse_sum;
            comps.intensity_sum[m] = light_sum;
            comps.roughness_sum[m] = rough_sum;
        });
    }
}

}  // namespace detail

inline flat_seed_components label_flat_seed_components(const water_rasters& in, raster_view<const std::uint8_t> level,
                                                       raster_view<const std::int32_t> taken,
                                                       const flat_water_seeds_options& opt,
                                                       raster<std::int32_t> storage, const execution& run)
{
    constexpr const char* fn = "label_flat_seed_components";
    detail::validate(in, fn);
    detail::validate(opt, fn);
    detail::check_execution(run, fn);
    detail::require(!in.count.empty(), fn, "in.count is required (the densities of the components need it)");
    detail::require_same_shape(in.min_z, level, fn, "min_z", "level");
    if (!taken.empty()) detail::require_same_shape(in.min_z, taken, fn, "min_z", "taken");
    const std::ptrdiff_t rows = in.min_z.rows(), cols = in.min_z.cols();
    flat_seed_components comps{std::move(storage), {}, {}, {}, {}, {}, {}};
    detail::ensure_shape(comps.labels, rows, cols);  // every cell is written
    const auto level_sizes = connected_components(
        level, comps.labels,
        connected_components_options{.conn = connectivity::eight, .run = {.threads = run.threads}});
    std::vector<std::ptrdiff_t> first_row, last_row;
    detail::renumber_flat_components(in, taken, level_sizes, opt.min_cells, comps, first_row, last_row);
    detail::sum_flat_components(in, first_row, last_row, comps);
    return comps;
}

}  // namespace lidarfx
