// SPDX-License-Identifier: Apache-2.0
// Shared pieces of the lidarfx subcommands: argument parsing, a progress bar, reading surveys to rasters.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <lidarfx/core/grid.hpp>
#include <lidarfx/core/parallel.hpp>
#include <lidarfx/kernels/points/rasterize.hpp>

#include "io/crs.hpp"
#include "io/las.hpp"
#include "io/output_folder.hpp"
#include "io/tables.hpp"
#include "io/tmy3.hpp"
#include "io/vectors.hpp"

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

/// A progress bar on stderr: "label [#####.....]  45%" on a terminal; when stderr is not a terminal (a log, a
/// pipe), plain lines "label 40 %" at most every 10 % and every 10 s, and "label 100 %". Returns true (never cancels).
progress_callback progress_bar(const std::string& label);

/// A refusal of what the command line asks (a value out of range, a grid over the memory budget, a cell far
/// too small for the data): the program prints it and exits with code 2.
struct usage_error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// The file formats a command writes: ESRI ASCII grids, GeoTIFF (only when built with GDAL), PNG pictures;
/// and for vector outputs (tables and polygons) CSV, GeoJSON and GeoPackage (only when built with GDAL).
struct output_formats {
    bool asc = true, tif = true, png = true;
    bool csv = true, geojson = true, gpkg = io::vectors_available();
};

/// How read_survey reads and what it refuses; survey_options_from() fills it from --cell, --threads,
/// --memory, --crop and --force.
struct survey_options {
    double cell_m = 2.0;  ///< cell size, metres (whatever the unit of the files' CRS)
    int threads = 0;      ///< 0 = all cores
    bool show_progress = true;
    std::uint64_t memory_budget_bytes = 0;  ///< 0: half the physical memory
    double bytes_per_cell = 64;             ///< what the command keeps per grid cell (its memory estimate)
    std::optional<bounds> crop;             ///< keep the points inside, build the grid over it (units of the CRS)
    bool force = false;                     ///< run even when the cell is far too small for the point density
    output_formats formats;                 ///< what the command writes (--formats)
    bool class_ground = false;              ///< also keep survey::class_ground (4 bytes per cell)
    bool class_buildings = false;           ///< also count survey::class_buildings (4 bytes per cell)
};

/// --formats: raster formats asc,tif,png and vector formats csv,geojson,gpkg, any non-empty subset. Each
/// kind keeps its default when the list names none of it (rasters: all; vectors: csv and geojson, and gpkg
/// when built with GDAL). @throws usage_error on an unknown name, or tif or gpkg asked for explicitly in a
/// build without GDAL.
output_formats output_formats_from(const arguments& a);

/// Runs every job once on up to `threads` threads (0 = all cores); after all have stopped, rethrows the
/// first exception any job threw (in job order).
void run_jobs(const std::vector<std::function<void()>>& jobs, int threads);

/// Keeps freed memory for reuse instead of giving it back to the kernel at once (glibc only; elsewhere a no-op).
/// Reading allocates chunk and file buffers of megabytes per file and per tile; returned to the kernel, every
/// new one costs a page fault and a zero fill per 4 KiB page, which doubled the time of a tiled read. Call once
/// at the start of a program.
void keep_freed_memory();

/// --cell (default 2), --threads (default 0), --memory (bytes: 4GiB, 512MiB, 2G, 1e9), --crop
/// xmin,ymin,xmax,ymax and --force of `a`, validated; `bytes_per_cell` is the command's estimate.
survey_options survey_options_from(const arguments& a, double bytes_per_cell);

/// "4GiB", "512 MiB", "2G", "1.5e9" → bytes. @throws usage_error naming `option`.
std::uint64_t parse_bytes(const std::string& text, const std::string& option);

/// The rasters of one or more LAS files on one grid snapped to multiples of the cell size. Everything is in
/// metres: x, y and z of the points were multiplied by their CRS's units on reading (a survey in feet gives a
/// grid, heights and areas in metres); to_crs_units() gives the grid back in the CRS's units for outputs.
struct survey {
    rasterize_result rasters;
    raster<std::uint8_t> scan_covered;  ///< cells a scan line crossed between two returns (scan_coverage);
                                        ///< empty when no file has GPS times
    io::survey_crs crs;                 ///< CRS and units of the first file (every file has the same units)
    std::string crs_wkt;                ///< the CRS of the first file as WKT, empty when none (crs.wkt)
    int epsg = 0;                       ///< horizontal EPSG code of the first file (0 = none or user-defined)
    std::size_t points = 0;             ///< points read
    std::size_t files = 0;
    /// The lowest point of class 2 (ground) in each cell, metres, NaN where none; empty unless
    /// survey_options::class_ground
    raster<float> class_ground;
    std::size_t class_ground_points = 0;  ///< points of class 2 on the grid (with survey_options::class_ground)
    /// Points of class 6 (building) in each cell; empty unless survey_options::class_buildings
    raster<std::uint32_t> class_buildings;
    std::size_t class_building_points = 0;  ///< points of class 6 on the grid (with survey_options::class_buildings)
    double unit_xy = 1, unit_z = 1;         ///< metres per unit of the files' x and y, and of z
};

