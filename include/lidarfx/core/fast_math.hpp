// SPDX-License-Identifier: Apache-2.0
// fast_math: branch-free elementary functions that let kernel loops vectorize.
#pragma once

#include <cstddef>
#include <numbers>

namespace lidarfx::detail {

/// Polynomial c[0] x^(N-1) + c[1] x^(N-2) + ... + c[N-1] by Horner's scheme, p = p * x + c[i]; the loop is
/// unrolled, so kernel loops that call it still vectorize.
template <class T, std::size_t N>
constexpr T horner(T x, const T (&c)[N]) noexcept
{
    T p = c[0];
    for (std::size_t i = 1; i < N; ++i) p = p * x + c[i];
    return p;
}

/// atan(x) in degrees for x >= 0 in float arithmetic (+inf gives 90, NaN gives NaN), branch-free so that loops
/// calling it vectorize 16 lanes wide. t = min(x, 1/x) in [0, 1], atan(t) = t P(t^2) with P a degree-8
/// minimax fit (relative error 1.4e-7 evaluated in float), and atan(x) = pi/2 - atan(1/x) for x > 1.
inline float atan_deg(float x) noexcept
{
    const bool above = x > 1.0f;
    const float t = above ? 1.0f / x : x;
    const float s = t * t;
    const float p = horner(s, {0.0029035008046776056f, -0.01628280244767666f, 0.04303903877735138f,
                               -0.07533648610115051f, 0.10654664784669876f, -0.14207130670547485f,
                               0.19993053376674652f, -0.3333309292793274f, 1.0f});
    const float a = t * p * static_cast<float>(180 / std::numbers::pi);
    return above ? 90.0f - a : a;
}

}  // namespace lidarfx::detail

namespace lidarfx {

/// Degrees to radians: deg * (pi / 180), the constant rounded once (pi from <numbers>).
constexpr double deg_to_rad(double deg) noexcept
{
    return deg * (std::numbers::pi / 180);
}

/// Radians to degrees: rad * (180 / pi), the constant rounded once (pi from <numbers>).
constexpr double rad_to_deg(double rad) noexcept
{
    return rad * (180 / std::numbers::pi);
}

}  // namespace lidarfx
