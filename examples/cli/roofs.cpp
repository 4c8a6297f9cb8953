// SPDX-License-Identifier: Apache-2.0
// lidarfx roofs: rooftop PV suitability per roof plane (or per building, the paper's method) from a surface
// model and building footprints.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <lidarfx/lidarfx.hpp>

#include "cli_common.hpp"
#include "command.hpp"
#include "elevation_input.hpp"
#include "io/ascii_grid.hpp"
#include "io/footprints.hpp"
#include "io/geotiff.hpp"
#include "io/tables.hpp"
#include "io/tmy3.hpp"
#include "outputs.hpp"
#include "roof_outputs.hpp"
#include "solar_place.hpp"

namespace {

constexpr const char* usage =
    "usage: lidarfx roofs IN.las|IN.laz [MORE ...] FOOTPRINTS --out DIR [--cell M] [--mode planes|paper]\n"
    "       lidarfx roofs DSM DTM FOOTPRINTS --out DIR [--mode planes|paper]\n"
    "DSM, DTM: rasters on one grid, ESRI ASCII (.asc with its .prj) or, with GDAL, GeoTIFF and any raster GDAL\n"
    "reads; heights and cells in the units of the DSM's CRS.\n"
    "Rooftop PV suitability. FOOTPRINTS: Polygon/MultiPolygon features with an integer id (field building_id, or\n"
    "--id-field): a GeoJSON FeatureCollection, or when built with GDAL any vector file OGR reads (GeoPackage,\n"
    "Shapefile, FlatGeobuf, ...; a file without building_id then takes its feature ids). Footprints in another\n"
    "CRS than the survey's are reprojected to it; a file that states no CRS (GeoJSON without a crs member) is\n"
    "taken to be in the survey's. From LAS files the DSM is the highest return per\n"
    "cell (IDW-filled) and the DTM the vendor's ground (class 2) or a ground filter's, as --ground says.\n"
    "Mode planes (default): every roof plane with its own fitted tilt, azimuth and area; mode paper: one PV\n"
    "plane per building by the published method (aspect mode, half-std band). Writes roof_patches.csv\n"
    "(building_id,patch_id,tilt_deg,azimuth_deg,area_m2,sloped_area_m2,kwp,suitable,centroid_x_crs,...;\n"
    "area_m2 horizontal, one row per plane or building, flat roofs included), roof_patches.geojson,\n"
    "roof_patches.png (patches coloured by azimuth, suitable ones outlined) and footprints.csv (what happened to\n"
    "every footprint: used, invalid, outside the grid, no cells); with GDAL also roof_patches.gpkg.\n"
    "options (defaults in brackets):\n"
    "  --id-field F   the footprints' integer id field [building_id]\n"
    "  --formats L    what to write: png and csv, geojson, gpkg [all that this build can write]\n"
    "  --cell M       cell size for LAS input, metres [1]\n"
    "  --xy-unit U    unit of the DSM's and DTM's corners and cell size when the DSM states no CRS (a .prj beside\n"
    "                 an .asc, as GDAL writes it): m, ft (international foot), us-ft (US survey foot); such a\n"
    "                 DSM is refused without them; with a CRS they must agree with it\n"
    "  --z-unit U     unit of their heights (m, ft, us-ft), as --xy-unit\n"
    "  --mode M       planes | paper [planes]\n"
    "  --ground G     the DTM from LAS files, gaps filled by IDW [auto]: class2 = the lowest class-2 (ground)\n"
    "                 point per cell; filter = a morphological ground filter on the lowest points (windows up\n"
    "                 to 40 m); model = ground_model's edge hulls (fails under blocks of buildings); auto =\n"
    "                 class2 when >= 1 % of the points are class 2, else filter\n"
    "  --tmy FILE     a TMY3 year: adds annual_kwh_m2 (irradiation on each patch's plane, with shadows and sky\n"
    "                 view) and annual_kwh (times kWp and a performance ratio of 0.8) to the patches\n"
    "  --lat/--lon    the place in degrees; without --tmy, the yields of a clear-sky year there\n"
    "  --memory SIZE  the memory budget (4GiB, 512MiB) that the survey grid, the DSM and DTM, the footprints\n"
    "                 and the weather file are checked against before they are read (exit code 2) [half the\n"
    "                 memory]\n"
    "  --threads N    threads, 0 = all cores [0]; same result for every N\n"
    "The place of the sun, as lidarfx solar puts it: --lat/--lon when given, else the survey's centre when its CRS\n"
    "is known and lidarfx has PROJ, else the TMY station; with a known CRS and PROJ, sun azimuths are turned from\n"
    "true to grid north by the meridian convergence at the survey's centre.\n";

}  // namespace

