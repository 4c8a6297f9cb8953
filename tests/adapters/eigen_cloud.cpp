// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/adapters/eigen_cloud.hpp>

#include <Eigen/Core>

using namespace lidarfx;

TEST_CASE("adapters/eigen_cloud: rows are points, read in place")
{
    Eigen::MatrixX3d m(3, 3);
    m << 1, 2, 3, 4, 5, 6, 7, 8, 9;
    eigen_cloud c(m);
    static_assert(point_cloud<decltype(c)>);
    CHECK(c.size() == 3);
    CHECK(c.x(2) == 7);
    CHECK(c.z(1) == 6);
    CHECK(c.intensity(0) == 0);
    m(1, 2) = -6;  // a view, not a copy
    CHECK(c.z(1) == -6);

    Eigen::Matrix<float, Eigen::Dynamic, 4, Eigen::RowMajor> with_intensity(2, 4);
    with_intensity << 0, 0, 1, 50, 1, 1, 2, 60;
    eigen_cloud ci(with_intensity);
    CHECK(ci.intensity(1) == 60);

    Eigen::MatrixXd two_columns(4, 2);
    CHECK_THROWS_WITH_AS(eigen_cloud{two_columns}, "eigen_cloud: points.cols() must be >= 3 (x, y, z) (got 2)",
                         invalid_input);
}
