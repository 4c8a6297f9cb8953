// SPDX-License-Identifier: Apache-2.0
// Reference isotonic regression: the min-max formula, every block mean evaluated from scratch.
#pragma once

#include <algorithm>
#include <cstddef>
#include <limits>
#include <span>
#include <vector>

namespace reference {

/// Weighted mean of values[j..k] (inclusive), summed directly; weights empty means all 1.
inline double weighted_mean(std::span<const double> values, std::span<const double> weights, std::size_t j,
                            std::size_t k)
{
    double sum = 0, weight = 0;
    for (std::size_t t = j; t <= k; ++t) {
        const double w = weights.empty() ? 1.0 : weights[t];
        sum += w * values[t];
        weight += w;
    }
    return sum / weight;
}

/// The weighted least-squares non-decreasing fit by the min-max formula (Barlow et al. 1972, Statistical
/// Inference under Order Restrictions, thm 1.4.4): fit_i = max_{j <= i} min_{k >= i} mean(values[j..k]).
/// A non-increasing fit is the negated non-decreasing fit of the negated values. O(n^4): for n up to ~30.
inline std::vector<double> isotonic_min_max(std::span<const double> values, std::span<const double> weights,
                                            bool non_increasing)
{
    const std::size_t n = values.size();
    const double sign = non_increasing ? -1.0 : 1.0;
    std::vector<double> v(n);
    for (std::size_t i = 0; i < n; ++i) v[i] = sign * values[i];
    std::vector<double> fit(n);
    for (std::size_t i = 0; i < n; ++i) {
        double best = -std::numeric_limits<double>::infinity();
        for (std::size_t j = 0; j <= i; ++j) {
            double low = std::numeric_limits<double>::infinity();
            for (std::size_t k = i; k < n; ++k) low = std::min(low, weighted_mean(v, weights, j, k));
            best = std::max(best, low);
        }
        fit[i] = sign * best;
    }
    return fit;
}

}  // namespace reference
