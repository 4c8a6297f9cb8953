// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/core/error.hpp>
#include <lidarfx/kernels/filter/line_opening.hpp>
#include <lidarfx/kernels/filter/morphology.hpp>

#include <cstdint>
#include <random>

using namespace lidarfx;

namespace {

/// The plain definition: walk both ways from every mask cell along each of the four lines and count the run.
raster<std::uint8_t> line_opening_by_walking(const raster<std::uint8_t>& m, int length)
{
    raster<std::uint8_t> out(m.rows(), m.cols(), 0);
    const int steps[4][2] = {{0, 1}, {1, 0}, {1, 1}, {1, -1}};
    const auto set = [&](std::ptrdiff_t r, std::ptrdiff_t c) {
        return r >= 0 && c >= 0 && r < m.rows() && c < m.cols() && m(r, c) != 0;
    };
    for (std::ptrdiff_t r = 0; r < m.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < m.cols(); ++c) {
            if (!m(r, c)) continue;
            for (const auto& d : steps) {
                int run = 1;
                for (std::ptrdiff_t k = 1; set(r + k * d[0], c + k * d[1]); ++k) ++run;
                for (std::ptrdiff_t k = 1; set(r - k * d[0], c - k * d[1]); ++k) ++run;
                if (run >= length) out(r, c) = 1;
            }
        }
    return out;
}

raster<std::uint8_t> random_line_mask(std::ptrdiff_t rows, std::ptrdiff_t cols, double share, unsigned seed)
{
    std::mt19937 rng(seed);
    std::bernoulli_distribution on(share);
    raster<std::uint8_t> m(rows, cols, 0);
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c) m(r, c) = on(rng) ? 1 : 0;
    return m;
}

}  // namespace

TEST_CASE("line_opening keeps exactly the cells on a straight run of at least the length, as a walk finds them")
{
    for (unsigned seed = 1; seed <= 40; ++seed) {
        const std::ptrdiff_t rows = 1 + seed % 13, cols = 1 + (seed * 7) % 17;
        const double share = 0.3 + 0.015 * seed;
        const auto m = random_line_mask(rows, cols, share, seed);
        for (int length : {1, 2, 3, 4, 7}) {
            CAPTURE(seed);
            CAPTURE(length);
            CHECK(line_opening(m, length) == line_opening_by_walking(m, length));
        }
    }
}

TEST_CASE("line_opening keeps a diagonal band one cell wide that a square opening erases, and drops short blobs")
{
    raster<std::uint8_t> m(20, 20, 0);
    for (std::ptrdiff_t i = 0; i < 12; ++i) m(i + 2, 17 - i) = 1;  // anti-diagonal, 12 cells
    m(1, 1) = m(1, 2) = m(2, 1) = m(2, 2) = 1;                     // a 2 x 2 blob: no run of 3
    const auto kept = line_opening(m, 3);
    CHECK(kept(2, 17) == 1);
    CHECK(kept(13, 6) == 1);
    CHECK(kept(1, 1) == 0);
    CHECK(kept(2, 2) == 0);  // the blob's diagonal is 2 long
    CHECK(morph_open(m, 3)(7, 12) == 0);
    CHECK(line_opening(kept, 3) == kept);  // idempotent
}

TEST_CASE("line_opening: length 1 keeps the mask, empty rasters stay empty, out-of-range lengths are refused")
{
    const auto m = random_line_mask(9, 11, 0.5, 3);
    CHECK(line_opening(m, 1) == m);
    CHECK(line_opening(raster<std::uint8_t>(0, 0), 4).size() == 0);
    CHECK_THROWS_AS(line_opening(m, 0), invalid_input);
    CHECK_THROWS_AS(line_opening(m, 256), invalid_input);
    CHECK_THROWS_AS(line_opening(m, 2, {.threads = -1}), invalid_input);
}

TEST_CASE("line_opening gives the same cells on blocks of rows and threads as the walk, long runs included")
{
    // Taller than one block of rows (64), with runs that cross the blocks' edges in every direction.
    for (unsigned seed = 1; seed <= 6; ++seed) {
        const auto m = random_line_mask(150 + seed, 90 + 3 * seed, 0.55 + 0.05 * seed, seed);
        for (int length : {2, 4, 6, 9}) {
            CAPTURE(seed);
            CAPTURE(length);
            const auto walked = line_opening_by_walking(m, length);
            CHECK(line_opening(m, length, {.threads = 1}) == walked);
            CHECK(line_opening(m, length, {.threads = 3}) == walked);
        }
    }
}
