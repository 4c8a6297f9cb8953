// SPDX-License-Identifier: Apache-2.0
// Implementation of enforce_shorelines (included at the end of pipelines/water/enforce_shorelines.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "lidarfx/core/error.hpp"

namespace lidarfx {

namespace detail {

/// The highest finite `surface` among the 8 neighbours of (r, c); NaN when none is finite.
inline float highest_neighbour(raster_view<const float> surface, std::ptrdiff_t r, std::ptrdiff_t c)
{
    float high = NAN;
    for (std::ptrdiff_t rr = std::max<std::ptrdiff_t>(r - 1, 0); rr <= std::min(r + 1, surface.rows() - 1); ++rr)
        for (std::ptrdiff_t cc = std::max<std::ptrdiff_t>(c - 1, 0); cc <= std::min(c + 1, surface.cols() - 1); ++cc)
            if (const float w = surface(rr, cc); std::isfinite(w) && !(w <= high)) high = w;
    return high;
}

}  // namespace detail

inline shoreline_check enforce_shorelines(raster_view<float> ground, raster_view<const float> water_surface,
                                          shoreline_rule rule)
{
    detail::require_same_shape(ground, water_surface, "enforce_shorelines", "ground", "water_surface");
    shoreline_check out;
    for (std::ptrdiff_t r = 0; r < ground.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < ground.cols(); ++c) {
            if (std::isfinite(water_surface(r, c)) || !std::isfinite(ground(r, c))) continue;
            const float h = detail::highest_neighbour(water_surface, r, c);
            if (!(ground(r, c) < h)) continue;
            ++out.below;
            if (const double depth = static_cast<double>(h) - ground(r, c); depth > out.worst_m) {
                out.worst_m = depth;
                out.worst_row = r;
                out.worst_col = c;
            }
            if (rule == shoreline_rule::lift) ground(r, c) = h;
        }
    return out;
}

}  // namespace lidarfx
