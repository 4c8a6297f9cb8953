// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/pipelines/water/grow_waterbody.hpp>

#include "reference/grow_waterbody.hpp"

#include <algorithm>
#include <cmath>
#include <random>

using namespace lidarfx;

namespace {

// A random scene for growing: a low-angle, low-intensity "lake" blob around the centre, rough bright land
// around it, sprinkled NaN (dropout) cells and ineligible (vegetation) cells.
water_field random_field(std::mt19937& rng, std::ptrdiff_t rows, std::ptrdiff_t cols, int bins)
{
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    water_field f;
    f.angle_deg = raster<float>(rows, cols);
    f.eligible = raster<std::uint8_t>(rows, cols);
    f.intensity_bin = raster<std::int32_t>(rows, cols);
    f.bins = bins;
    const double cr = static_cast<double>(rows) / 2, cc = static_cast<double>(cols) / 2;
    const double radius = 0.25 * static_cast<double>(std::min(rows, cols)) * (0.5 + u(rng));
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const double d = std::hypot(static_cast<double>(r) - cr, static_cast<double>(c) - cc);
            const bool lake = d < radius;
            f.angle_deg(r, c) = lake ? 6.0f * u(rng) : 2.0f + 30.0f * u(rng);
            if (u(rng) < 0.05f) f.angle_deg(r, c) = NAN;
            f.eligible(r, c) = u(rng) < 0.93f ? 1 : 0;
            const int b = lake ? static_cast<int>(u(rng) * static_cast<float>(bins) * 0.3f)
                               : static_cast<int>((0.3f + 0.7f * u(rng)) * static_cast<float>(bins - 1));
            f.intensity_bin(r, c) = std::isnan(f.angle_deg(r, c)) ? -1 : std::clamp(b, 0, bins - 1);
        }
    return f;
}

std::vector<std::uint8_t> membership(const grow_waterbody_result& g, std::ptrdiff_t n)
{
    std::vector<std::uint8_t> m(static_cast<std::size_t>(n), 0);
    for (auto i : g.cells) {
        REQUIRE(m[i] == 0);  // each cell joins once
        m[i] = 1;
    }
    return m;
}

}  // namespace

TEST_CASE("water/grow_waterbody: one bucket-queue flood equals a BFS per threshold step with KS stops")
{
    std::mt19937 rng(20261125);
    int rejections = 0, full_runs = 0;
    for (int trial = 0; trial < 60; ++trial) {
        CAPTURE(trial);
        const std::ptrdiff_t rows = 1 + static_cast<std::ptrdiff_t>(rng() % 60),
                             cols = 1 + static_cast<std::ptrdiff_t>(rng() % 70);
        const auto f = random_field(rng, rows, cols, 2 + static_cast<int>(rng() % 200));
        grow_waterbody_options o;
        o.theta_start_deg = static_cast<double>(rng() % 4);
        o.theta_step_deg = 0.5 + static_cast<double>(rng() % 4) * 0.75;
        o.theta_max_deg = o.theta_start_deg + static_cast<double>(rng() % 40);
        o.min_ks_samples = trial % 3 == 0 ? 0 : 30;
        o.ks.alpha = trial % 2 ? 0.05 : 0.01;
        o.sample = trial % 5 < 2 ? ks_sample_mode::increment : ks_sample_mode::cumulative;
        std::vector<std::ptrdiff_t> seed;
        const auto centre = (rows / 2) * cols + cols / 2;
        seed.push_back(centre);
        if (trial % 4 == 0) seed.push_back(static_cast<std::ptrdiff_t>(rng() % static_cast<unsigned>(rows * cols)));

        grow_waterbody_workspace workspace;
        const auto flood = grow_waterbody(f, seed, o, workspace);
        const auto expected = reference::grow(f, seed, o);
        CHECK(membership(flood, rows * cols) == expected);
        rejections += flood.stopped_by_ks;
        full_runs += !flood.stopped_by_ks && !flood.cells.empty();
        if (!flood.cells.empty()) {
            CHECK(flood.theta_deg == o.theta_start_deg + flood.steps_accepted * o.theta_step_deg);
            CHECK(flood.theta_deg <= o.theta_max_deg);
        }
        // The workspace makes a second call independent of the first.
        const auto again = grow_waterbody(f, seed, o, workspace);
        CHECK(again.cells == flood.cells);
    }
    // The random scenes exercise both endings.
    CHECK(rejections > 5);
    CHECK(full_runs > 5);
}

