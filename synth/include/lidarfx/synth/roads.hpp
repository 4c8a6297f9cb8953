// SPDX-License-Identifier: Apache-2.0
// Roads and bridge decks for synthetic scenes: straight strips of given width, flat across.
#pragma once

#include <array>
#include <cmath>
#include <limits>

#include "lidarfx/core/fast_math.hpp"

namespace lidarfx::synth {

/// A straight strip of road (or of a bridge deck): centre line through (x, y) heading `azimuth_deg`
/// (clockwise from north), `width_m` wide, reaching `half_length_m` either way from (x, y) (infinite by
/// default).
struct road_strip {
    double x = 0, y = 0;     ///< a point on the centre line (its middle), metres
    double azimuth_deg = 0;  ///< heading of the centre line, clockwise from north
    double width_m = 7;      ///< full width, metres
    double half_length_m = std::numeric_limits<double>::infinity();

    /// (along, across) coordinates of (px, py): along the heading from (x, y), and across to its right.
    std::array<double, 2> local(double px, double py) const noexcept
    {
        const double a = deg_to_rad(azimuth_deg), dx = px - x, dy = py - y;
        const double s = std::sin(a), c = std::cos(a);
        return {dx * s + dy * c, dx * c - dy * s};
    }

    /// World point at local (along, across).
    std::array<double, 2> world(double along, double across) const noexcept
    {
        const double a = deg_to_rad(azimuth_deg);
        const double s = std::sin(a), c = std::cos(a);
        return {x + along * s + across * c, y + along * c - across * s};
    }

    /// Distance from (px, py) to the nearer long edge, metres; negative on the strip (ignores its ends).
    double edge_distance(double px, double py) const noexcept { return std::abs(local(px, py)[1]) - 0.5 * width_m; }

    /// True when (px, py) lies on the strip (edges included).
    bool contains(double px, double py) const noexcept
    {
        const auto [along, across] = local(px, py);
        return std::abs(across) <= 0.5 * width_m && std::abs(along) <= half_length_m;
    }
};

/// A flat bridge deck: a strip at elevation `z` (top surface, metres). Pulses over it return from the deck
/// and never reach the ground or water below.
struct bridge_deck {
    road_strip span;        ///< plan of the deck
    double z = 0;           ///< deck surface elevation, metres
    double intensity = 80;  ///< mean intensity of the deck surface
};

}  // namespace lidarfx::synth
