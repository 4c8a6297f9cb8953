// SPDX-License-Identifier: Apache-2.0
// lidarfx water: waterbody maps from LAS files (dissertation ch. 2 with lidarfx's refinements).
#include "water_run.hpp"

#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>

#include <lidarfx/lidarfx.hpp>

#include "outputs.hpp"
#include "tile_store.hpp"
#include "tiled_survey.hpp"

namespace lidarfx::cli {

namespace {

constexpr const char* usage =
    "usage: lidarfx water IN.las|IN.laz|DIR [MORE ...] --cell METRES --out DIR [options]\n"
    "Extracts waterbodies: writes water.asc (1 water, 0 land, -9999 no data), waterbody_labels.asc (0 land,\n"
    "1..n by decreasing area), GeoTIFF twins when built with GDAL, water_overlay.png, waterbodies.csv,\n"
    "waterbodies.geojson and (with GDAL) waterbodies.gpkg. Inputs that cannot support the method (no intensity, too "
    "few points per cell)\n"
    "are refused with the reason and exit code 3; --force runs anyway. Lengths, heights and areas are metres\n"
    "whatever the files' unit (feet are converted); maps and polygons are in the files' CRS. Files in degrees\n"
    "(a geographic CRS) are refused (exit code 2): reproject them first. A folder given as input stands for\n"
    "its *.las and *.laz files, sorted by name.\n"
    "options (defaults in brackets):\n"
    "  --cell M              cell size, metres [2]\n"
    "  --threads N           threads for reading and the raster kernels, 0 = all cores [0]; same result\n"
    "  --veg-height M        vegetation height h, metres [2]\n"
    "  --min-seed-cells N    smallest dropout seed, cells [50]\n"
    "  --dropout-seeds-only  seed only from dropouts (the library's default options): about 1.7x faster on\n"
    "                        rasters, but misses turbid or specular water that returns every pulse [off]\n"
    "  --flat-seeds          also seed from level, sparse cells, with the level-surface cue (the flood's\n"
    "                        level follows min z only where the surface is level): finds turbid or specular\n"
    "                        water without dropouts; flat_seed_water_method() [on]\n"
    "  --theta-start D       first angular threshold, degrees [2]\n"
    "  --theta-step D        threshold step, degrees [1]\n"
    "  --theta-max D         last threshold, degrees [30]\n"
    "  --alpha A             KS significance level [0.05]\n"
    "  --one-sided           use the one-sided KS critical value sqrt(-ln(a)/2) instead of the documents' table\n"
    "  --level-tolerance M   narrow-water refinement tolerance, metres, 0 = off [0.15]\n"
    "  --island-min-area A   islands at least this large stay land, m2 [200]\n"
    "  --bridge-span M       bridge gaps up to this long, metres, 0 = off [30]; also the longest deck\n"
    "                        crossed to seed a river stretch that only the far side of a bridge reached\n"
    "  --hull-radius M       survey footprint: empty space that a disc of this radius reaches from outside\n"
    "                        was not flown (no data, never water), metres, 0 = off [50]\n"
    "  --memory SIZE         refuse grids whose estimate exceeds SIZE (4GiB, 512MiB) [half the memory]\n"
    "  --tile M              read the survey in tiles of M x M metres, --threads tiles at a time (surveys\n"
    "                        whose points do not fit in memory), 0 = untiled [0]; same outputs. Finished\n"
    "                        tiles are kept in DIR/.lidarfx-tiles/: the same command run again after an\n"
    "                        interruption resumes there; the folder is removed when the run completes\n"
    "  --crop X0,Y0,X1,Y1    only points inside this box, in the units of the files' CRS\n"
    "  --force               run even when the inputs cannot support the method\n";

/// Refuses a flag's value (usage_error "--flag must be rule (got value)") unless `ok`.
void need(bool ok, const char* flag, const char* rule, double value)
{
    if (!ok) {
        std::ostringstream why;
        why << "--" << flag << " must be " << rule << " (got " << value << ")";
        throw usage_error(why.str());
    }
}

}  // namespace

const std::vector<std::string>& water_value_options()
{
    static const std::vector<std::string> names{"cell",
                                                "out",
                                                "threads",
                                                "veg-height",
                                                "min-seed-cells",
                                                "theta-start",
                                                "theta-step",
                                                "theta-max",
                                                "alpha",
                                                "level-tolerance",
                                                "island-min-area",
                                                "bridge-span",
                                                "hull-radius",
                                                "memory",
                                                "crop",
                                                "formats",
                                                "tile"};
    return names;
}

const std::vector<std::string>& water_flag_options()
{
    static const std::vector<std::string> names{"help", "force", "one-sided", "flat-seeds", "dropout-seeds-only"};
    return names;
}

survey read_survey_local(const std::vector<std::string>& files, const survey_options& opt, double tile_edge_m,
                         const std::filesystem::path& tiles_dir)
{
    if (tile_edge_m == 0) return read_survey(files, opt);
    return read_survey_tiled(files, opt, tile_edge_m, tiles_dir);
}

water_method water_method_from(const arguments& a)
{
    if (a.has("flat-seeds") && a.has("dropout-seeds-only"))
        throw usage_error("--flat-seeds and --dropout-seeds-only exclude each other");
    // What the water family reports as the method (flat seeds and the level-surface cue) unless told otherwise.
    extract_waterbodies_options opt =
        a.has("dropout-seeds-only") ? extract_waterbodies_options{} : flat_seed_water_method();
    opt.run.threads = a.integer("threads", 0);
    opt.vegetation.height_m = a.number("veg-height", opt.vegetation.height_m);
    const int min_seed = a.integer("min-seed-cells", static_cast<int>(opt.seeds.min_cells));
    if (min_seed < 1) {
        throw usage_error("--min-seed-cells must be >= 1 (got " + std::to_string(min_seed) + ")");
    }
    opt.seeds.min_cells = static_cast<std::size_t>(min_seed);
    opt.grow.theta_start_deg = a.number("theta-start", opt.grow.theta_start_deg);
    opt.grow.theta_step_deg = a.number("theta-step", opt.grow.theta_step_deg);
    opt.grow.theta_max_deg = a.number("theta-max", opt.grow.theta_max_deg);
    opt.grow.ks.alpha = a.number("alpha", opt.grow.ks.alpha);
    if (a.has("one-sided")) opt.grow.ks.critical = ks_critical::one_sided;
    // --level-tolerance is the water level's tolerance of the narrow-water refinement and of the water seen
    // past a bridge deck; --bridge-span the longest deck joined across and crossed by seeds (0: neither).
    opt.level.tolerance_m = a.number("level-tolerance", opt.level.tolerance_m);
    opt.bridges.water_tolerance_m = opt.level.tolerance_m;
    opt.islands.island_min_area_m2 = a.number("island-min-area", opt.islands.island_min_area_m2);
    opt.bridges.max_span_m = a.number("bridge-span", opt.bridges.max_span_m);
    opt.bridge_seeds.max_span_m = opt.bridges.max_span_m;
    if (opt.bridges.max_span_m == 0) {
        opt.join_bridges = false;
        opt.bridge_seed_rounds = 0;
    }
    const double hull_radius_m = a.number("hull-radius", survey_footprint_options{}.hull_radius_m);
    opt.check_inputs = !a.has("force");
    opt.run.progress = progress_bar("waterbodies");
    // Each flag is checked under its own name before any work (the library would name its option instead).
    const auto& g = opt.grow;
    need(opt.vegetation.height_m > 0 && std::isfinite(opt.vegetation.height_m), "veg-height", "a finite number > 0",
         opt.vegetation.height_m);
    need(g.theta_start_deg >= 0 && g.theta_start_deg <= 90, "theta-start", "in [0, 90] degrees", g.theta_start_deg);
    need(g.theta_step_deg > 0 && g.theta_step_deg <= 90, "theta-step", "in (0, 90] degrees", g.theta_step_deg);
    need(g.theta_max_deg >= g.theta_start_deg && g.theta_max_deg <= 90, "theta-max", "in [--theta-start, 90] degrees",
         g.theta_max_deg);
    need(g.ks.alpha > 0 && g.ks.alpha < 1, "alpha", "in (0, 1)", g.ks.alpha);
    need(opt.level.tolerance_m >= 0 && std::isfinite(opt.level.tolerance_m), "level-tolerance",
         "a finite number >= 0 (metres)", opt.level.tolerance_m);
    need(opt.islands.island_min_area_m2 >= 0, "island-min-area", ">= 0 (m2; inf keeps every island)",
         opt.islands.island_min_area_m2);
    need(opt.bridges.max_span_m >= 0, "bridge-span", ">= 0 (metres; 0 disables)", opt.bridges.max_span_m);
    need(hull_radius_m >= 0 && std::isfinite(hull_radius_m), "hull-radius", "a finite number >= 0 (metres; 0 disables)",
         hull_radius_m);
    return {opt, hull_radius_m};
}

double tile_edge_from(const arguments& a)
{
    const double tile_edge_m = a.number("tile", 0);
    need(tile_edge_m >= 0 && std::isfinite(tile_edge_m), "tile", "a finite number >= 0 (metres; 0 = untiled)",
         tile_edge_m);
    return tile_edge_m;
}

int run_water(const std::vector<std::string>& args, const survey_source& source)
{
    const arguments a(args, water_value_options(), water_flag_options());
    if (const auto code = stop_for_usage(a, usage, true)) return *code;
    const auto [opt, hull_radius_m] = water_method_from(a);
    const auto survey_options = survey_options_from(a, water_bytes_per_cell);
    const double tile_edge_m = tile_edge_from(a);
    const auto files = survey_files(a.positional());
    io::output_folder out(a.text("out", ""), {files.begin(), files.end()});
    for (const auto& name : waterbody_file_names(survey_options.formats)) out.declare(name);
    const std::filesystem::path tiles_dir = out.path() / ".lidarfx-tiles";
    const auto s = source(files, survey_options, tile_edge_m, tiles_dir);
    print_survey(s);
    const auto found = find_waterbodies(s, opt, hull_radius_m);
    const auto& w = found.result;
    print_diagnostics(w.diagnostics);
    if (!w.ran) {
        std::cerr << "lidarfx water: these data cannot support waterbody extraction (see above); no map was "
                     "written. Use --force to run anyway.\n";
        return 3;
    }
    print_waterbodies(w);
    write_waterbodies(out, s, w, found.footprint, survey_options.formats, opt.run.threads);
    commit_and_report(out, command_line("water", args));
    if (tile_edge_m > 0) remove_tile_folder(tiles_dir);  // the run is complete: its tiles are no longer needed
    return 0;
}

}  // namespace lidarfx::cli
