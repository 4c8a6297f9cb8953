// SPDX-License-Identifier: Apache-2.0
// building_outlines: the outline polygons of every building in world coordinates (extract_buildings step 6).
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/grid.hpp"
#include "lidarfx/kernels/vector/polygonize.hpp"

namespace lidarfx {

/// Outlines of buildings 1..count of `building_id` on grid g (element b - 1 for building b): polygonize's
/// polygons along cell edges, exterior counter-clockwise then holes, one polygon per 4-connected part, in the
/// grid's world coordinates. O(cells + boundary length x log(boundary length)).
/// @throws invalid_input if the shape differs from g's or a building id is outside [0, count].
template <raster_input Ids>
std::vector<std::vector<polygon>> building_outlines(const Ids& building_id, std::size_t count, const grid& g)
{
    std::vector<std::vector<polygon>> out(count);
    for (auto& lp : polygonize(building_id, g)) {
        detail::require(lp.label > 0 && static_cast<std::size_t>(lp.label) <= count, "building_outlines", "building_id",
                        "in [0, count]", lp.label);
        out[static_cast<std::size_t>(lp.label - 1)] = std::move(lp.polygons);
    }
    return out;
}

}  // namespace lidarfx
