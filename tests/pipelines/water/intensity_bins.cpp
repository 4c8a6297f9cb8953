// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/core/error.hpp>
#include <lidarfx/pipelines/water/intensity_bins.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "water_test_rasters.hpp"

using namespace lidarfx;
using water_test::grid_of;

namespace {

/// Bins by definition: the rank of nearbyint(v / resolution) among the sorted distinct rounded values.
intensity_bins_result reference_bins(const raster<float>& v, const raster<std::uint8_t>& dropout, double resolution)
{
    std::vector<double> distinct;
    for (std::ptrdiff_t i = 0; i < v.size(); ++i)
        if (!dropout.data()[i] && std::isfinite(v.data()[i]))
            distinct.push_back(std::nearbyint(static_cast<double>(v.data()[i]) * (1.0 / resolution)));
    std::sort(distinct.begin(), distinct.end());
    distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
    intensity_bins_result out{raster<std::int32_t>(v.rows(), v.cols(), -1),
                              std::max(1, static_cast<int>(distinct.size()))};
    for (std::ptrdiff_t i = 0; i < v.size(); ++i) {
        if (dropout.data()[i] || !std::isfinite(v.data()[i])) continue;
        const double q = std::nearbyint(static_cast<double>(v.data()[i]) * (1.0 / resolution));
        out.bin.data()[i] =
            static_cast<std::int32_t>(std::lower_bound(distinct.begin(), distinct.end(), q) - distinct.begin());
    }
    return out;
}

}  // namespace

TEST_CASE("water/intensity_bins: ranks of the rounded values; dropouts and NaN have none")
{
    const auto v = grid_of<float>({{3.4f, 3.6f, 7.0f},  //
                                   {7.0f, NAN, 55.0f},
                                   {2.5f, 3.5f, 0.0f}});
    const auto d = grid_of<std::uint8_t>({{0, 0, 0},  //
                                          {0, 0, 0},
                                          {0, 0, 1}});
    // Rounded: 3, 4, 7 / 7, -, 55 / 2 (tie to even), 4 (tie to even), dropout -> ranks over {2, 3, 4, 7, 55}.
    const auto b = intensity_bins(v, d);
    CHECK(b.bins == 5);
    CHECK(b.bin == grid_of<std::int32_t>({{1, 2, 3},  //
                                          {3, -1, 4},
                                          {0, 2, -1}}));
    // A coarser quantum merges values: v / 5 rounds to 0 (2.5: a tie, to even), 1 (3.4, 3.5, 3.6, 7) or 11 (55).
    const auto coarse = intensity_bins(v, d, {.resolution = 5.0});
    CHECK(coarse.bins == 3);
    CHECK(coarse.bin == grid_of<std::int32_t>({{1, 1, 1},  //
                                               {1, -1, 2},
                                               {0, 1, -1}}));
}

TEST_CASE("water/intensity_bins: no sample at all gives one bin and -1 everywhere")
{
    const raster<float> v(2, 3, 9.0f);
    const raster<std::uint8_t> d(2, 3, 1);
    const auto b = intensity_bins(v, d);
    CHECK(b.bins == 1);
    CHECK(b.bin == raster<std::int32_t>(2, 3, -1));
}

TEST_CASE("water/intensity_bins: small, negative and very wide ranges all equal the definition")
{
    std::mt19937 rng(99);
    for (int trial = 0; trial < 100; ++trial) {
        CAPTURE(trial);
        const std::ptrdiff_t rows = 1 + rng() % 20, cols = 1 + rng() % 20;
        // Five regimes: 16-bit LAS values, values with negatives, a range wider than 2^24, values on both
        // sides of the +-1e9 limit of the integer pass (a narrow range there), values far beyond it.
        const int regime = trial % 5;
        const double lo = regime == 0   ? 0.0
                          : regime == 1 ? -500.0
                          : regime == 2 ? -3.0e7
                          : regime == 3 ? 0.99999e9
                                        : -1.0e15;
        const double hi = regime == 0   ? 65535.0
                          : regime == 1 ? 500.0
                          : regime == 2 ? 3.0e7
                          : regime == 3 ? 1.00001e9
                                        : 1.0e15;
        std::uniform_real_distribution<double> value(lo, hi);
        raster<float> v(rows, cols);
        raster<std::uint8_t> d(rows, cols);
        for (std::ptrdiff_t i = 0; i < v.size(); ++i) {
            v.data()[i] = rng() % 10 == 0 ? NAN : static_cast<float>(value(rng));
            d.data()[i] = rng() % 7 == 0;
        }
        if (regime == 3 && trial % 2) {  // the mirror image: just below -1e9 and above it
            for (std::ptrdiff_t i = 0; i < v.size(); ++i) v.data()[i] = -v.data()[i];
        }
        const double resolution = trial % 2 || regime >= 3 ? 1.0 : 0.25 * static_cast<double>(1 + rng() % 8);
        const auto got = intensity_bins(v, d, {.resolution = resolution});
        const auto expected = reference_bins(v, d, resolution);
        CHECK(got.bins == expected.bins);
        CHECK(got.bin == expected.bin);
    }
}

