// SPDX-License-Identifier: Apache-2.0
// merge_roof_surfaces: adjacent roof surfaces of one building merged, best pair first, while one plane fits
// both (extract_buildings step 5, after the remaining cells are assigned).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numeric>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/plane_fit.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/pipelines/buildings/grow_roof_surfaces.hpp"
#include "lidarfx/pipelines/buildings/local_planes.hpp"

namespace lidarfx {

/// Settings of merge_roof_surfaces.
struct merge_roof_surfaces_options {
    double merge_rms_m = 0.1;  ///< adjacent surfaces merge while one plane fits both with an RMS <=
                               ///< plane_tolerance x merge_rms_m / plane_rms_m, metres; finite and >= 0
};

/// Merges adjacent surfaces (4-neighbour cells, which always share a building) while one plane fits both: of
/// all adjacent pairs, the one whose joint least-squares fit (over fit_roof_regions' sums) leaves the least
/// RMS / plane_tolerance(planar, tan^2 tilt) x plane_rms_m (ties to the smaller pair), while that is <=
/// merge_rms_m; a merged surface keeps the smaller id, and later pairs use the joint sums. Ids are not made
/// consecutive (number_roof_surfaces numbers them). z and cell_m in metres. O(pairs x merges + cells).
/// @throws invalid_input on bad options or cell_m, or if z and the regions differ in shape.
inline void merge_roof_surfaces(roof_regions& regions, raster_view<const float> z, double cell_m,
                                const local_planes_options& planar = {}, const merge_roof_surfaces_options& opt = {});

namespace detail {

/// Root of x in a union-find forest (path halving).
inline std::int32_t uf_find(std::vector<std::int32_t>& parent, std::int32_t x) noexcept
{
    while (parent[static_cast<std::size_t>(x)] != x) {
        parent[static_cast<std::size_t>(x)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
        x = parent[static_cast<std::size_t>(x)];
    }
    return x;
}

/// The distinct pairs (g, h), g < h, of surfaces with 4-adjacent cells, sorted.
inline std::vector<std::pair<std::int32_t, std::int32_t>> adjacent_surfaces(const roof_regions& regions)
{
    const std::ptrdiff_t rows = regions.region.rows(), cols = regions.region.cols();
    std::vector<std::pair<std::int32_t, std::int32_t>> pairs;
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const std::int32_t g = regions.region(r, c);
            if (g <= 0) continue;
            for (int k = 0; k < 2; ++k) {  // south and east neighbours
                const std::ptrdiff_t rr = r + (k == 0 ? 1 : 0), cc = c + (k == 1 ? 1 : 0);
                if (rr >= rows || cc >= cols) continue;
                const std::int32_t h = regions.region(rr, cc);
                if (h > 0 && h != g) pairs.emplace_back(std::min(g, h), std::max(g, h));
            }
        }
    }
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    return pairs;
}

}  // namespace detail

// ---- implementation ----

inline void merge_roof_surfaces(roof_regions& regions, raster_view<const float> z, double cell_m,
                                const local_planes_options& planar, const merge_roof_surfaces_options& opt)
{
    constexpr const char* function = "merge_roof_surfaces";
    detail::require_positive(cell_m, function, "cell_m");
    detail::check_local_planes(planar, function);
    detail::require(opt.merge_rms_m >= 0 && opt.merge_rms_m < 1e300, function, "merge_rms_m", "finite and >= 0",
                    opt.merge_rms_m);
    detail::require_same_shape(z, regions.region, function, "z", "regions");
    auto sums = fit_roof_regions(regions, z, cell_m);
    std::vector<std::int32_t> parent(static_cast<std::size_t>(regions.count) + 1);
    std::iota(parent.begin(), parent.end(), 0);
    auto pairs = detail::adjacent_surfaces(regions);
    for (;;) {
        double least = std::numeric_limits<double>::infinity();
        std::pair<std::int32_t, std::int32_t> chosen{0, 0};
        for (auto& [g, h] : pairs) {
            g = detail::uf_find(parent, g);
            h = detail::uf_find(parent, h);
            if (g == h) continue;
            plane_sums joint = sums[static_cast<std::size_t>(g)];
            joint.add(sums[static_cast<std::size_t>(h)]);
            // RMS relative to the tolerance of planar cells at its slope.
            const auto f = detail::plane_abc_rms(joint);
            const double rise = f[3] / plane_tolerance(planar, f[0] * f[0] + f[1] * f[1], cell_m) * planar.plane_rms_m;
            if (rise < least || (rise == least && std::pair{std::min(g, h), std::max(g, h)} < chosen)) {
                least = rise;
                chosen = {std::min(g, h), std::max(g, h)};
            }
        }
        if (!(least <= opt.merge_rms_m)) break;
        parent[static_cast<std::size_t>(chosen.second)] = chosen.first;
        sums[static_cast<std::size_t>(chosen.first)].add(sums[static_cast<std::size_t>(chosen.second)]);
    }
    for (auto& g : regions.region) {
        if (g > 0) g = detail::uf_find(parent, g);
    }
}

}  // namespace lidarfx
