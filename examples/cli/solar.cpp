// SPDX-License-Identifier: Apache-2.0
// lidarfx solar: annual and monthly irradiation maps of a surface model (dissertation ch. 3).
#include <algorithm>
#include <array>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <lidarfx/lidarfx.hpp>

#include "cli_common.hpp"
#include "command.hpp"
#include "elevation_input.hpp"
#include "io/ascii_grid.hpp"
#include "io/crs.hpp"
#include "io/figure.hpp"
#include "io/geographic.hpp"
#include "io/geotiff.hpp"
#include "io/png.hpp"
#include "io/quicklook.hpp"
#include "io/tables.hpp"
#include "io/tmy3.hpp"
#include "outputs.hpp"
#include "solar_facades.hpp"
#include "solar_place.hpp"

namespace {

constexpr const char* usage =
    "usage: lidarfx solar IN.las|IN.laz [MORE ...] | DSM --out DIR [--tmy FILE.csv]\n"
    "                     [--lat DEG --lon DEG] [--cell M] [--year Y | --year-from-tmy]\n"
    "                     [--diffuse isotropic|perez] [--svf cosine|share] [--surface horizontal|terrain]\n"
    "                     [--facades [--ground auto|class2|filter|model]] [--threads N]\n"
    "                     [--formats asc,tif,png,csv,geojson,gpkg]\n"
    "Irradiation of a surface model over a year, on horizontal surfaces or (--surface terrain) on each cell's own\n"
    "plane: beam = DNI * cos(incidence) where the cell sees the sun (cast shadows per daylight hour), diffuse =\n"
    "DHI * sky view factor (tilted: times (1 + cos tilt) / 2). Writes annual_kwh_m2.asc,\n"
    "month_01_kwh_m2.asc .. month_12_kwh_m2.asc, svf.asc (GeoTIFF twins when built with GDAL), annual_kwh_m2.png\n"
    "and svf.png (with a colour bar, its range and unit) and summary.csv (per month: mean, min, max kWh/m2 of\n"
    "the map and the weather's GHI sum). From LAS files the DSM is the highest return per cell, gaps filled by\n"
    "IDW. A DSM raster: ESRI ASCII (.asc), or with GDAL a GeoTIFF or any raster GDAL reads; NoData cells are\n"
    "holes, heights and cells are in its CRS's units (feet become metres, degrees are refused): an .asc takes its\n"
    "CRS from the .prj beside it (as GDAL writes it; lidarfx rasterize writes one). A raster without a CRS needs\n"
    "--xy-unit and --z-unit. Weather: a TMY3 file (--tmy; its station gives\n"
    "the time zone); without --tmy, a cloudless year from the clear-sky model (Haurwitz + Erbs). The place of the\n"
    "sun: --lat/--lon when given, else the survey's centre when its CRS is known and lidarfx has PROJ, else the TMY\n"
    "station. With a known CRS and PROJ, sun azimuths are also turned from true to grid north by the meridian\n"
    "convergence at the survey's centre (--lat/--lon given or not).\n"
    "options (defaults in brackets):\n"
    "  --cell M       cell size for LAS input, metres [1]\n"
    "  --xy-unit U    unit of a DSM raster's corner and cell size when it states no CRS: m, ft (international\n"
    "                 foot), us-ft (US survey foot); with a CRS it must agree with it\n"
    "  --z-unit U     unit of a DSM raster's heights (m, ft, us-ft), as --xy-unit\n"
    "  --year Y       the year the records are placed in [2021]: the clear-sky year, or the year every TMY row\n"
    "                 is re-stamped to (same local month, day and hour), so the sun follows one calendar year\n"
    "  --year-from-tmy  keep the TMY rows' own years (a TMY takes each month from a different year) instead\n"
    "                 of re-stamping them; needs --tmy, excludes --year\n"
    "  --diffuse M    sky model of the diffuse part [isotropic]: isotropic = DHI * SVF (the dissertation's);\n"
    "                 perez = Perez et al. 1990 anisotropic sky, its circumsolar part shaded with the beam\n"
    "  --svf D        sky view factor written to svf.* and used for the diffuse part [cosine]: cosine = the\n"
    "                 view factor of a horizontal surface, the mean of cos^2(horizon angle) over the azimuths\n"
    "                 (the SVF of GRASS r.skyview and SAGA); share = the share of point sources at 15-85 degrees\n"
    "                 on each azimuth, and the zenith, that the cell sees (the dissertation's; 0.01-0.02 higher)\n"
    "  --svf-directions N  azimuths of the horizon sweeps, i * 360 / N [72]\n"
    "  --keep-outliers  keep the DSM's isolated spikes and pits; by default a cell standing more than 10 m above\n"
    "                 (below) all but a few of its 5 x 5 neighbours (a bird, a return through a canopy gap) takes\n"
    "                 their median before shadows and sky view, and dsm_outliers.csv lists each such cell\n"
    "  --surface S    horizontal = every cell a horizontal surface [horizontal]; terrain = each cell tilted by\n"
    "                 its own slope and aspect (Horn's 3x3 differences of the DSM): roofs and slopes as they are\n"
    "  --facades      also find the buildings (extract_buildings) and the energy of every roof patch and facade\n"
    "                 sub-patch (8 per wall): buildings.geojson (outlines; id, ground/eave/ridge z, height, roof\n"
    "                 areas), facade_patches.csv (building_id,patch_id,level,facing_azimuth_deg,height_m (centre\n"
    "                 above the wall's foot),area_m2,annual_kwh_m2,q1..q4_kwh_m2_day), surface_table.csv (north/\n"
    "                 south/east/west facades and rooftops: quarterly kWh/m2/day, annual kWh/m2/yr),\n"
    "                 bill_savings.csv (12 modules of 65x39 in, 16 %, inverter 95 %, -6 %, 0.11 per kWh) and\n"
    "                 buildings_energy.png (roofs and walls coloured by annual kWh/m2). From LAS files trees are\n"
    "                 told from roofs by their split pulses (a part where 20 % of the points came from pulses\n"
    "                 with several returns is vegetation)\n"
    "  --ground G     the terrain under the buildings of --facades, LAS input [auto]: class2 = the lowest\n"
    "                 class-2 (ground) point per cell; filter = a morphological ground filter on the lowest\n"
    "                 points (windows up to 40 m); model = from the DSM's edge hulls (fails under blocks of\n"
    "                 buildings); auto = class2 when >= 1 % of the points are class 2, else filter. With\n"
    "                 class2 or filter the files are read twice: a building's edge cells are decided by the\n"
    "                 share of their points standing 2.5 m above that terrain (half or more: building)\n"
    "  --buildings B  where the buildings of --facades come from, LAS input [points]: points = found from the\n"
    "                 surface, the terrain and the returns (above); class6 = the cells where at least half of\n"
    "                 the points are of the vendor's building class (ASPRS 6), parts under 15 m2 dropped\n"
    "  --memory SIZE  the memory budget (4GiB, 512MiB) that the survey grid, the DSM and the\n"
    "                 weather file are checked against before they are read (exit code 2) [half the memory]\n"
    "  --threads N    threads, 0 = all cores [0]; same result for every N\n";

// Mean, min and max of the finite cells.
struct map_stats {
    double mean = std::numeric_limits<double>::quiet_NaN(), min = mean, max = mean;
};

map_stats stats_of(const lidarfx::raster<float>& m)
{
    map_stats s;
    double sum = 0.0;
    std::size_t n = 0;
    for (std::ptrdiff_t r = 0; r < m.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < m.cols(); ++c) {
            const double v = m(r, c);
            if (!std::isfinite(v)) continue;
            s.min = n == 0 ? v : std::min(s.min, v);
            s.max = n == 0 ? v : std::max(s.max, v);
            sum += v;
            ++n;
        }
    }
    if (n > 0) s.mean = sum / static_cast<double>(n);
    return s;
}

