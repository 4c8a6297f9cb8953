// SPDX-License-Identifier: Apache-2.0
// hydro_qa: the hydro-flattening checks of a finished DEM, per waterbody.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/pipelines/water/river_profile.hpp"

namespace lidarfx {

/// The checks a hydro-flattened DEM must pass, per waterbody.
enum class hydro_check_kind {
    flatness,        ///< lake: max − min of the DEM over the body; river: the largest max − min of a
                     ///< cross-section. Metres; passes at <= flat_tolerance_m
    monotonic_fall,  ///< river: sections whose level lies above the level of the section upstream. Count; passes at 0
    shoreline,       ///< land cells beside the body whose ground lies below its water. Count; passes at 0
    minimum_size,    ///< lake: area, m², river: nominal width, m; passes at >= the minimum of its kind
};

/// The name of a check as written in tables: flatness, monotonic_fall, shoreline, minimum_size.
constexpr std::string_view hydro_check_name(hydro_check_kind k) noexcept
{
    switch (k) {
        case hydro_check_kind::flatness:
            return "flatness";
        case hydro_check_kind::monotonic_fall:
            return "monotonic_fall";
        case hydro_check_kind::shoreline:
            return "shoreline";
        case hydro_check_kind::minimum_size:
            return "minimum_size";
    }
    return "unknown";
}

/// One check of one body.
struct hydro_check {
    std::int32_t body = 0;  ///< the body's id (its label)
    hydro_check_kind kind = hydro_check_kind::flatness;
    double value = 0;  ///< what was measured (units per kind)
    double limit = 0;  ///< the limit it is held to
    bool pass = false;
    double worst_m = 0;  ///< flatness: = value; shoreline: the depth of the deepest shore cell below the water,
                         ///< metres; 0 otherwise
    std::ptrdiff_t worst_row = -1, worst_col = -1;  ///< the worst offending cell, raster cells (-1 when none)
};

/// What hydro_qa checks a body against.
struct hydro_qa_body {
    std::int32_t id = 0;                     ///< the body's label in `body`
    bool river = false;                      ///< a river (its sections in `profile`) or a lake
    double size = 0;                         ///< lake: area, m²; river: nominal width, m
    double min_size = 0;                     ///< the minimum of its kind, in the same unit
    const river_profile* profile = nullptr;  ///< rivers: their sections (not owned)
};

/// Checks a hydro-flattened DEM (`dem`, metres) against its water (`water_surface`, metres, NaN off the water;
/// `body`, the flattened body's id per cell, 0 elsewhere): per body, in the order given, flatness (tolerance
/// flat_tolerance_m, metres), monotonic_fall (rivers only), shoreline (land cells 8-adjacent to the body whose
/// DEM lies below the highest water surface of the body beside them; the worst is the deepest) and
/// minimum_size. O(cells + sum of the bodies' boxes).
/// @throws invalid_input on rasters of different shapes, or a river without a profile.
inline std::vector<hydro_check> hydro_qa(raster_view<const float> dem, raster_view<const float> water_surface,
                                         raster_view<const std::int32_t> body, std::span<const hydro_qa_body> bodies,
                                         double flat_tolerance_m = 0.001);

}  // namespace lidarfx

#include "lidarfx/pipelines/water/detail/hydro_qa_impl.hpp"