TEST_CASE("water/intensity_bins: values on both sides of the 16-bit presence window equal the definition")
{
    // Presence is marked while rounding when every sample lies in [0, 2^16); one value just outside (-1 or
    // 65536 after rounding), in the first, a middle or the last row, sends the whole raster the other way.
    std::mt19937 rng(7);
    for (const float outside : {-1.0f, -0.6f, 65535.6f, 65536.0f, 70000.0f}) {
        for (int where = 0; where < 4; ++where) {
            raster<float> v(9, 13);
            raster<std::uint8_t> d(9, 13, 0);
            for (std::ptrdiff_t i = 0; i < v.size(); ++i) v.data()[i] = static_cast<float>(rng() % 65536);
            v.data()[0] = 0.0f;
            v.data()[1] = 65535.0f;
            const std::ptrdiff_t at = where == 0 ? 5 : where == 1 ? 60 : where == 2 ? v.size() - 1 : -1;
            if (at >= 0) v.data()[at] = outside;
            CAPTURE(outside);
            CAPTURE(where);
            const auto got = intensity_bins(v, d);
            const auto expected = reference_bins(v, d, 1.0);
            CHECK(got.bins == expected.bins);
            CHECK(got.bin == expected.bin);
        }
    }
}

TEST_CASE("water/intensity_bins: strided views read only their cells")
{
    raster<float> big(6, 9, 1000.0f);
    raster<std::uint8_t> big_d(6, 9, 0);
    raster<float> v(4, 5);
    raster<std::uint8_t> d(4, 5, 0);
    for (std::ptrdiff_t r = 0; r < 4; ++r)
        for (std::ptrdiff_t c = 0; c < 5; ++c) big(r + 1, c + 2) = v(r, c) = static_cast<float>((r * 7 + c * 3) % 6);
    const auto got = intensity_bins(big.view().window(1, 2, 4, 5), big_d.view().window(1, 2, 4, 5));
    CHECK(got.bins == 6);
    CHECK(got.bin == intensity_bins(v, d).bin);
}

TEST_CASE("water/intensity_bins: bad arguments are refused")
{
    const raster<float> v(2, 2, 1.0f);
    const raster<std::uint8_t> d(2, 3, 0), d2(2, 2, 0);
    CHECK_THROWS_WITH_AS(intensity_bins(v, d),
                         "intensity_bins: mean_intensity and dropout must have the same shape (got 2x2 and 2x3)",
                         invalid_input);
    CHECK_THROWS_WITH_AS(intensity_bins(v, d2, {.resolution = 0}),
                         "intensity_bins: resolution must be finite and > 0 (got 0)", invalid_input);
}

TEST_CASE("water/intensity_bins: several blocks of rows on several threads give the definition's ranks")
{
    // Rasters taller than one block (64 rows), each block holding values the others lack, in and out of the
    // 16-bit presence window.
    std::mt19937 rng(5);
    for (const double hi : {65535.0, 200000.0}) {
        raster<float> v(1100, 23);
        raster<std::uint8_t> d(1100, 23);
        for (std::ptrdiff_t r = 0; r < v.rows(); ++r)
            for (std::ptrdiff_t c = 0; c < v.cols(); ++c) {
                v(r, c) =
                    static_cast<float>(std::fmod(static_cast<double>(r) * 137.0 + static_cast<double>(rng() % 50), hi));
                d(r, c) = rng() % 9 == 0;
            }
        const auto expected = reference_bins(v, d, 1.0);
        for (const int threads : {1, 2, 5}) {
            CAPTURE(hi);
            CAPTURE(threads);
            const auto got = intensity_bins(v, d, {}, {.threads = threads});
            CHECK(got.bins == expected.bins);
            CHECK(got.bin == expected.bin);
        }
    }
    const raster<float> v(2, 2, 1.0f);
    const raster<std::uint8_t> d(2, 2, 0);
    CHECK_THROWS_AS(intensity_bins(v, d, {}, {.threads = -1}), invalid_input);
}
