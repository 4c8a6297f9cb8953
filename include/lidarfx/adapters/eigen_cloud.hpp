// SPDX-License-Identifier: Apache-2.0
// eigen_cloud: a point_cloud view over an Eigen matrix with one point per row (x, y, z[, intensity, ...]).
#pragma once

#include <cstddef>

#include <Eigen/Core>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/point_cloud.hpp"

namespace lidarfx {

/// Reads points from the rows of an Eigen matrix without copying: columns 0, 1, 2 are x, y, z (metres);
/// if the matrix has a 4th column it is the intensity. Any storage order and scalar type work; the matrix
/// must outlive the view. @throws invalid_input if the matrix has fewer than 3 columns.
template <class Derived>
class eigen_cloud {
public:
    explicit eigen_cloud(const Eigen::MatrixBase<Derived>& points) : m_(points.derived())
    {
        detail::require(m_.cols() >= 3, "eigen_cloud", "points.cols()", ">= 3 (x, y, z)", m_.cols());
    }
    std::size_t size() const noexcept { return static_cast<std::size_t>(m_.rows()); }
    double x(std::size_t i) const { return static_cast<double>(m_(static_cast<Eigen::Index>(i), 0)); }
    double y(std::size_t i) const { return static_cast<double>(m_(static_cast<Eigen::Index>(i), 1)); }
    double z(std::size_t i) const { return static_cast<double>(m_(static_cast<Eigen::Index>(i), 2)); }
    /// Column 3 when present, else 0.
    double intensity(std::size_t i) const
    {
        return m_.cols() > 3 ? static_cast<double>(m_(static_cast<Eigen::Index>(i), 3)) : 0.0;
    }

private:
    const Derived& m_;
};

template <class Derived>
eigen_cloud(const Eigen::MatrixBase<Derived>&) -> eigen_cloud<Derived>;

}  // namespace lidarfx
