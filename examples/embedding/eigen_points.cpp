// SPDX-License-Identifier: Apache-2.0
// Embedding example: points held in an Eigen matrix (one point per row) read through lidarfx's
// point_cloud concept without copying, and placed on a grid snapped to the cell size.
#include <cstdio>

#include <Eigen/Core>

#include <lidarfx/adapters/eigen_cloud.hpp>
#include <lidarfx/lidarfx.hpp>

int main()
{
    Eigen::MatrixX4d pts(4, 4);  // x, y, z, intensity
    pts << 10.2, 20.7, 3.0, 120, 11.9, 21.1, 3.4, 80, 15.0, 25.0, 2.0, 10, 10.0, 20.0, 2.5, 60;
    const lidarfx::eigen_cloud cloud(pts);

    lidarfx::bounds box{cloud.x(0), cloud.y(0), cloud.x(0), cloud.y(0)};
    for (std::size_t i = 1; i < cloud.size(); ++i) {
        box.xmin = std::min(box.xmin, cloud.x(i));
        box.xmax = std::max(box.xmax, cloud.x(i));
        box.ymin = std::min(box.ymin, cloud.y(i));
        box.ymax = std::max(box.ymax, cloud.y(i));
    }
    const lidarfx::grid g = lidarfx::snapped_grid(box, 2.0);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const auto cell = g.cell_of(cloud.x(i), cloud.y(i));
        std::printf("point %zu (%.1f, %.1f) intensity %.0f -> cell (%td, %td)\n", i, cloud.x(i), cloud.y(i),
                    cloud.intensity(i), cell->row, cell->col);
    }
    return 0;
}
