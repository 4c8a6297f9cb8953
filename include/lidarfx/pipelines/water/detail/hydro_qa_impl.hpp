// SPDX-License-Identifier: Apache-2.0
// Implementation of hydro_qa (included at the end of pipelines/water/hydro_qa.hpp).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/grid.hpp"
#include "lidarfx/pipelines/water/lake_level.hpp"

namespace lidarfx {

inline std::vector<hydro_check> hydro_qa(raster_view<const float> dem, raster_view<const float> water_surface,
                                         raster_view<const std::int32_t> body, std::span<const hydro_qa_body> bodies,
                                         double flat_tolerance_m)
{
    constexpr const char* fn = "hydro_qa";
    detail::require_same_shape(dem, water_surface, fn, "dem", "water_surface");
    detail::require_same_shape(dem, body, fn, "dem", "body");
    // The box of every id, in one pass.
    std::int32_t top = 0;
    for (const auto& b : bodies) {
        detail::require(b.id > 0, fn, "bodies[i].id", "> 0", b.id);
        top = std::max(top, b.id);
    }
    std::vector<cell_box> box(static_cast<std::size_t>(top) + 1);
    for (std::ptrdiff_t r = 0; r < body.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < body.cols(); ++c)
            if (const std::int32_t id = body(r, c); id > 0 && id <= top) box[static_cast<std::size_t>(id)].extend(r, c);
    std::vector<hydro_check> out;
    for (const auto& b : bodies) {
        detail::require(!b.river || b.profile != nullptr, fn, "a river needs its profile");
        const cell_box& bx = box[static_cast<std::size_t>(b.id)];
        // Flatness: lakes over the body, rivers per section.
        hydro_check flat{b.id, hydro_check_kind::flatness, 0, flat_tolerance_m, true};
        const std::size_t groups = b.river ? b.profile->level_m.size() : 1;
        std::vector<float> low(groups, std::numeric_limits<float>::infinity()), high(groups, -low[0]);
        std::vector<std::array<std::ptrdiff_t, 2>> where(groups, {-1, -1});
        for (std::ptrdiff_t r = bx.row_min; r <= bx.row_max; ++r)
            for (std::ptrdiff_t c = bx.col_min; c <= bx.col_max; ++c) {
                if (body(r, c) != b.id) continue;
                std::size_t g = 0;
                if (b.river) {
                    const river_profile& p = *b.profile;
                    const bool in_profile = r >= p.box.row_min && r <= p.box.row_max && c >= p.box.col_min &&
                                            c <= p.box.col_max;  // water added beyond it has no section
                    const std::int32_t k = in_profile ? p.section(r - p.box.row_min, c - p.box.col_min) : -1;
                    if (k < 0) continue;
                    g = static_cast<std::size_t>(k);
                }
                low[g] = std::min(low[g], dem(r, c));
                if (dem(r, c) > high[g]) {
                    high[g] = dem(r, c);
                    where[g] = {r, c};
                }
            }
        for (std::size_t g = 0; g < groups; ++g)
            if (high[g] >= low[g] && static_cast<double>(high[g]) - low[g] > flat.value) {
                flat.value = static_cast<double>(high[g]) - low[g];
                flat.worst_row = where[g][0];
                flat.worst_col = where[g][1];
            }
        flat.pass = flat.value <= flat_tolerance_m;
        flat.worst_m = flat.value;
        out.push_back(flat);
        if (b.river) {
            const river_profile& p = *b.profile;
            hydro_check fall{b.id, hydro_check_kind::monotonic_fall, 0, 0, true};
            for (std::size_t s = 0; s + 1 < p.level_m.size(); ++s)
                if (p.level_m[s + 1] > p.level_m[s]) {
                    if (fall.value == 0) {
                        fall.worst_row = static_cast<std::ptrdiff_t>(std::lround(p.centre[s + 1][0]));
                        fall.worst_col = static_cast<std::ptrdiff_t>(std::lround(p.centre[s + 1][1]));
                    }
                    fall.value += 1;
                }
            fall.pass = fall.value == 0;
            out.push_back(fall);
        }
        // Shoreline: land beside the body below its water.
        hydro_check shore{b.id, hydro_check_kind::shoreline, 0, 0, true};
        double worst = 0;
        if (!bx.empty())
            detail::for_each_shore_cell(body, b.id, bx, [&](std::ptrdiff_t r, std::ptrdiff_t c) {
                if (std::isfinite(water_surface(r, c)) || !std::isfinite(dem(r, c))) return;
                float h = NAN;
                for (std::ptrdiff_t rr = std::max<std::ptrdiff_t>(r - 1, 0); rr <= std::min(r + 1, dem.rows() - 1);
                     ++rr)
                    for (std::ptrdiff_t cc = std::max<std::ptrdiff_t>(c - 1, 0); cc <= std::min(c + 1, dem.cols() - 1);
                         ++cc)
                        if (body(rr, cc) == b.id && std::isfinite(water_surface(rr, cc)) &&
                            !(water_surface(rr, cc) <= h))
                            h = water_surface(rr, cc);
                if (!(dem(r, c) < h)) return;
                shore.value += 1;
                if (static_cast<double>(h) - dem(r, c) > worst) {
                    worst = static_cast<double>(h) - dem(r, c);
                    shore.worst_row = r;
                    shore.worst_col = c;
                }
            });
        shore.pass = shore.value == 0;
        shore.worst_m = worst;
        out.push_back(shore);
        out.push_back({b.id, hydro_check_kind::minimum_size, b.size, b.min_size, b.size >= b.min_size});
    }
    return out;
}

}  // namespace lidarfx
