// SPDX-License-Identifier: Apache-2.0
// A small survey without files, for the I/O tests of the program's raster outputs.
#pragma once

#include <cmath>
#include <cstdint>

#include <lidarfx/core/grid.hpp>
#include <lidarfx/core/raster.hpp>

#include "cli/cli_common.hpp"

namespace io_test {

/// A small survey without files: a 40 x 30 grid with returns on the left half.
inline lidarfx::cli::survey small_survey()
{
    lidarfx::cli::survey s;
    auto& pr = s.rasters;
    pr.g = lidarfx::grid{1000.0, 2000.0, 2.0, 30, 40};
    pr.min_z = lidarfx::raster<float>(30, 40, NAN);
    pr.max_z = lidarfx::raster<float>(30, 40, NAN);
    pr.mean_intensity = lidarfx::raster<float>(30, 40, 0.0f);
    pr.count = lidarfx::raster<std::uint32_t>(30, 40, 0);
    pr.dropout = lidarfx::raster<std::uint8_t>(30, 40, 1);
    pr.multiple_returns = lidarfx::raster<std::uint8_t>(30, 40, 0);
    for (std::ptrdiff_t r = 0; r < 30; ++r)
        for (std::ptrdiff_t c = 0; c < 20; ++c) {
            pr.min_z(r, c) = pr.max_z(r, c) = static_cast<float>(r + c);
            pr.count(r, c) = 3;
            pr.dropout(r, c) = 0;
        }
    s.points = 1800;
    s.files = 1;
    return s;
}

}  // namespace io_test
