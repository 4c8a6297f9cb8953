// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/kernels/filter/vegetation_mask.hpp>

#include "reference/morphology.hpp"
#include "reference/progress.hpp"
#include "test_values.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

using namespace lidarfx;

namespace {

/// min_z = 100 everywhere, max_z = 100 + spread; a 1 in `tall` gives a spread of 5 m, a 0 of 1 m.
struct surfaces {
    raster<float> min_z, max_z;
};

surfaces from_mask(std::ptrdiff_t rows, std::ptrdiff_t cols, const std::vector<int>& tall)
{
    surfaces s{raster<float>(rows, cols, 100.0f), raster<float>(rows, cols)};
    for (std::ptrdiff_t i = 0; i < rows * cols; ++i)
        s.max_z.data()[i] = tall[static_cast<std::size_t>(i)] ? 105.0f : 101.0f;
    return s;
}

raster<std::uint8_t> mask_of(std::ptrdiff_t rows, std::ptrdiff_t cols, const std::vector<int>& cells)
{
    raster<std::uint8_t> m(rows, cols);
    for (std::ptrdiff_t i = 0; i < rows * cols; ++i)
        m.data()[i] = static_cast<std::uint8_t>(cells[static_cast<std::size_t>(i)]);
    return m;
}

}  // namespace

TEST_CASE("raster/vegetation_mask: strictly more than height_m; NaN is no vegetation")
{
    raster<float> lo(1, 5, 10.0f), hi(1, 5);
    hi(0, 0) = 13.0f;  // spread 3 > 2
    hi(0, 1) = 12.0f;  // spread 2, not > 2
    hi(0, 2) = nan_f;  // no return
    hi(0, 3) = 10.5f;
    hi(0, 4) = 30.0f;
    lo(0, 4) = nan_f;
    const auto m = vegetation_mask(lo, hi, {.closing_size_cells = 1});
    CHECK(m == mask_of(1, 5, {1, 0, 0, 0, 0}));
    CHECK(vegetation_mask(lo, hi, {.height_m = 0.4, .closing_size_cells = 1}) == mask_of(1, 5, {1, 1, 0, 1, 0}));
}

TEST_CASE("raster/vegetation_mask: the closing fills gaps inside a canopy and keeps the border clipped")
{
    // Hand-checked 3x3 closing: the hole at (1, 1) fills; the lone corner cell survives (border clipped).
    const auto s = from_mask(5, 5, {1, 1, 1, 0, 0, 1, 0, 1, 0, 0, 1, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1});
    CHECK(vegetation_mask(s.min_z, s.max_z, {.closing_size_cells = 3}) ==
          mask_of(5, 5, {1, 1, 1, 0, 0, 1, 1, 1, 0, 0, 1, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1}));
    CHECK(vegetation_mask(s.min_z, s.max_z, {.closing_size_cells = 1}) ==
          mask_of(5, 5, {1, 1, 1, 0, 0, 1, 0, 1, 0, 0, 1, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1}));
}

TEST_CASE("raster/vegetation_mask: the default 5x5 closing bridges gaps of up to 4 cells, not 5")
{
    // Two stands of trees over the full height; columns in between are ground.
    for (int gap : {3, 4, 5}) {
        CAPTURE(gap);
        const std::ptrdiff_t rows = 9, cols = 8 + gap;
        std::vector<int> tall(static_cast<std::size_t>(rows * cols));
        for (std::ptrdiff_t r = 0; r < rows; ++r)
            for (std::ptrdiff_t c = 0; c < cols; ++c)
                tall[static_cast<std::size_t>(r * cols + c)] = (c < 4 || c >= 4 + gap);
        const auto s = from_mask(rows, cols, tall);
        const auto m = vegetation_mask(s.min_z, s.max_z);
        for (std::ptrdiff_t r = 0; r < rows; ++r) {
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                const bool between = c >= 4 && c < 4 + gap;
                CHECK(m(r, c) == (between && gap == 5 ? 0 : 1));
            }
        }
    }
}

