// SPDX-License-Identifier: Apache-2.0
// Airborne scan pattern for synthetic scenes: flight strips of jittered scan lines over a square.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/synth/random.hpp"

namespace lidarfx::synth {

/// Geometry of a linear (rotating-polygon) airborne scanner flying north-south strips.
struct scan_pattern {
    double flying_height_m = 1000;   ///< height above ground, metres, > 0
    double max_scan_angle_deg = 15;  ///< half field of view, degrees, in (0, 60]; sets the strip width
    double across_jitter = 0.35;     ///< across-track jitter, fraction of the pulse spacing, in [0, 0.45]
    double along_jitter = 0.15;      ///< along-track jitter, fraction of the line spacing, in [0, 0.15]
    double pulse_rate_hz = 200000;   ///< pulses per second (sets the pulses' times), > 0
    double strip_turn_s = 60;        ///< time between the last pulse of a strip and the first of the next, s
};

/// One laser pulse: footprint centre and the scan angle it was fired at.
struct pulse {
    double x = 0, y = 0;        ///< footprint, metres
    double scan_angle_deg = 0;  ///< off-nadir angle, degrees; > 0 east of the flight line
    double time_s = 0;          ///< when it was fired: pulse index / pulse_rate_hz + strip_turn_s per strip, seconds
};

/// Fires `size_m^2 * density_per_m2` pulses (rounded to whole lines and pulses) over [0, size_m]^2 and
/// calls emit(pulse) for each. The square is cut into the fewest equal north-south strips no wider than
/// the swath 2 H tan(max angle); strips alternate north- and southbound. Each strip is scanned in lines
/// perpendicular to the flight, spacing 1/sqrt(density) both ways; a line drifts forward as it is scanned
/// (the aircraft moves) and every pulse is jittered, so local density varies as on real surveys while the
/// mean is exact. Scan angle = atan(across-track offset / H); pulses are fired in the order emitted, at
/// pulse_rate_hz, with strip_turn_s between strips. Deterministic from `seed`.
/// O(pulses). @throws invalid_input on size_m or density_per_m2 <= 0, or options out of range.
template <class Emit>
void scan_square(double size_m, double density_per_m2, std::uint64_t seed, const scan_pattern& pattern, Emit&& emit)
{
    constexpr const char* fn = "scan_square";
    lidarfx::detail::require_positive(size_m, fn, "size_m");
    lidarfx::detail::require_positive(density_per_m2, fn, "density_per_m2");
    lidarfx::detail::require_positive(pattern.flying_height_m, fn, "flying_height_m");
    lidarfx::detail::require(pattern.max_scan_angle_deg > 0 && pattern.max_scan_angle_deg <= 60, fn,
                             "max_scan_angle_deg", "in (0, 60]", pattern.max_scan_angle_deg);
    lidarfx::detail::require(pattern.across_jitter >= 0 && pattern.across_jitter <= 0.45, fn, "across_jitter",
                             "in [0, 0.45]", pattern.across_jitter);
    lidarfx::detail::require_positive(pattern.pulse_rate_hz, fn, "pulse_rate_hz");
    lidarfx::detail::require(pattern.strip_turn_s >= 0, fn, "strip_turn_s", ">= 0", pattern.strip_turn_s);
    lidarfx::detail::require(pattern.along_jitter >= 0 && pattern.along_jitter <= 0.15, fn, "along_jitter",
                             "in [0, 0.15]", pattern.along_jitter);

    const double swath = 2.0 * pattern.flying_height_m * std::tan(deg_to_rad(pattern.max_scan_angle_deg));
    const auto strips = static_cast<long long>(std::max(1.0, std::ceil(size_m / swath - 1e-9)));
    const double strip_width = size_m / static_cast<double>(strips);
    const double spacing = 1.0 / std::sqrt(density_per_m2);
    const auto lines = static_cast<long long>(std::max(1.0, std::round(size_m / spacing)));
    const auto per_line = static_cast<long long>(std::max(1.0, std::round(strip_width / spacing)));
    const double along = size_m / static_cast<double>(lines);
    const double across = strip_width / static_cast<double>(per_line);

    rng random(seed, 0x5CA9);
    long long fired = 0;
    for (long long s = 0; s < strips; ++s) {
        const double x_left = static_cast<double>(s) * strip_width;
        const double x_flight = x_left + 0.5 * strip_width;
        const bool northbound = s % 2 == 0;
        for (long long k = 0; k < lines; ++k) {
            const long long line = northbound ? k : lines - 1 - k;
            for (long long j = 0; j < per_line; ++j) {
                // The forward drift (0.2..0.8 of a line spacing across the strip) plus jitter keeps every
                // pulse inside its own line cell, so pulses never leave the square.
                const double drift = 0.2 + 0.6 * (static_cast<double>(j) + 0.5) / static_cast<double>(per_line);
                const double dy = northbound ? drift : 1.0 - drift;
                const double x =
                    x_left + (static_cast<double>(j) + 0.5 + pattern.across_jitter * random.triangular()) * across;
                const double y = (static_cast<double>(line) + dy + pattern.along_jitter * random.triangular()) * along;
                const double time = static_cast<double>(fired++) / pattern.pulse_rate_hz +
                                    static_cast<double>(s) * pattern.strip_turn_s;
                emit(pulse{x, y, rad_to_deg(std::atan((x - x_flight) / pattern.flying_height_m)), time});
            }
        }
    }
}

}  // namespace lidarfx::synth
