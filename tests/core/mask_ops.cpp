// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/core/error.hpp>
#include <lidarfx/core/mask_ops.hpp>
#include <lidarfx/core/raster.hpp>

#include <cstdint>
#include <random>
#include <utility>

using namespace lidarfx;

namespace {

/// A random mask of 0 and any nonzero byte.
raster<std::uint8_t> random_mask(std::mt19937& rng, std::ptrdiff_t rows, std::ptrdiff_t cols)
{
    raster<std::uint8_t> m(rows, cols, 0);
    for (auto& v : m) v = rng() % 3 == 0 ? 0 : static_cast<std::uint8_t>(1 + rng() % 255);
    return m;
}

}  // namespace

TEST_CASE("core/mask_ops: not, and, or, clear_outside and mask_of_labels against the cell-by-cell rules")
{
    std::mt19937 rng(5);
    for (const auto& [rows, cols] : {std::pair{0, 0}, std::pair{1, 1}, std::pair{3, 65}, std::pair{17, 130}}) {
        const auto a = random_mask(rng, rows, cols), b = random_mask(rng, rows, cols);
        raster<std::uint8_t> n(rows, cols), x(rows, cols), o(rows, cols);
        mask_not(a, n);
        mask_and(a, b, x);
        mask_or(a, b, o);
        raster<std::uint8_t> cleared = a;
        clear_outside(cleared.view(), b);
        raster<std::int32_t> labels(rows, cols);
        for (auto& l : labels) l = static_cast<std::int32_t>(rng() % 7) - 2;
        raster<std::int32_t> labels_in = labels;
        clear_outside(labels_in.view(), b);
        raster<std::uint8_t> fg(rows, cols);
        mask_of_labels(labels, fg);
        for (std::ptrdiff_t r = 0; r < rows; ++r) {
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                REQUIRE(n(r, c) == (a(r, c) == 0 ? 1 : 0));
                REQUIRE(x(r, c) == ((a(r, c) != 0 && b(r, c) != 0) ? 1 : 0));
                REQUIRE(o(r, c) == ((a(r, c) != 0 || b(r, c) != 0) ? 1 : 0));
                REQUIRE(cleared(r, c) == (b(r, c) != 0 && a(r, c) != 0 ? 1 : 0));
                REQUIRE(labels_in(r, c) == (b(r, c) != 0 ? labels(r, c) : 0));
                REQUIRE(fg(r, c) == (labels(r, c) > 0 ? 1 : 0));
            }
        }
        // An output may be an input.
        raster<std::uint8_t> in_place = a;
        mask_and(in_place, b, in_place);
        CHECK(in_place == x);
        in_place = a;
        mask_or(in_place, b, in_place);
        CHECK(in_place == o);
    }
}

TEST_CASE("core/mask_ops: strided views are read and written in place")
{
    raster<std::uint8_t> padded(3, 10, 9);
    const raster_view<std::uint8_t> view(padded.data(), 3, 6, 10);
    raster<std::uint8_t> zero(3, 6, 0);
    mask_and(view, zero, view);
    for (std::ptrdiff_t r = 0; r < 3; ++r)
        for (std::ptrdiff_t c = 0; c < 10; ++c) REQUIRE(padded(r, c) == (c < 6 ? 0 : 9));
}

TEST_CASE("core/mask_ops: shapes that differ are refused")
{
    raster<std::uint8_t> a(2, 3), b(3, 2);
    raster<std::int32_t> l(2, 2);
    CHECK_THROWS_WITH_AS(mask_and(a, b, a), "mask_and: a and b must have the same shape (got 2x3 and 3x2)",
                         invalid_input);
    CHECK_THROWS_AS(mask_or(a, a, b), invalid_input);
    CHECK_THROWS_AS(mask_not(a, b), invalid_input);
    CHECK_THROWS_AS(clear_outside(a.view(), b), invalid_input);
    CHECK_THROWS_AS(clear_outside(l.view(), a), invalid_input);
    CHECK_THROWS_AS(mask_of_labels(l, a), invalid_input);
}

TEST_CASE("core/mask_ops: mask_any finds a mask empty or not wherever its one set cell lies")
{
    // It must see a cell anywhere, in rows shorter and longer than its 64-cell blocks, and in a strided view.
    for (const auto& [rows, cols] : {std::pair{1, 1}, std::pair{1, 64}, std::pair{3, 65}, std::pair{5, 200}}) {
        raster<std::uint8_t> mask(rows, cols, 0);
        CHECK_FALSE(mask_any(mask));
        for (int r = 0; r < rows; ++r) {
            for (int c = 0; c < cols; ++c) {
                mask(r, c) = 7;
                const bool seen = mask_any(mask);
                mask(r, c) = 0;
                REQUIRE(seen);
            }
        }
    }
    CHECK_FALSE(mask_any(raster<std::uint8_t>()));
    raster<std::uint8_t> padded(4, 100, 0);
    padded(2, 90) = 1;  // outside the view's 80 columns: not seen
    const raster_view<const std::uint8_t> view(padded.data(), 4, 80, 100);
    CHECK_FALSE(mask_any(view));
    padded(3, 79) = 1;
    CHECK(mask_any(view));
}
