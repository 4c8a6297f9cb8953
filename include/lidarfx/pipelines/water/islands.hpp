// SPDX-License-Identifier: Apache-2.0
// fill_small_islands: small land holes inside one waterbody become part of it; islands stay land.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/kernels/label/connected_components.hpp"
#include "lidarfx/pipelines/water/water_rasters.hpp"

namespace lidarfx {

/// Options of fill_small_islands.
struct fill_small_islands_options {
    double island_min_area_m2 = 200.0;  ///< holes of at least this area stay land (islands), smaller ones
                                        ///< become water, m²; >= 0, 0 keeps every hole. Default 200 m².
    execution run = {};                 ///< threads of the labelling (same result for any count), progress
};

namespace detail {

inline void validate(const fill_small_islands_options& o, const char* fn)
{
    require(o.island_min_area_m2 >= 0, fn, "island_min_area_m2", ">= 0", o.island_min_area_m2);
    require(o.run.threads >= 0, fn, "run.threads", ">= 0", o.run.threads);
}

}  // namespace detail

/// Fills the small holes of waterbodies. A hole is a 4-connected component of land cells (label 0) that
/// touches no raster edge and whose 4-neighbours all carry one body's label; it becomes part of that body
/// when its area, cells · cell_m², is below island_min_area_m2 (it holds fewer than
/// ceil(island_min_area_m2 / cell_m²) cells). Land next to two bodies, or reaching the border, stays land.
/// Built on the label kernels: the land inside the bounding box of all bodies, grown by one cell, is
/// labelled once (connected_components, 4-connected); parts on the box's edge or too large are dropped,
/// one pass finds each remaining part's neighbour bodies, and one fills. O(cells). Progress: 0 on entry,
/// 1 when done. Returns the number of cells filled.
/// @throws invalid_input on cell_m <= 0, options out of range, negative labels; cancelled.
inline std::size_t fill_small_islands(raster_view<std::int32_t> labels, double cell_m,
                                      const fill_small_islands_options& opt = {})
{
    constexpr const char* fn = "fill_small_islands";
    detail::require_positive(cell_m, fn, "cell_m");
    detail::validate(opt, fn);
    const std::ptrdiff_t rows = labels.rows(), cols = labels.cols();
    // Bounding box of the bodies: every hole lies inside it.
    std::ptrdiff_t r0 = rows, c0 = cols, r1 = -1, c1 = -1;
    std::int32_t lowest = 0;
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        const std::int32_t* row = labels.row(r);
        std::ptrdiff_t first = cols, last = -1;
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            lowest = std::min(lowest, row[c]);
            if (row[c] > 0) {
                first = std::min(first, c);
                last = c;
            }
        }
        if (last < 0) continue;
        r0 = std::min(r0, r);
        r1 = r;
        c0 = std::min(c0, first);
        c1 = std::max(c1, last);
    }
    detail::require(lowest >= 0, fn, "labels", ">= 0", lowest);
    detail::report(opt.run.progress, 0.0, fn);
    // Clamped so that any area converts; no raster holds 2^60 cells.
    const auto max_hole_cells =
        static_cast<std::size_t>(std::min(std::ceil(opt.island_min_area_m2 / (cell_m * cell_m)), 0x1p60));
    std::size_t filled = 0;
    if (max_hole_cells > 0 && r1 >= 0) {
        // The box grown by one cell: where its edge is not the raster's border, the edge is land that reaches
        // the border outside the box, so the holes of the box are exactly the holes of the raster.
        r0 = std::max<std::ptrdiff_t>(0, r0 - 1), c0 = std::max<std::ptrdiff_t>(0, c0 - 1);
        r1 = std::min(rows - 1, r1 + 1), c1 = std::min(cols - 1, c1 + 1);
        const std::ptrdiff_t nr = r1 - r0 + 1, nc = c1 - c0 + 1;
        const auto box = labels.window(r0, c0, nr, nc);
        raster<std::uint8_t> land(nr, nc, uninitialized);
        for (std::ptrdiff_t r = 0; r < nr; ++r) {
            const std::int32_t* in = box.row(r);
            std::uint8_t* out = land.row(r);
            for (std::ptrdiff_t c = 0; c < nc; ++c) out[c] = in[c] == 0;
        }
        const auto parts =
            connected_components(land, components_options{.conn = connectivity::four, .threads = opt.run.threads});
        // owner[k]: the body around part k while it may be a hole; 0 = none seen yet, -1 = not a hole (too
        // large, on the box's edge, or next to two bodies).
        std::vector<std::int32_t> owner(parts.sizes.size(), 0);
        owner[0] = -1;
        for (std::size_t k = 1; k < parts.sizes.size(); ++k)
            if (parts.sizes[k] >= max_hole_cells) owner[k] = -1;
        for (std::ptrdiff_t c = 0; c < nc; ++c)
            owner[static_cast<std::size_t>(parts.labels(0, c))] = owner[static_cast<std::size_t>(parts.labels(nr - 1, c))] = -1;
        for (std::ptrdiff_t r = 0; r < nr; ++r)
            owner[static_cast<std::size_t>(parts.labels(r, 0))] = owner[static_cast<std::size_t>(parts.labels(r, nc - 1))] = -1;
        const auto meet = [](std::int32_t& o, std::int32_t l) {
            if (l > 0 && o >= 0) o = o == 0 || o == l ? l : -1;
        };
        for (std::ptrdiff_t r = 1; r < nr - 1; ++r) {
            const std::int32_t* part = parts.labels.row(r);
            for (std::ptrdiff_t c = 1; c < nc - 1; ++c) {
                auto& o = owner[static_cast<std::size_t>(part[c])];
                if (o < 0) continue;
                meet(o, box(r - 1, c));
                meet(o, box(r + 1, c));
                meet(o, box(r, c - 1));
                meet(o, box(r, c + 1));
            }
        }
        for (std::ptrdiff_t r = 1; r < nr - 1; ++r) {
            const std::int32_t* part = parts.labels.row(r);
            std::int32_t* out = box.row(r);
            for (std::ptrdiff_t c = 1; c < nc - 1; ++c) {
                const auto o = owner[static_cast<std::size_t>(part[c])];
                if (o <= 0) continue;
                out[c] = o;
                ++filled;
            }
        }
    }
    detail::report(opt.run.progress, 1.0, fn);
    return filled;
}

}  // namespace lidarfx
