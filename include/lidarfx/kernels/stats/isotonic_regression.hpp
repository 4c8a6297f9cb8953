// SPDX-License-Identifier: Apache-2.0
// isotonic_regression: the weighted least-squares fit of a sequence by a monotone one (pool adjacent violators).
// Implementation in detail/isotonic_regression_impl.hpp.
#pragma once

#include <span>
#include <vector>

namespace lidarfx {

/// Which way an isotonic fit may move along the sequence.
enum class monotone_direction {
    non_decreasing,  ///< fit[i] <= fit[i + 1]
    non_increasing,  ///< fit[i] >= fit[i + 1]: a river's water levels from upstream to downstream
};

/// The monotone sequence closest to `values` in weighted least squares: it minimises
/// sum_i weights[i] · (fit[i] − values[i])² subject to the order `direction`. Computed by pooling adjacent
/// violators: runs that break the order merge into one block at their weighted mean, so the fit is a
/// sequence of constant blocks, each the weighted mean of its values. Weights are > 0 (an empty `weights`
/// means all 1). Units are those of `values`. O(n) time and memory.
/// @throws invalid_input on sizes that differ (when weights is not empty), a value that is not finite or a
/// weight that is not finite and > 0.
inline std::vector<double> isotonic_regression(std::span<const double> values, std::span<const double> weights,
                                               monotone_direction direction);

}  // namespace lidarfx

#include "lidarfx/kernels/stats/detail/isotonic_regression_impl.hpp"
