// SPDX-License-Identifier: Apache-2.0
// roof_planes: every roof plane of one building from its surface cells, by normal-guided region growing,
// robust least-squares plane fits, merging of adjacent coplanar segments, a competitive reassignment of each
// cell to the plane that fits it best and the cut of planes that are two faces (the `planes` mode of
// roof_suitability).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "lidarfx/core/plane_fit.hpp"

namespace lidarfx {

/// Settings of roof_planes (roof_suitability's planes mode). Distances in metres, angles in degrees.
/// Noise-dependent tolerances are set per building from sigma, the building's elevation noise estimated as
/// sqrt(1.5) x the median rms residual of the 3x3 plane fits around its cells.
struct roof_planes_options {
    double min_angle_deg = 5.0;    ///< smallest normal tolerance of region growing and merging; > 0
    double max_angle_deg = 20.0;   ///< largest normal tolerance (tolerance = 2.5 x the normal noise of a 3x3 fit)
    double min_distance_m = 0.15;  ///< smallest distance of a cell from its plane (tolerance = max(this, 3 sigma))
    int min_seed_cells = 6;        ///< a grown region smaller than this is released (clutter, ridges); >= 3
    double min_plane_m2 = 3.0;     ///< final planes of a smaller horizontal area are clutter (cells left out)
    double max_plane_rms_m = 0.6;  ///< final planes with a larger rms residual are clutter (tree crowns); > 0
    int reassign_rounds = 3;       ///< rounds of cell reassignment and refit; >= 1
};

/// One building's surface on its bounding box (h x w cells, row-major): z in metres (NaN = not a roof cell;
/// best relative to a reference height of the building, to keep the plane sums well conditioned), cell size in
/// metres; cell (r, c) of the box lies at x = c cell_m (east), y = -r cell_m (north).
struct roof_box_surface {
    std::ptrdiff_t h = 0, w = 0;  ///< rows and columns of the box
    double cell_m = 1;            ///< cell size, metres, > 0
    std::vector<double> z;        ///< h x w elevations, metres; NaN = not a roof cell
    double x(std::ptrdiff_t i) const noexcept { return static_cast<double>(i % w) * cell_m; }
    double y(std::ptrdiff_t i) const noexcept { return -static_cast<double>(i / w) * cell_m; }
    bool in(std::ptrdiff_t i) const noexcept { return !std::isnan(z[static_cast<std::size_t>(i)]); }
    /// Calls f(j) for the 4-neighbours j of cell i that are roof cells.
    template <class F>
    void for_neighbours(std::ptrdiff_t i, F&& f) const
    {
        const std::ptrdiff_t r = i / w, c = i % w;
        if (r > 0 && in(i - w)) f(i - w);
        if (r + 1 < h && in(i + w)) f(i + w);
        if (c > 0 && in(i - 1)) f(i - 1);
        if (c + 1 < w && in(i + 1)) f(i + 1);
    }
};

/// The planes found on one building.
struct roof_planes_result {
    std::vector<std::int32_t> label;  ///< per box cell the plane index + 1 (0 = none: clutter, edges, no data)
    std::vector<plane_fit> fits;      ///< each plane's fit (tilt_deg(), azimuth_deg()); rms over all its cells
    std::vector<std::size_t> cells;   ///< each plane's number of cells
    double sigma_m = 0;               ///< the building's noise estimate, metres
};

/// Segments the roof planes of one building (see roof_planes_options):
/// 1. a 3x3 least-squares plane around each cell (roof neighbours only) gives its normal and rms residual, and
///    the building's noise sigma (sqrt(1.5) x their median rms) sets the tolerances;
/// 2. regions grow from the most planar free cell over 4-neighbours whose normal lies within the angle
///    tolerance of the region's plane and whose elevation lies within the distance tolerance of it (the plane
///    refitted as the region doubles); regions under min_seed_cells are released;
/// 3. adjacent planes merge when their joint least-squares fit is hardly worse than theirs;
/// 4. reassign_rounds times: every cell goes to the plane that reaches it with the smallest residual, planes
///    are refitted, and merged again between rounds;
/// 4b. planes that are two faces (a small gable whose every 3x3 window straddles the ridge): planar groups of
///    >= min_seed_cells cells left without a plane become planes; then planes of <= 400 cells whose rms lies
///    between min_distance_m / 2 and max_plane_rms_m are cut along the best straight line when the parts'
///    normals differ by > 2 x the angle tolerance and an F test (>= 10) says the cut explains far more than
///    noise, parts again in turn; when planes were added, a merge and reassign_rounds more rounds follow;
/// 5. final fits on each plane's interior cells; planes under min_plane_m2 or rougher than max_plane_rms_m
///    (tree crowns, chimneys) are dropped, their cells left without a plane. Planes numbered by first cell.
/// Tilt, facing and areas follow from the fits (plane_fit). O(cells log cells), plus O(n^2 log n) at worst
/// for the cuts of a plane of n <= 400 cells (27 directions per cut, at most n / 4 cuts). Options are not
/// checked here (roof_suitability checks them); an empty surface gives no plane. Never throws except
/// std::bad_alloc.
inline roof_planes_result roof_planes(const roof_box_surface& s, const roof_planes_options& o = {});

}  // namespace lidarfx

#include "lidarfx/pipelines/pv/detail/roof_planes_impl.hpp"
