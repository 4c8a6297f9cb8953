// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/core/parallel_bands.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <thread>
#include <vector>

using namespace lidarfx;

namespace {

// A band's rows as {r0, r1}; the first band sleeps so that, on several threads, later bands finish first.
std::vector<std::ptrdiff_t> band_bounds(std::ptrdiff_t r0, std::ptrdiff_t r1)
{
    if (r0 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(2));
    return {r0, r1};
}

}  // namespace

TEST_CASE("core/parallel_bands: one slot per band, in band order, the last band short")
{
    const std::vector<std::vector<std::ptrdiff_t>> expected{{0, 4}, {4, 8}, {8, 10}};
    for (int threads = 1; threads <= 4; ++threads) {
        CAPTURE(threads);
        CHECK(parallel_bands(10, 4, threads, band_bounds) == expected);
    }
    // band_rows dividing rows: no short band; band_rows above rows: one band of all rows.
    CHECK(parallel_bands(8, 4, 2, band_bounds) == std::vector<std::vector<std::ptrdiff_t>>{{0, 4}, {4, 8}});
    CHECK(parallel_bands(3, 16, 2, band_bounds) == std::vector<std::vector<std::ptrdiff_t>>{{0, 3}});
}

TEST_CASE("core/parallel_bands: the same slots for threads 1 to 4")
{
    for (std::ptrdiff_t rows : {1, 7, 100, 1001}) {
        CAPTURE(rows);
        // Each band's sum of sin(r) over its rows, a result that depends on the order of the additions.
        const auto sums = [rows](int threads) {
            return parallel_bands(rows, 16, threads, [](std::ptrdiff_t r0, std::ptrdiff_t r1) {
                double sum = 0;
                for (auto r = r0; r < r1; ++r) sum += std::sin(static_cast<double>(r));
                return sum;
            });
        };
        const std::vector<double> reference = sums(1);
        REQUIRE(reference.size() == static_cast<std::size_t>((rows + 15) / 16));
        double first = 0;
        for (std::ptrdiff_t r = 0; r < std::min<std::ptrdiff_t>(rows, 16); ++r)
            first += std::sin(static_cast<double>(r));
        CHECK(reference.front() == first);
        for (int threads = 2; threads <= 4; ++threads) {
            CAPTURE(threads);
            CHECK(sums(threads) == reference);
        }
    }
}

TEST_CASE("core/parallel_bands: rows = 0 gives no slots and no call; errors are the body's or name parallel_bands")
{
    for (int threads = 1; threads <= 4; ++threads) {
        int calls = 0;
        const auto slots = parallel_bands(0, 16, threads, [&](std::ptrdiff_t, std::ptrdiff_t) { return ++calls; });
        CHECK(slots.empty());
        CHECK(calls == 0);
    }
    const auto one = [](std::ptrdiff_t, std::ptrdiff_t) { return 1; };
    CHECK_THROWS_WITH_AS(parallel_bands(10, 0, 1, one), "parallel_bands: band_rows must be >= 1 (got 0)",
                         invalid_input);
    CHECK_THROWS_AS(parallel_bands(10, 1, -1, one), invalid_input);
    CHECK_THROWS_WITH_AS(parallel_bands(100, 10, 2,
                                        [](std::ptrdiff_t r0, std::ptrdiff_t) {
                                            if (r0 == 50) throw std::runtime_error("boom");
                                            return r0;
                                        }),
                         "boom", std::runtime_error);
}
