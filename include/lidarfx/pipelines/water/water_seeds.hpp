// SPDX-License-Identifier: Apache-2.0
// water_seeds: where waterbodies start growing, from the dropout mask (cells without returns).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/mask_ops.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/kernels/filter/line_opening.hpp"
#include "lidarfx/kernels/filter/morphology.hpp"
#include "lidarfx/kernels/label/connected_components.hpp"

namespace lidarfx {

/// Options of water_seeds.
struct water_seeds_options {
    int opening_size_cells = 5;   ///< side of the square opening the dropout mask, cells; odd, >= 1. Default 5.
    std::size_t min_cells = 100;  ///< seeds keep components of at least this many cells; >= 1. Default 100.
    int line_length_cells = 0;    ///< also keep the mask cells on a straight run (row, column or diagonal) of at
                                  ///< least this many mask cells (line_opening): narrow water that the square
                                  ///< opening erases, as a river a few cells wide on coarse cells; 0 = off,
                                  ///< else in [2, 255]. Default 0 (the dissertation's seeds)
};

/// Seeds of waterbodies (dissertation 2.3.2): the dropout mask opened by an opening_size_cells square
/// (morph_open; removes dropouts narrower than the square, as on land), with line_length_cells the cells of
/// its straight runs of that length added (line_opening: thin but long water stays), its 8-connected components of at
/// least min_cells cells, ranked by size: label 1 = largest, ties in raster-scan order of their first
/// cell. Cells of smaller components are background (sizes[0] counts them). Mask: nonzero = dropout.
/// The labels are written into `labels` (given another shape, it is replaced by one of the mask's), whose
/// memory the result takes: a caller that labels again reuses it (a new raster's pages cost their first touch).
/// O(cells). `run`: threads of the kernels, progress (0 on entry, 1 when done) and cancellation; never changes
/// the result.
/// @throws invalid_input on options or run out of range; cancelled when progress returns false.
template <raster_input Mask>
components water_seeds(const Mask& dropout, const water_seeds_options& opt, raster<std::int32_t>&& labels,
                       const execution& run = {});

/// water_seeds (see above) with its labels in a raster of its own.
template <raster_input Mask>
components water_seeds(const Mask& dropout, const water_seeds_options& opt = {}, const execution& run = {});

/// Cells of each component as linear indices r * cols + c in raster-scan order: result[label] for labels
/// 1..count(), result[0] empty (the form grow_waterbody takes its seed in). O(cells).
inline std::vector<std::vector<std::ptrdiff_t>> seed_cells(const components& seeds);

// ---- implementation ----

namespace detail {

inline void validate(const water_seeds_options& o, const char* fn)
{
    require(o.opening_size_cells >= 1 && o.opening_size_cells % 2 == 1, fn, "opening_size_cells", "odd and >= 1",
            o.opening_size_cells);
    require(o.min_cells >= 1, fn, "min_cells", ">= 1", o.min_cells);
    require(o.line_length_cells == 0 || (o.line_length_cells >= 2 && o.line_length_cells <= 255), fn,
            "line_length_cells", "0 or in [2, 255]", o.line_length_cells);
}

}  // namespace detail

template <raster_input Mask>
components water_seeds(const Mask& dropout, const water_seeds_options& opt, raster<std::int32_t>&& labels,
                       const execution& run)
{
    constexpr const char* fn = "water_seeds";
    detail::validate(opt, fn);
    detail::check_execution(run, fn);
    detail::report(run.progress, 0.0, fn);
    const int threads = run.threads;
    auto opened =
        morph_open(dropout, morphology_options{.size_cells = opt.opening_size_cells, .run = {.threads = threads}});
    if (opt.line_length_cells > 0)
        mask_or(line_opening(dropout, opt.line_length_cells, {.threads = threads}), opened, opened);
    detail::ensure_shape(labels, opened.rows(), opened.cols());  // every cell is written
    components seeds{std::move(labels), {}};
    seeds.sizes = connected_components(
        opened, seeds.labels, connected_components_options{.conn = connectivity::eight, .run = {.threads = threads}});
    // Ranked by size, the seeds to keep are the ranks 1..kept; the others become background. One pass
    // renumbers and drops (as rank_by_size, then a pass dropping the small ones, would).
    const std::size_t n = seeds.count();
    auto rank = rank_components_by_size(seeds.sizes);
    std::vector<std::size_t> ranked(n + 1, seeds.sizes[0]);
    for (std::size_t l = 1; l <= n; ++l) ranked[static_cast<std::size_t>(rank[l])] = seeds.sizes[l];
    std::size_t kept = 0;
    while (kept + 1 < ranked.size() && ranked[kept + 1] >= opt.min_cells) ++kept;
    for (std::size_t l = 1; l <= n; ++l) {
        if (static_cast<std::size_t>(rank[l]) > kept) {
            ranked[0] += seeds.sizes[l];
            rank[l] = 0;
        }
    }
    ranked.resize(kept + 1);
    relabel_components(seeds.labels, rank);
    seeds.sizes = std::move(ranked);
    detail::report(run.progress, 1.0, fn);
    return seeds;
}

template <raster_input Mask>
components water_seeds(const Mask& dropout, const water_seeds_options& opt, const execution& run)
{
    return water_seeds(dropout, opt, raster<std::int32_t>(), run);
}

namespace detail {

/// The cells of each seed in one buffer: cells of label l are cells[offset[l] .. offset[l + 1]), in
/// raster-scan order. One allocation (huge pages when large) instead of a growing vector per seed.
struct seed_cell_runs {
    std::vector<std::ptrdiff_t, raster_allocator<std::ptrdiff_t>> cells;
    std::vector<std::size_t> offset;
    std::span<const std::ptrdiff_t> of(std::size_t label) const noexcept
    {
        return std::span<const std::ptrdiff_t>(cells).subspan(offset[label], offset[label + 1] - offset[label]);
    }
};

/// The cells of each seed as runs of one buffer (counting sort by label), run l in raster-scan order. The
/// run lengths come from seeds.sizes when they match the labels (as connected_components gives them);
/// otherwise the labels are counted. Blocks of 64 cells without a seed are skipped after one vectorized
/// test: seeds cover a small share of a survey. O(cells).
/// @throws invalid_input on a label outside [0, count()].
inline seed_cell_runs seed_cells_flat(const components& seeds, const char* fn = "seed_cells")
{
    seed_cell_runs out;
    const std::size_t count = seeds.count();
    const std::int32_t* labels = seeds.labels.data();
    const std::ptrdiff_t n = seeds.labels.size();
    constexpr std::ptrdiff_t block = 64;
    // Calls f(i) for every cell with a label != 0, in order.
    const auto for_each_seed_cell = [&](auto&& f) {
        for (std::ptrdiff_t b = 0; b < n; b += block) {
            const std::ptrdiff_t end = std::min(n, b + block);
            std::int32_t any = 0;
            for (std::ptrdiff_t i = b; i < end; ++i) any |= labels[i];
            if (any == 0) continue;
            for (std::ptrdiff_t i = b; i < end; ++i)
                if (labels[i] != 0) f(i);
        }
    };
    const auto fill = [&] {
        for (std::size_t l = 1; l < out.offset.size(); ++l) out.offset[l] += out.offset[l - 1];
        out.cells.resize(out.offset.back());  // default-initialized: every slot is written below
        std::vector<std::size_t> next(out.offset.begin(), out.offset.end() - 1);
        bool fits = true;
        for_each_seed_cell([&](std::ptrdiff_t i) {
            const std::int32_t l = labels[i];
            if (l < 0 || static_cast<std::size_t>(l) > count) [[unlikely]]
                require(false, fn, "seeds.labels", "in [0, count()]", l);
            const auto k = static_cast<std::size_t>(l);
            if (next[k] < out.offset[k + 1])
                out.cells[next[k]++] = i;
            else
                fits = false;
        });
        for (std::size_t l = 1; l <= count; ++l) fits = fits && next[l] == out.offset[l + 1];
        return fits;
    };
    out.offset.assign(count + 2, 0);
    for (std::size_t l = 1; l <= count; ++l) out.offset[l + 1] = seeds.sizes[l];
    if (!fill()) {  // sizes that do not match the labels: count the labels instead
        out.offset.assign(count + 2, 0);
        for_each_seed_cell([&](std::ptrdiff_t i) { ++out.offset[static_cast<std::size_t>(labels[i]) + 1]; });
        fill();
    }
    return out;
}

}  // namespace detail

inline std::vector<std::vector<std::ptrdiff_t>> seed_cells(const components& seeds)
{
    const auto runs = detail::seed_cells_flat(seeds);
    std::vector<std::vector<std::ptrdiff_t>> out(seeds.count() + 1);
    for (std::size_t l = 1; l < out.size(); ++l) {
        const auto cells = runs.of(l);
        out[l].assign(cells.begin(), cells.end());
    }
    return out;
}

}  // namespace lidarfx
