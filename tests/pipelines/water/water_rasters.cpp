// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/pipelines/water/assess_water_inputs.hpp>
#include <lidarfx/pipelines/water/measure_waterbodies.hpp>
#include <lidarfx/pipelines/water/water_angles.hpp>
#include <lidarfx/pipelines/water/water_rasters.hpp>
#include <lidarfx/pipelines/water/water_seeds.hpp>
#include <lidarfx/pipelines/water/water_vegetation.hpp>

#include "water_test_rasters.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

using namespace lidarfx;

TEST_CASE("water/to_water_rasters: views the six rasters of rasterize() without copying")
{
    rasterize_result pr;
    pr.g = grid{0, 0, 2.0, 3, 4};
    pr.min_z = pr.max_z = pr.mean_intensity = raster<float>(3, 4, 1.0f);
    pr.count = raster<std::uint32_t>(3, 4, 2);
    pr.dropout = pr.multiple_returns = raster<std::uint8_t>(3, 4, 0);
    const water_rasters in = to_water_rasters(pr);
    CHECK(in.min_z.data() == pr.min_z.data());
    CHECK(in.max_z.data() == pr.max_z.data());
    CHECK(in.mean_intensity.data() == pr.mean_intensity.data());
    CHECK(in.dropout.data() == pr.dropout.data());
    CHECK(in.multiple_returns.data() == pr.multiple_returns.data());
    CHECK(in.count.data() == pr.count.data());
}

TEST_CASE("water/water_rasters: every step that reads the survey refuses mismatched or empty rasters")
{
    raster<float> z(4, 4, 1.0f), z2(4, 5, 1.0f);
    raster<std::uint8_t> d(4, 4), d2(3, 4);
    raster<std::uint32_t> n2(4, 3);
    CHECK_THROWS_WITH_AS(assess_water_inputs(water_rasters{z, z2, z, d}, 2.0),
                         "assess_water_inputs: min_z and max_z must have the same shape (got 4x4 and 4x5)",
                         invalid_input);
    CHECK_THROWS_WITH_AS(water_vegetation(water_rasters{z, z, z2, d}),
                         "water_vegetation: min_z and mean_intensity must have the same shape (got 4x4 and 4x5)",
                         invalid_input);
    CHECK_THROWS_WITH_AS(water_angles(water_rasters{z, z, z, d2}, 1.0),
                         "water_angles: min_z and dropout must have the same shape (got 4x4 and 3x4)", invalid_input);
    // The optional rasters are checked only when given.
    CHECK_NOTHROW(assess_water_inputs(water_rasters{z, z, z, d}, 2.0));
    CHECK_THROWS_WITH_AS(assess_water_inputs(water_rasters{z, z, z, d, d2}, 2.0),
                         "assess_water_inputs: min_z and multiple_returns must have the same shape (got 4x4 and 3x4)",
                         invalid_input);
    CHECK_THROWS_WITH_AS(assess_water_inputs(water_rasters{z, z, z, d, {}, n2}, 2.0),
                         "assess_water_inputs: min_z and count must have the same shape (got 4x4 and 4x3)",
                         invalid_input);
    const raster<float> none(0, 0);
    const raster<std::uint8_t> no_mask(0, 0);
    CHECK_THROWS_WITH_AS(assess_water_inputs(water_rasters{none, none, none, no_mask}, 2.0),
                         "assess_water_inputs: the rasters are empty (0 cells)", invalid_input);
    std::vector<waterbody> bodies;
    raster<std::int32_t> labels(4, 4, 0);
    CHECK_THROWS_AS(measure_waterbodies(labels, bodies, water_rasters{z, z2, z, d}, 1.0), invalid_input);
}

