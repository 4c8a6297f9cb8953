// SPDX-License-Identifier: Apache-2.0
// ESRI ASCII grid (.asc) writer and reader for the examples.
#pragma once

#include <string>

#include <lidarfx/core/grid.hpp>
#include <lidarfx/core/raster.hpp>

namespace lidarfx::io {

/// The NODATA_value written for NaN cells.
inline constexpr double ascii_nodata = -9999.0;

/// Writes `values` on `g` as an ESRI ASCII grid: header (ncols, nrows, xllcorner, yllcorner, cellsize,
/// NODATA_value -9999), then one line per row, north first. Numbers use the shortest text that reads back
/// to the same float, so a write/read round trip is exact; NaN cells are written as -9999 (so a cell that
/// holds -9999 itself reads back as NaN). O(cells).
/// @throws invalid_input when the shapes differ, the grid is invalid or empty; std::runtime_error naming
/// the file when it cannot be written.
void write_ascii_grid(const std::string& path, raster_view<const float> values, const grid& g);

/// Reads an ESRI ASCII grid. Header keys are case-insensitive, in any order: ncols, nrows, cellsize,
/// xllcorner or xllcenter, yllcorner or yllcenter (each axis independently), optional NODATA_value.
/// Cells equal to NODATA_value become NaN; without that line no cell is NoData (as in GDAL).
/// Sets `g` to the grid (upper-left corner = lower-left corner + nrows * cellsize). O(cells).
/// @throws std::runtime_error naming the file and the problem: missing, repeated or unknown header keys,
/// non-positive sizes, bad numbers, fewer or more values than nrows * ncols.
raster<float> read_ascii_grid(const std::string& path, grid& g);

}  // namespace lidarfx::io
