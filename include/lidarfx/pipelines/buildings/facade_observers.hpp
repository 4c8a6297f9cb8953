// SPDX-License-Identifier: Apache-2.0
// facade_observers (make_facade_observers): where facade sub-patches sit on the solar kernels' ray lines: the observer
// cells in front of the walls, and a walk over the ray lines of one azimuth that visits every cell of a line in walk
// order.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "lidarfx/core/raster.hpp"
#include "lidarfx/kernels/solar/ray_lines.hpp"
#include "lidarfx/kernels/solar/shadow_probes.hpp"
#include "lidarfx/pipelines/buildings/facade_patches.hpp"

namespace lidarfx::detail {

/// The cells in front of walls (a wall's sub-patches are seen from the centre of its front cell), and which
/// sub-patches each one serves: observer o holds patches[first[o] .. first[o + 1]).
struct facade_observers {
    raster<std::int32_t> index;  ///< observer number of a cell, -1 where no wall faces it
    std::vector<std::ptrdiff_t> row, col;
    std::vector<std::size_t> first;    ///< size observers + 1
    std::vector<std::size_t> patches;  ///< indices into the sub-patch list, grouped by observer
    shadow_probes probes;  ///< the observer cells as probes of raylines_shadow_probed (probe k = observer k)
};

inline facade_observers make_facade_observers(std::ptrdiff_t rows, std::ptrdiff_t cols,
                                              std::span<const facade_patch> subs)
{
    facade_observers o;
    o.index = raster<std::int32_t>(rows, cols, -1);
    std::vector<std::size_t> count;
    for (const facade_patch& p : subs) {
        std::int32_t& k = o.index(p.front_row, p.front_col);
        if (k < 0) {
            k = static_cast<std::int32_t>(o.row.size());
            o.row.push_back(p.front_row);
            o.col.push_back(p.front_col);
            count.push_back(0);
        }
        ++count[static_cast<std::size_t>(k)];
    }
    o.first.assign(count.size() + 1, 0);
    for (std::size_t k = 0; k < count.size(); ++k) o.first[k + 1] = o.first[k] + count[k];
    o.patches.resize(subs.size());
    std::vector<std::size_t> next(o.first.begin(), o.first.end() - 1);
    for (std::size_t i = 0; i < subs.size(); ++i) {
        o.patches[next[static_cast<std::size_t>(o.index(subs[i].front_row, subs[i].front_col))]++] = i;
    }
    o.probes = make_shadow_probes(rows, cols, o.row, o.col);
    return o;
}

/// Calls visit(line - k0, r, c) for every cell of the ray lines [k0, k1) of `l` (kernels/solar/ray_lines.hpp),
/// each line's cells in walk order (away from the azimuth, so the cells towards the azimuth come first), lines
/// interleaved as in raylines_shadow's sweeps. `sh` = l.shifts().
template <class Visit>
void walk_ray_lines(const ray_lines& l, const std::vector<std::ptrdiff_t>& sh, std::ptrdiff_t k0, std::ptrdiff_t k1,
                    Visit&& visit)
{
    const std::ptrdiff_t rows = l.rows, cols = l.cols;
    if (l.steep) {
        for (std::ptrdiff_t i = 0; i < rows; ++i) {
            const std::ptrdiff_t r = l.forward() ? i : rows - 1 - i;
            const std::ptrdiff_t s = sh[static_cast<std::size_t>(r)];
            const std::ptrdiff_t c0 = std::max<std::ptrdiff_t>(0, k0 + s), c1 = std::min(cols, k1 + s);
            for (std::ptrdiff_t c = c0; c < c1; ++c) visit(c - s - k0, r, c);
        }
        return;
    }
    const bool fwd = l.forward();
    const auto [lo, hi] = ray_lines::rows_of(sh, k0, k1, rows);
    for (std::ptrdiff_t i = lo; i < hi; ++i) {
        const std::ptrdiff_t r = l.rows_forward() ? i : lo + hi - 1 - i;
        const auto [c0, c1] = l.columns(sh, r, k0, k1);
        for (std::ptrdiff_t j = c0; j < c1; ++j) {
            const std::ptrdiff_t c = fwd ? j : c0 + c1 - 1 - j;
            visit(r - sh[static_cast<std::size_t>(c)] - k0, r, c);
        }
    }
}

}  // namespace lidarfx::detail
