// SPDX-License-Identifier: Apache-2.0
// Implementation of trim_raised_edge_cells (included at the end of pipelines/water/trim_raised_edge_cells.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/parallel_bands.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

#include "lidarfx/pipelines/water/detail/edge_cell_classes.hpp"

namespace lidarfx {

namespace detail {

inline void validate(const trim_raised_edge_cells_options& o, const char* fn)
{
    require(o.window_cells >= 1, fn, "window_cells", ">= 1", o.window_cells);
    require(o.min_rise_m >= 0, fn, "min_rise_m", ">= 0", o.min_rise_m);
    require(o.max_rise_m > o.min_rise_m, fn, "max_rise_m", "> min_rise_m", o.max_rise_m);
    require(o.min_level_cells >= 1, fn, "min_level_cells", ">= 1", o.min_level_cells);
}

}  // namespace detail

inline std::size_t trim_raised_edge_cells(raster_view<std::int32_t> labels, raster_view<const float> min_z,
                                          const trim_raised_edge_cells_options& opt, const execution& run)
{
    constexpr const char* fn = "trim_raised_edge_cells";
    detail::validate(opt, fn);
    detail::require_same_shape(labels, min_z, fn, "labels", "min_z");
    detail::check_execution(run, fn);
    const std::ptrdiff_t rows = labels.rows(), cols = labels.cols();
    if (rows == 0 || cols == 0) return 0;
    const std::ptrdiff_t k = opt.window_cells;
    // Bands of rows on run.threads threads, each with the cell classes of its rows and its own list of cells
    // trimmed; the labels change after all bands are done, so every band reads them as they came in.
    const raster_view<const std::int32_t> in = labels;
    const auto trimmed_in = parallel_bands(rows, 256, run.threads, [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
        detail::shore_class_rows cls(in, k, true, r0);  // 0 land, 1 interior body cell, 2 edge body cell
        std::vector<std::ptrdiff_t> trimmed;
        std::vector<float> level;
        std::vector<std::uint8_t> edge(static_cast<std::size_t>(cols));  // an edge cell
        struct window_row {
            const std::uint8_t* cls;
            const float* z;
            const std::int32_t* labels;
        };
        std::vector<window_row> window;
        for (std::ptrdiff_t r = r0; r < r1; ++r) {
            if (!cls.has_body(r)) continue;
            cls.reach(r);
            const std::uint8_t* cl = cls.row(r);
            for (std::ptrdiff_t c = 0; c < cols; ++c) edge[static_cast<std::size_t>(c)] = cl[c] == 2;
            const float* z = min_z.row(r);  // read at edge cells and in their windows only
            // The window rows holding a body cell, the same for every edge cell of the row: found once.
            window.clear();
            for (std::ptrdiff_t rr = std::max<std::ptrdiff_t>(0, r - k), last = std::min(rows - 1, r + k); rr <= last;
                 ++rr)
                if (const std::uint8_t* cw = cls.row(rr)) window.push_back({cw, min_z.row(rr), in.row(rr)});
            // Row r + k enters the windows here, its heights not in cache: their loads (at both ends of each
            // window) are all started first, not one window after the other.
            if (r + k < rows) {
                const float* z_new = min_z.row(r + k);
                for (std::ptrdiff_t c = detail::next_positive(edge.data(), 0, cols); c < cols;
                     c = detail::next_positive(edge.data(), c + 1, cols)) {
                    detail::prefetch_read(z_new + std::max<std::ptrdiff_t>(0, c - k));
                    detail::prefetch_read(z_new + std::min(cols - 1, c + k));
                }
            }
            for (std::ptrdiff_t c = detail::next_positive(edge.data(), 0, cols); c < cols;
                 c = detail::next_positive(edge.data(), c + 1, cols)) {
                if (!std::isfinite(z[c])) continue;
                const std::int32_t own = in(r, c);
                const std::ptrdiff_t c0 = std::max<std::ptrdiff_t>(0, c - k), c1 = std::min(cols - 1, c + k);
                const std::size_t width = static_cast<std::size_t>(c1 - c0 + 1);
                std::size_t n = 0;
                for (const auto& w : window) {
                    if (level.size() < n + width) level.resize(n + width);  // grows with the heights kept
                    float* out = level.data();
                    // Every height is written and kept when it counts (no branch on the mix of cells).
                    for (std::ptrdiff_t cc = c0; cc <= c1; ++cc) {
                        out[n] = w.z[cc];
                        n +=
                            static_cast<std::size_t>((w.cls[cc] == 1) & (w.labels[cc] == own) & std::isfinite(w.z[cc]));
                    }
                }
                if (n < opt.min_level_cells) continue;
                const double rise =
                    static_cast<double>(z[c]) - static_cast<double>(detail::upper_median(level.data(), n));
                if (rise > opt.min_rise_m && rise <= opt.max_rise_m) trimmed.push_back(r * cols + c);
            }
        }
        return trimmed;
    });
    std::size_t count = 0;
    for (const auto& band : trimmed_in) {
        for (const std::ptrdiff_t i : band) labels(i / cols, i % cols) = 0;
        count += band.size();
    }
    return count;
}

}  // namespace lidarfx
