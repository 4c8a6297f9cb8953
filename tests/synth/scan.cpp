// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/synth/scan.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace lidarfx;
using namespace lidarfx::synth;

TEST_CASE("synth/scan_square: pulse count, bounds, scan angles")
{
    for (const double size : {10.0, 100.0, 333.0, 1200.0}) {
        for (const double density : {0.5, 2.0, 7.0}) {
            std::size_t n = 0;
            double max_angle = 0;
            bool inside = true;
            scan_square(size, density, 1, {}, [&](const pulse& p) {
                ++n;
                inside = inside && p.x >= 0 && p.y >= 0 && p.x <= size && p.y <= size;
                max_angle = std::max(max_angle, std::abs(p.scan_angle_deg));
            });
            CHECK(inside);
            CHECK(max_angle <= 15.0);
            // Lines and pulses per line are rounded to whole numbers: within one line / one column.
            const double expected = size * size * density;
            CHECK(std::abs(static_cast<double>(n) - expected) <= 2.0 * size * std::sqrt(density) + 1);
        }
    }
}

TEST_CASE("synth/scan_square: density is even at the scale of 10 m blocks; strips share the square")
{
    const double size = 1200, density = 2.0;
    const int blocks = 120;
    std::vector<int> count(blocks * blocks, 0);
    std::vector<double> angle_at_edge;
    scan_square(size, density, 3, {}, [&](const pulse& p) {
        const int c = std::min(blocks - 1, static_cast<int>(p.x / 10)),
                  r = std::min(blocks - 1, static_cast<int>(p.y / 10));
        ++count[r * blocks + c];
    });
    // 200 pulses expected per block; jitter moves a few across block borders.
    const auto [lo, hi] = std::minmax_element(count.begin(), count.end());
    CHECK(*lo >= 170);
    CHECK(*hi <= 230);
    // 1200 m needs 3 strips of 400 m (the swath at 1000 m and +-15 degrees is 536 m): angles reach
    // atan(200 / 1000) = 11.3 degrees at the strip edges, and are 0 at the strip centres.
    double max_angle = 0, max_error = 0;
    scan_square(size, 0.1, 3, {}, [&](const pulse& p) {
        max_angle = std::max(max_angle, std::abs(p.scan_angle_deg));
        const double centre = (std::floor(p.x / 400) + 0.5) * 400;
        max_error = std::max(max_error, std::abs(p.scan_angle_deg - rad_to_deg(std::atan((p.x - centre) / 1000))));
    });
    CHECK(max_error < 1e-9);
    CHECK(max_angle == doctest::Approx(11.31).epsilon(0.01));
}

TEST_CASE("synth/scan_square: deterministic from the seed")
{
    std::vector<double> a, b, c;
    scan_square(50, 2, 9, {}, [&](const pulse& p) { a.push_back(p.x + 1e3 * p.y); });
    scan_square(50, 2, 9, {}, [&](const pulse& p) { b.push_back(p.x + 1e3 * p.y); });
    scan_square(50, 2, 10, {}, [&](const pulse& p) { c.push_back(p.x + 1e3 * p.y); });
    CHECK(a == b);
    CHECK(a != c);
    std::vector<double> plain;
    scan_square(50, 2, 9, {.across_jitter = 0, .along_jitter = 0}, [&](const pulse& p) { plain.push_back(p.x); });
    CHECK(plain.size() == a.size());
}

TEST_CASE("synth/scan_square: bad arguments are refused")
{
    const auto none = [](const pulse&) {};
    CHECK_THROWS_WITH_AS(scan_square(0, 1, 1, {}, none), "scan_square: size_m must be finite and > 0 (got 0)",
                         invalid_input);
    CHECK_THROWS_WITH_AS(scan_square(10, -1, 1, {}, none),
                         "scan_square: density_per_m2 must be finite and > 0 (got -1)", invalid_input);
    CHECK_THROWS_WITH_AS(scan_square(10, 1, 1, {.max_scan_angle_deg = 70}, none),
                         "scan_square: max_scan_angle_deg must be in (0, 60] (got 70)", invalid_input);
    CHECK_THROWS_AS(scan_square(10, 1, 1, {.flying_height_m = 0}, none), invalid_input);
    CHECK_THROWS_AS(scan_square(10, 1, 1, {.across_jitter = 0.5}, none), invalid_input);
    CHECK_THROWS_AS(scan_square(10, 1, 1, {.along_jitter = -0.1}, none), invalid_input);
}