// The records moved into `year`: each keeps its local (UTC + zone_h) month, day and time of day. A 29 February
// cannot move into a common year: refused, naming the file and the ways out.
std::vector<lidarfx::irradiance_record> restamp_year(std::vector<lidarfx::irradiance_record> records, int year,
                                                     double zone_h, const std::string& file)
{
    namespace chr = std::chrono;
    const chr::seconds zone{static_cast<long long>(std::lround(zone_h * 3600.0))};
    for (auto& r : records) {
        const chr::sys_seconds local = r.start_utc + zone;
        const chr::sys_days day = chr::floor<chr::days>(local);
        const chr::year_month_day ymd{day};
        const chr::year_month_day moved{chr::year{year}, ymd.month(), ymd.day()};
        if (!moved.ok()) {
            throw lidarfx::cli::usage_error(file + " has a record on 29 February, which " + std::to_string(year) +
                                            " does not have: give a leap --year or --year-from-tmy");
        }
        r.start_utc = chr::sys_days{moved} + (local - day) - zone;
    }
    return records;
}

std::string fixed(double v, int digits)
{
    std::ostringstream o;
    o << std::fixed << std::setprecision(digits) << v;
    return o.str();
}

/// What lidarfx solar keeps per DSM cell, bytes: the survey rasters or the DSM, the annual and 12 monthly maps, sky
/// view, shadows and the outputs' buffers (its memory estimate for --memory).
constexpr double solar_bytes_per_cell =
    154;  // with --facades: point counts, class ground (and filled), raised (and their lowest)