/// Points counted in 256 x 256 bins over a survey's header box (metres): what refuse_outliers decides on.
/// Counts are integers: bins filled on several threads and merged do not depend on the split.
struct outlier_bins {
    static constexpr int bins = 256;
    bounds box;
    double bw = 1, bh = 1;             ///< bin width and height, metres
    std::vector<std::uint64_t> count;  ///< bins x bins, row j (from ymin) then column i (from xmin)

    explicit outlier_bins(const bounds& box);
    /// Counts points at x, y (metres; non-finite ones are skipped; outside the box, in the border bins).
    void add(std::span<const double> x, std::span<const double> y);
    void merge(const outlier_bins& other);
};

/// Points far from all the others (one point 200 km away) would stretch the grid over empty space. The bins
/// that hold all but the outermost 1e-4 of the `total` points along each axis, widened by 5 %, form the core
/// box. When points outside it make the grid more than twice the core's area, the run is refused
/// (usage_error) naming their count, where they are (in CRS units: metres / unit_m) and the --crop that keeps
/// the rest.
void refuse_outliers(const outlier_bins& bins, std::uint64_t total, double unit_m);

/// outlier_bins over `box` (metres) of every point of the files, read in a pass of their own on `threads`
/// threads; unit_m converts the files' x and y to metres.
outlier_bins count_outlier_bins(const std::vector<std::string>& paths, const bounds& box, double unit_m, int threads,
                                std::uint64_t memory_budget_bytes = 0);

/// What read_survey learns from the files' headers before reading any point, everything in metres.
struct survey_layout {
    survey head;                        ///< crs, crs_wkt, epsg and files set; no rasters yet
    grid g;                             ///< the snapped grid over the files' bounds (or the crop box)
    std::vector<bounds> extents;        ///< each file's header bounds, in input order
    std::vector<std::uint64_t> points;  ///< each file's header point count
    std::uint64_t total = 0;            ///< points of every file
    double unit_xy = 1, unit_z = 1;     ///< metres per unit of the files' x and y, and of z
    bounds header_box;                  ///< the union of the files' header boxes, metres (before any crop)
    /// The outlier check is left to the reader: it counts outlier_bins over header_box as it reads every
    /// point once and calls refuse_outliers before returning (survey_layout_of with reader_checks_outliers).
    bool outliers_unchecked = false;
    std::uint64_t memory_budget_bytes = 0;  ///< --memory (0: half the physical memory), for the LAZ readers
};

/// The header checks of read_survey, before any point is read: the same file twice, CRS and units
/// (degrees and mixed units refused), outliers, crop, the grid's memory against the budget and the cell
/// against the density; then the grid. @throws as read_survey.
/// With reader_checks_outliers, a grid that passes the memory and density checks leaves the outlier check to
/// the reader (outliers_unchecked) instead of reading every point in a pass of its own; otherwise, and always
/// when a check fails (outliers would explain it), the pass runs here first.
survey_layout survey_layout_of(const std::vector<std::string>& paths, const survey_options& opt,
                               bool reader_checks_outliers = false);

/// Multiplies a chunk's x, y and z by the layout's units (metres per unit).
void to_metres(io::las_points& points, const survey_layout& layout);

/// --memory of `a` in bytes, 0 when it is not given (then memory_budget_of takes half the physical memory).
/// @throws usage_error for a size that does not parse.
std::uint64_t memory_option(const arguments& a);

/// The TMY3 year of --tmy FILE (io::read_tmy3), its coverage said on stderr as one line. A file that breaks the
/// rules of a weather year is a usage_error (exit code 2). What `solar` and `roofs` share of their weather.
io::tmy3_data read_weather_year(const std::string& path);

/// The memory budget of a run: `memory_budget_bytes` (--memory), or half the physical memory when it is 0.
std::uint64_t memory_budget_of(std::uint64_t memory_budget_bytes);

/// Refuses (usage_error, exit code 2) a grid read from `path` (a DSM or DTM, from its header, before any value
/// is read) whose memory estimate, g.rows x g.cols x bytes_per_cell (what the command keeps per cell), exceeds
/// the budget (memory_budget_of): the message names the grid, the estimate, the budget and what to do.
void refuse_grid_over_budget(const std::string& path, const grid& g, double bytes_per_cell,
                             std::uint64_t memory_budget_bytes);

/// Says on stderr how many cells of the grid read from `path` held no finite height (inf, -inf, nan: they are no
/// data now), when there were any.
void report_non_finite_heights(const std::string& path, std::size_t cells);

