// SPDX-License-Identifier: Apache-2.0
// halo: the reach in cells of each local raster step: how far from a cell the inputs that decide it can lie, so a
// tile computed with a halo that wide gives its core cells exactly (tiled_local, docs/scale.md).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>

#include "lidarfx/core/error.hpp"
#include "lidarfx/kernels/filter/angular_filter.hpp"
#include "lidarfx/kernels/filter/morphology.hpp"
#include "lidarfx/kernels/interpolate/idw_fill.hpp"
#include "lidarfx/pipelines/water/extract_waterbodies.hpp"

// Reach of a step = the largest Chebyshev distance (cells) between an output cell and an input cell that can
// change it. Steps that are not local and have no reach: survey_footprint (a disc rolls in from beyond the
// grid and a flood fill follows the uncovered cells, so a cell can depend on the whole grid), idw_fill with an
// unlimited radius (radius_m = 0), connected_components (stitch_labels.hpp instead), waterbody growth and
// horizon_map angles below any elevation bound (the horizon can be set by a cell at any distance).

namespace lidarfx {

/// Reach of angular_filter: its (2 radius_cells + 1)^2 window, so radius_cells.
inline std::ptrdiff_t angular_filter_reach(const angular_filter_options& opt)
{
    detail::require(opt.radius_cells >= 1, "angular_filter_reach", "radius_cells", ">= 1", opt.radius_cells);
    return opt.radius_cells;
}

/// Reach of `steps` morphology steps by the same rectangle (1 for morph_dilate / morph_erode, 2 for morph_open /
/// morph_close): steps x max(size_cells / 2, height_cells / 2) (integer halves; height 0 = size).
inline std::ptrdiff_t morphology_reach(const morphology_options& opt, int steps = 1)
{
    constexpr const char* fn = "morphology_reach";
    detail::require(opt.size_cells >= 1 && opt.size_cells % 2 == 1, fn, "size_cells", "odd and >= 1", opt.size_cells);
    detail::require(opt.height_cells >= 0 && (opt.height_cells == 0 || opt.height_cells % 2 == 1), fn, "height_cells",
                    "odd and >= 1, or 0", opt.height_cells);
    detail::require(steps >= 1, fn, "steps", ">= 1", steps);
    const int height = opt.height_cells == 0 ? opt.size_cells : opt.height_cells;
    return static_cast<std::ptrdiff_t>(steps) * std::max(opt.size_cells / 2, height / 2);
}

/// Reach of slope_aspect: Horn's 3 x 3 window, so 1.
constexpr std::ptrdiff_t slope_aspect_reach() noexcept
{
    return 1;
}

/// Reach of idw_fill with a finite radius: idw_fill_reach_cells(opt, cell_m) (kernels/interpolate/idw_fill.hpp),
/// the largest whole number of cells n with n <= radius_m / cell_m + 1e-9.
/// @throws invalid_input as idw_fill_reach_cells: radius_m 0 (unlimited, not local) or not finite and > 0, or
/// cell_m not finite and > 0.
inline std::ptrdiff_t idw_fill_reach(const idw_fill_options& opt, double cell_m)
{
    return idw_fill_reach_cells(opt, cell_m);
}

/// Reach of a cast shadow (raylines_shadow) or of a horizon above an elevation (horizon_map where only angles
/// >= min_elevation_deg matter): a cell d metres away along the ray rises above the elevation only if
/// relief_m >= d tan(min_elevation_deg), so reach = ceil(relief_m / (tan(min_elevation_deg) cell_m)) cells,
/// relief_m = zmax - zmin of the surface (metres). Along the grid axes the ray is a row or column and this is
/// exact; at other azimuths add 1 for the rendering of the digital ray line (and see docs/scale.md: the lines
/// are anchored at the raster's first row or column, so a window renders them differently).
/// @throws invalid_input if relief_m is negative or not finite, cell_m is not finite and > 0, or
/// min_elevation_deg is not in (0, 90).
inline std::ptrdiff_t shadow_reach(double relief_m, double min_elevation_deg, double cell_m)
{
    constexpr const char* fn = "shadow_reach";
    detail::require(relief_m >= 0 && relief_m <= 1.0e300, fn, "relief_m", "finite and >= 0", relief_m);
    detail::require_positive(cell_m, fn, "cell_m");
    detail::require(min_elevation_deg > 0 && min_elevation_deg < 90, fn, "min_elevation_deg", "in (0, 90)",
                    min_elevation_deg);
    const double cells = relief_m / (std::tan(min_elevation_deg * (std::numbers::pi / 180.0)) * cell_m);
    detail::require(cells < 1.0e15, fn, "relief_m / (tan(min_elevation_deg) cell_m)", "below 1e15 cells", cells);
    return static_cast<std::ptrdiff_t>(std::ceil(cells));
}

/// Reaches of the local steps of the waterbody method (extract_waterbodies); its other steps (seed components,
/// growth, measurement) are not local and run on the survey-wide rasters (docs/scale.md).
struct water_step_reach {
    std::ptrdiff_t vegetation_closing = 0;  ///< water_vegetation: morph_close, 2 x (closing size / 2)
    std::ptrdiff_t angles = 0;              ///< water_angles: angular_filter radius
    std::ptrdiff_t seed_opening = 0;        ///< water_seeds: morph_open of the dropout mask, 2 x (opening size / 2)
    /// The largest of the three: a halo that serves every local step.
    std::ptrdiff_t largest() const noexcept { return std::max({vegetation_closing, angles, seed_opening}); }
};

/// Reaches of the waterbody method's local steps for the given options. @throws invalid_input as the steps do
/// for sizes that are even or < 1 or a radius < 1, and when angles.input is idw_filled (the angles then read
/// min z filled by idw_fill with an unlimited radius, which is not local).
inline water_step_reach water_reach(const extract_waterbodies_options& opt)
{
    detail::require(opt.angles.input == angular_input::returns_only, "water_reach",
                    "angles.input must be returns_only: with idw_filled the angles read an IDW fill of unlimited "
                    "radius, which is not local (no halo makes a tile exact)");
    return {morphology_reach({.size_cells = opt.vegetation.closing_size_cells}, 2),
            angular_filter_reach({.radius_cells = opt.angles.radius_cells}),
            morphology_reach({.size_cells = opt.seeds.opening_size_cells}, 2)};
}

}  // namespace lidarfx
