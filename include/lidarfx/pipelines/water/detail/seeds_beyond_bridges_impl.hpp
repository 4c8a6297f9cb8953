// SPDX-License-Identifier: Apache-2.0
// Implementation of seeds_beyond_bridges (included at the end of pipelines/water/seeds_beyond_bridges.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <vector>
#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/parallel_bands.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/pipelines/water/detail/body_within.hpp"
#include "lidarfx/pipelines/water/water_surface_slope.hpp"

namespace lidarfx {

namespace detail {

inline void validate(const seeds_beyond_bridges_options& o, const char* fn)
{
    require(o.max_span_m > 0, fn, "max_span_m", "> 0", o.max_span_m);
    require(o.min_clearance_m >= 0, fn, "min_clearance_m", ">= 0", o.min_clearance_m);
    require(o.level_tolerance_m >= 0, fn, "level_tolerance_m", ">= 0", o.level_tolerance_m);
    require(o.beyond_cells >= 1, fn, "beyond_cells", ">= 1", o.beyond_cells);
    require(o.behind_cells >= 0, fn, "behind_cells", ">= 0", o.behind_cells);
    require(o.approach_cells >= 0, fn, "approach_cells", ">= 0", o.approach_cells);
    require(o.clear_cells >= 0, fn, "clear_cells", ">= 0", o.clear_cells);
}

}  // namespace detail

inline raster<std::uint8_t> seeds_beyond_bridges(raster_view<const std::int32_t> labels, raster_view<const float> min_z,
                                                 raster_view<const std::uint8_t> eligible, double cell_m,
                                                 const seeds_beyond_bridges_options& opt,
                                                 surface_slope_source surface_slope, const execution& run)
{
    constexpr const char* fn = "seeds_beyond_bridges";
    detail::require_positive(cell_m, fn, "cell_m");
    detail::validate(opt, fn);
    detail::require_same_shape(labels, min_z, fn, "labels", "min_z");
    detail::require_same_shape(labels, eligible, fn, "labels", "eligible");
    const bool sloped_out = !surface_slope.empty() && opt.max_surface_slope >= 0;
    if (sloped_out) detail::require_same_shape(labels, surface_slope, fn, "labels", "surface_slope");
    detail::check_execution(run, fn);
    const std::ptrdiff_t rows = labels.rows(), cols = labels.cols();
    raster<std::uint8_t> seeds(rows, cols, 0);
    const auto inside = [&](std::ptrdiff_t r, std::ptrdiff_t c) { return r >= 0 && r < rows && c >= 0 && c < cols; };
    constexpr int steps[8][2] = {{0, 1}, {0, -1}, {1, 0}, {-1, 0}, {1, 1}, {-1, -1}, {1, -1}, {-1, 1}};
    // The walks from body cell (r, c) of `body`, the cells they mark appended to `marked` (a cell may appear more
    // than once).
    const auto walk_from = [&](std::ptrdiff_t r, std::ptrdiff_t c, std::int32_t body,
                               std::vector<std::ptrdiff_t>& marked) {
        const float z0 = min_z(r, c);
        if (!std::isfinite(z0)) return;
        const auto level_with = [&](float z) { return std::abs(static_cast<double>(z) - z0) <= opt.level_tolerance_m; };
        for (const auto& step : steps) {
            const std::ptrdiff_t dr = step[0], dc = step[1];
            // Only a cell at the body's edge along this line starts a walk.
            if (!inside(r + dr, c + dc) || labels(r + dr, c + dc) != 0) continue;
            bool channel = true;
            for (std::ptrdiff_t k = 1; k <= opt.behind_cells && channel; ++k)
                channel = inside(r - k * dr, c - k * dc) && labels(r - k * dr, c - k * dc) == body;
            if (!channel) continue;
            const double step_m = (dr != 0 && dc != 0) ? cell_m * std::numbers::sqrt2 : cell_m;
            const auto span = static_cast<std::ptrdiff_t>(std::floor(opt.max_span_m / step_m));
            // Up to the deck: a few land cells at the water's level (the body may stop short of the deck);
            // then over it: land cells with no return or standing clear of the water.
            std::ptrdiff_t k = 1;
            for (; k <= opt.approach_cells && inside(r + k * dr, c + k * dc); ++k) {
                const std::ptrdiff_t rr = r + k * dr, cc = c + k * dc;
                if (labels(rr, cc) != 0 || !(level_with(min_z(rr, cc)) || std::isnan(min_z(rr, cc)))) break;
            }
            const std::ptrdiff_t deck_from = k;
            bool raised = false;
            for (; k <= span && inside(r + k * dr, c + k * dc); ++k) {
                const std::ptrdiff_t rr = r + k * dr, cc = c + k * dc;
                if (labels(rr, cc) != 0) break;
                const float z = min_z(rr, cc);
                if (std::isfinite(z) && !(z >= z0 + opt.min_clearance_m)) break;
                raised |= std::isfinite(z);
            }
            if (!raised || k == deck_from) continue;
            // Beyond it: beyond_cells water-like cells in a row.
            bool water_like = true;
            for (std::ptrdiff_t j = 0; j < opt.beyond_cells && water_like; ++j) {
                const std::ptrdiff_t rr = r + (k + j) * dr, cc = c + (k + j) * dc;
                water_like = inside(rr, cc) && labels(rr, cc) == 0 && eligible(rr, cc) != 0 &&
                             level_with(min_z(rr, cc)) &&
                             !(sloped_out && surface_slope(rr, cc) > opt.max_surface_slope);
            }
            if (!water_like) continue;
            for (std::ptrdiff_t j = 0; j < opt.beyond_cells; ++j)
                marked.push_back((r + (k + j) * dr) * cols + c + (k + j) * dc);
        }
    };
    // Bands of rows on run.threads threads, each marking cells in a list of its own; the walks read the labels
    // only, so the seeds are set after.
    const auto marked_in = parallel_bands(rows, 128, run.threads, [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
        std::vector<std::ptrdiff_t> marked;
        // Per row, 1 for the body cells that may start a walk: none inside a body (all 8 neighbours its own),
        // where most body cells are.
        std::vector<std::uint8_t> may_start(static_cast<std::size_t>(cols));
        std::uint8_t* start = may_start.data();
        for (std::ptrdiff_t r = r0; r < r1; ++r) {
            const std::int32_t* here = labels.row(r);
            // Land is passed over in blocks; each stretch of body cells is flagged in one vectorized loop.
            for (std::ptrdiff_t c = detail::next_positive(here, 0, cols); c < cols;
                 c = detail::next_positive(here, c, cols)) {
                const std::ptrdiff_t from = c;
                while (c < cols && here[c] > 0) ++c;
                std::fill(start + from, start + c, std::uint8_t{1});  // the raster's border: all may start
                if (r > 0 && r + 1 < rows) {
                    const std::int32_t* above = labels.row(r - 1);
                    const std::int32_t* below = labels.row(r + 1);
                    const std::ptrdiff_t to = std::min(c, cols - 1);
                    LIDARFX_IVDEP
                    for (std::ptrdiff_t x = std::max<std::ptrdiff_t>(from, 1); x < to; ++x) {
                        const std::int32_t b = here[x];
                        start[x] = static_cast<std::uint8_t>(
                            (above[x - 1] != b) | (above[x] != b) | (above[x + 1] != b) | (here[x - 1] != b) |
                            (here[x + 1] != b) | (below[x - 1] != b) | (below[x] != b) | (below[x + 1] != b));
                    }
                }
                for (std::ptrdiff_t x = detail::next_positive(start, from, c); x < c;
                     x = detail::next_positive(start, x + 1, c))
                    walk_from(r, x, here[x], marked);
            }
        }
        return marked;
    });
    for (const auto& marked : marked_in)
        for (const std::ptrdiff_t cell : marked) seeds(cell / cols, cell % cols) = 1;
    // Only where nothing was found yet: a marked cell within clear_cells of a body is the bank of water
    // already found (a walk over a deck's end lands on it), not water cut off by the deck.
    for (const auto& marked : marked_in) {
        for (const std::ptrdiff_t cell : marked) {
            const std::ptrdiff_t r = cell / cols, c = cell % cols;
            if (detail::body_within(labels, r, c, opt.clear_cells)) seeds(r, c) = 0;
        }
    }
    return seeds;
}

}  // namespace lidarfx
