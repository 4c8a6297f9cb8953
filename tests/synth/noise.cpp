// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/synth/noise.hpp>

#include <algorithm>
#include <cmath>

using namespace lidarfx::synth;

TEST_CASE("synth/gradient_noise: zero on lattice points, bounded, continuous")
{
    for (int i = -5; i <= 5; ++i) {
        for (int j = -5; j <= 5; ++j) CHECK(gradient_noise(i, j, 3) == 0.0);
    }
    rng r(11);
    double max_abs = 0, max_slope = 0;
    for (int k = 0; k < 20000; ++k) {
        const double x = r.uniform(-50, 50), y = r.uniform(-50, 50);
        const double v = gradient_noise(x, y, 3);
        max_abs = std::max(max_abs, std::abs(v));
        const double step = 1e-4;
        max_slope = std::max({max_slope, std::abs(gradient_noise(x + step, y, 3) - v) / step,
                              std::abs(gradient_noise(x, y + step, 3) - v) / step});
    }
    // d/dx of a bilinear blend of corner terms: <= 1 (unit gradients) + fade' (<= 1.875) * |n10 - n00|
    // (<= 2 sqrt 2), times the sqrt 2 output scale: < 8.9.
    CHECK(max_slope < 8.9);
    CHECK(max_abs <= 1.0);
    CHECK(max_abs > 0.5);  // not degenerate
}

TEST_CASE("synth/gradient_noise: continuous across cell borders, seed changes the field")
{
    rng r(12);
    int differ = 0;
    double max_jump = 0;
    for (int k = 0; k < 1000; ++k) {
        const double y = r.uniform(-10, 10);
        const double x = std::floor(r.uniform(-10, 10));
        max_jump = std::max(max_jump, std::abs(gradient_noise(x - 1e-9, y, 8) - gradient_noise(x + 1e-9, y, 8)));
        differ += gradient_noise(x + 0.5, y, 8) != gradient_noise(x + 0.5, y, 9);
    }
    CHECK(max_jump < 1e-7);  // slope < 8.9, so a 2e-9 step changes the value by < 2e-8
    CHECK(differ > 990);
}

TEST_CASE("synth/noise_field: wavelength sets the scale, values centre on 0")
{
    const noise_field f{.seed = 4, .wavelength_m = 50, .octaves = 4, .gain = 0.5};
    double sum = 0, sq = 0, near_diff = 0, far_diff = 0, max_abs = 0;
    int n = 0;
    for (double y = 0; y < 2000; y += 7.3) {
        for (double x = 0; x < 2000; x += 7.3) {
            const double v = f(x, y);
            max_abs = std::max(max_abs, std::abs(v));
            sum += v;
            sq += v * v;
            near_diff += std::abs(f(x + 2, y) - v);
            far_diff += std::abs(f(x + 200, y) - v);
            ++n;
        }
    }
    CHECK(max_abs <= 1.0);
    CHECK(std::abs(sum / n) < 0.03);
    const double sd = std::sqrt(sq / n);
    CHECK(sd > 0.1);
    CHECK(sd < 0.5);
    CHECK(near_diff < 0.3 * far_diff);  // smooth at 2 m, decorrelated at 4 wavelengths
    const noise_field g = f;
    CHECK(g(123.4, 567.8) == f(123.4, 567.8));
}

TEST_CASE("synth/smoothstep: clamps and is smooth")
{
    CHECK(smoothstep(1, 3, 0) == 0.0);
    CHECK(smoothstep(1, 3, 1) == 0.0);
    CHECK(smoothstep(1, 3, 2) == 0.5);
    CHECK(smoothstep(1, 3, 3) == 1.0);
    CHECK(smoothstep(1, 3, 9) == 1.0);
    bool monotone = true;
    for (double t = 1; t < 3; t += 0.01) monotone = monotone && smoothstep(1, 3, t + 0.01) >= smoothstep(1, 3, t);
    CHECK(monotone);
}