TEST_CASE("water/water_rasters: the steps that read the survey give the same result on strided views")
{
    std::mt19937 rng(2718);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const std::ptrdiff_t rows = 23, cols = 31, r0 = 3, c0 = 5;
    water_test::survey big(rows + 7, cols + 11), small(rows, cols);
    // Poison outside the window: steep, bright, vegetated, all dropouts.
    big.min_z.fill(500.0f);
    big.max_z.fill(900.0f);
    big.intensity.fill(7.0f);
    big.dropout.fill(1);
    big.multiple.fill(1);
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            small.min_z(r, c) = 10.0f + 2.0f * u(rng);
            small.max_z(r, c) = small.min_z(r, c) + 3.0f * u(rng) * u(rng);
            small.intensity(r, c) = 100.0f * u(rng);
            small.multiple(r, c) = u(rng) < 0.05f;
            if (u(rng) < 0.3f || (r > 5 && r < 15 && c > 8 && c < 20)) small.drop(r, c);
            big.min_z(r + r0, c + c0) = small.min_z(r, c);
            big.max_z(r + r0, c + c0) = small.max_z(r, c);
            big.intensity(r + r0, c + c0) = small.intensity(r, c);
            big.dropout(r + r0, c + c0) = small.dropout(r, c);
            big.multiple(r + r0, c + c0) = small.multiple(r, c);
            big.count(r + r0, c + c0) = small.count(r, c);
        }
    const auto win = [&](const auto& ras) { return ras.view().window(r0, c0, rows, cols); };
    const water_rasters strided{win(big.min_z),   win(big.max_z),    win(big.intensity),
                                win(big.dropout), win(big.multiple), win(big.count)};
    const water_rasters plain = small.view();
    CHECK(water_vegetation(strided) == water_vegetation(plain));
    for (const auto input : {angular_input::returns_only, angular_input::idw_filled}) {
        const auto a = water_angles(strided, 1.5, {.input = input}), b = water_angles(plain, 1.5, {.input = input});
        CHECK(std::memcmp(a.data(), b.data(), static_cast<std::size_t>(a.size()) * sizeof(float)) == 0);
    }
    const auto seeds = water_seeds(strided.dropout, {.opening_size_cells = 3, .min_cells = 20});
    CHECK(seeds.count() >= 1);
    CHECK(seeds.labels == water_seeds(plain.dropout, {.opening_size_cells = 3, .min_cells = 20}).labels);
    auto labels_a = seeds.labels, labels_b = seeds.labels;
    std::vector<waterbody> bodies_a, bodies_b;
    measure_waterbodies(labels_a, bodies_a, strided, 1.5);
    measure_waterbodies(labels_b, bodies_b, plain, 1.5);
    CHECK(labels_a == labels_b);
    REQUIRE(bodies_a.size() == bodies_b.size());
    for (std::size_t k = 0; k < bodies_a.size(); ++k) {
        CHECK(bodies_a[k].cells == bodies_b[k].cells);
        CHECK(bodies_a[k].box == bodies_b[k].box);
        CHECK(std::memcmp(&bodies_a[k].mean_intensity, &bodies_b[k].mean_intensity, sizeof(double)) == 0);
        CHECK(std::memcmp(&bodies_a[k].water_level_m, &bodies_b[k].water_level_m, sizeof(double)) == 0);
    }
}

TEST_CASE("water/median: the element at position n / 2 of the sorted values, below and above the radix size")
{
    std::mt19937 rng(5);
    const std::size_t radix_from = std::size_t{1} << 16;
    for (const std::size_t n : {std::size_t{1}, std::size_t{2}, std::size_t{7}, radix_from - 1, radix_from,
                                radix_from + 1, 3 * radix_from + 5}) {
        for (int kind = 0; kind < 8; ++kind) {
            std::vector<float> v(n);
            std::normal_distribution<float> level(12.5f, 0.3f);
            std::uniform_int_distribution<int> few(-3, 3);
            for (std::size_t i = 0; i < n; ++i) {
                switch (kind) {
                    case 0:
                        v[i] = level(rng);
                        break;  // heights of one level
                    case 1:
                        v[i] = static_cast<float>(few(rng)) * 0.5f;
                        break;  // ties, negatives, zeros
                    case 2:
                        v[i] = i % 2 ? 0.0f : -0.0f;
                        break;  // signed zeros only
                    case 4:
                        v[i] = 3.25f;
                        break;  // one value (no spread)
                    case 5:
                        v[i] = i % 3 == 0   ? std::numeric_limits<float>::max()   // the widest finite range,
                               : i % 3 == 1 ? -std::numeric_limits<float>::max()  // and subnormals
                                            : std::numeric_limits<float>::denorm_min() * static_cast<float>(i % 5);
                        break;
                    case 6:
                        v[i] = 7.0f + std::ldexp(static_cast<float>(i % 65537), -20);
                        break;  // 2^17 keys (2 ulps a step)
                    case 7:
                        v[i] = 7.0f + std::ldexp(static_cast<float>(i % 65537), -21);
                        break;  // 2^16 + 1 keys: shift 1
                    default:
                        v[i] = i % 97 == 0 ? std::numeric_limits<float>::infinity() : -level(rng);  // inf, < 0
                }
            }
            auto sorted = v;
            std::sort(sorted.begin(), sorted.end());
            const double expected = sorted[n / 2];
            const double m = detail::median(v);
            CHECK(m == expected);
            CHECK_FALSE((std::signbit(m) && m == 0));  // a median of zeros is +0
        }
    }
    std::vector<float> none;
    CHECK(std::isnan(detail::median(none)));
}
