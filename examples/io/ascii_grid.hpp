// SPDX-License-Identifier: Apache-2.0
// ESRI ASCII grid (.asc) writer and reader for the examples.
#pragma once

#include <string>

#include <lidarfx/core/grid.hpp>
#include <lidarfx/core/raster.hpp>

namespace lidarfx::io {

inline constexpr double ascii_nodata = -9999.0;

/// Writes `values` on `g` as an ESRI ASCII grid; NaN cells are written as -9999 (NODATA_value).
/// @throws std::runtime_error naming the file when it cannot be written; invalid_input on shape mismatch.
void write_ascii_grid(const std::string& path, raster_view<const float> values, const grid& g);

/// Reads an ESRI ASCII grid (corner or centre registration); NODATA cells become NaN.
/// @throws std::runtime_error naming the file and the problem.
raster<float> read_ascii_grid(const std::string& path, grid& g);

}  // namespace lidarfx::io
