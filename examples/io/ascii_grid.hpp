// SPDX-License-Identifier: Apache-2.0
// ESRI ASCII grid (.asc) writer and reader for the examples.
#pragma once

#include <cstddef>
#include <cstdint>
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

/// The header of an ESRI ASCII grid, read without its values: what a caller needs to check the grid against a
/// memory budget before anything of its size is allocated.
struct ascii_grid_header {
    grid g;                          ///< as read_ascii_grid sets it
    bool has_nodata = false;         ///< a NODATA_value line is present
    double nodata = 0;               ///< its value
    std::uintmax_t data_offset = 0;  ///< bytes from the file's start to its first value
    std::uintmax_t file_bytes = 0;   ///< the file's size
};

/// Reads the header of an ESRI ASCII grid (its first lines only). Header keys are case-insensitive, in any
/// order: ncols, nrows, cellsize, xllcorner or xllcenter, yllcorner or yllcenter (each axis independently),
/// optional NODATA_value. Checks ncols and nrows (positive integers, at most 2^40 cells), the cell size (finite,
/// > 0) and the corner (finite). O(header).
/// @throws std::runtime_error naming the file and the problem (missing, repeated or unknown keys, bad numbers).
ascii_grid_header read_ascii_grid_header(const std::string& path);

/// Reads an ESRI ASCII grid: read_ascii_grid_header; then, before the grid is allocated, whether the bytes after
/// the header can hold nrows * ncols values (each takes at least one character and a separator), so that a header
/// promising more cells than its file holds fails at once; then the values, streamed from the file in blocks of
/// 1 MiB (memory: the grid and one block). Cells equal to NODATA_value become NaN; without that line no cell
/// is NoData (as in GDAL). Non-finite values (inf, -inf, nan) are no data too: they become NaN, and their count
/// is stored in `*non_finite_cells` when it is given. Values beyond float's range are bad values. Sets `g` to the
/// grid (upper-left corner = lower-left corner + nrows * cellsize). O(cells).
/// @throws std::runtime_error naming the file and the problem: as read_ascii_grid_header, a file too short for
/// its cells ("truncated data: expected N values, but the B bytes after the header hold at most M"), bad numbers
/// (with their row and column), fewer or more values than nrows * ncols.
raster<float> read_ascii_grid(const std::string& path, grid& g, std::size_t* non_finite_cells = nullptr);

/// The path of the .prj file that holds the CRS of the ESRI ASCII grid `asc_path` (as GDAL writes and reads it):
/// the same name with the extension .prj ("dsm.asc" gives "dsm.prj").
std::string prj_path_of(const std::string& asc_path);

/// The text of the .prj file beside the ESRI ASCII grid `asc_path` (prj_path_of), "" when there is none.
/// @throws std::runtime_error naming the file when it exists but cannot be read.
std::string read_prj_beside(const std::string& asc_path);

}  // namespace lidarfx::io
