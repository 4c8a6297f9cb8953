// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/core/error.hpp>
#include <lidarfx/kernels/stats/isotonic_regression.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <random>
#include <span>
#include <vector>

#include "reference/isotonic.hpp"

using namespace lidarfx;

namespace isotonic_test {

constexpr auto up = monotone_direction::non_decreasing;
constexpr auto down = monotone_direction::non_increasing;

bool ordered(const std::vector<double>& fit, monotone_direction direction)
{
    for (std::size_t i = 0; i + 1 < fit.size(); ++i)
        if (direction == up ? fit[i] > fit[i + 1] : fit[i] < fit[i + 1]) return false;
    return true;
}

/// Largest |fit - ref| over the sequence, relative to the largest |value| (at least 1).
double relative_gap(const std::vector<double>& fit, const std::vector<double>& ref, std::span<const double> values)
{
    double scale = 1, gap = 0;
    for (const double v : values) scale = std::max(scale, std::abs(v));
    for (std::size_t i = 0; i < fit.size(); ++i) gap = std::max(gap, std::abs(fit[i] - ref[i]));
    return gap / scale;
}

/// The kernel and the min-max reference agree in both directions (to rounding: the two sum the block means in a
/// different order, so 1e-12 of the largest value).
void check_against_reference(std::span<const double> values, std::span<const double> weights)
{
    for (const auto direction : {up, down}) {
        const auto fit = isotonic_regression(values, weights, direction);
        const auto ref = reference::isotonic_min_max(values, weights, direction == down);
        REQUIRE(fit.size() == values.size());
        CHECK(ordered(fit, direction));
        CHECK(relative_gap(fit, ref, values) <= 1e-12);
    }
}

/// The optimality conditions of a weighted isotonic fit, a reference that needs no brute force: the fit is
/// ordered; it is made of maximal runs of one value, each the weighted mean of its values; within a run of mean m,
/// every prefix has a mean on the far side of m from the order (>= m for non-decreasing), so no split would
/// lower the squared error; the weighted sum is that of the values.
void check_optimality(std::span<const double> values, std::span<const double> weights, monotone_direction direction)
{
    const auto fit = isotonic_regression(values, weights, direction);
    REQUIRE(fit.size() == values.size());
    CHECK(ordered(fit, direction));
    double scale = 1, total = 0, fitted = 0, weight = 0;
    for (const double v : values) scale = std::max(scale, std::abs(v));
    const double tol = 1e-11 * scale;  // rounding of means over up to a few hundred terms
    const double sign = direction == up ? 1.0 : -1.0;
    for (std::size_t i = 0; i < values.size(); ++i) {
        const double w = weights.empty() ? 1.0 : weights[i];
        total += w * values[i];
        fitted += w * fit[i];
        weight += w;
    }
    CHECK(std::abs(fitted - total) / weight <= tol);
    for (std::size_t begin = 0; begin < fit.size();) {
        std::size_t end = begin + 1;
        while (end < fit.size() && fit[end] == fit[begin]) ++end;
        const double mean = reference::weighted_mean(values, weights, begin, end - 1);
        CHECK(std::abs(fit[begin] - mean) <= tol);
        for (std::size_t k = begin; k + 1 < end; ++k)
            CHECK(sign * (reference::weighted_mean(values, weights, begin, k) - mean) >= -tol);
        if (end < fit.size()) CHECK(sign * (fit[end] - fit[begin]) > 0);  // blocks differ where the run ends
        begin = end;
    }
}

}  // namespace isotonic_test

using isotonic_test::down;
using isotonic_test::up;

TEST_CASE("stats/isotonic_regression: equals the min-max formula on random sequences up to 8 long")
{
    const unsigned seed = 20260312;
    std::mt19937 rng(seed);
    std::uniform_int_distribution<std::size_t> length(0, 8);
    std::normal_distribution<double> value(0, 5);
    std::uniform_real_distribution<double> log_weight(-3, 3);
    std::uniform_int_distribution<int> coarse(-2, 2);  // few distinct values: many ties
    for (int trial = 0; trial < 400; ++trial) {
        const std::size_t n = length(rng);
        std::vector<double> values(n), weights(n);
        for (std::size_t i = 0; i < n; ++i) {
            values[i] = trial % 4 == 0 ? coarse(rng) : value(rng);
            weights[i] = std::pow(10.0, log_weight(rng));
        }
        CAPTURE(seed);
        CAPTURE(trial);
        isotonic_test::check_against_reference(values, weights);
        isotonic_test::check_against_reference(values, {});  // empty weights: all 1
    }
}

