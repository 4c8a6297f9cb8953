// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/core/raster.hpp>
#include <lidarfx/pipelines/water/seed_water_level.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

using namespace lidarfx;

TEST_CASE("water/seed_water_level: the low quantile of the returns around a seed is the water's level")
{
    // 10 x 10 cells: a 4 x 4 seed of dropouts (rows/cols 3-6) in water at 100 m; the land (cols >= 7)
    // stands 0.8 m higher and makes most of the ring.
    raster<float> min_z(10, 10, 100.0f);
    std::vector<std::ptrdiff_t> seed;
    for (std::ptrdiff_t r = 0; r < 10; ++r) {
        for (std::ptrdiff_t c = 0; c < 10; ++c) {
            if (c >= 7 || r <= 1) min_z.view()(r, c) = 100.8f;
            if (r >= 3 && r <= 6 && c >= 3 && c <= 6) {
                min_z.view()(r, c) = NAN;
                seed.push_back(r * 10 + c);
            }
        }
    }
    CHECK(seed_water_level(seed, min_z) == doctest::Approx(100.0));
    CHECK(seed_water_level(seed, min_z, {.ring_cells = 2, .quantile = 1.0}) == doctest::Approx(100.8));
    // Ring 1 reads rows/cols 2-7: row 2 and cols 2-6 water, col 7 land.
    CHECK(seed_water_level(seed, min_z, {.ring_cells = 1, .quantile = 0.5}) == doctest::Approx(100.0));
}

TEST_CASE("water/seed_water_level: no return around the seed gives NaN; bad options throw")
{
    raster<float> min_z(3, 3, NAN);
    const std::vector<std::ptrdiff_t> seed{4};
    CHECK(std::isnan(seed_water_level(seed, min_z)));
    CHECK_THROWS(seed_water_level(seed, min_z, {.ring_cells = 0}));
    CHECK_THROWS(seed_water_level(seed, min_z, {.quantile = 1.5}));
    const std::vector<std::ptrdiff_t> outside{9};
    CHECK_THROWS(seed_water_level(outside, min_z));
}

TEST_CASE("water/seed_water_level: equals the quantile of the ring's sorted distinct cells, on random seeds")
{
    // Reference: every finite cell within ring_cells of a seed cell, listed, sorted by index, made distinct;
    // the element at floor(quantile (n - 1)) of their sorted min z.
    const auto reference = [](const std::vector<std::ptrdiff_t>& seed, const raster<float>& z, int ring, double q) {
        std::vector<std::ptrdiff_t> cells;
        for (const auto i : seed) {
            const std::ptrdiff_t r = i / z.cols(), c = i % z.cols();
            for (std::ptrdiff_t rr = r - ring; rr <= r + ring; ++rr)
                for (std::ptrdiff_t cc = c - ring; cc <= c + ring; ++cc)
                    if (rr >= 0 && cc >= 0 && rr < z.rows() && cc < z.cols() && std::isfinite(z.view()(rr, cc)))
                        cells.push_back(rr * z.cols() + cc);
        }
        std::sort(cells.begin(), cells.end());
        cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
        if (cells.empty()) return static_cast<double>(NAN);
        std::vector<float> values;
        for (const auto i : cells) values.push_back(z.data()[i]);
        std::sort(values.begin(), values.end());
        return static_cast<double>(
            values[static_cast<std::size_t>(std::floor(q * static_cast<double>(values.size() - 1)))]);
    };
    std::mt19937 rng(5);
    for (int trial = 0; trial < 200; ++trial) {
        CAPTURE(trial);
        const std::ptrdiff_t rows = 1 + static_cast<std::ptrdiff_t>(rng() % 90),
                             cols = 1 + static_cast<std::ptrdiff_t>(rng() % 90);
        raster<float> z(rows, cols);
        std::vector<std::ptrdiff_t> seed;
        const float p_seed = static_cast<float>(rng() % 100) / 100.0f;
        std::uniform_real_distribution<float> unit(0, 1);
        for (std::ptrdiff_t i = 0; i < rows * cols; ++i) {
            const bool in_seed = unit(rng) < p_seed * 0.3f;
            z.data()[i] = in_seed || unit(rng) < 0.2f ? NAN : 50.0f + static_cast<float>(rng() % 200) / 100.0f;
            if (in_seed) seed.push_back(i);
        }
        const int ring = 1 + static_cast<int>(rng() % 3);
        const double q = static_cast<double>(rng() % 11) / 10.0;
        const double expected = reference(seed, z, ring, q),
                     got = seed_water_level(seed, z, {.ring_cells = ring, .quantile = q});
        if (std::isnan(expected))
            CHECK(std::isnan(got));
        else
            CHECK(got == expected);
    }
    CHECK(std::isnan(seed_water_level({}, raster<float>(3, 3, 1.0f))));  // no seed cell: no ring
}