/// One DSM cell that remove_surface_outliers replaced: where (cell and CRS coordinates of its centre) and its
/// height before and after, metres.
struct outlier_row {
    std::string kind;
    std::int64_t row = 0, col = 0;
    double x = 0, y = 0, z_m = 0, replaced_by_m = 0;
};

/// The replaced cells in raster order; the log names the first ten.
std::vector<outlier_row> list_outliers(const lidarfx::raster<float>& dsm, const lidarfx::surface_outliers_result& o,
                                       const lidarfx::grid& g)
{
    std::vector<outlier_row> rows;
    for (std::ptrdiff_t r = 0; r < dsm.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < dsm.cols(); ++c) {
            if (o.outlier(r, c) == 0) continue;
            const auto xy = g.center(r, c);
            rows.push_back({o.outlier(r, c) == 1 ? "spike" : "pit", r, c, xy[0], xy[1], dsm(r, c), o.surface(r, c)});
        }
    }
    for (std::size_t i = 0; i < rows.size() && i < 10; ++i) {
        std::cout << "  " << rows[i].kind << " at row " << rows[i].row << ", col " << rows[i].col << " (x "
                  << fixed(rows[i].x, 2) << ", y " << fixed(rows[i].y, 2) << "): " << fixed(rows[i].z_m, 2) << " m -> "
                  << fixed(rows[i].replaced_by_m, 2) << " m\n";
    }
    if (rows.size() > 10) std::cout << "  ... and " << rows.size() - 10 << " more in dsm_outliers.csv\n";
    return rows;
}

/// How the log, the figure and the manifest name the SVF: "cosine-weighted, 72 azimuths".
std::string svf_description(const std::string& svf, int directions)
{
    return std::string(svf == "cosine" ? "cosine-weighted" : "share of point sources") + ", " +
           std::to_string(directions) + " azimuths";
}