TEST_CASE("stats/isotonic_regression: meets the optimality conditions on long random sequences")
{
    const unsigned seed = 77;
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0, 0.05);
    std::uniform_real_distribution<double> weight(0.1, 40);
    for (int trial = 0; trial < 20; ++trial) {
        // A river's section levels: a steady fall, noise, and a pier's outliers.
        const std::size_t n = 50 + 10 * static_cast<std::size_t>(trial);
        std::vector<double> values(n), weights(n);
        for (std::size_t i = 0; i < n; ++i) {
            values[i] = 100 - 0.01 * static_cast<double>(i) + noise(rng) + (i % 37 == 5 ? 2.0 : 0.0);
            weights[i] = weight(rng);
        }
        CAPTURE(seed);
        CAPTURE(trial);
        isotonic_test::check_optimality(values, weights, down);
        isotonic_test::check_optimality(values, weights, up);
        isotonic_test::check_optimality(values, {}, down);
    }
}

TEST_CASE("stats/isotonic_regression: non_increasing is the negated non_decreasing fit of the negated values")
{
    std::mt19937 rng(5);
    std::normal_distribution<double> value(0, 1);
    std::uniform_real_distribution<double> weight(0.5, 2);
    for (int trial = 0; trial < 50; ++trial) {
        std::vector<double> values(30), negated(30), weights(30);
        for (std::size_t i = 0; i < values.size(); ++i) {
            values[i] = value(rng);
            negated[i] = -values[i];
            weights[i] = weight(rng);
        }
        const auto fit = isotonic_regression(values, weights, down);
        auto mirrored = isotonic_regression(negated, weights, up);
        for (double& v : mirrored) v = -v;
        CHECK(fit == mirrored);  // the same arithmetic on negated numbers: exactly equal
    }
}

TEST_CASE("stats/isotonic_regression: keeps an ordered sequence, pools a reversed one into its mean")
{
    const std::vector<double> rising{1, 2, 2, 3.5, 7, 7.25};
    CHECK(isotonic_regression(rising, {}, up) == rising);
    const std::vector<double> falling{7.25, 7, 3.5, 2, 2, 1};
    CHECK(isotonic_regression(falling, {}, down) == falling);
    // Against the order, the best monotone fit is the constant (weighted) mean: 2 * 1 + 1 * 4 + 1 * 7 over 4.
    const std::vector<double> against{1, 4, 7};
    const std::vector<double> w{2, 1, 1};
    const auto pooled = isotonic_regression(against, w, down);
    REQUIRE(pooled.size() == 3);
    for (const double v : pooled) CHECK(v == doctest::Approx(13.0 / 4).epsilon(1e-15));
    for (const double v : isotonic_regression(falling, {}, up)) CHECK(v == doctest::Approx(22.75 / 6).epsilon(1e-15));
}

