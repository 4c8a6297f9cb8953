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
    rasterize_result rasters;
    std::string crs_wkt;         ///< WKT of the first file, if it has one
    int epsg = 0;                ///< horizontal EPSG code of the first file (0 = unknown)
    std::size_t points = 0;      ///< points read
    std::size_t files = 0;
};

/// Reads every point of `paths` in chunks and rasterizes them on the snapped grid covering the union of
/// the files' header bounds; points outside those bounds (a header that lies) are reported as an error.
/// @throws std::runtime_error naming the file on bad input files.
survey read_survey(const std::vector<std::string>& paths, double cell_m, bool show_progress);

/// Writes `name`.asc (and `name`.tif when GDAL is available) of a float raster into `dir`.
void write_raster(const std::filesystem::path& dir, const std::string& name, raster_view<const float> values,
                  const grid& g, const std::string& crs_wkt, int epsg);

/// Prints "  wrote <path>" for the files a command produced.
void say_wrote(const std::filesystem::path& path);

}  // namespace lidarfx::cli
