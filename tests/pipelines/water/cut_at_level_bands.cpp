// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/core/error.hpp>
#include <lidarfx/kernels/label/connected_components.hpp>
#include <lidarfx/pipelines/water/cut_at_level_bands.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <tuple>
#include <utility>
#include <vector>

using namespace lidarfx;

TEST_CASE("water/cut_at_level_bands: the plain loop over every cell")
{
    // The plain form: per part the mean min z over returns, every cell's band index (NaN off the mask or
    // without a return) in full rows, and the cut of each row read from the uncut rows (a cut cell becomes 0,
    // the others keep their value).
    const auto plain = [](raster<std::uint8_t> mask, const raster<float>& z, double band) {
        const std::ptrdiff_t rows = mask.rows(), cols = mask.cols();
        const auto parts = connected_components(mask, connectivity::eight);
        std::vector<double> mean(parts.count() + 1, 0.0), finite(parts.count() + 1, 0.0);
        for (std::ptrdiff_t r = 0; r < rows; ++r) {
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                const auto l = static_cast<std::size_t>(parts.labels(r, c));
                if (l > 0 && std::isfinite(z(r, c))) mean[l] += z(r, c), finite[l] += 1;
            }
        }
        for (std::size_t l = 1; l < mean.size(); ++l) mean[l] = finite[l] > 0 ? mean[l] / finite[l] : 0.0;
        const auto index = [&](std::ptrdiff_t r, std::ptrdiff_t c) {
            const auto l = static_cast<std::size_t>(parts.labels(r, c));
            return l > 0 ? std::floor((z(r, c) - mean[l]) / band + 0.5) : std::numeric_limits<double>::quiet_NaN();
        };
        const raster<std::uint8_t> uncut = mask;
        for (std::ptrdiff_t r = 0; r + 1 < rows; ++r) {
            for (std::ptrdiff_t c = 0; c + 1 < cols; ++c) {
                const double h = index(r, c), right = index(r, c + 1), down = index(r + 1, c);
                const bool known = !std::isnan(h);
                const bool cut_right = uncut(r, c + 1) != 0 && right != h && known && !std::isnan(right);
                const bool cut_down = uncut(r + 1, c) != 0 && down != h && known && !std::isnan(down);
                if (cut_right || cut_down) mask(r, c) = 0;
            }
        }
        return mask;
    };
    std::uint32_t state = 777;  // LCG: deterministic
    const auto next = [&] { return (state = state * 1664525u + 1013904223u) >> 8; };
    constexpr float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    const std::pair<std::ptrdiff_t, std::ptrdiff_t> shapes[] = {{0, 0},  {1, 1},  {1, 70},   {70, 1},  {2, 2},
                                                                {3, 64}, {5, 65}, {40, 130}, {64, 129}};
    for (const auto& item : shapes) {
        const auto& rows = std::get<0>(item);
        const auto& cols = std::get<1>(item);
        for (int trial = 0; trial < 12; ++trial) {
            // Mask densities from empty to full; heights on a slope (several bands per part), NaN and inf among them.
            const std::uint32_t density = trial == 0 ? 0 : trial == 1 ? 100 : next() % 100;
            raster<std::uint8_t> mask(rows, cols, 0);
            raster<float> z(rows, cols, 0.0f);
            for (std::ptrdiff_t r = 0; r < rows; ++r) {
                for (std::ptrdiff_t c = 0; c < cols; ++c) {
                    mask(r, c) = static_cast<std::uint8_t>(next() % 100 < density ? 1 + next() % 255 : 0);
                    const std::uint32_t x = next() % 40;
                    z(r, c) = x == 0                ? nan
                              : x == 1 && trial > 6 ? (next() % 2 ? inf : -inf)
                                                    : 10.0f + 0.013f * static_cast<float>(r + 2 * c) +
                                                          0.001f * static_cast<float>(next() % 50);
                }
            }
            if (trial == 3) std::fill(z.begin(), z.end(), nan);  // a mask without returns: nothing is cut
            for (const double band : {0.3, 0.05}) {
                const auto expected = plain(mask, z, band);
                auto got = mask;
                const auto parts = connected_components(got, connectivity::eight);
                cut_at_level_bands(got, parts.labels, parts.count(), z, band);
                CAPTURE(rows);
                CAPTURE(cols);
                CAPTURE(trial);
                REQUIRE(std::equal(got.begin(), got.end(), expected.begin(), expected.end()));
            }
        }
    }
}

TEST_CASE("water/cut_at_level_bands: bad arguments are refused")
{
    raster<std::uint8_t> mask(2, 3, 1);
    raster<std::int32_t> parts(2, 3, 1), short_parts(1, 3, 1);
    raster<float> z(2, 3, 1.0f);
    CHECK_THROWS_AS(cut_at_level_bands(mask, short_parts, 1, z, 0.3), invalid_input);
    CHECK_THROWS_WITH_AS(cut_at_level_bands(mask, parts, 1, z, 0.0),
                         "cut_at_level_bands: band must be finite and > 0 (got 0)", invalid_input);
    CHECK_THROWS_WITH_AS(cut_at_level_bands(mask, parts, 0, z, 0.3),
                         "cut_at_level_bands: parts must be labels in [0, count] (got 1)", invalid_input);
}
