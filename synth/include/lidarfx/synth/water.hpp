// SPDX-License-Identifier: Apache-2.0
// Water for synthetic scenes: lake outlines, meandering river channels, islands, and how water returns.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>

#include "lidarfx/synth/random.hpp"

namespace lidarfx::synth {

/// A star-shaped lake: the shoreline radius toward direction theta is
/// R(theta) = mean_radius_m * (1 + sum_k (a_k cos k theta + b_k sin k theta)), k = 2..7.
struct lake_outline {
    double x = 0, y = 0;             ///< centre, metres
    double mean_radius_m = 100;      ///< mean shoreline radius, metres, > 0
    std::array<double, 6> a{}, b{};  ///< harmonic coefficients of orders 2..7 (sum of |a|+|b| < 1)

    /// Random irregular outline: harmonic amplitudes falling as 1/k, scaled so the radius stays within
    /// mean_radius_m * (1 +- irregularity); irregularity in [0, 0.9].
    static lake_outline random(rng& random, double x, double y, double mean_radius_m, double irregularity)
    {
        lake_outline lake{x, y, mean_radius_m, {}, {}};
        double total = 0;
        for (std::size_t k = 0; k < 6; ++k) {
            const double amplitude = random.uniform(0.3, 1.0) / static_cast<double>(k + 2);
            const double c = random.uniform(-1.0, 1.0), s = random.uniform(-1.0, 1.0);
            const double norm = std::max(1e-9, std::abs(c) + std::abs(s));
            lake.a[k] = amplitude * c / norm;
            lake.b[k] = amplitude * s / norm;
            total += amplitude;
        }
        for (std::size_t k = 0; k < 6; ++k) {
            lake.a[k] *= irregularity / total;
            lake.b[k] *= irregularity / total;
        }
        return lake;
    }

    /// Largest possible shoreline radius (bound from the coefficients), metres.
    double max_radius() const noexcept
    {
        double sum = 0;
        for (std::size_t k = 0; k < 6; ++k) sum += std::abs(a[k]) + std::abs(b[k]);
        return mean_radius_m * (1.0 + sum);
    }

    /// Shoreline radius toward the unit direction (cos theta, sin theta), metres. O(1), no trigonometry:
    /// cos k theta and sin k theta come from complex powers of the direction.
    double radius_toward(double c, double s) const noexcept
    {
        double ck = c * c - s * s, sk = 2 * c * s, sum = 0;  // order 2
        for (std::size_t k = 0; k < 6; ++k) {
            sum += a[k] * ck + b[k] * sk;
            const double next_c = ck * c - sk * s;
            sk = sk * c + ck * s;
            ck = next_c;
        }
        return mean_radius_m * (1.0 + sum);
    }

    /// Radial distance from the shoreline: |p - centre| - R(theta), metres; negative inside the lake.
    /// (Measured along the ray from the centre, so it approximates the true distance to the shore.)
    double shore_distance(double px, double py) const noexcept
    {
        const double dx = px - x, dy = py - y, r = std::hypot(dx, dy);
        if (r < 1e-9) return -mean_radius_m;
        return r - radius_toward(dx / r, dy / r);
    }
};

/// A river flowing east across the scene: centre line y(x) = y_mid + sum of two sines (meanders), width
/// w(x) = mean_width_m + width_swing_m * (0.6 sin(...) + 0.4 sin(...)), water level falling linearly
/// eastwards. Distances across the channel are first-order perpendicular offsets (dy / sqrt(1 + y'^2)).
struct river_channel {
    double y_mid = 320;                                 ///< mean northing of the centre line, metres
    std::array<double, 2> meander_amplitude_m{60, 20};  ///< amplitudes of the two meander sines
    std::array<double, 2> meander_wavelength_m{450, 190};
    std::array<double, 2> meander_phase{0, 0};  ///< radians
    double mean_width_m = 27.5;                 ///< mean water width, metres
    double width_swing_m = 12.5;                ///< width varies within mean +- swing
    std::array<double, 2> width_wavelength_m{290, 130};
    std::array<double, 2> width_phase{0, 0};  ///< radians
    double level_west_z = 50;                 ///< water level at x = 0, metres
    double level_drop_per_m = 1.5 / 640;      ///< fall of the water level per metre eastwards

    static constexpr double two_pi = 2 * std::numbers::pi;

    /// Northing of the centre line at easting x.
    double centre_y(double x) const noexcept
    {
        double y = y_mid;
        for (std::size_t k = 0; k < 2; ++k)
            y += meander_amplitude_m[k] * std::sin(two_pi * x / meander_wavelength_m[k] + meander_phase[k]);
        return y;
    }

