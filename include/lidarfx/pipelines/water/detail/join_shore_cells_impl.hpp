// SPDX-License-Identifier: Apache-2.0
// Implementation of join_shore_cells (included at the end of pipelines/water/join_shore_cells.hpp).
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

inline void validate(const join_shore_cells_options& o, const char* fn)
{
    require(o.window_cells >= 1, fn, "window_cells", ">= 1", o.window_cells);
    require(o.min_contrast > 0 && o.min_contrast <= 1, fn, "min_contrast", "in (0, 1]", o.min_contrast);
    require(o.min_water_share > 0 && o.min_water_share <= 1, fn, "min_water_share", "in (0, 1]", o.min_water_share);
    require(o.min_body_neighbours >= 1 && o.min_body_neighbours <= 8, fn, "min_body_neighbours", "in [1, 8]",
            o.min_body_neighbours);
}

}  // namespace detail

inline std::size_t join_shore_cells(raster_view<std::int32_t> labels, raster_view<const std::uint32_t> count,
                                    raster_view<const std::uint8_t> excluded, raster_view<const std::uint8_t> footprint,
                                    const join_shore_cells_options& opt, const execution& run)
{
    constexpr const char* fn = "join_shore_cells";
    detail::validate(opt, fn);
    detail::require_same_shape(labels, count, fn, "labels", "count");
    if (!excluded.empty()) detail::require_same_shape(labels, excluded, fn, "labels", "excluded");
    if (!footprint.empty()) detail::require_same_shape(labels, footprint, fn, "labels", "footprint");
    detail::check_execution(run, fn);
    const std::ptrdiff_t rows = labels.rows(), cols = labels.cols();
    if (rows == 0 || cols == 0) return 0;
    enum : std::uint8_t { far_land = 0, next_to_body = 1, body = 2 };
    const std::ptrdiff_t k = opt.window_cells;
    struct joining {
        std::ptrdiff_t r, c;
        std::int32_t label;
    };
    // Bands of rows on run.threads threads, each with the cell classes of its rows and its own list of cells
    // joined; the labels change after all bands are done, so every band reads them as they came in.
    const raster_view<const std::int32_t> in = labels;
    const auto joined_in = parallel_bands(rows, 256, run.threads, [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
        detail::shore_class_rows cls(in, k, false, r0);
        std::vector<joining> joined;
        std::vector<std::uint8_t> candidate(static_cast<std::size_t>(cols));  // next to a body, inside
        struct window_row {
            const std::uint8_t* cls;
            const std::uint32_t* count;
            const std::uint8_t* excluded;  // nullptr: none
        };
        std::vector<window_row> window;
        for (std::ptrdiff_t r = r0; r < r1; ++r) {
            if (!cls.has_body(r - 1) && !cls.has_body(r) && !cls.has_body(r + 1)) continue;  // no body near this row
            cls.reach(r);
            const std::uint8_t* cl = cls.row(r);
            const std::uint8_t* inside = footprint.empty() ? nullptr : footprint.row(r);
            for (std::ptrdiff_t c = 0; c < cols; ++c)
                candidate[static_cast<std::size_t>(c)] =
                    static_cast<std::uint8_t>((cl[c] == next_to_body) & (!inside || inside[c] != 0));
            // The window rows, the same for every candidate of the row: found once.
            window.clear();
            for (std::ptrdiff_t rr = std::max<std::ptrdiff_t>(0, r - k), last = std::min(rows - 1, r + k); rr <= last;
                 ++rr)
                window.push_back({cls.row(rr) ? cls.row(rr) : cls.zero_row(), count.row(rr),
                                  excluded.empty() ? nullptr : excluded.row(rr)});
            for (std::ptrdiff_t c = detail::next_positive(candidate.data(), 0, cols); c < cols;
                 c = detail::next_positive(candidate.data(), c + 1, cols)) {
                // Body neighbours and their most frequent label.
                std::int32_t nb[8];
                int n_nb = 0;
                for (std::ptrdiff_t dr = -1; dr <= 1; ++dr) {
                    for (std::ptrdiff_t dc = -1; dc <= 1; ++dc) {
                        const std::ptrdiff_t rr = r + dr, cc = c + dc;
                        if ((dr | dc) == 0 || rr < 0 || cc < 0 || rr >= rows || cc >= cols) continue;
                        if (in(rr, cc) > 0) nb[n_nb++] = in(rr, cc);
                    }
                }
                if (n_nb < opt.min_body_neighbours) continue;
                const std::ptrdiff_t c0 = std::max<std::ptrdiff_t>(0, c - k), c1 = std::min(cols - 1, c + k);
                double water_sum = 0, water_cells = 0, land_sum = 0, land_cells = 0;
                for (const auto& w : window) {
                    for (std::ptrdiff_t cc = c0; cc <= c1; ++cc) {
                        if (w.cls[cc] == body) {
                            water_sum += w.count[cc];
                            water_cells += 1;
                        } else if (w.cls[cc] == far_land && w.count[cc] > 0 && !(w.excluded && w.excluded[cc])) {
                            land_sum += w.count[cc];
                            land_cells += 1;
                        }
                    }
                }
                if (land_cells == 0 || water_cells == 0) continue;
                const double n_land = land_sum / land_cells, n_water = water_sum / water_cells;
                if (!(n_land - n_water >= opt.min_contrast * n_land)) continue;
                if (!((n_land - count(r, c)) >= opt.min_water_share * (n_land - n_water))) continue;
                std::int32_t best = 0;  // the most frequent neighbour label, the smallest among equals
                int best_votes = 0;
                for (int i = 0; i < n_nb; ++i) {
                    const int votes = static_cast<int>(std::count(nb, nb + n_nb, nb[i]));
                    if (votes > best_votes || (votes == best_votes && nb[i] < best)) best = nb[i], best_votes = votes;
                }
                joined.push_back({r, c, best});
            }
        }
        return joined;
    });
    std::size_t joined_cells = 0;
    for (const auto& band : joined_in) {
        for (const auto& j : band) labels(j.r, j.c) = j.label;
        joined_cells += band.size();
    }
    return joined_cells;
}

}  // namespace lidarfx
