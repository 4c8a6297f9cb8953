// SPDX-License-Identifier: Apache-2.0
// lidarfx rasterize: per-cell rasters of LAS files (min z, max z, mean intensity, count, dropout).
#include <filesystem>
#include <iostream>

#include <lidarfx/lidarfx.hpp>

#include "cli_common.hpp"
#include "command.hpp"
#include "io/png.hpp"
#include "io/quicklook.hpp"
#include "outputs.hpp"

namespace {

constexpr const char* usage =
    "usage: lidarfx rasterize IN.las|IN.laz [MORE ...] --cell METRES --out DIR [--threads N] [--memory SIZE]\n"
    "                         [--crop XMIN,YMIN,XMAX,YMAX] [--formats asc,tif,png] [--force]\n"
    "Writes min_z, max_z, mean_intensity, count and dropout as ESRI ASCII grids (.asc; GeoTIFF .tif too\n"
    "when built with GDAL) on a grid aligned to multiples of the cell size (no data = -9999), and PNG\n"
    "quicklooks. Default cell: 2 m. --threads N: 0 = all cores (default), 1 = read and rasterize on one\n"
    "thread; the rasters are the same for every N. A grid over the memory budget (--memory, default half the\n"
    "physical memory) or a cell far too small for the point density is refused at once (exit code 2) with a\n"
    "cell size that fits; --force runs a too-small cell anyway. Outputs appear complete or not at all, with\n"
    "DIR/manifest.json (sizes, SHA-256) written last; one run per folder at a time. --cell is metres; the\n"
    "grids are georeferenced in the files' CRS (--crop in its units) and min_z and max_z are in its vertical\n"
    "unit (feet stay feet, as a GIS reads them; manifest.json names the unit). Files in degrees (a geographic\n"
    "CRS) are refused: reproject first.\n";

int run_rasterize(const std::vector<std::string>& args)
{
    const lidarfx::cli::arguments a(args, {"cell", "out", "threads", "memory", "crop", "formats"}, {"help", "force"});
    if (const auto code = lidarfx::cli::stop_for_usage(a, usage, true)) return *code;
    // Per cell: the accumulator (24 B), the rasters (18 B) and the writers' float copies and pictures.
    const auto options = lidarfx::cli::survey_options_from(a, 56);
    lidarfx::io::output_folder out(a.text("out", ""), {a.positional().begin(), a.positional().end()});
    for (const auto& name : lidarfx::cli::point_raster_file_names(options.formats)) out.declare(name);
    const auto s = lidarfx::cli::read_survey(a.positional(), options);
    lidarfx::cli::print_survey(s);
    lidarfx::cli::write_point_rasters(out, s, options.formats, options.threads);
    lidarfx::cli::commit_and_report(out, lidarfx::cli::command_line("rasterize", args));
    return 0;
}

const lidarfx::cli::registration reg{"rasterize", "LAS files -> min/max z, intensity, count, dropout rasters",
                                     run_rasterize};

}  // namespace