int run_solar(const std::vector<std::string>& args)
{
    namespace cli = lidarfx::cli;
    const cli::arguments a(args,
                           {"out", "tmy", "lat", "lon", "cell", "year", "threads", "memory", "crop", "formats",
                            "diffuse", "svf", "svf-directions", "surface", "xy-unit", "z-unit", "ground", "buildings"},
                           {"help", "force", "year-from-tmy", "facades", "keep-outliers"});
    if (const auto code = cli::stop_for_usage(a, usage, true)) return *code;
    const int threads = a.integer("threads", 0);
    if (threads < 0) throw cli::usage_error("--threads must be >= 0 (got " + std::to_string(threads) + ")");
    const cli::output_formats formats = cli::output_formats_from(a);
    const std::string diffuse = a.text("diffuse", "isotropic");
    if (diffuse != "isotropic" && diffuse != "perez") {
        throw cli::usage_error("--diffuse must be isotropic or perez (got " + diffuse + ")");
    }
    const std::string svf = a.text("svf", "cosine");
    if (svf != "cosine" && svf != "share") throw cli::usage_error("--svf must be cosine or share (got " + svf + ")");
    const int svf_directions = a.integer("svf-directions", 72);
    if (svf_directions < 4 || svf_directions > 3600) {
        throw cli::usage_error("--svf-directions must be in [4, 3600] (got " + std::to_string(svf_directions) + ")");
    }
    const std::string surface = a.text("surface", "horizontal");
    if (surface != "horizontal" && surface != "terrain") {
        throw cli::usage_error("--surface must be horizontal or terrain (got " + surface + ")");
    }
    const bool terrain = surface == "terrain";
    const std::string ground_choice = a.text("ground", "auto");
    cli::check_ground_choice(ground_choice);
    if (a.has("ground") && !a.has("facades")) throw cli::usage_error("--ground needs --facades");
    const std::string buildings_choice = a.text("buildings", "points");
    if (buildings_choice != "points" && buildings_choice != "class6")
        throw cli::usage_error("--buildings must be points or class6 (got '" + buildings_choice + "')");
    if (a.has("buildings") && !a.has("facades")) throw cli::usage_error("--buildings needs --facades");
    if (buildings_choice == "class6" && ground_choice == "model")
        throw cli::usage_error(
            "--buildings class6 with --ground model: a survey classified into buildings has its "
            "ground class; take it (--ground class2) or the filter (--ground filter), since the "
            "terrain found from the DSM fails under blocks of buildings and gives wrong heights");

    // Weather first: a bad file fails before the survey is read.
    const bool year_from_tmy = a.has("year-from-tmy");
    if (year_from_tmy && !a.has("tmy")) throw cli::usage_error("--year-from-tmy needs --tmy FILE.csv");
    if (year_from_tmy && a.has("year")) throw cli::usage_error("--year and --year-from-tmy exclude each other");
    const int records_year = a.integer("year", 2021);
    if (records_year < 1900 || records_year > 2200)
        throw cli::usage_error("--year must be in [1900, 2200] (got " + std::to_string(records_year) + ")");
    std::vector<lidarfx::irradiance_record> records;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    double lat = a.number("lat", nan), lon = a.number("lon", nan);
    if (a.has("lat") && !(lat >= -90.0 && lat <= 90.0)) throw cli::usage_error("--lat must be in [-90, 90] degrees");
    if (a.has("lon") && !(lon >= -180.0 && lon <= 180.0)) {
        throw cli::usage_error("--lon must be in [-180, 180] degrees");
    }
    double station_lat = nan, station_lon = nan;
    double zone_h = 0.0;
    if (a.has("tmy")) {
        const auto tmy = cli::read_weather_year(a.text("tmy", ""));
        records = tmy.records;
        zone_h = tmy.station.utc_offset_h;
        station_lat = tmy.station.latitude_deg;
        station_lon = tmy.station.longitude_deg;
        std::cout << "weather: TMY3 " << tmy.station.id << " " << tmy.station.name << ", " << records.size()
                  << " hours, UTC" << (zone_h >= 0 ? "+" : "") << zone_h;
        if (year_from_tmy) {
            std::cout << ", the rows' own years\n";
        } else {
            records = restamp_year(records, records_year, zone_h, a.text("tmy", ""));
            std::cout << ", re-stamped to " << records_year << "\n";
        }
    }
    const auto& inputs = a.positional();
    const bool single_grid = inputs.size() == 1 && !cli::is_point_cloud_path(inputs[0]);
    if (a.has("ground") && single_grid)
        throw cli::usage_error("--ground chooses the terrain of LAS input; " + inputs[0] + " is a DSM raster");
    if (a.has("buildings") && single_grid)
        throw cli::usage_error("--buildings chooses how the buildings of LAS input are found; " + inputs[0] +
                               " is a DSM raster");
    // A raster's CRS and units first (from its header or .prj); refused when nothing can give the place.
    lidarfx::io::survey_crs grid_crs;
    if (single_grid) {
        grid_crs = cli::raster_crs(inputs[0], a);
        if (!a.has("tmy") && grid_crs.source.empty())
            cli::require_place(lat, lon, inputs[0] + " states no coordinate system (no .prj beside an .asc)");
    }
    if (!a.has("tmy") && !lidarfx::io::proj_available())
        cli::require_place(lat, lon, "this lidarfx was built without PROJ");

    // The surface model. place_crs: the CRS whose centre PROJ may place ("" when none).
    lidarfx::raster<float> dsm;
    lidarfx::raster<std::uint32_t> points, split_points;  // points per cell and of split pulses (LAS input)
    cli::raised_points raised;                            // of them, raised above the terrain (LAS input)
    lidarfx::raster<std::uint8_t> classified_buildings;   // --buildings class6: the cells of the vendor's buildings
    lidarfx::raster<float> class_ground;                  // the class-2 terrain chosen by --ground (LAS input)
    lidarfx::grid g;
    double cell_m = 0.0;
    std::string crs_wkt, place_crs;
    int epsg = 0;
    const std::uint64_t memory_budget = cli::memory_option(a);
    if (single_grid) {
        // The header against --memory before any cell is allocated, as for a survey's grid.
        cli::refuse_grid_over_budget(inputs[0], cli::raster_file_grid(inputs[0]), solar_bytes_per_cell, memory_budget);
        cli::elevation_raster e = cli::read_elevation_raster(inputs[0], grid_crs);
        dsm = std::move(e.values);
        g = e.file_grid;  // outputs land where the input lies, in its units
        cell_m = e.g.cell;
        crs_wkt = grid_crs.wkt;
        epsg = grid_crs.epsg;
        place_crs = grid_crs.for_outputs();
        std::cout << "DSM: " << inputs[0] << ", " << g.rows << " x " << g.cols << " cells of " << fixed(cell_m, 3)
                  << " m, " << grid_crs.describe() << "\n";
    } else {
        auto survey_options = cli::survey_options_from(a, solar_bytes_per_cell);
        if (!a.has("cell")) survey_options.cell_m = 1.0;  // solar's default: 1 m cells
        survey_options.class_ground = a.has("facades") && (ground_choice == "auto" || ground_choice == "class2");
        survey_options.class_buildings = buildings_choice == "class6";
        auto s = cli::read_survey(inputs, survey_options);
        cli::print_survey(s);
        if (a.has("facades")) {
            if (buildings_choice == "class6") classified_buildings = cli::class_building_cells(s);
            class_ground = cli::chosen_ground(s, ground_choice, threads);
            if (buildings_choice != "class6" && !class_ground.empty()) {
                // The terrain filled as extract_buildings fills it; each building's rim is then decided by the
                // share of its points raised above it, counted in a second pass over the files, and the roof
                // under an overhanging crown found by the lowest of them.
                const double raised_m = lidarfx::building_candidates_options{}.min_height_m;
                class_ground = lidarfx::fill_ground(class_ground, s.rasters.g.cell, {}, {.threads = threads});
                raised = cli::count_raised_points(inputs, s, survey_options, class_ground, raised_m);
                std::cout << "building edges: by the share of each cell's points standing " << raised_m
                          << " m above that terrain, and roofs under overhanging crowns by the lowest of them (a "
                             "second pass over the files)\n";
            }
            points = std::move(s.rasters.count);
            split_points = std::move(s.rasters.multiple_return_count);
        }
        g = s.rasters.g;
        cell_m = g.cell;  // read_survey works in metres
        dsm = lidarfx::idw_fill(s.rasters.max_z, cell_m, {.run = {.threads = threads}}).filled;
        g = cli::to_crs_units(g, s);
        crs_wkt = s.crs_wkt;
        epsg = s.epsg;
        place_crs = s.crs.for_outputs();
    }

    // Where the sun is seen from, and how the grid is turned against true north.
    const cli::solar_place place = cli::resolve_solar_place(a, {.g = g,
                                                                .place_crs = place_crs,
                                                                .input = inputs[0],
                                                                .station_latitude_deg = station_lat,
                                                                .station_longitude_deg = station_lon,
                                                                .utc_offset_h = zone_h});
    const lidarfx::solar_site& site = place.site;
    std::cout << "place: " << place.description << "\n";
    if (!a.has("tmy")) {
        records = lidarfx::clear_sky_records(records_year, site.latitude_deg, site.longitude_deg);
        std::cout << "weather: no --tmy given, using the clear-sky model (Haurwitz GHI, Erbs split) for "
                  << records_year << "\n";
    }

    // Isolated spikes (birds, noise) and pits (returns through canopy gaps) out of the DSM before any shadow is cast.
    std::vector<outlier_row> outlier_rows;
    if (a.has("keep-outliers")) {
        std::cout << "DSM outliers: kept (--keep-outliers)\n";
    } else {
        lidarfx::surface_outliers_result outliers =
            lidarfx::remove_surface_outliers(dsm, {.run = {.threads = threads}});
        std::cout << "DSM outliers: " << outliers.spikes << " spikes and " << outliers.pits
                  << " pits replaced by the median of their 5 x 5 neighbourhood (dsm_outliers.csv)\n";
        outlier_rows = list_outliers(dsm, outliers, g);
        dsm = std::move(outliers.surface);
    }

    lidarfx::io::output_folder out(a.text("out", ""), {inputs.begin(), inputs.end()});
    std::vector<std::string> names{"summary.csv", "dsm_outliers.csv"};
    for (const std::string& n : cli::raster_file_names("annual_kwh_m2", formats)) names.push_back(n);
    for (const std::string& n : cli::raster_file_names("svf", formats)) names.push_back(n);
    for (int m = 1; m <= 12; ++m) {
        char month[32];
        std::snprintf(month, sizeof month, "month_%02d_kwh_m2", m);
        for (const std::string& n : cli::raster_file_names(month, formats)) names.push_back(n);
    }
    if (formats.png) {
        names.push_back("annual_kwh_m2.png");
        names.push_back("svf.png");
    }
    if (a.has("facades")) {
        for (const std::string& n : cli::facade_file_names(formats)) names.push_back(n);
    }
    for (const auto& n : names) out.declare(n);

    const lidarfx::irradiance_maps_options maps_options{
        .sky = {.svf_method = svf == "cosine" ? lidarfx::sky_view_factor_method::cosine_weighted
                                              : lidarfx::sky_view_factor_method::source_share,
                .svf_directions = svf_directions,
                .diffuse = diffuse == "perez" ? lidarfx::diffuse_model::perez : lidarfx::diffuse_model::isotropic},
        .run = {.threads = threads, .progress = cli::progress_bar("irradiance")}};
    // Each cell's own plane (--surface terrain): Horn's slope and aspect of the DSM, flat cells facing north.
    lidarfx::slope_aspect_result orientation;
    if (terrain) orientation = lidarfx::slope_aspect(dsm, cell_m, {.run = {.threads = threads}});
    const auto res = lidarfx::irradiance_maps(dsm, cell_m, site, records, orientation.slope_deg.view(),
                                              orientation.aspect_deg.view(), maps_options);
    std::cout << "sky view factor: " << svf_description(svf, svf_directions) << " (svf.* and the diffuse part)\n";
    std::cout << "surfaces: " << (terrain ? "each cell's own slope and aspect" : "horizontal") << "\n";
    std::cout << std::fixed << std::setprecision(1) << "daylight records: " << res.sun_up_records << " of "
              << records.size() << "; GHI of the year " << res.ghi_kwh_m2 << " kWh/m2\n";

    // The maps and their figures are written side by side (each file by one thread; the bytes do not depend on it).
    std::vector<std::function<void()>> writes;
    writes.emplace_back(
        [&] { cli::write_raster(out, "annual_kwh_m2", res.annual_kwh_m2.view(), g, crs_wkt, epsg, formats); });
    writes.emplace_back([&] { cli::write_raster(out, "svf", res.sky_view_factor.view(), g, crs_wkt, epsg, formats); });
    std::array<map_stats, 12> month_stats;
    for (int m = 0; m < 12; ++m) {
        writes.emplace_back([&, m] {
            const auto i = static_cast<std::size_t>(m);
            char name[32];
            std::snprintf(name, sizeof name, "month_%02d_kwh_m2", m + 1);
            cli::write_raster(out, name, res.month_kwh_m2[i].view(), g, crs_wkt, epsg, formats);
            month_stats[i] = stats_of(res.month_kwh_m2[i]);
        });
    }
    if (formats.png) {
        namespace io = lidarfx::io;
        // Figures on the input's grid: the cell in the CRS's unit, cells without a value as no data.
        const auto legend_png = [&](const std::string& name, const lidarfx::raster<float>& m, const std::string& what,
                                    const char* unit) {
            const io::figure_bar bar = io::finite_bar(m, unit);
            const io::figure fig = io::make_figure(io::colorize(m.view(), bar.min, bar.max), io::non_finite_cells(m),
                                                   {.title = name + ": " + what + " (" + unit + ")",
                                                    .cell_size = g.cell,
                                                    .unit = io::short_unit_name(cell_m / g.cell, "units"),
                                                    .bar = bar});
            out.write(name, [&](const std::string& path) { io::write_png_rgb(path, fig.image); });
        };
        writes.emplace_back([&, legend_png] {
            legend_png("annual_kwh_m2.png", res.annual_kwh_m2,
                       terrain ? "annual irradiation, terrain surfaces" : "annual irradiation, horizontal surfaces",
                       "kWh/m²");
        });
        writes.emplace_back([&, legend_png] {
            legend_png("svf.png", res.sky_view_factor, "sky view factor, " + svf_description(svf, svf_directions),
                       "SVF");
        });
    }
    cli::run_jobs(writes, threads);
    std::vector<std::vector<lidarfx::io::table_value>> rows;
    for (std::size_t m = 0; m < 12; ++m) {
        const map_stats& st = month_stats[m];
        rows.push_back({static_cast<int>(m) + 1, st.mean, st.min, st.max, res.month_ghi_kwh_m2[m]});
    }
    const map_stats year = stats_of(res.annual_kwh_m2);
    rows.push_back({"year", year.mean, year.min, year.max, res.ghi_kwh_m2});
    out.write("dsm_outliers.csv", [&](const std::string& path) {
        namespace io = lidarfx::io;
        std::vector<std::vector<io::table_value>> table;
        for (const outlier_row& o : outlier_rows)
            table.push_back({o.kind, o.row, o.col, o.x, o.y, o.z_m, o.replaced_by_m});
        io::write_csv(path,
                      {io::text_column("kind"), io::text_column("row"), io::text_column("col"), io::crs_column("x_crs"),
                       io::crs_column("y_crs"), io::metres_column("z_m"), io::metres_column("replaced_by_m")},
                      table);
    });
    out.write("summary.csv", [&](const std::string& path) {
        namespace io = lidarfx::io;
        io::write_csv(path,
                      {io::text_column("month"), io::kwh_m2_column("mean_kwh_m2"), io::kwh_m2_column("min_kwh_m2"),
                       io::kwh_m2_column("max_kwh_m2"), io::kwh_m2_column("ghi_kwh_m2")},
                      rows);
    });
    std::cout << "annual irradiation: mean " << year.mean << ", min " << year.min << ", max " << year.max
              << " kWh/m2\n";
    out.set_units_note("kWh/m2 per cell (" +
                       std::string(terrain ? "each cell's own slope and aspect" : "horizontal surfaces") +
                       "), SVF in [0, 1] (" + svf_description(svf, svf_directions) +
                       "), on the input's grid; sun for " + place.description);
    if (a.has("facades")) {
        cli::write_facade_outputs(
            out, {.dsm = dsm.view(),
                  .returns = {points.view(), split_points.view(), raised.counts.view(), raised.lowest.view()},
                  .ground = class_ground.view(),
                  .classified_buildings = classified_buildings.view(),
                  .cell_m = cell_m,
                  .grid_crs = g,
                  .crs_wkt = crs_wkt,
                  .epsg = epsg,
                  .site = site,
                  .records = records,
                  .threads = threads,
                  .png = formats.png,
                  .formats = formats});
    }
    cli::commit_and_report(out, cli::command_line("solar", args));
    return 0;
}

const lidarfx::cli::registration reg{"solar", "DSM or LAS files + TMY3 -> annual and monthly irradiation maps",
                                     run_solar};

}  // namespace
