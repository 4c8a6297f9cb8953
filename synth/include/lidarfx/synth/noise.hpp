// SPDX-License-Identifier: Apache-2.0
// Smooth random fields for synthetic scenes: hashed 2-D gradient noise and its fractal sum.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>

#include "lidarfx/synth/random.hpp"

namespace lidarfx::synth {

/// Gradient (Perlin) noise at (x, y) in lattice units: unit gradients hashed from (seed, lattice corner)
/// among 16 directions, blended with the quintic fade 6t^5 - 15t^4 + 10t^3 (C2-continuous, so slopes of
/// a terrain built from it are smooth). 0 on every lattice point; range about [-1, 1] (scaled by sqrt 2).
/// Deterministic and portable: only +, *, floor. O(1), four hashes.
inline double gradient_noise(double x, double y, std::uint64_t seed) noexcept
{
    // cos and sin of k * 22.5 degrees, k = 0..15.
    static constexpr std::array<double, 16> gx{1.0,  0.9238795325112867,  0.7071067811865476,  0.3826834323650898,
                                               0.0,  -0.3826834323650898, -0.7071067811865476, -0.9238795325112867,
                                               -1.0, -0.9238795325112867, -0.7071067811865476, -0.3826834323650898,
                                               0.0,  0.3826834323650898,  0.7071067811865476,  0.9238795325112867};
    const double fx = std::floor(x), fy = std::floor(y);
    const auto ix = static_cast<std::int64_t>(fx), iy = static_cast<std::int64_t>(fy);
    const double dx = x - fx, dy = y - fy;
    const auto corner = [&](std::int64_t i, std::int64_t j, double px, double py) {
        // One mix of a keyed linear combination is enough to decorrelate neighbouring corners.
        const std::uint64_t h = mix64(seed ^ (static_cast<std::uint64_t>(i) * 0x9E3779B97F4A7C15ull) ^
                                      (static_cast<std::uint64_t>(j) * 0xD1B54A32D192ED03ull));
        const auto k = static_cast<std::size_t>(h >> 60);
        return gx[k] * px + gx[(k + 12) & 15] * py;  // sin(a) = cos(a - 90 degrees)
    };
    const auto fade = [](double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); };
    const double n00 = corner(ix, iy, dx, dy), n10 = corner(ix + 1, iy, dx - 1.0, dy);
    const double n01 = corner(ix, iy + 1, dx, dy - 1.0), n11 = corner(ix + 1, iy + 1, dx - 1.0, dy - 1.0);
    const double u = fade(dx), v = fade(dy);
    const double bottom = n00 + u * (n10 - n00), top = n01 + u * (n11 - n01);
    return std::numbers::sqrt2 * (bottom + v * (top - bottom));
}

/// A smooth random field over the plane, in metres: the fractal sum of `octaves` gradient noises, octave k
/// at wavelength wavelength_m / 2^k with amplitude gain^k, divided by the sum of amplitudes so the
/// result stays in about [-1, 1] (typical standard deviation 0.2-0.3). Thresholding it gives blobs of
/// about half the wavelength (dropout patches, woods); scaling it gives rolling terrain.
struct noise_field {
    std::uint64_t seed = 1;     ///< seed; each octave hashes with its own derived seed
    double wavelength_m = 100;  ///< wavelength of the first octave, metres, > 0
    int octaves = 4;            ///< number of octaves, >= 1
    double gain = 0.5;          ///< amplitude ratio between successive octaves, in (0, 1]

    /// Field value at world point (x, y) metres. O(octaves).
    double operator()(double x, double y) const noexcept
    {
        double sum = 0, norm = 0, amplitude = 1, frequency = 1.0 / wavelength_m;
        for (int k = 0; k < octaves; ++k) {
            // A fixed rotation-free offset per octave keeps lattice points of octaves from coinciding.
            sum += amplitude * gradient_noise(x * frequency + 0.37 * k, y * frequency + 0.71 * k,
                                              seed + 0x632BE59BD9B4E019ull * static_cast<std::uint64_t>(k));
            norm += amplitude;
            amplitude *= gain;
            frequency *= 2.0;
        }
        return sum / norm;
    }
};

/// Hermite smoothstep: 0 for t <= a, 1 for t >= b, 3s^2 - 2s^3 in between (s = (t - a)/(b - a)); a < b.
constexpr double smoothstep(double a, double b, double t) noexcept
{
    const double s = t <= a ? 0.0 : t >= b ? 1.0 : (t - a) / (b - a);
    return s * s * (3.0 - 2.0 * s);
}

}  // namespace lidarfx::synth
