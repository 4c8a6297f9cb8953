// SPDX-License-Identifier: Apache-2.0
// Output sets shared by the subcommands: survey rasters and waterbody maps, with their pictures and tables.
#pragma once

#include <filesystem>

#include <lidarfx/pipelines/water/extract_waterbodies.hpp>

#include "cli_common.hpp"

namespace lidarfx::cli {

/// Prints what a survey holds (files, points, grid, density, points ignored).
void print_survey(const survey& s);

/// min_z, max_z, mean_intensity, count, dropout (.asc/.tif) and PNG quicklooks of the survey rasters.
void write_point_rasters(io::output_folder& dir, const survey& s);

/// The names write_point_rasters and write_waterbodies give their files (checked before long work).
std::vector<std::string> point_raster_file_names();
std::vector<std::string> waterbody_file_names();

/// water.asc (1 water, 0 land, -9999 no data), waterbody_labels.asc (0 land, 1..n by decreasing area),
/// GeoTIFF twins, water_overlay.png (waterbodies over a hillshade), waterbodies.csv, waterbodies.geojson.
void write_waterbodies(io::output_folder& dir, const survey& s, const extract_waterbodies_result& w);

/// Prints the diagnostics of the inputs: problems and warnings.
void print_diagnostics(const water_diagnostics& d);

/// Prints a table of the waterbodies found.
void print_waterbodies(const extract_waterbodies_result& w, std::size_t max_rows = 10);

}  // namespace lidarfx::cli