    /// Derivative dy/dx of the centre line at easting x.
    double centre_slope(double x) const noexcept
    {
        double s = 0;
        for (std::size_t k = 0; k < 2; ++k) {
            const double w = two_pi / meander_wavelength_m[k];
            s += meander_amplitude_m[k] * w * std::cos(w * x + meander_phase[k]);
        }
        return s;
    }

    /// Water width at easting x, metres.
    double width(double x) const noexcept
    {
        return mean_width_m + width_swing_m * (0.6 * std::sin(two_pi * x / width_wavelength_m[0] + width_phase[0]) +
                                               0.4 * std::sin(two_pi * x / width_wavelength_m[1] + width_phase[1]));
    }

    /// Water surface elevation at easting x, metres.
    double level(double x) const noexcept { return level_west_z - level_drop_per_m * x; }

    /// Signed offset of (px, py) from the centre line across the channel, metres (> 0 north of it).
    double offset(double px, double py) const noexcept
    {
        const double s = centre_slope(px);
        return (py - centre_y(px)) / std::sqrt(1.0 + s * s);
    }
};

/// A synthetic round island (or rock) in a lake: a dome rising from `shore_rise_m` above the water at its
/// rim to shore_rise_m + height_m at its centre.
struct island_truth {
    double x = 0, y = 0;   ///< centre, metres
    double radius_m = 10;  ///< radius, metres
    double height_m = 2;   ///< dome height above the rim, metres
    static constexpr double shore_rise_m = 0.25;

    double area_m2() const noexcept { return std::numbers::pi * radius_m * radius_m; }

    /// Height above the water level at (px, py), or a negative number off the island.
    double height_above_water(double px, double py) const noexcept
    {
        const double dx = px - x, dy = py - y, q = 1.0 - (dx * dx + dy * dy) / (radius_m * radius_m);
        return q < 0 ? -1.0 : shore_rise_m + height_m * std::sqrt(q);
    }
};

/// How pulses over water return (dissertation 2.2.3-2.2.4): water absorbs near infrared, so returns are
/// weak, many pulses give none, and only near nadir (or off a wave facing the sensor) a specular glint
/// comes back strongly. Dropouts come in three kinds: contiguous patches (a smooth random field above a
/// per-waterbody quantile, so each waterbody has `patch_share` of its area in patches), single 2 m cells
/// dropping every pulse (`speck_share_water` of water cells, `speck_share_land` of land cells), and
/// pulse-by-pulse losses rising with the scan angle.
struct water_returns {
    double patch_share = 0.4;         ///< share of each waterbody's area inside dropout patches
    double patch_wavelength_m = 90;   ///< wavelength of the patch field: patches of tens of metres
    double speck_cell_m = 2.0;        ///< side of the lattice cells of single dropouts (aligned to 0)
    double speck_share_water = 0.10;  ///< share of lattice cells whose water pulses all drop
    double speck_share_land = 0.015;  ///< share of lattice cells where every pulse drops (any cover)
    double pulse_drop_nadir = 0.15;   ///< dropout probability of other water pulses at nadir ...
    double pulse_drop_edge = 0.50;    ///< ... and at the swath edge (quadratic in the scan angle)
    double specular_peak = 0.08;      ///< glint probability at nadir, falling as exp(-(angle/width)^2)
    double specular_width_deg = 2.0;
    double specular_floor = 0.003;            ///< glint probability at any angle (waves facing the sensor)
    double low_min = 2, low_max = 20;         ///< range of ordinary water intensities (skewed towards low_min)
    double glint_min = 200, glint_max = 400;  ///< range of specular intensities

    /// Probability that a water pulse outside patches and specks is lost at `scan_angle_deg`.
    double pulse_drop_probability(double scan_angle_deg, double max_scan_angle_deg) const noexcept
    {
        const double t = scan_angle_deg / max_scan_angle_deg;
        return pulse_drop_nadir + (pulse_drop_edge - pulse_drop_nadir) * std::min(1.0, t * t);
    }

    /// Probability that a returned water pulse is a specular glint at `scan_angle_deg`.
    double specular_probability(double scan_angle_deg) const noexcept
    {
        const double t = scan_angle_deg / specular_width_deg;
        return specular_floor + specular_peak * std::exp(-t * t);
    }

    /// Intensity of a returned water pulse: a glint with specular_probability, else low.
    double intensity(double scan_angle_deg, rng& random) const noexcept
    {
        if (random.chance(specular_probability(scan_angle_deg))) return random.uniform(glint_min, glint_max);
        const double u = random.uniform();
        return low_min + (low_max - low_min) * u * u;
    }
};

}  // namespace lidarfx::synth
