// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/kernels/stats/zonal_statistics.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

using namespace lidarfx;

TEST_CASE("stats/zonal_statistics: matches per-label statistics computed from gathered samples")
{
    std::mt19937 rng(77);
    std::uniform_int_distribution<int> label(0, 6);
    std::normal_distribution<double> value(10, 3);
    raster<std::int32_t> labels(41, 37);
    raster<float> values(41, 37);
    std::vector<std::vector<double>> groups(7);
    for (std::ptrdiff_t r = 0; r < 41; ++r)
        for (std::ptrdiff_t c = 0; c < 37; ++c) {
            labels(r, c) = r == 0 && c == 0 ? 9 : label(rng);  // labels 7 and 8 exist but are empty, 9 only NaN
            values(r, c) = (r * 37 + c) % 13 == 0 ? NAN : static_cast<float>(value(rng));
            if (!std::isnan(values(r, c))) groups[static_cast<std::size_t>(labels(r, c))].push_back(values(r, c));
        }
    const auto stats = zonal_statistics(labels, values);
    REQUIRE(stats.size() == 10);
    for (std::size_t k = 0; k < 7; ++k) {
        auto g = groups[k];
        std::sort(g.begin(), g.end());
        double mean = 0;
        for (double v : g) mean += v;
        mean /= static_cast<double>(g.size());
        double sq = 0;
        for (double v : g) sq += (v - mean) * (v - mean);
        const double median = g.size() % 2 ? g[g.size() / 2] : 0.5 * (g[g.size() / 2 - 1] + g[g.size() / 2]);
        INFO("label ", k);
        REQUIRE(stats[k].count == g.size());
        CHECK(stats[k].mean == doctest::Approx(mean).epsilon(1e-12));
        CHECK(stats[k].std == doctest::Approx(std::sqrt(sq / static_cast<double>(g.size()))).epsilon(1e-12));
        CHECK(stats[k].median == median);
        CHECK(stats[k].min == g.front());
        CHECK(stats[k].max == g.back());
    }
    CHECK(stats[8].count == 0);
    CHECK(std::isnan(stats[8].mean));
    CHECK(stats[9].count == 0);
}

TEST_CASE("stats/zonal_statistics: one cell, empty raster, bad labels and shapes")
{
    CHECK(zonal_statistics(raster<std::int32_t>(0, 0), raster<float>(0, 0)).size() == 1);
    const auto one = zonal_statistics(raster<std::int32_t>(1, 1, 3), raster<float>(1, 1, 2.5f));
    REQUIRE(one.size() == 4);
    CHECK(one[3].count == 1);
    CHECK(one[3].median == 2.5);
    CHECK(one[3].std == 0.0);
    CHECK_THROWS_AS(zonal_statistics(raster<std::int32_t>(1, 1, -1), raster<float>(1, 1)), invalid_input);
    CHECK_THROWS_AS(zonal_statistics(raster<std::int32_t>(2, 1), raster<float>(1, 2)), invalid_input);
}

TEST_CASE("stats/zonal_circular_statistics: mean across north, mode with ties, histogram bins centred on degrees")
{
    raster<std::int32_t> labels(1, 8, 1);
    raster<float> angles(1, 8);
    const float a[8] = {350, 10, 355, 5, 359.6f, 0.4f, -10, 370};  // -10 = 350, 370 = 10
    for (int i = 0; i < 8; ++i) angles(0, i) = a[i];
    labels(0, 7) = 2;
    const auto s = zonal_circular_statistics(labels, angles);
    REQUIRE(s.size() == 3);
    CHECK(s[1].count == 7);
    CHECK(s[1].mean_deg ==
          doctest::Approx(358.5682).epsilon(1e-6));  // offsets -10 10 -5 5 -0.4 0.4 -10: north, not 180
    CHECK(s[1].resultant_length > 0.98);
    CHECK(s[1].mode_deg == 0.0);  // bins 350 (350, -10) and 0 (359.6, 0.4) hold two each: the smaller bin wins
    CHECK(s[1].histogram[350] == 2);
    CHECK(s[1].histogram[0] == 2);
    CHECK(s[2].mode_deg == 10.0);
    CHECK(s[2].histogram.size() == 360);
}

TEST_CASE("stats/zonal_circular_statistics: opposite angles cancel, bin widths, refusals")
{
    raster<std::int32_t> labels(1, 4, 1);
    raster<float> angles(1, 4);
    angles(0, 0) = 90;
    angles(0, 1) = 270;
    angles(0, 2) = 95;
    angles(0, 3) = NAN;
    const auto s = zonal_circular_statistics(labels, angles, {.bin_width_deg = 10, .keep_histograms = false});
    CHECK(s[1].count == 3);
    CHECK(s[1].mode_deg == 90.0);  // one each in bins 90 ([85, 95)), 100 (95 is on its lower edge) and 270
    CHECK(s[1].histogram.empty());
    CHECK(s[1].resultant_length < 0.4);
    CHECK_THROWS_AS(zonal_circular_statistics(labels, angles, {.bin_width_deg = 7}), invalid_input);
    CHECK_THROWS_AS(zonal_circular_statistics(labels, angles, {.bin_width_deg = 0}), invalid_input);
}
