// SPDX-License-Identifier: Apache-2.0
// Implementation of isotonic_regression (included at the end of kernels/stats/isotonic_regression.hpp).
#pragma once

#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

#include "lidarfx/core/error.hpp"

namespace lidarfx {

inline std::vector<double> isotonic_regression(std::span<const double> values, std::span<const double> weights,
                                               monotone_direction direction)
{
    constexpr const char* fn = "isotonic_regression";
    const std::size_t n = values.size();
    detail::require(weights.empty() || weights.size() == n, fn, "weights must be empty or as long as values");
    // Solved as non-decreasing: a non-increasing fit is the negated non-decreasing fit of the negated values.
    const double sign = direction == monotone_direction::non_decreasing ? 1.0 : -1.0;
    struct block {
        double mean, weight;
        std::size_t count;
    };
    std::vector<block> blocks;
    blocks.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double w = weights.empty() ? 1.0 : weights[i];
        detail::require(std::isfinite(values[i]), fn, "values[i]", "finite", values[i]);
        detail::require(std::isfinite(w) && w > 0, fn, "weights[i]", "finite and > 0", w);
        block b{sign * values[i], w, 1};
        while (!blocks.empty() && blocks.back().mean > b.mean) {
            const block& last = blocks.back();
            const double weight = last.weight + b.weight;  // the mean as a convex combination: no overflow
            b = {last.mean * (last.weight / weight) + b.mean * (b.weight / weight), weight, last.count + b.count};
            blocks.pop_back();
        }
        blocks.push_back(b);
    }
    std::vector<double> fit;
    fit.reserve(n);
    for (const block& b : blocks) fit.insert(fit.end(), b.count, sign * b.mean);
    return fit;
}

}  // namespace lidarfx
