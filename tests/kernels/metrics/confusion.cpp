// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/kernels/metrics/confusion.hpp>

using namespace lidarfx;

TEST_CASE("metrics/confusion_counts: counts and scores on a hand-checked case")
{
    raster<std::uint8_t> truth(2, 3), pred(2, 3);
    // truth 1 1 0 / 0 0 1 ; pred 1 0 1 / 0 0 1
    truth(0, 0) = truth(0, 1) = truth(1, 2) = 1;
    pred(0, 0) = pred(0, 2) = pred(1, 2) = 1;
    const auto c = confusion_counts(pred, truth, 2.0);
    CHECK(c.true_positive == 2);
    CHECK(c.false_negative == 1);
    CHECK(c.false_positive == 1);
    CHECK(c.true_negative == 2);
    CHECK(c.accuracy() == doctest::Approx(4.0 / 6.0));
    CHECK(c.sensitivity() == doctest::Approx(2.0 / 3.0));
    CHECK(c.specificity() == doctest::Approx(2.0 / 3.0));
    CHECK(c.precision() == doctest::Approx(2.0 / 3.0));
    CHECK(c.iou() == doctest::Approx(0.5));
    CHECK(c.area_m2(c.true_positive) == 8.0);

    raster<std::uint8_t> valid(2, 3, 1);
    valid(0, 2) = 0;
    const auto cv = confusion_counts(pred, truth, 1.0, valid);
    CHECK(cv.ignored == 1);
    CHECK(cv.false_positive == 0);
    CHECK(cv.total() == 5);
}

TEST_CASE("metrics/confusion_counts: empty truth and bad input")
{
    raster<std::uint8_t> zero(3, 3);
    const auto c = confusion_counts(zero, zero, 1.0);
    CHECK(c.accuracy() == 1.0);
    CHECK(c.sensitivity() == 1.0);
    CHECK(c.iou() == 1.0);
    CHECK_THROWS_WITH_AS(confusion_counts(zero, raster<std::uint8_t>(3, 2), 1.0),
                         "confusion_counts: predicted and truth must have the same shape (got 3x3 and 3x2)",
                         invalid_input);
    CHECK_THROWS_WITH_AS(confusion_counts(zero, zero, 0.0), "confusion_counts: cell_m must be finite and > 0 (got 0)",
                         invalid_input);
    CHECK_THROWS_WITH_AS(confusion_counts(zero, zero, 1.0, raster<std::uint8_t>(2, 3)),
                         "confusion_counts: predicted and valid must have the same shape (got 3x3 and 2x3)",
                         invalid_input);
}
