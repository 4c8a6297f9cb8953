// SPDX-License-Identifier: Apache-2.0
// Output sets shared by the subcommands: survey rasters and waterbody maps, with their pictures and tables.
#pragma once

#include <filesystem>
#include <string>

#include <lidarfx/kernels/filter/survey_footprint.hpp>
#include <lidarfx/pipelines/water/extract_waterbodies.hpp>

#include "cli_common.hpp"

namespace lidarfx::cli {

/// The unit of heights in a file placed in the survey's CRS: the vertical unit of the CRS the file records, or
/// its horizontal unit when that CRS has no vertical part (as a reader of the file assumes).
struct height_unit {
    double metres = 1;  ///< metres per unit
    std::string name;
};
height_unit file_height_unit(const survey& s);

/// What a manifest says about units: heights and areas in metres, places in the survey's CRS.
std::string units_note(const survey& s);

/// Prints what a survey holds (files, points, grid, density, points ignored).
void print_survey(const survey& s);

/// min_z, max_z, mean_intensity, count, dropout (.asc/.tif) and PNG quicklooks of the survey rasters.
/// `formats` says which files; the files are written on up to `threads` threads (0 = all cores).
void write_point_rasters(io::output_folder& dir, const survey& s, const output_formats& formats = {}, int threads = 0);

/// The names write_point_rasters and write_waterbodies give their files (checked before long work).
std::vector<std::string> point_raster_file_names(const output_formats& formats = {});
std::vector<std::string> waterbody_file_names(const output_formats& formats = {});

/// Waterbodies of a survey found inside its footprint, and that footprint.
struct survey_waterbodies {
    raster<std::uint8_t> footprint;  ///< 1 = inside the area flown (footprint_of)
    extract_waterbodies_result result;
};

/// extract_waterbodies on the survey's rasters, limited to footprint_of(s, hull_radius_m, opt.run.threads).
survey_waterbodies find_waterbodies(const survey& s, const extract_waterbodies_options& opt,
                                    double hull_radius_m = survey_footprint_options{}.hull_radius_m);

/// water.asc (1 water, 0 land, -9999 no data: outside the footprint, or no return within 2 cells),
/// waterbody_labels.asc (0 land, 1..n by decreasing area, -9999 outside the footprint), GeoTIFF twins,
/// water_overlay.png (waterbodies over a hillshade), waterbodies.csv, waterbodies.geojson, waterbodies.gpkg
/// (with GDAL); which of them follows `formats`.
/// `footprint`: 1 = inside the area flown (footprint_of). The files are written on `threads` threads
/// (0 = all cores); the same bytes whatever the count.
void write_waterbodies(io::output_folder& dir, const survey& s, const extract_waterbodies_result& w,
                       raster_view<const std::uint8_t> footprint, const output_formats& formats = {}, int threads = 0);

/// Prints the diagnostics of the inputs: problems and warnings.
void print_diagnostics(const water_diagnostics& d);

/// Prints a table of the waterbodies found.
void print_waterbodies(const extract_waterbodies_result& w, std::size_t max_rows = 10);

}  // namespace lidarfx::cli