namespace lidarfx::cli {
namespace {

/// What lidarfx roofs keeps per grid cell, bytes: the survey rasters (or the DSM and DTM), the buildings' labels,
/// planes and patches (its memory estimate for --memory).
constexpr double roofs_bytes_per_cell = 68;  // with the class-2 ground

// The surface models of the run, in metres, on one grid.
struct roof_inputs {
    raster<float> dsm, dtm;
    grid g;               // metres (read_survey's grid, or the DSM's grid in metres)
    grid out_grid;        // the same cells in the input's CRS units, for outputs
    double unit_m = 1.0;  // metres per CRS unit of x and y
    std::string crs_wkt;
    int epsg = 0;
    std::string place_crs;  // the CRS whose centre PROJ may place for the sun ("" when none)
};

// A DSM and a DTM raster rather than LAS/LAZ files.
bool grid_inputs(const std::vector<std::string>& inputs)
{
    return inputs.size() == 2 && !is_point_cloud_path(inputs[0]) && !is_point_cloud_path(inputs[1]);
}

// The survey's CRS from the DSM raster's CRS (an .asc's .prj) or the first LAS header alone, so footprints are checked
// and placed before any point or cell is read; read_roof_inputs takes the grids' CRS from it.
io::survey_crs inputs_crs(const std::vector<std::string>& inputs, const arguments& a)
{
    if (grid_inputs(inputs)) return raster_crs(inputs[0], a);  // the DSM's (its .prj for ESRI ASCII)
    for (const std::string& f : inputs) {
        if (!is_point_cloud_path(f))
            throw usage_error(f + ": give either LAS/LAZ files or exactly two rasters, the DSM and the DTM");
    }
    return io::crs_of(io::las_reader(inputs[0]).header());  // read_survey warns, not this
}

roof_inputs read_roof_inputs(const std::vector<std::string>& inputs, const io::survey_crs& grid_crs, const arguments& a,
                             int threads)
{
    roof_inputs in;
    if (grid_inputs(inputs)) {
        if (a.has("ground")) throw usage_error("--ground chooses the DTM of LAS input; here the DTM is " + inputs[1]);
        // Both headers first: the grids must agree and fit --memory before any cell is allocated.
        const grid g1 = raster_file_grid(inputs[0]), g2 = raster_file_grid(inputs[1]);
        if (g2.rows != g1.rows || g2.cols != g1.cols || g2.x0 != g1.x0 || g2.y0 != g1.y0 || g2.cell != g1.cell)
            throw usage_error(inputs[1] + ": the DTM must be on the DSM's grid (same origin, cell size and size)");
        const std::uint64_t budget = memory_option(a);
        refuse_grid_over_budget(inputs[0] + " and " + inputs[1], g1, roofs_bytes_per_cell, budget);
        const io::survey_crs& crs = grid_crs;  // the DSM's, for both
        elevation_raster dsm = read_elevation_raster(inputs[0], crs);
        in.dtm = read_elevation_raster(inputs[1], crs).values;
        in.dsm = std::move(dsm.values);
        in.g = dsm.g;                 // in metres
        in.out_grid = dsm.file_grid;  // in the CRS's units
        in.unit_m = crs.horizontal_unit_m;
        in.crs_wkt = crs.wkt;
        in.epsg = crs.epsg;
        in.place_crs = crs.for_outputs();
        return in;
    }
    auto survey_opts = survey_options_from(a, roofs_bytes_per_cell);
    if (!a.has("cell")) survey_opts.cell_m = 1.0;  // roofs' default: 1 m cells
    const std::string ground_choice = a.text("ground", "auto");
    survey_opts.class_ground = ground_choice == "auto" || ground_choice == "class2";
    survey s = read_survey(inputs, survey_opts);
    print_survey(s);
    in.g = s.rasters.g;
    const raster<float> class_ground = chosen_ground(s, ground_choice, threads);
    ground_model_result ground = ground_model(s.rasters.max_z, in.g.cell, {}, {.threads = threads});
    if (!class_ground.empty()) replace_ground(ground, class_ground, in.g.cell, {}, {.threads = threads});
    in.dsm = ground.surface;
    in.dtm = ground.ground;
    in.out_grid = to_crs_units(in.g, s);
    in.unit_m = s.crs.horizontal_unit_m;
    in.crs_wkt = s.crs_wkt;
    in.epsg = s.epsg;
    in.place_crs = s.crs.for_outputs();
    return in;
}

// Footprints in the metre space of the grid (file coordinates times the unit), burned with the cell-centre rule.
struct burned_footprints {
    burn_result burn;
    io::footprint_collection file;
};

burned_footprints burn_footprints(io::footprint_collection file, const roof_inputs& in)
{
    burned_footprints b{{}, std::move(file)};
    std::vector<labelled_polygon> list;
    for (const io::footprint& f : b.file.footprints) {
        labelled_polygon lp{f.building_id, f.parts};
        for (polygon& p : lp.parts)
            for (auto& ring : p.rings)
                for (auto& v : ring) v = {v[0] * in.unit_m, v[1] * in.unit_m};
        list.push_back(std::move(lp));
    }
    b.burn = burn_polygons(list, in.g);
    return b;
}

// Puts the footprints in the survey's CRS: a file without a CRS is taken to be in it (with a note), one in
// another CRS is reprojected through OGR/PROJ; footprints with a CRS on a survey without one are refused.
// `survey_crs` is the survey's CRS as WKT or "EPSG:n", "" when it states none (inputs_crs).
void place_footprints(io::footprint_collection& footprints, const std::string& file, const std::string& survey_crs)
{
    if (footprints.crs.empty()) {
        if (!survey_crs.empty())
            std::cerr << "note: " << file << " states no CRS; its footprints are taken to be in the survey's CRS\n";
        return;
    }
    const int code = io::epsg_of_crs(footprints.crs);
    const std::string named = code > 0                      ? "EPSG:" + std::to_string(code)
                              : footprints.crs.size() <= 60 ? footprints.crs
                                                            : "a CRS without EPSG code";
    if (survey_crs.empty())
        throw usage_error(
            file + ": the footprints are in " + named +
            " but the survey states no CRS, so lidarfx cannot place them on it; give the survey its CRS "
            "(a .prj beside the DSM and DTM) or give footprints in the survey's coordinates without a CRS");
    if (io::same_crs(footprints.crs, survey_crs)) return;
    if (!io::vectors_available())
        throw usage_error(
            file + ": the footprints are in " + named +
            ", not in the survey's CRS, and reprojecting them needs OGR/PROJ: " + io::vectors_rebuild_hint);
    try {
        io::reproject_footprints(footprints, footprints.crs, survey_crs, file);
    } catch (const invalid_input& e) {
        throw usage_error(e.what());
    }
    std::cerr << "note: " << file << ": footprints reprojected from " << named << " to the survey's CRS\n";
}

int run_roofs(const std::vector<std::string>& args)
{
    const arguments a(args,
                      {"out", "cell", "mode", "threads", "memory", "crop", "formats", "tmy", "lat", "lon", "id-field",
                       "xy-unit", "z-unit", "ground"},
                      {"help", "force"});
    if (const auto code = stop_for_usage(a, usage, true)) return *code;
    const int threads = a.integer("threads", 0);
    if (threads < 0) throw usage_error("--threads must be >= 0 (got " + std::to_string(threads) + ")");
    const std::string mode = a.text("mode", "planes");
    if (mode != "planes" && mode != "paper") throw usage_error("--mode must be planes or paper (got " + mode + ")");
    const std::string ground_choice = a.text("ground", "auto");
    check_ground_choice(ground_choice);
    const output_formats formats = output_formats_from(a);
    std::vector<std::string> inputs = a.positional();
    if (inputs.size() < 2 || has_extension(inputs.back(), ".las") || has_extension(inputs.back(), ".laz") ||
        has_extension(inputs.back(), ".asc") || has_extension(inputs.back(), ".tif") ||
        has_extension(inputs.back(), ".tiff"))
        throw usage_error(
            "the last input must be the footprints (.geojson; with GDAL also .gpkg, .shp, .fgb, ...): lidarfx roofs "
            "IN.las FOOTPRINTS.geojson --out DIR");
    const std::string footprint_file = inputs.back();
    if (!io::is_geojson_name(footprint_file) && !io::vectors_available())
        throw usage_error(footprint_file + ": footprints other than GeoJSON are read through OGR, and " +
                          io::vectors_rebuild_hint + "; or convert them: ogr2ogr footprints.geojson " + footprint_file);
    inputs.pop_back();

    // Weather for the yields (optional): a TMY3 year (its rows' own years), or the clear-sky year 2021 at
    // --lat/--lon. The place of the sun is resolved as `lidarfx solar` does once the grid is known.
    std::vector<irradiance_record> records;
    const double lat = a.number("lat", NAN), lon = a.number("lon", NAN);
    if (a.has("lat") != a.has("lon")) throw usage_error("--lat and --lon go together");
    if (a.has("lat") && !(lat >= -90.0 && lat <= 90.0)) throw usage_error("--lat must be in [-90, 90] degrees");
    if (a.has("lon") && !(lon >= -180.0 && lon <= 180.0)) throw usage_error("--lon must be in [-180, 180] degrees");
    solar_place_sources place_sources;
    place_sources.station_latitude_deg = NAN;
    place_sources.station_longitude_deg = NAN;
    if (a.has("tmy")) {
        const auto tmy = read_weather_year(a.text("tmy", ""));
        records = tmy.records;
        place_sources.station_latitude_deg = tmy.station.latitude_deg;
        place_sources.station_longitude_deg = tmy.station.longitude_deg;
        place_sources.utc_offset_h = tmy.station.utc_offset_h;
    }

    // Footprints first: a bad file fails before the survey is read and before the output folder exists.
    io::footprint_collection footprints;
    try {
        // The read counts against --memory on its own (0 = half the physical memory), before the grid exists.
        const std::uint64_t budget = memory_option(a);
        footprints =
            io::read_footprints(footprint_file, {.memory_budget_bytes = budget, .id_field = a.text("id-field", "")});
    } catch (const invalid_input& e) {
        throw usage_error(e.what());
    }
    for (const std::string& note : footprints.notes) std::cerr << "note: " << note << "\n";
    const io::survey_crs survey_crs = inputs_crs(inputs, a);
    place_footprints(footprints, footprint_file, survey_crs.for_outputs());
    io::output_folder out(a.text("out", ""), {a.positional().begin(), a.positional().end()});
    std::vector<std::string> names = roof_patch_file_names(formats);
    names.push_back("footprints.csv");
    for (const auto& n : names) out.declare(n);
    const roof_inputs in = read_roof_inputs(inputs, survey_crs, a, threads);
    const burned_footprints fp = burn_footprints(std::move(footprints), in);

    roof_suitability_options opt;
    opt.mode = mode == "paper" ? roof_mode::paper : roof_mode::planes;
    opt.run = {.threads = threads, .progress = progress_bar("roofs")};
    const roof_suitability_result r = roof_suitability(in.dsm, in.dtm, fp.burn.labels, in.g, opt);

    // What happened to every footprint.
    std::vector<std::vector<io::table_value>> report;
    std::map<std::int32_t, std::size_t> patches_of;
    for (const roof_patch& p : r.patches) ++patches_of[p.building_id];
    std::size_t used = 0;
    for (std::size_t i = 0; i < fp.file.footprints.size(); ++i) {
        const io::footprint& f = fp.file.footprints[i];
        const burn_account& acc = fp.burn.footprints[i];
        std::string status = "used";
        if (acc.outside)
            status = "outside the grid";
        else if (acc.cells == 0)
            status = acc.contested ? "covered by other footprints" : "no cell centre inside";
        else
            ++used;
        report.push_back({f.building_id, static_cast<std::int64_t>(f.feature), status,
                          static_cast<std::int64_t>(acc.cells), static_cast<std::int64_t>(acc.contested),
                          static_cast<std::int64_t>(patches_of[f.building_id])});
    }
    for (const io::footprint_problem& p : fp.file.problems)
        report.push_back({p.building_id, static_cast<std::int64_t>(p.feature), p.problem, std::int64_t{0},
                          std::int64_t{0}, std::int64_t{0}});
    out.write("footprints.csv", [&](const std::string& path) {
        io::write_csv(path,
                      {io::text_column("building_id"), io::text_column("feature"), io::text_column("status"),
                       io::text_column("cells"), io::text_column("contested_cells"), io::text_column("patches")},
                      report);
    });

    std::vector<roof_patch_yield> yields;
    if (a.has("tmy") || a.has("lat")) {
        place_sources.g = in.out_grid;
        place_sources.place_crs = in.place_crs;
        place_sources.input = inputs[0];
        const solar_place place = resolve_solar_place(a, place_sources);
        std::cout << "place: " << place.description << "\n";
        if (!a.has("tmy")) records = clear_sky_records(2021, place.site.latitude_deg, place.site.longitude_deg);
        yields = roof_yield(in.dsm, in.g.cell, r, place.site, records,
                            {.run = {.threads = threads, .progress = progress_bar("yield")}});
        double kwh = 0;
        for (const roof_patch_yield& y : yields) kwh += y.annual_kwh;
        std::cout << std::fixed << std::setprecision(0) << "annual yield of all patches: " << kwh << " kWh ("
                  << (a.has("tmy") ? "TMY3 " + a.text("tmy", "") : std::string("clear-sky year")) << ")\n";
    }
    write_roof_patches(out, r, {in.dsm, in.g.cell, in.out_grid, in.unit_m, in.epsg, in.crs_wkt}, formats, yields);

    std::size_t suitable = 0;
    double kwp = 0;
    for (const roof_patch& p : r.patches) {
        if (!p.suitable) continue;
        ++suitable;
        kwp += p.kwp;
    }
    std::cout << std::fixed << std::setprecision(1) << "footprints: " << used << " used of "
              << fp.file.footprints.size() + fp.file.problems.size() << " (see footprints.csv)\n"
              << "roof patches (" << mode << " mode): " << r.patches.size() << ", suitable " << suitable << ", " << kwp
              << " kWp\n";
    std::size_t outside = 0;
    for (const burn_account& acc : fp.burn.footprints) outside += acc.outside ? 1 : 0;
    if (outside > 0 && outside == fp.burn.footprints.size())
        std::cerr << "note: every footprint lies outside the grid; are they in the survey's CRS? (a file that states "
                     "no CRS is taken to be in it: a WGS 84 GeoJSON needs a crs member)\n";
    commit_and_report(out, command_line("roofs", args));
    return 0;
}

const registration reg{"roofs", "DSM + DTM (or LAS) + footprints -> rooftop PV planes and suitability", run_roofs};

}  // namespace
}  // namespace lidarfx::cli