TEST_CASE("water/grow_waterbody: hand-checked flood stops before the land")
{
    // 1 x 40 strip: 20 lake cells (angle 1, dark) then 20 shore cells (angle 5, bright).
    water_field f;
    f.angle_deg = raster<float>(1, 40);
    f.eligible = raster<std::uint8_t>(1, 40, 1);
    f.intensity_bin = raster<std::int32_t>(1, 40);
    f.bins = 10;
    for (int c = 0; c < 40; ++c) {
        f.angle_deg(0, c) = c < 20 ? 1.0f : 5.0f;
        f.intensity_bin(0, c) = c < 20 ? 0 : 9;
    }
    grow_waterbody_options o{.theta_start_deg = 2, .theta_step_deg = 1, .theta_max_deg = 10, .min_ks_samples = 1};
    grow_waterbody_workspace workspace;
    const std::vector<std::ptrdiff_t> seed{0};
    const auto g = grow_waterbody(f, seed, o, workspace);
    // Step 0 (θ 2°) holds the 20 dark cells; step 3 (θ 5°) adds 20 bright ones:
    // D = 1 - 20/40 = 0.5 > 1.36·sqrt(60/800) = 0.372 -> rejected, the 20 dark cells remain.
    CHECK(g.cells.size() == 20);
    CHECK(g.stopped_by_ks);
    CHECK(g.steps_accepted == 2);  // steps 1, 2 added nothing and were accepted
    CHECK(g.theta_deg == 4.0);

    f.eligible(0, 2) = 0;  // vegetation cuts the strip
    const auto cut = grow_waterbody(f, seed, o, workspace);
    CHECK(cut.cells.size() == 2);
    CHECK_FALSE(cut.stopped_by_ks);
}

TEST_CASE("water/grow_waterbody: bad options and fields are refused")
{
    water_field f;
    f.angle_deg = raster<float>(2, 2);
    f.eligible = raster<std::uint8_t>(2, 2, 1);
    f.intensity_bin = raster<std::int32_t>(2, 2);
    grow_waterbody_workspace workspace;
    const std::vector<std::ptrdiff_t> seed{0};
    CHECK_THROWS_WITH_AS(grow_waterbody(f, seed, {.theta_start_deg = 5, .theta_max_deg = 3}, workspace),
                         "grow_waterbody: theta_max_deg must be >= theta_start_deg and <= 90 (got 3)", invalid_input);
    CHECK_THROWS_WITH_AS(grow_waterbody(f, seed, {.theta_step_deg = 0}, workspace),
                         "grow_waterbody: theta_step_deg must be in (0, 90] (got 0)", invalid_input);
    grow_waterbody_options bad_alpha;
    bad_alpha.ks.alpha = 1.5;
    CHECK_THROWS_AS(grow_waterbody(f, seed, bad_alpha, workspace), invalid_input);
    const std::vector<std::ptrdiff_t> outside{4};
    CHECK_THROWS_AS(grow_waterbody(f, outside, {}, workspace), invalid_input);
    // Intensity bins outside [-1, bins): one past the last, and one with the bits above 2^24 set.
    for (const std::int32_t bad : {1, std::int32_t{1} << 24, std::int32_t{1} << 29, std::int32_t{1} << 30}) {
        f.intensity_bin(0, 1) = bad;
        CHECK_THROWS_AS(grow_waterbody(f, seed, {}, workspace), invalid_input);
    }
    f.intensity_bin(0, 1) = 0;
    f.eligible = raster<std::uint8_t>(3, 2);
    CHECK_THROWS_AS(grow_waterbody(f, seed, {}, workspace), invalid_input);
}

TEST_CASE("water/grow_waterbody: a workspace over a caller's labels stamps only the eligible cells it visits")
{
    water_field f;
    f.angle_deg = raster<float>(3, 8, 1.0f);
    f.eligible = raster<std::uint8_t>(3, 8, 1);
    f.intensity_bin = raster<std::int32_t>(3, 8, -1);
    raster<std::int32_t> labels(3, 8, 0);
    for (std::ptrdiff_t r = 0; r < 3; ++r) {  // a body in column 4: taken, not eligible
        labels(r, 4) = 5;
        f.eligible(r, 4) = 0;
    }
    grow_waterbody_workspace borrowed(labels.view());
    const std::vector<std::ptrdiff_t> seed{0};
    const auto own = grow_waterbody(f, seed, {});  // a workspace of its own gives the same flood
    const auto first = grow_waterbody(f, seed, {}, borrowed);
    CHECK(first.cells.size() == 12);
    CHECK(first.cells == own.cells);
    for (std::ptrdiff_t r = 0; r < 3; ++r) {
        CHECK(labels(r, 4) == 5);
        for (std::ptrdiff_t c = 0; c < 4; ++c) CHECK(labels(r, c) < 0);
        for (std::ptrdiff_t c = 5; c < 8; ++c) CHECK(labels(r, c) == 0);
    }
    const auto second = grow_waterbody(f, seed, {}, borrowed);  // a new stamp: the first flood's marks are no visit
    CHECK(second.cells == first.cells);
    borrowed.clear_marks();
    for (std::ptrdiff_t r = 0; r < 3; ++r)
        for (std::ptrdiff_t c = 0; c < 8; ++c) CHECK(labels(r, c) == (c == 4 ? 5 : 0));
    raster<std::int32_t> small(2, 8, 0);
    grow_waterbody_workspace wrong(small.view());
    CHECK_THROWS_AS(grow_waterbody(f, seed, {}, wrong), invalid_input);
}
