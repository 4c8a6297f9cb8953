// SPDX-License-Identifier: Apache-2.0
// morphological_ground: the progressive morphological filter against a plain reference (openings by walking
// every window) on random surfaces, and what it keeps and removes on a hand-made town.
#include <doctest/doctest.h>

#include <lidarfx/pipelines/buildings/morphological_ground.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

using namespace lidarfx;

namespace {

/// Opening by walking: the minimum, then the maximum, of the (2 r + 1)^2 window clipped at the border, NaN
/// ignored (a window without a value gives NaN).
raster<float> opening_by_walking(const raster<float>& z, int r)
{
    const auto extreme = [r](const raster<float>& in, bool lowest) {
        raster<float> out(in.rows(), in.cols());
        for (std::ptrdiff_t i = 0; i < in.rows(); ++i) {
            for (std::ptrdiff_t j = 0; j < in.cols(); ++j) {
                float best = std::numeric_limits<float>::quiet_NaN();
                for (std::ptrdiff_t a = std::max<std::ptrdiff_t>(0, i - r); a <= std::min(in.rows() - 1, i + r); ++a) {
                    for (std::ptrdiff_t b = std::max<std::ptrdiff_t>(0, j - r); b <= std::min(in.cols() - 1, j + r);
                         ++b) {
                        const float v = in(a, b);
                        if (std::isnan(v)) continue;
                        if (std::isnan(best) || (lowest ? v < best : v > best)) best = v;
                    }
                }
                out(i, j) = best;
            }
        }
        return out;
    };
    return extreme(extreme(z, true), false);
}

/// The filter's definition walked: flags where z_(k-1) - z_k exceeds t_k for a window k.
raster<std::uint8_t> ground_by_walking(const raster<float>& z, double cell_m, const morphological_ground_options& o)
{
    raster<std::uint8_t> ground(z.rows(), z.cols(), 1);
    raster<float> surface = z;
    const int last = std::max(1, static_cast<int>(std::lround(o.max_window_m / (2.0 * cell_m))));
    int previous = 0;
    for (int r = 1;; r = std::min(2 * r, last)) {
        raster<float> opened = opening_by_walking(surface, r);
        const double t = previous == 0
                             ? o.initial_height_m
                             : std::min(o.max_height_m, o.initial_height_m + o.slope * 2.0 * (r - previous) * cell_m);
        for (std::ptrdiff_t i = 0; i < z.rows(); ++i) {
            for (std::ptrdiff_t j = 0; j < z.cols(); ++j) {
                if (static_cast<double>(surface(i, j)) - static_cast<double>(opened(i, j)) > t) ground(i, j) = 0;
                if (std::isnan(z(i, j))) ground(i, j) = 0, opened(i, j) = z(i, j);
            }
        }
        surface = opened;
        previous = r;
        if (r == last) break;
    }
    return ground;
}

}  // namespace

TEST_CASE("morphological_ground: the ground cells of the definition, on random surfaces and any thread count")
{
    std::mt19937 rng(2003);
    std::uniform_real_distribution<float> height(0.0f, 6.0f);
    std::bernoulli_distribution hole(0.05);
    for (const double window : {3.0, 9.0, 21.0}) {
        raster<float> z(23, 31);
        for (float& v : z) v = hole(rng) ? std::numeric_limits<float>::quiet_NaN() : height(rng);
        const morphological_ground_options o{
            .max_window_m = window, .slope = 0.2, .initial_height_m = 0.5, .max_height_m = 2.0};
        const auto want = ground_by_walking(z, 1.0, o);
        for (const int threads : {1, 3}) {
            CAPTURE(window);
            CAPTURE(threads);
            const auto got = morphological_ground(z, 1.0, o, {.threads = threads});
            CHECK(got.is_ground == want);
            std::size_t count = 0;
            bool values = true;
            for (std::ptrdiff_t r = 0; r < z.rows(); ++r) {
                for (std::ptrdiff_t c = 0; c < z.cols(); ++c) {
                    count += want(r, c);
                    values = values && (want(r, c) ? got.ground(r, c) == z(r, c) : std::isnan(got.ground(r, c)));
                }
            }
            CHECK(got.ground_cells == count);
            CHECK(values);
        }
    }
}

TEST_CASE("morphological_ground: buildings narrower than the largest window go, slopes and wider plateaus stay")
{
    // 1 m cells over a ground that climbs 0.2 m per metre eastwards; a 30 x 20 m block 9 m high, a 3 x 3 m
    // kiosk 3 m high, and a plateau 60 x 60 m wide 4 m high (wider than the 40 m window: ground).
    raster<float> z(120, 200);
    for (std::ptrdiff_t r = 0; r < z.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < z.cols(); ++c) z(r, c) = 0.2f * static_cast<float>(c);
    const auto raise = [&](std::ptrdiff_t r0, std::ptrdiff_t r1, std::ptrdiff_t c0, std::ptrdiff_t c1, float h) {
        for (std::ptrdiff_t r = r0; r < r1; ++r)
            for (std::ptrdiff_t c = c0; c < c1; ++c) z(r, c) += h;
    };
    raise(10, 40, 10, 30, 9.0f);
    raise(60, 63, 20, 23, 3.0f);
    raise(30, 90, 110, 170, 4.0f);
    const auto g = morphological_ground(z, 1.0, {.slope = 0.3});
    CHECK(g.is_ground(25, 20) == 0);   // the block
    CHECK(g.is_ground(61, 21) == 0);   // the kiosk
    CHECK(g.is_ground(60, 140) == 1);  // the middle of the plateau
    CHECK(g.is_ground(100, 60) == 1);  // the slope
    CHECK(g.is_ground(5, 195) == 1);
    CHECK_THROWS_AS(morphological_ground(z, 0.0), invalid_input);
    CHECK_THROWS_AS(morphological_ground(z, 1.0, {.max_height_m = 0.1}), invalid_input);
    CHECK_THROWS_AS(morphological_ground(z, 1.0, {.slope = -1.0}), invalid_input);
}
