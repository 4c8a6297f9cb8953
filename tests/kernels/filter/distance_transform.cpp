// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/kernels/filter/distance_transform.hpp>

#include "reference/footprint.hpp"
#include "reference/morphology.hpp"
#include "reference/progress.hpp"

#include <cmath>
#include <cstdint>
#include <random>

using namespace lidarfx;

namespace {

/// Number of cells where the transform differs from the brute-force reference.
std::ptrdiff_t differences(raster_view<const std::uint8_t> features, const distance_transform_options& opt = {})
{
    const auto fast = squared_distance_transform(features, opt);
    const auto slow = reference::squared_distance(features);
    std::ptrdiff_t wrong = 0;
    for (std::ptrdiff_t r = 0; r < features.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < features.cols(); ++c) wrong += static_cast<double>(fast(r, c)) != slow(r, c);
    return wrong;
}

}  // namespace

TEST_CASE("filter/squared_distance_transform: equals the brute-force distance on random masks of every density")
{
    std::mt19937 rng(20261201);
    for (const double density : {0.0, 0.001, 0.02, 0.2, 0.7, 1.0}) {
        for (const auto& item : {std::pair{1, 1}, {1, 37}, {41, 1}, {23, 31}, {64, 9}}) {
            const auto& rows = std::get<0>(item);
            const auto& cols = std::get<1>(item);
            const auto m = reference::random_mask(rng, rows, cols, density);
            CAPTURE(density);
            CAPTURE(rows);
            CAPTURE(cols);
            CHECK(differences(m) == 0);
        }
    }
}

TEST_CASE("filter/squared_distance_transform: a single feature gives r^2 + c^2; none gives infinity everywhere")
{
    raster<std::uint8_t> one(50, 70, 0);
    one(10, 20) = 7;  // any nonzero value is a feature
    const auto d = squared_distance_transform(one);
    CHECK(d(10, 20) == 0.0f);
    CHECK(d(49, 69) == float(39 * 39 + 49 * 49));
    CHECK(d(0, 0) == float(10 * 10 + 20 * 20));
    const auto none = squared_distance_transform(raster<std::uint8_t>(5, 6, 0));
    for (const float v : none) CHECK(v == no_feature_distance);
    CHECK(squared_distance_transform(raster<std::uint8_t>(0, 4)).size() == 0);
}

TEST_CASE("filter/squared_distance_transform: the same for any thread count; progress ends at 1; cancels")
{
    std::mt19937 rng(7);
    const auto m = reference::random_mask(rng, 300, 700, 0.003);
    const auto one = squared_distance_transform(m, {.run = {.threads = 1}});
    for (const int threads : {2, 3, 0}) CHECK(squared_distance_transform(m, {.run = {.threads = threads}}) == one);
    reference::progress_log log;
    squared_distance_transform(m, {.run = {.threads = 2, .progress = log.callback()}});
    CHECK(log.monotone_to_one());
    CHECK_THROWS_WITH_AS(squared_distance_transform(m, {.run = {.progress = reference::cancel_at_once()}}),
                         "squared_distance_transform: cancelled", cancelled);
    CHECK_THROWS_AS(squared_distance_transform(m, {.run = {.threads = -1}}), invalid_input);
}
