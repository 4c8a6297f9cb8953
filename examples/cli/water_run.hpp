// SPDX-License-Identifier: Apache-2.0
// lidarfx water's run, shared by the lidarfx program and the MPI driver (which supplies the survey).
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <lidarfx/pipelines/water/extract_waterbodies.hpp>

#include "cli_common.hpp"

namespace lidarfx::cli {

/// What `lidarfx water` keeps per grid cell, bytes: the survey rasters (43 B while reading), the method's
/// rasters (labels, angles, masks, bins) and the footprint's (two padded distance transforms).
inline constexpr double water_bytes_per_cell = 128;

/// The options of `lidarfx water` that take a value, and its flags.
const std::vector<std::string>& water_value_options();
const std::vector<std::string>& water_flag_options();

/// How a run gets its survey: (input files, survey options, tile edge in metres (0 = untiled), folder
/// for the finished tiles of a tiled run) -> the survey, as read_survey gives it.
using survey_source = std::function<survey(const std::vector<std::string>& files, const survey_options& opt,
                                           double tile_edge_m, const std::filesystem::path& tiles_dir)>;

/// read_survey when tile_edge_m is 0, else read_survey_tiled resuming in tiles_dir.
survey read_survey_local(const std::vector<std::string>& files, const survey_options& opt, double tile_edge_m,
                         const std::filesystem::path& tiles_dir);

/// The waterbody method of `lidarfx water` and the footprint's hull radius (metres), from its options in `a`
/// (every flag checked under its own name; usage_error otherwise): what `lidarfx hydroflatten` runs too.
struct water_method {
    extract_waterbodies_options options;
    double hull_radius_m = 50;
};
water_method water_method_from(const arguments& a);

/// --tile (metres, 0 = untiled), checked. @throws usage_error when negative or not finite.
double tile_edge_from(const arguments& a);

/// `lidarfx water ARGS`: the exit code (0 written, 2 usage, 3 data that cannot support the method).
int run_water(const std::vector<std::string>& args, const survey_source& source = read_survey_local);

}  // namespace lidarfx::cli
