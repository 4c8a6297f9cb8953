// SPDX-License-Identifier: Apache-2.0
// Implementation of join_level_cells (included at the end of pipelines/water/join_level_cells.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>
#include "lidarfx/core/error.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

namespace detail {

inline void validate(const join_level_cells_options& o, const char* fn)
{
    require(o.tolerance_m >= 0, fn, "tolerance_m", ">= 0", o.tolerance_m);
    require(o.max_rise_m >= 0, fn, "max_rise_m", ">= 0", o.max_rise_m);
    require(o.depth_cells >= 0, fn, "depth_cells", ">= 0", o.depth_cells);
}

}  // namespace detail

namespace detail {

/// join_level_cells after its checks, on a region whose cells hold `stamp` in `seen` already, and only
/// they: every other cell must differ from `stamp` on entry. Joined cells get the stamp too; with `taken`
/// (not null) they also get taken[j] = 0 (grow_waterbodies: a new body's label is the stamp, the eligible
/// raster is taken).
inline void join_level_cells_stamped(std::vector<std::ptrdiff_t>& region, raster_view<const float> min_z,
                                     raster_view<const float> max_z, const std::uint8_t* eligible, std::uint8_t* taken,
                                     std::int32_t* seen, std::int32_t stamp, const join_level_cells_options& opt)
{
    if (opt.tolerance_m <= 0 || opt.depth_cells <= 0) return;
    const std::ptrdiff_t rows = min_z.rows(), cols = min_z.cols();
    struct entry {
        std::ptrdiff_t cell;
        float level;
        int depth;
    };
    std::vector<entry> frontier;
    // Only region cells on the region's edge can reach a new cell: interior ones start nothing.
    const auto on_edge = [&](std::ptrdiff_t r, std::ptrdiff_t c) {
        if (r > 0 && c > 0 && r + 1 < rows && c + 1 < cols) {  // all 8 neighbours exist: no loop, no branch
            const std::int32_t* up = seen + (r - 1) * cols + c;
            const std::int32_t* mid = up + cols;
            const std::int32_t* down = mid + cols;
            return ((up[-1] != stamp) | (up[0] != stamp) | (up[1] != stamp) | (mid[-1] != stamp) | (mid[1] != stamp) |
                    (down[-1] != stamp) | (down[0] != stamp) | (down[1] != stamp)) != 0;
        }
        for (std::ptrdiff_t rr = std::max<std::ptrdiff_t>(0, r - 1); rr <= std::min(rows - 1, r + 1); ++rr)
            for (std::ptrdiff_t cc = std::max<std::ptrdiff_t>(0, c - 1); cc <= std::min(cols - 1, c + 1); ++cc)
                if (seen[rr * cols + cc] != stamp) return true;
        return false;
    };
    const cell_splitter split(cols);
    // Where the region fills at least a quarter of its bounding box, its edge is flagged by one pass over the
    // box's rows (sequential and vectorized; the 8 neighbours of each cell read in the region's order cost
    // about 3x more), then read in the region's order; otherwise cell by cell.
    std::ptrdiff_t r0 = rows, r1 = -1, c0 = cols, c1 = -1;
    for (const auto i : region) {
        const auto [r, c] = split(i);
        r0 = std::min(r0, r);
        r1 = std::max(r1, r);
        c0 = std::min(c0, c);
        c1 = std::max(c1, c);
    }
    const std::ptrdiff_t box_cols = c1 - c0 + 1;
    std::vector<std::uint8_t> edge;
    if (!region.empty() && static_cast<std::size_t>((r1 - r0 + 1) * box_cols) <= 4 * region.size()) {
        edge.resize(static_cast<std::size_t>((r1 - r0 + 1) * box_cols));
        for (std::ptrdiff_t r = r0; r <= r1; ++r) {
            std::uint8_t* flag = edge.data() + (r - r0) * box_cols;  // flag[c - c0]
            const std::int32_t* here = seen + r * cols;
            // Columns whose 8 neighbours all exist, branch-free; the raster's border cell by cell.
            const auto at_border = [&](std::ptrdiff_t c) {
                flag[c - c0] = static_cast<std::uint8_t>(here[c] == stamp && on_edge(r, c));
            };
            if (r == 0 || r + 1 == rows) {
                for (std::ptrdiff_t c = c0; c <= c1; ++c) at_border(c);
                continue;
            }
            if (c0 == 0) at_border(0);
            if (c1 == cols - 1 && c1 > 0) at_border(c1);
            const std::ptrdiff_t from = std::max<std::ptrdiff_t>(c0, 1), to = std::min(c1, cols - 2);
            const std::int32_t* up = here - cols;
            const std::int32_t* down = here + cols;
            const std::int32_t s = stamp;
            for (std::ptrdiff_t c = from; c <= to; ++c) {
                flag[c - c0] = static_cast<std::uint8_t>(
                    (here[c] == s) & ((up[c - 1] != s) | (up[c] != s) | (up[c + 1] != s) | (here[c - 1] != s) |
                                      (here[c + 1] != s) | (down[c - 1] != s) | (down[c] != s) | (down[c + 1] != s)));
            }
        }
    }
    for (const auto i : region) {
        const auto [r, c] = split(i);
        if (edge.empty() ? !on_edge(r, c) : !edge[static_cast<std::size_t>((r - r0) * box_cols + (c - c0))]) continue;
        if (const float z = min_z(r, c); std::isfinite(z)) frontier.push_back({i, z, 0});
    }
    for (std::size_t q = 0; q < frontier.size(); ++q) {
        const entry e = frontier[q];
        if (e.depth >= opt.depth_cells) continue;
        const auto [r, c] = split(e.cell);
        for (std::ptrdiff_t dr = -1; dr <= 1; ++dr) {
            for (std::ptrdiff_t dc = -1; dc <= 1; ++dc) {
                const std::ptrdiff_t rr = r + dr, cc = c + dc;
                if ((dr == 0 && dc == 0) || rr < 0 || cc < 0 || rr >= rows || cc >= cols) continue;
                const std::ptrdiff_t j = rr * cols + cc;
                if (seen[j] == stamp || !eligible[j]) continue;
                // The whole cell must lie at the water level: a shore cell holding water and bank returns
                // has its lowest return on the water but its highest on the bank.
                const float lo = min_z(rr, cc), hi = max_z(rr, cc);
                if (!std::isfinite(lo) || std::abs(static_cast<double>(lo) - e.level) > opt.tolerance_m ||
                    !(static_cast<double>(hi) - e.level <= opt.max_rise_m)) {
                    continue;
                }
                seen[j] = stamp;
                if (taken) taken[j] = 0;
                region.push_back(j);
                frontier.push_back({j, e.level, e.depth + 1});
            }
        }
    }
}

}  // namespace detail

inline void join_level_cells(std::vector<std::ptrdiff_t>& region, raster_view<const float> min_z,
                             raster_view<const float> max_z, const raster<std::uint8_t>& eligible,
                             const join_level_cells_options& opt)
{
    constexpr const char* fn = "join_level_cells";
    detail::require_same_shape(min_z, max_z, fn, "min_z", "max_z");
    detail::require_same_shape(min_z, eligible, fn, "min_z", "eligible");
    detail::validate(opt, fn);
    const std::ptrdiff_t n = eligible.size();
    for (const auto i : region) {
        if (i < 0 || i >= n) [[unlikely]]
            detail::require(false, fn, "region cell index", "inside the rasters", i);
    }
    if (opt.tolerance_m <= 0 || opt.depth_cells <= 0) return;
    raster<std::int32_t> visited(min_z.rows(), min_z.cols(), 0);
    constexpr std::int32_t stamp = 1;
    std::int32_t* seen = visited.data();
    for (const auto i : region) seen[i] = stamp;
    detail::join_level_cells_stamped(region, min_z, max_z, eligible.data(), nullptr, seen, stamp, opt);
}

}  // namespace lidarfx
