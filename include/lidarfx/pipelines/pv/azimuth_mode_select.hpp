// SPDX-License-Identifier: Apache-2.0
// azimuth_mode_select: the rooftop PV paper's rules that turn the mode of a building's roof aspects into the
// azimuth of its PV plane (appendix step 5: two-, three- and four-plane roofs, complex roofs unsuitable),
// with the roof form detected from the aspect histogram and the decision returned with its reason.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "lidarfx/core/error.hpp"

namespace lidarfx {

/// Settings of azimuth_mode_select. Angles in degrees clockwise from north.
struct azimuth_mode_select_options {
    double window_deg = 10.0;            ///< a plane "has cells near" an azimuth when some aspect lies within this
    double four_plane_low_deg = 90.0;    ///< four/three-plane turn applies to modes in [low, high] ...
    double four_plane_high_deg = 160.0;  ///< ... (the paper's text says 180; DESIGN.md and the issue 160: a mode
                                         ///< in (160, 180] already faces south and is kept)
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

namespace detail {

inline double wrap_deg(double a) noexcept
{
    double m = std::fmod(a, 360.0);
    return m < 0 ? m + 360.0 : m;
}

/// Smallest angle between two azimuths, degrees in [0, 180].
inline double azimuth_gap_deg(double a, double b) noexcept
{
    const double d = std::fabs(wrap_deg(a - b));
    return d > 180.0 ? 360.0 - d : d;
}

/// Number of major planes in a 1-degree circular histogram (see azimuth_mode_select_options).
inline int count_aspect_planes(std::span<const std::uint32_t> h, const azimuth_mode_select_options& o)
{
    const std::ptrdiff_t n = 360;
    double total = 0;
    for (const auto v : h) total += v;
    if (total <= 0) return 0;
    const auto at = [&](std::ptrdiff_t i) {
        return static_cast<double>(h[static_cast<std::size_t>(((i % n) + n) % n)]);
    };
    const auto half = static_cast<std::ptrdiff_t>(std::lround(o.smooth_deg));
    const auto wide = static_cast<std::ptrdiff_t>(std::lround(o.plane_halfwidth_deg));
    std::vector<double> smooth(static_cast<std::size_t>(n)), mass(static_cast<std::size_t>(n));
    for (std::ptrdiff_t i = 0; i < n; ++i) {
        double s = 0, m = 0;
        for (std::ptrdiff_t d = -half; d <= half; ++d) s += at(i + d);
        for (std::ptrdiff_t d = -wide; d <= wide; ++d) m += at(i + d);
        smooth[static_cast<std::size_t>(i)] = s;
        mass[static_cast<std::size_t>(i)] = m;
    }
    // Candidates: local maxima of the smoothed histogram (plateaus count once, at their first bin), largest
    // first; a candidate counts when it holds enough cells and lies far enough from every plane already kept.
    std::vector<std::ptrdiff_t> peaks;
    for (std::ptrdiff_t i = 0; i < n; ++i) {
        const double v = smooth[static_cast<std::size_t>(i)];
        const double prev = smooth[static_cast<std::size_t>((i + n - 1) % n)];
        const double next = smooth[static_cast<std::size_t>((i + 1) % n)];
        if (v > 0 && v > prev && v >= next) peaks.push_back(i);
    }
    std::stable_sort(peaks.begin(), peaks.end(), [&](std::ptrdiff_t a, std::ptrdiff_t b) {
        return smooth[static_cast<std::size_t>(a)] > smooth[static_cast<std::size_t>(b)];
    });
    std::vector<std::ptrdiff_t> kept;
    for (const std::ptrdiff_t p : peaks) {
        if (mass[static_cast<std::size_t>(p)] < o.min_plane_share * total) continue;
        const bool far = std::all_of(kept.begin(), kept.end(), [&](std::ptrdiff_t q) {
            return azimuth_gap_deg(static_cast<double>(p), static_cast<double>(q)) >= o.min_plane_separation_deg;
        });
        if (far) kept.push_back(p);
    }
    return static_cast<int>(kept.size());
}

}  // namespace detail

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
                                             const azimuth_mode_select_options& opt = {})
{
    constexpr const char* fn = "azimuth_mode_select";
    detail::require(aspect_histogram.size() == 360, fn, "aspect_histogram", "360 one-degree bins",
                    aspect_histogram.size());
    detail::require(opt.window_deg >= 0 && opt.window_deg <= 180, fn, "window_deg", "in [0, 180]", opt.window_deg);
    detail::require(opt.four_plane_low_deg <= opt.four_plane_high_deg, fn, "four_plane_low_deg",
                    "<= four_plane_high_deg", opt.four_plane_low_deg);
    detail::require(opt.min_plane_share > 0 && opt.min_plane_share <= 1, fn, "min_plane_share", "in (0, 1]",
                    opt.min_plane_share);
    azimuth_selection s;
    const auto best = std::max_element(aspect_histogram.begin(), aspect_histogram.end());
    if (*best == 0) return s;
    s.mode_deg = static_cast<double>(best - aspect_histogram.begin());
    s.planes = detail::count_aspect_planes(aspect_histogram, opt);
    s.form = s.planes >= 5 ? roof_form::complex : static_cast<roof_form>(s.planes);
    if (s.planes > 4) {
        s.reason = azimuth_reason::too_many_planes;
        return s;
    }
    s.suitable = true;
    const auto has_aspect_near = [&](double a) {
        for (std::size_t k = 0; k < 360; ++k)
            if (aspect_histogram[k] > 0 && detail::azimuth_gap_deg(static_cast<double>(k), a) <= opt.window_deg)
                return true;
        return false;
    };
    const double m = s.mode_deg;
    const bool north_half = m > 270.0 || m < 90.0;
    const bool east_side = m >= opt.four_plane_low_deg && m <= opt.four_plane_high_deg;
    const bool may_lack_side = s.planes == 1 || s.planes == 3;
    s.azimuth_deg = m;
    s.reason = azimuth_reason::kept;
    if (north_half) {
        const double swapped = detail::wrap_deg(m + 180.0);
        if (may_lack_side && !has_aspect_near(swapped)) {
            s.reason = azimuth_reason::swap_abandoned;
        } else {
            s.azimuth_deg = swapped;
            s.reason = azimuth_reason::swapped;
        }
    } else if (east_side && s.planes >= 3) {
        std::uint64_t west = 0, east = 0;
        for (std::size_t k = 1; k < 180; ++k) east += aspect_histogram[k];
        for (std::size_t k = 181; k < 360; ++k) west += aspect_histogram[k];
        const double turned = detail::wrap_deg(m + 90.0);
        if (west <= east) {
            s.reason = azimuth_reason::kept_east;
        } else if (s.planes == 3 && !has_aspect_near(turned)) {
            s.reason = azimuth_reason::swap_abandoned;
        } else {
            s.azimuth_deg = turned;
            s.reason = azimuth_reason::turned_west;
        }
    }
    return s;
}

}  // namespace lidarfx
