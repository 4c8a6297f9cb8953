// SPDX-License-Identifier: Apache-2.0
// Surface and terrain models read from raster files (ESRI ASCII, GeoTIFF or any raster GDAL opens), in metres.
#pragma once

#include <string>

#include <lidarfx/core/grid.hpp>
#include <lidarfx/core/raster.hpp>

#include "cli_common.hpp"
#include "io/crs.hpp"

namespace lidarfx::cli {

/// True when `path` is read as a point cloud (.las, .laz, any case); every other input of a command that takes
/// a DSM is a raster file.
bool is_point_cloud_path(const std::string& path);

/// The CRS and units of the raster file `path`: an ESRI ASCII grid (.asc) from the .prj beside it, any other file
/// from the CRS GDAL reads in it. A file without a CRS needs --xy-unit and --z-unit (m, ft = international foot,
/// us-ft = US survey foot); with a CRS they may be given but must agree with it. Warnings go to stderr.
/// @throws usage_error when the units are unknown or disagree, the CRS is geographic (cells in degrees), or a
/// format other than ESRI ASCII is given to a lidarfx built without GDAL (the message says how to convert it).
io::survey_crs raster_crs(const std::string& path, const arguments& a);

/// A surface or terrain model ready for the library: heights and grid in metres, and the grid as the file states
/// it (in its CRS's units, for outputs that land where the input lies).
struct elevation_raster {
    raster<float> values;  ///< heights in metres; no data (NoData, inf, nan) is NaN
    grid g;                ///< the grid in metres
    grid file_grid;        ///< the grid in the file's units
};

/// The grid of the raster file `path` as its header states it (no values read). @throws as raster_crs.
grid raster_file_grid(const std::string& path);

/// Reads the raster file `path` with the CRS `crs` (raster_crs): reports cells without a finite height on stderr
/// and converts heights and grid to metres. North-up files with square cells only. The caller checks the grid
/// (raster_file_grid) against its memory budget first (refuse_grid_over_budget), for one grid or several.
/// @throws std::runtime_error naming the file when it cannot be read.
elevation_raster read_elevation_raster(const std::string& path, const io::survey_crs& crs);

}  // namespace lidarfx::cli