TEST_CASE("stats/isotonic_regression: hand-checked pools, ties, one outlier, extreme weights, n = 0 and 1")
{
    // 1, 3, 2, 4: the violators 3, 2 pool at 2.5.
    CHECK(isotonic_regression(std::vector<double>{1, 3, 2, 4}, {}, up) == std::vector<double>{1, 2.5, 2.5, 4});
    // Weighted: 3 (weight 3) and 2 (weight 1) pool at 2.75.
    CHECK(isotonic_regression(std::vector<double>{1, 3, 2, 4}, std::vector<double>{1, 3, 1, 1}, up) ==
          std::vector<double>{1, 2.75, 2.75, 4});
    // All equal: the fit is the values.
    for (const auto direction : {up, down}) {
        const auto fit = isotonic_regression(std::vector<double>(7, 0.1), std::vector<double>(7, 3.0), direction);
        REQUIRE(fit.size() == 7);
        for (const double v : fit) CHECK(v == doctest::Approx(0.1).epsilon(1e-15));
    }
    // One huge outlier in a falling profile pools with its upstream neighbours only as far as it must.
    const std::vector<double> levels{10, 9, 8, 1e6, 6, 5};
    const auto fit = isotonic_regression(levels, {}, down);
    const double pooled = (10 + 9 + 8 + 1e6) / 4;
    REQUIRE(fit.size() == 6);
    for (std::size_t i = 0; i < 4; ++i) CHECK(fit[i] == doctest::Approx(pooled).epsilon(1e-15));
    CHECK(fit[4] == 6);
    CHECK(fit[5] == 5);
    isotonic_test::check_against_reference(levels, {});
    // A weight 1e12 times the others pins its block to its value (to 1e-12 of the spread).
    const std::vector<double> v{0, 5, 1};
    const auto pinned = isotonic_regression(v, std::vector<double>{1, 1e12, 1}, up);
    CHECK(pinned[0] == 0);
    CHECK(pinned[1] == doctest::Approx(5).epsilon(1e-11));
    CHECK(pinned[2] == pinned[1]);
    // Weights from 1e-200 to 1e200 are accepted and give the min-max fit.
    isotonic_test::check_against_reference(std::vector<double>{3, -1, 2, 2, 8, -4, 0},
                                           std::vector<double>{1e-200, 1e200, 1, 1e-100, 1e100, 1, 1e-300});
    CHECK(isotonic_regression(std::vector<double>{}, {}, up).empty());
    CHECK(isotonic_regression(std::vector<double>{}, std::vector<double>{}, down).empty());
    CHECK(isotonic_regression(std::vector<double>{-3.5}, std::vector<double>{0.25}, down) == std::vector<double>{-3.5});
}

TEST_CASE("stats/isotonic_regression: refuses mismatched sizes, values that are not finite, weights <= 0 or NaN")
{
    const std::vector<double> v{1, 2, 3};
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    CHECK_THROWS_AS(isotonic_regression(v, std::vector<double>{1, 1}, up), invalid_input);
    CHECK_THROWS_AS(isotonic_regression(v, std::vector<double>{1, 1, 1, 1}, down), invalid_input);
    CHECK_THROWS_AS(isotonic_regression(std::vector<double>{}, std::vector<double>{1}, up), invalid_input);
    for (const double bad : {nan, inf, -inf}) {
        CAPTURE(bad);
        CHECK_THROWS_AS(isotonic_regression(std::vector<double>{1, bad, 3}, {}, up), invalid_input);
        CHECK_THROWS_AS(isotonic_regression(std::vector<double>{1, 2, bad}, {}, down), invalid_input);
    }
    for (const double bad : {0.0, -0.0, -1.0, nan, inf, -inf}) {
        CAPTURE(bad);
        CHECK_THROWS_AS(isotonic_regression(v, std::vector<double>{1, 1, bad}, up), invalid_input);
        CHECK_THROWS_AS(isotonic_regression(v, std::vector<double>{bad, 1, 1}, down), invalid_input);
    }
    CHECK_THROWS_WITH_AS(isotonic_regression(v, std::vector<double>{1, -2, 1}, up),
                         "isotonic_regression: weights[i] must be finite and > 0 (got -2)", invalid_input);
}

// Pooled means are convex combinations and equal neighbours are not pooled: finite inputs near the top of the
// double range ({1e308, 1e308}; {1e200, 1} with weights {1e200, 1}) fit finitely.
TEST_CASE("stats/isotonic_regression: finite values and weights give a finite fit at the ends of the range")
{
    const auto ordered = isotonic_regression(std::vector<double>{1e308, 1e308}, {}, up);
    CHECK(ordered == std::vector<double>{1e308, 1e308});
    const auto heavy = isotonic_regression(std::vector<double>{1e200, 1}, std::vector<double>{1e200, 1}, up);
    REQUIRE(heavy.size() == 2);
    CHECK(heavy[0] == doctest::Approx(1e200).epsilon(1e-12));
    CHECK(heavy[1] == doctest::Approx(1e200).epsilon(1e-12));
}
