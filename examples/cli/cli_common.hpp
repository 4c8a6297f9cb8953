// SPDX-License-Identifier: Apache-2.0
// Shared pieces of the lidarfx subcommands: argument parsing, a progress bar, reading surveys to rasters.
#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <lidarfx/core/grid.hpp>
#include <lidarfx/core/parallel.hpp>
#include <lidarfx/kernels/points/rasterize.hpp>

#include "io/output_folder.hpp"

namespace lidarfx::cli {

/// Command-line arguments: positional values and --name value / --flag options, checked against the
/// names a command accepts.
class arguments {
public:
    /// `valued`: options that take a value; `flags`: options without one. Unknown options throw.
    arguments(const std::vector<std::string>& args, const std::vector<std::string>& valued,
              const std::vector<std::string>& flags);
    const std::vector<std::string>& positional() const noexcept { return positional_; }
    bool has(const std::string& name) const { return values_.count(name) > 0; }
    std::string text(const std::string& name, const std::string& fallback) const;
    double number(const std::string& name, double fallback) const;
    int integer(const std::string& name, int fallback) const;

private:
    std::vector<std::string> positional_;
    std::map<std::string, std::string> values_;
};

/// Handles --help (usage on stdout, exit code 0) and, when `needs_inputs_and_out`, missing input files or
/// --out (usage on stderr, exit code 2); nullopt when the command should go on.
std::optional<int> stop_for_usage(const arguments& a, const char* usage, bool needs_inputs_and_out);

/// A progress bar on stderr: "label [#####.....]  45%"; returns true (never cancels).
progress_callback progress_bar(const std::string& label);

/// The rasters of one or more LAS files on one grid snapped to multiples of the cell size.
struct survey {
    point_rasters rasters;
    std::string crs_wkt;         ///< WKT of the first file, if it has one
    int epsg = 0;                ///< horizontal EPSG code of the first file (0 = unknown)
    std::size_t points = 0;      ///< points read
    std::size_t files = 0;
};

/// Reads every point of `paths` in chunks and rasterizes them on the snapped grid covering the union of
/// the files' header bounds; points outside those bounds (a header that lies) are reported as an error.
/// With `threads` != 1 (0 = all cores) the next chunk is read while the current one is rasterized; the
/// chunks are added in file order either way, so the rasters do not depend on `threads`.
/// @throws std::runtime_error naming the file on bad input files.
survey read_survey(const std::vector<std::string>& paths, double cell_m, bool show_progress, int threads = 1);

/// Writes `name`.asc (and `name`.tif when GDAL is available) of a float raster into `out`.
void write_raster(io::output_folder& out, const std::string& name, raster_view<const float> values, const grid& g,
                  const std::string& crs_wkt, int epsg);

/// Names `write_raster` gives a raster called `name` (for output_folder::check_name before long work).
std::vector<std::string> raster_file_names(const std::string& name);

/// "lidarfx <command> <args...>", for manifests.
std::string command_line(const std::string& command, const std::vector<std::string>& args);

/// Commits `out` (files move into place, manifest.json last) and prints "  wrote <path>" for each file.
void commit_and_report(io::output_folder& out, const std::string& command);

}  // namespace lidarfx::cli
