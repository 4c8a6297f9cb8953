// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/core/error.hpp>
#include <lidarfx/core/raster.hpp>

#include <cmath>

using namespace lidarfx;

TEST_CASE("core/error: messages name the function, the argument and the value")
{
    CHECK_THROWS_WITH_AS(detail::require_positive(-2.5, "angular_filter", "cell"),
                         "angular_filter: cell must be finite and > 0 (got -2.5)", invalid_input);
    CHECK_THROWS_AS(detail::require_positive(NAN, "f", "cell"), invalid_input);
    CHECK_THROWS_AS(detail::require_positive(INFINITY, "f", "cell"), invalid_input);
    CHECK_NOTHROW(detail::require_positive(1e-9, "f", "cell"));
    raster<int> a(2, 3), b(3, 2);
    CHECK_THROWS_WITH_AS(detail::require_same_shape(a, b, "f", "in", "out"),
                         "f: in and out must have the same shape (got 2x3 and 3x2)", invalid_input);
    // invalid_input is a std::invalid_argument, so hosts can catch either.
    CHECK_THROWS_AS(detail::require(false, "f", "bad"), std::invalid_argument);
}