TEST_CASE("raster/vegetation_mask: equals threshold then brute-force closing on random strided rasters")
{
    const unsigned seed = 2718;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> ground(50.0f, 60.0f), spread(0.0f, 4.0f);
    std::bernoulli_distribution hole(0.05);
    for (int trial = 0; trial < 12; ++trial) {
        raster<float> lo(31, 40), hi(31, 40);
        for (std::ptrdiff_t i = 0; i < lo.size(); ++i) {
            lo.data()[i] = hole(rng) ? nan_f : ground(rng);
            hi.data()[i] = lo.data()[i] + spread(rng);
        }
        const auto lo_w = lo.view().window(2, 3, 27, 33), hi_w = hi.view().window(1, 5, 27, 33);  // strided
        const vegetation_mask_options opt{.height_m = 1.5 + 0.25 * (trial % 3),
                                          .closing_size_cells = 1 + 2 * (trial % 4),
                                          .run = {.threads = 1 + trial % 3}};
        reference::mask threshold(27, 33);
        for (std::ptrdiff_t r = 0; r < 27; ++r)
            for (std::ptrdiff_t c = 0; c < 33; ++c)
                threshold(r, c) =
                    static_cast<std::uint8_t>(static_cast<double>(hi_w(r, c)) - lo_w(r, c) > opt.height_m);
        CAPTURE(seed);
        CAPTURE(trial);
        const auto expected = reference::close(threshold.view(), opt.closing_size_cells, opt.closing_size_cells);
        CHECK(vegetation_mask(lo_w, hi_w, opt) == expected);
        CHECK(vegetation_mask(raster<float>(lo_w), raster<double>(hi_w), opt) == expected);

        raster<std::uint8_t> target(30, 40, 7);
        vegetation_mask(lo_w, hi_w, target.view().window(1, 2, 27, 33), opt);
        CHECK(raster<std::uint8_t>(target.view().window(1, 2, 27, 33)) == expected);
        CHECK(target(0, 2) == 7);
    }
}

TEST_CASE("raster/vegetation_mask: progress is monotone and ends at 1; returning false cancels")
{
    std::mt19937 rng(31);
    std::uniform_real_distribution<float> ground(50.0f, 60.0f), spread(0.0f, 4.0f);
    raster<float> lo(300, 50), hi(300, 50);  // five blocks of 64 rows for the threshold, two strips for the closing
    for (std::ptrdiff_t i = 0; i < lo.size(); ++i) {
        lo.data()[i] = ground(rng);
        hi.data()[i] = lo.data()[i] + spread(rng);
    }
    for (int closing : {1, 5}) {
        const auto want = vegetation_mask(lo, hi, {.closing_size_cells = closing});
        for (int threads : {1, 2}) {
            CAPTURE(closing);
            CAPTURE(threads);
            const reference::progress_log log;
            const vegetation_mask_options opt{.closing_size_cells = closing,
                                              .run = {.threads = threads, .progress = log.callback()}};
            CHECK(vegetation_mask(lo, hi, opt) == want);
            CHECK(log.monotone_to_one(threads == 1 ? 5 : 1));
            const vegetation_mask_options stop{.closing_size_cells = closing,
                                               .run = {.threads = threads, .progress = reference::cancel_at_once()}};
            CHECK_THROWS_WITH_AS(vegetation_mask(lo, hi, stop), "vegetation_mask: cancelled", cancelled);
        }
    }
}

TEST_CASE("raster/vegetation_mask: bad arguments throw invalid_input")
{
    const raster<float> a(3, 4), b(4, 3);
    CHECK_THROWS_WITH_AS(vegetation_mask(a, b),
                         "vegetation_mask: min_z and max_z must have the same shape (got 3x4 and 4x3)", invalid_input);
    raster<std::uint8_t> out(3, 3);
    CHECK_THROWS_WITH_AS(vegetation_mask(a, a, out),
                         "vegetation_mask: min_z and out must have the same shape (got 3x4 and 3x3)", invalid_input);
    CHECK_THROWS_WITH_AS(vegetation_mask(a, a, {.height_m = -1.0}),
                         "vegetation_mask: height_m must be finite and >= 0 (got -1)", invalid_input);
    CHECK_THROWS_AS(vegetation_mask(a, a, {.height_m = std::nan("")}), invalid_input);
    CHECK_THROWS_WITH_AS(vegetation_mask(a, a, {.closing_size_cells = 4}),
                         "vegetation_mask: closing_size_cells must be odd and >= 1 (got 4)", invalid_input);
    CHECK_THROWS_WITH_AS(vegetation_mask(a, a, {.closing_size_cells = -3}),
                         "vegetation_mask: closing_size_cells must be odd and >= 1 (got -3)", invalid_input);
    CHECK_THROWS_WITH_AS(vegetation_mask(a, a, {.run = {.threads = -1}}),
                         "vegetation_mask: run.threads must be >= 0 (got -1)", invalid_input);
}