/// Reads every point of `paths` in chunks and rasterizes them on the snapped grid covering the union of
/// the files' header bounds (or the crop box); points outside those bounds (a header that lies) are reported
/// as an error naming the file. Coordinates are converted to metres by the units of each file's CRS (io::crs_of,
/// whose warnings are printed once each); files in different units, or in degrees (a geographic CRS, where
/// cells and distances in metres mean nothing), are refused with a usage_error suggesting a reprojection. Before
/// reading any point it refuses (usage_error, exit code 2) a grid whose memory estimate (cells x bytes_per_cell)
/// exceeds the budget, and, unless `force`, a cell so small that 99 % of the cells would be empty at the survey's mean
/// density; both messages name a cell size that fits. With `threads` != 1 the next chunk is read while the current one
/// is rasterized; the chunks are added in file order either way, so the rasters do not depend on `threads`.
/// @throws std::runtime_error naming the file on bad input files.
survey read_survey(const std::vector<std::string>& paths, const survey_options& opt);

/// The ground cells a --ground choice takes from a survey read with class_ground (metres, NaN where not ground;
/// the caller fills them, e.g. replace_ground): class2 = the class-2 raster (moved out of `s`); filter =
/// morphological_ground on the lowest point of each cell; model = empty (the caller finds the terrain from the
/// DSM); auto = class2 when at least 1 % of the points are class 2, else filter. Says which on stdout.
/// @throws usage_error for class2 on a survey without a point of class 2, or for another choice
/// (check_ground_choice).
raster<float> chosen_ground(survey& s, const std::string& choice, int threads);

/// The points of each cell standing a height above the terrain: how many, and the lowest of them.
struct raised_points {
    raster<std::uint32_t> counts;  ///< points at least the height above the terrain
    raster<float> lowest;          ///< the lowest of them, metres; NaN = none
};

/// Reads the files of `s` again (as read_survey did: in chunks, in metres, within opt.memory_budget_bytes) and
/// counts, per cell of s.rasters.g, the points at least height_m above `terrain` (count_points_above; terrain in
/// metres, of the grid's shape), with the lowest of them: the raised points by which extract_buildings decides
/// each building's rim and finds the roof under overhanging crowns. Memory: one chunk of points and the two rasters
/// (8 bytes per cell). @throws std::runtime_error naming the file on bad input files.
raised_points count_raised_points(const std::vector<std::string>& paths, const survey& s, const survey_options& opt,
                                  raster_view<const float> terrain, double height_m);

/// The cells of a survey read with class_buildings where at least half of the points are of class 6 (the
/// vendor's buildings): --buildings class6. Says how many class-6 points there are on stdout.
/// @throws usage_error for a survey without a point of class 6.
raster<std::uint8_t> class_building_cells(const survey& s);

/// Refuses (usage_error) a --ground value other than auto, class2, filter or model.
void check_ground_choice(const std::string& choice);

/// The survey's footprint (survey_footprint over the cells with returns or crossed by a scan line): 1 =
/// inside the area flown. hull_radius_m <= 0 gives every cell as inside.
raster<std::uint8_t> footprint_of(const survey& s, double hull_radius_m, int threads);

/// `g` (in metres, as read_survey builds it) in the units of the survey's CRS: origin and cell size divided by
/// the horizontal unit, so that outputs land where the files' CRS places them. Cell values are not touched:
/// heights stay in metres.
grid to_crs_units(const grid& g, const survey& s);

/// Writes `name`.asc (with `name`.prj, its CRS as ESRI WKT, when the CRS is known) and `name`.tif (when GDAL is
/// available; it holds the CRS) of a float raster into `out`, as `formats` asks.
void write_raster(io::output_folder& out, const std::string& name, raster_view<const float> values, const grid& g,
                  const std::string& crs_wkt, int epsg, const output_formats& formats = {});

/// Writes the polygons `features` as `name`.geojson and `name`.gpkg (layer `name`) into `out`, as `formats`
/// asks, in the CRS of the survey: `epsg` when known, else its WKT `crs_wkt` (the GeoPackage holds that WKT; the
/// GeoJSON's crs member names the EPSG code OGR identifies for it, and is left out when none matches).
void write_polygons(io::output_folder& out, const std::string& name, const std::vector<io::geojson_feature>& features,
                    const std::string& crs_wkt, int epsg, const output_formats& formats = {});

/// Names `write_polygons` gives polygons called `name`.
std::vector<std::string> polygon_file_names(const std::string& name, const output_formats& formats = {});

/// Names `write_raster` gives a raster called `name` (for output_folder::declare before long work).
std::vector<std::string> raster_file_names(const std::string& name, const output_formats& formats = {});

/// True when `path` ends with `extension` (".asc", ".geojson"), letters compared without case.
bool has_extension(const std::string& path, const std::string& extension);

/// "lidarfx <command> <args...>", for manifests.
std::string command_line(const std::string& command, const std::vector<std::string>& args);

/// Commits `out` (files move into place, manifest.json last) and prints "  wrote <path>" for each file.
void commit_and_report(io::output_folder& out, const std::string& command);

}  // namespace lidarfx::cli
