// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/core/error.hpp>
#include <lidarfx/pipelines/water/join_adjacent_dropouts.hpp>

#include <algorithm>
#include <cstdint>
#include <random>

using namespace lidarfx;

TEST_CASE("water/join_adjacent_dropouts: seed cells and the eligible dropouts among their 8 neighbours")
{
    std::mt19937 rng(3);
    for (const std::ptrdiff_t rows : {1, 2, 9, 33}) {
        for (const std::ptrdiff_t cols : {1, 5, 70}) {
            raster<std::uint8_t> seed(rows, cols), dropout(rows, cols), eligible(rows, cols);
            for (std::ptrdiff_t i = 0; i < seed.size(); ++i) {
                seed.data()[i] = rng() % 6 == 0 ? static_cast<std::uint8_t>(1 + rng() % 200) : 0;
                dropout.data()[i] = rng() % 2;
                eligible.data()[i] = rng() % 4 != 0;
            }
            const auto got = join_adjacent_dropouts(seed, dropout, eligible, {.threads = 1});
            for (std::ptrdiff_t r = 0; r < rows; ++r) {
                for (std::ptrdiff_t c = 0; c < cols; ++c) {
                    bool near = false;
                    for (std::ptrdiff_t rr = std::max<std::ptrdiff_t>(0, r - 1); rr <= std::min(rows - 1, r + 1); ++rr)
                        for (std::ptrdiff_t cc = std::max<std::ptrdiff_t>(0, c - 1); cc <= std::min(cols - 1, c + 1);
                             ++cc)
                            near = near || seed(rr, cc) != 0;
                    const bool on = seed(r, c) != 0 || (near && dropout(r, c) != 0 && eligible(r, c) != 0);
                    REQUIRE(got(r, c) == (on ? 1 : 0));
                }
            }
        }
    }
    raster<std::uint8_t> a(2, 2), b(2, 3);
    CHECK_THROWS_AS(join_adjacent_dropouts(a, b, a), invalid_input);
    CHECK_THROWS_AS(join_adjacent_dropouts(a, a, b), invalid_input);
}
