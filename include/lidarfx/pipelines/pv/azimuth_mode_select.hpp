// SPDX-License-Identifier: Apache-2.0
// azimuth_mode_select: the rooftop PV paper's rules that turn the mode of a building's roof aspects into the
// azimuth of its PV plane (appendix step 5: two-, three- and four-plane roofs, complex roofs unsuitable),
// with the roof form detected from the aspect histogram and the decision returned with its reason.
#pragma once

#include <cmath>
#include <cstdint>
#include <span>

namespace lidarfx {

/// Settings of azimuth_mode_select. Angles in degrees clockwise from north.
struct azimuth_mode_select_options {
    double window_deg = 10.0;            ///< a plane "has cells near" an azimuth when some aspect lies within this
    double four_plane_low_deg = 90.0;    ///< four/three-plane turn applies to modes in [low, high] ...
    double four_plane_high_deg = 160.0;  ///< ... (the paper's text says 180; a mode in (160, 180] already faces
                                         ///< south and is kept)
    /// Plane detection: the histogram is smoothed by a circular box of +-smooth_deg, and a plane is a local
    /// maximum holding at least min_plane_share of the building's cells within +-plane_halfwidth_deg, at
    /// least min_plane_separation_deg from a larger plane.
    double smooth_deg = 5.0;
    double plane_halfwidth_deg = 20.0;
    double min_plane_share = 0.08;
    double min_plane_separation_deg = 50.0;
};

/// Roof forms told apart by the number of major aspect planes.
enum class roof_form : std::uint8_t { no_cells, one_plane, two_planes, three_planes, four_planes, complex };

/// Why azimuth_mode_select chose what it chose.
enum class azimuth_reason : std::uint8_t {
    no_cells,         ///< the building has no aspect: unsuitable
    too_many_planes,  ///< more than four major planes: unsuitable (step 5d)
    kept,             ///< the mode already faces the southern half (or no rule applies): azimuth = mode
    swapped,          ///< two planes, mode in (270, 90): azimuth = mode + 180 (step 5a)
    swap_abandoned,   ///< one or three planes: no aspect within window_deg of the swapped/turned azimuth (5c)
    turned_west,      ///< three/four planes, mode in [low, high], more west- than east-facing cells: mode + 90 (5b)
    kept_east,        ///< three/four planes, mode in [low, high], west-facing cells not more: azimuth = mode
};

/// The outcome for one building.
struct azimuth_selection {
    double azimuth_deg = NAN;  ///< chosen PV azimuth in [0, 360); NaN when unsuitable
    double mode_deg = NAN;     ///< mode of the aspect histogram (the fullest 1-degree bin's centre)
    int planes = 0;            ///< major planes found
    roof_form form = roof_form::no_cells;
    azimuth_reason reason = azimuth_reason::no_cells;
    bool suitable = false;  ///< false for no_cells and too_many_planes
};

/// The PV azimuth of one building from its roof aspects, by the paper's rules (appendix step 5), given the
/// building's aspect histogram in 1-degree bins (bin k = aspects in [k - 0.5, k + 0.5), 360 bins; e.g.
/// zonal_circular_statistics' histogram). mode = the fullest bin (ties: the smallest azimuth). The roof form
/// is the number of major planes in the histogram (options). Then:
/// - no aspect: unsuitable (no_cells); more than four planes: unsuitable (too_many_planes);
/// - two planes: mode in (270, 360) or [0, 90) -> mode + 180 (swapped), else kept;
/// - one plane (a shed): as two planes, but the swap is abandoned when no aspect lies within window_deg of
///   mode + 180 (a north-facing shed has no south side);
/// - three or four planes: a mode in (270, 90) is swapped as for two planes; a mode in [low, high] (default
///   [90, 160]: the east-facing side) turns to mode + 90 when the building has more west-facing aspects
///   (180, 360) than east-facing ones (0, 180) (turned_west), else stays (kept_east); three planes abandon a
///   swap or turn when no aspect lies within window_deg of the new azimuth (one side is missing);
/// - else kept. The result may still face north of east or west: the caller's east-south-west filter decides.
/// @throws invalid_input if the histogram does not have 360 bins or an option is out of range.
inline azimuth_selection azimuth_mode_select(std::span<const std::uint32_t> aspect_histogram,
                                             const azimuth_mode_select_options& opt = {});

}  // namespace lidarfx

#include "lidarfx/pipelines/pv/detail/azimuth_mode_select_impl.hpp"
