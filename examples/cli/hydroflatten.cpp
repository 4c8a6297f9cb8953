// SPDX-License-Identifier: Apache-2.0
// lidarfx hydroflatten: a hydro-flattened bare-earth DEM, breaklines and the specification's checks from LAS files.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include <lidarfx/lidarfx.hpp>

#include "command.hpp"
#include "io/geotiff.hpp"
#include "io/vectors.hpp"
#include "io/vectors_z.hpp"
#include "outputs.hpp"
#include "tile_store.hpp"
#include "tiled_survey.hpp"
#include "water_run.hpp"

namespace lidarfx::cli {

namespace {

constexpr const char* usage =
    "usage: lidarfx hydroflatten IN.las|IN.laz|DIR [MORE ...] --cell METRES --out DIR [options]\n"
    "Hydro-flattens the survey's bare-earth DEM: finds its waterbodies as `lidarfx water` does, gives every lake one\n"
    "level and every river flat cross-sections whose levels only fall downstream (decks bridged at the interpolated\n"
    "level, islands under --min-island-area flattened with the water), raises shore ground that lies below the water\n"
    "beside it, and checks the result. Writes dem_hydroflattened.tif (GeoTIFF with the CRS; .asc with .prj under\n"
    "--formats asc instead, both with asc,tif), breaklines.gpkg (layers water_bodies: 3D polygons at the water\n"
    "level, river_centrelines: 3D lines through the sections), hydro_bodies.csv and hydro_qa.csv. Heights in the DEM\n"
    "and the breaklines are in the CRS's height unit (metres, or feet for a survey in feet), in the tables metres.\n"
    "The bare-earth DEM is the lowest return of each cell, its empty cells filled by inverse distance weighting, no\n"
    "data outside the area flown. Maps and lines in the files' CRS. Water smaller than the minimum sizes is left to\n"
    "the terrain.\n"
    "options (defaults in brackets; the options of `lidarfx water` apply too):\n"
    "  --cell M              cell size, metres [2]\n"
    "  --min-lake-area A     lakes and ponds at least this large are flattened, m2 [8093.71 = 2 acres]\n"
    "  --min-river-width M   rivers at least this wide (area / length) are flattened, metres [30.48 = 100 ft]\n"
    "  --min-island-area A   islands at least this large stay land, m2 [4046.86 = 1 acre]\n"
    "  --shoreline RULE      lift: raise shore ground below the water to it; flag: only count it [lift]\n"
    "  --threads N           threads, 0 = all cores [0]; same result\n"
    "  --tile M              read the survey in tiles of M x M metres (see lidarfx water --help) [0]; same result\n"
    "  --memory SIZE         refuse grids whose estimate exceeds SIZE (4GiB, 512MiB) [half the memory]\n"
    "  --crop X0,Y0,X1,Y1    only points inside this box, in the units of the files' CRS\n"
    "  --formats LIST        any of asc,tif,csv,gpkg [tif,csv,gpkg; asc without GDAL]\n"
    "  --force               run even when the inputs cannot support the waterbody method\n";

/// What hydroflatten keeps per cell beyond `lidarfx water`: the DEM and its flattened copy, the filled labels,
/// the water heights and surface, the body ids, the IDW fill's index and a river's sections and geodesic distances,
/// bytes.
constexpr double hydro_bytes_per_cell = water_bytes_per_cell + 64;

std::vector<std::string> hydro_value_options()
{
    auto names = water_value_options();
    names.insert(names.end(), {"min-lake-area", "min-river-width", "min-island-area", "shoreline"});
    return names;
}

/// --formats of hydroflatten: without a raster format named, the DEM is written as GeoTIFF only (as ASCII grid
/// when lidarfx has no GDAL); vectors are csv and gpkg unless named.
output_formats hydro_formats(const arguments& a)
{
    output_formats f = output_formats_from(a);
    const std::string list = a.text("formats", "");
    const auto names = [&](const char* n) { return list.find(n) != std::string::npos; };
    if (names("png") || names("geojson"))
        throw usage_error("--formats of hydroflatten: asc, tif, csv and gpkg (png and geojson are not written)");
    if (!names("asc") && !names("tif")) {
        f.tif = io::geotiff_available();
        f.asc = !f.tif;
    }
    f.png = f.geojson = false;
    return f;
}

std::string fixed(double v, int decimals)
{
    std::ostringstream s;
    s << std::fixed << std::setprecision(decimals) << v;
    return s.str();
}

/// The bare-earth DEM of the survey: lowest returns, holes filled by IDW, NaN outside the footprint.
raster<float> bare_earth(const survey& s, raster_view<const std::uint8_t> footprint, int threads)
{
    raster<float> dem = idw_fill(s.rasters.min_z, s.rasters.g.cell, {.run = {.threads = threads}}).filled;
    for (std::ptrdiff_t r = 0; r < dem.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < dem.cols(); ++c)
            if (!footprint(r, c)) dem(r, c) = NAN;
    return dem;
}

/// The body `id` of `h` (its bodies are in increasing id).
const hydro_body& body_of(const hydro_flatten_result& h, std::int32_t id)
{
    const auto at = std::lower_bound(h.bodies.begin(), h.bodies.end(), id,
                                     [](const hydro_body& b, std::int32_t wanted) { return b.id < wanted; });
    if (at == h.bodies.end() || at->id != id) throw std::logic_error("hydroflatten: no body " + std::to_string(id));
    return *at;
}

const char* type_name(const hydro_body& b)
{
    return b.type == hydro_body_type::river ? "river" : "lake";
}

/// The 3D polygons of the flattened bodies: each vertex (a cell corner) at the highest water level of the body's
/// cells around it, so that no breakline lies below its water.
io::layer_z water_body_layer(const hydro_flatten_result& h, const grid& in_crs)
{
    io::layer_z layer{"water_bodies", io::geometry_z::polygon, {}};
    const auto z_at = [&](std::int32_t id, double x, double y) {
        const auto col = static_cast<std::ptrdiff_t>(std::lround((x - in_crs.x0) / in_crs.cell));
        const auto row = static_cast<std::ptrdiff_t>(std::lround((in_crs.y0 - y) / in_crs.cell));
        double z = -INFINITY;
        for (std::ptrdiff_t r = row - 1; r <= row; ++r)
            for (std::ptrdiff_t c = col - 1; c <= col; ++c)
                if (r >= 0 && c >= 0 && r < h.body.rows() && c < h.body.cols() && h.body(r, c) == id)
                    z = std::max(z, static_cast<double>(h.water_surface(r, c)));
        return z;
    };
    for (const auto& lp : polygonize(h.body, in_crs)) {
        const hydro_body& b = body_of(h, lp.label);
        for (const auto& poly : lp.polygons) {
            io::feature_z f;
            for (const auto& ring : poly.rings) {
                std::vector<io::xyz> part;
                for (const auto& p : ring) part.push_back({p[0], p[1], z_at(lp.label, p[0], p[1])});
                f.parts.push_back(std::move(part));
            }
            f.properties = {{"id", b.id},
                            {"type", std::string(type_name(b))},
                            {"level_min_m", b.level_min_m},
                            {"level_max_m", b.level_max_m}};
            layer.features.push_back(std::move(f));
        }
    }
    return layer;
}

/// One 3D line per flattened river through the centres of its sections, upstream first, at their levels.
io::layer_z river_centre_layer(const hydro_flatten_result& h, const grid& in_crs)
{
    io::layer_z layer{"river_centrelines", io::geometry_z::line, {}};
    for (const auto& b : h.bodies) {
        if (!b.flattened || b.type != hydro_body_type::river) continue;
        std::vector<io::xyz> line;
        for (std::size_t k = 0; k < b.river.level_m.size(); ++k)
            if (b.river.cells[k] > 0)
                line.push_back({in_crs.x0 + (b.river.centre[k][1] + 0.5) * in_crs.cell,
                                in_crs.y0 - (b.river.centre[k][0] + 0.5) * in_crs.cell, b.river.level_m[k]});
        if (line.size() < 2) continue;
        layer.features.push_back(
            {{std::move(line)}, {{"id", b.id}, {"level_max_m", b.level_max_m}, {"level_min_m", b.level_min_m}}});
    }
    return layer;
}

void write_hydro_outputs(io::output_folder& out, const survey& s, const hydro_flatten_result& h,
                         const output_formats& formats)
{
    const grid in_crs = to_crs_units(s.rasters.g, s);
    // The DEM and the breaklines' Z speak the CRS's height unit, as every raster file of the program does; the
    // tables keep metres (their columns say so).
    const height_unit heights = file_height_unit(s);
    out.set_units_note("dem_hydroflattened and the breaklines' Z in " + heights.name + "; " + units_note(s));
    raster<float> dem = h.dem;
    for (float& v : dem) v = static_cast<float>(v / heights.metres);
    write_raster(out, "dem_hydroflattened", dem, in_crs, s.crs_wkt, s.epsg, formats);
    if (formats.csv) {
        const std::vector<io::csv_column> bodies_header{
            io::text_column("id"),        io::text_column("type"),          io::text_column("flattened"),
            io::area_column("area_m2"),   io::metres_column("length_m"),    io::metres_column("width_m"),
            io::metres_column("level_m"), io::metres_column("level_min_m"), io::metres_column("level_max_m"),
            io::metres_column("drop_m"),  io::text_column("sections"),      io::text_column("weirs"),
            io::crs_column("xmin_crs"),   io::crs_column("ymin_crs"),       io::crs_column("xmax_crs"),
            io::crs_column("ymax_crs")};
        std::vector<std::vector<io::table_value>> rows;
        for (const auto& b : h.bodies) {
            const bool lake = b.type == hydro_body_type::lake;
            const bounds e = in_crs.extent(b.box);
            rows.push_back({b.id, std::string(type_name(b)), std::int64_t{b.flattened ? 1 : 0}, b.shape.area_m2,
                            b.shape.length_m, b.shape.width_m, lake ? b.level_min_m : NAN, b.level_min_m, b.level_max_m,
                            b.flattened ? b.drop_m() : NAN, static_cast<std::uint64_t>(b.river.level_m.size()),
                            static_cast<std::uint64_t>(b.river.weirs), e.xmin, e.ymin, e.xmax, e.ymax});
        }
        out.write("hydro_bodies.csv", [&](const std::string& path) { io::write_csv(path, bodies_header, rows); });

        // One row per flattened body: each check's measure, limit and verdict, and where its worst offender is.
        const std::vector<io::csv_column> qa_header{io::text_column("id"),
                                                    io::text_column("type"),
                                                    io::text_column("pass"),
                                                    io::metres_column("flatness_m"),
                                                    io::metres_column("flatness_limit_m"),
                                                    io::text_column("flatness_pass"),
                                                    io::text_column("uphill_sections"),
                                                    io::text_column("monotonic_pass"),
                                                    io::text_column("shore_cells_below"),
                                                    io::metres_column("shore_worst_m"),
                                                    io::text_column("shoreline_pass"),
                                                    io::text_column("shore_cells_lifted"),
                                                    io::area_column("area_m2"),
                                                    io::area_column("min_area_m2"),
                                                    io::metres_column("width_m"),
                                                    io::metres_column("min_width_m"),
                                                    io::text_column("size_pass"),
                                                    io::text_column("worst_check"),
                                                    io::crs_column("worst_x_crs"),
                                                    io::crs_column("worst_y_crs")};
        std::vector<std::vector<io::table_value>> qa;
        for (std::size_t i = 0; i < h.qa.size();) {
            const std::int32_t id = h.qa[i].body;
            const hydro_body& b = body_of(h, id);
            const bool river = b.type == hydro_body_type::river;
            std::vector<io::table_value> row(qa_header.size());
            const auto cell = [&](const char* name) -> io::table_value& {
                const auto at = std::find_if(qa_header.begin(), qa_header.end(),
                                             [&](const io::csv_column& column) { return column.name == name; });
                return row[static_cast<std::size_t>(at - qa_header.begin())];
            };
            cell("id") = id, cell("type") = std::string(type_name(b));
            cell("shore_cells_lifted") = static_cast<std::uint64_t>(b.shore_cells_lifted);
            bool all = true;
            const hydro_check* worst = nullptr;
            for (; i < h.qa.size() && h.qa[i].body == id; ++i) {
                const hydro_check& q = h.qa[i];
                all = all && q.pass;
                if (!q.pass && q.worst_row >= 0 && worst == nullptr) worst = &q;
                const std::int64_t pass = q.pass ? 1 : 0;
                switch (q.kind) {
                    case hydro_check_kind::flatness:
                        cell("flatness_m") = q.value, cell("flatness_limit_m") = q.limit, cell("flatness_pass") = pass;
                        break;
                    case hydro_check_kind::monotonic_fall:
                        cell("uphill_sections") = static_cast<std::int64_t>(q.value), cell("monotonic_pass") = pass;
                        break;
                    case hydro_check_kind::shoreline:
                        cell("shore_cells_below") = static_cast<std::int64_t>(q.value),
                        cell("shore_worst_m") = q.worst_m;
                        cell("shoreline_pass") = pass;
                        break;
                    case hydro_check_kind::minimum_size:
                        cell(river ? "width_m" : "area_m2") = q.value;
                        cell(river ? "min_width_m" : "min_area_m2") = q.limit, cell("size_pass") = pass;
                        break;
                }
            }
            cell("pass") = std::int64_t{all ? 1 : 0};
            if (worst != nullptr) {
                cell("worst_check") = std::string(hydro_check_name(worst->kind));
                cell("worst_x_crs") = in_crs.x0 + (static_cast<double>(worst->worst_col) + 0.5) * in_crs.cell;
                cell("worst_y_crs") = in_crs.y0 - (static_cast<double>(worst->worst_row) + 0.5) * in_crs.cell;
            }
            qa.push_back(std::move(row));
        }
        out.write("hydro_qa.csv", [&](const std::string& path) { io::write_csv(path, qa_header, qa); });
    }
    if (formats.gpkg) {
        std::vector<io::layer_z> layers{water_body_layer(h, in_crs), river_centre_layer(h, in_crs)};
        for (auto& layer : layers)
            for (auto& feature : layer.features)
                for (auto& part : feature.parts)
                    for (auto& vertex : part) vertex[2] /= heights.metres;
        out.write("breaklines.gpkg",
                  [&](const std::string& path) { io::write_geopackage_z(path, layers, s.crs_wkt, s.epsg); });
    }
}

void print_hydro(const hydro_flatten_result& h)
{
    std::size_t flattened = 0, failed = 0;
    for (const auto& b : h.bodies) flattened += b.flattened;
    for (const auto& q : h.qa) failed += !q.pass;
    std::cout << "hydro-flattened: " << flattened << " of " << h.bodies.size() << " waterbodies ("
              << h.island_cells_flattened << " island cells flattened with the water, " << h.decks.deck_cells
              << " under bridge decks and " << h.decks.level_cells << " beside them, " << h.shorelines.below
              << " shore cells below the water)\n";
    for (const auto& b : h.bodies) {
        if (!b.flattened) continue;
        std::cout << "  #" << b.id << "  " << type_name(b) << "  " << fixed(b.shape.area_m2, 0) << " m2  width "
                  << fixed(b.shape.width_m, 1) << " m  level " << fixed(b.level_min_m, 3);
        if (b.type == hydro_body_type::river) std::cout << " .. " << fixed(b.level_max_m, 3) << " m";
        std::cout << '\n';
    }
    std::cout << "checks: " << h.qa.size() - failed << " of " << h.qa.size() << " pass\n";
}

int run_hydroflatten(const std::vector<std::string>& args)
{
    const arguments a(args, hydro_value_options(), water_flag_options());
    if (const auto code = stop_for_usage(a, usage, true)) return *code;
    auto [water, hull_radius_m] = water_method_from(a);
    hydro_flatten_options opt;
    opt.min_lake_area_m2 = a.number("min-lake-area", opt.min_lake_area_m2);
    opt.min_river_width_m = a.number("min-river-width", opt.min_river_width_m);
    opt.min_island_area_m2 = a.number("min-island-area", opt.min_island_area_m2);
    const std::string shoreline = a.text("shoreline", "lift");
    if (shoreline != "lift" && shoreline != "flag")
        throw usage_error("--shoreline must be lift or flag (got " + shoreline + ")");
    opt.shoreline = shoreline == "lift" ? shoreline_rule::lift : shoreline_rule::flag;
    for (const auto& [flag, value, unit] : {std::tuple{"min-lake-area", opt.min_lake_area_m2, "m2"},
                                            std::tuple{"min-river-width", opt.min_river_width_m, "metres"},
                                            std::tuple{"min-island-area", opt.min_island_area_m2, "m2"}})
        if (!(value >= 0 && std::isfinite(value)))
            throw usage_error("--" + std::string(flag) + " must be a finite number >= 0 (" + unit + "; got " +
                              fixed(value, 3) + ")");
    opt.run.threads = water.run.threads;
    auto survey_options = survey_options_from(a, hydro_bytes_per_cell);
    survey_options.formats = hydro_formats(a);
    const double tile_edge_m = tile_edge_from(a);
    const auto files = survey_files(a.positional());
    io::output_folder out(a.text("out", ""), {files.begin(), files.end()});
    for (const auto& name : raster_file_names("dem_hydroflattened", survey_options.formats)) out.declare(name);
    for (const auto* name : {"hydro_bodies.csv", "hydro_qa.csv", "breaklines.gpkg"}) out.declare(name);
    const std::filesystem::path tiles_dir = out.path() / ".lidarfx-tiles";
    const auto s = read_survey_local(files, survey_options, tile_edge_m, tiles_dir);
    print_survey(s);
    const auto found = find_waterbodies(s, water, hull_radius_m);
    print_diagnostics(found.result.diagnostics);
    if (!found.result.ran) {
        std::cerr << "lidarfx hydroflatten: these data cannot support waterbody extraction (see above); nothing was "
                     "written. Use --force to run anyway.\n";
        return 3;
    }
    print_waterbodies(found.result);
    const raster<float> dem = bare_earth(s, found.footprint, opt.run.threads);
    opt.run.progress = progress_bar("hydro-flattening");
    const auto h = hydro_flatten(dem, found.result.labels, s.rasters.min_z, s.rasters.max_z, s.rasters.g.cell, opt);
    print_hydro(h);
    write_hydro_outputs(out, s, h, survey_options.formats);
    commit_and_report(out, command_line("hydroflatten", args));
    if (tile_edge_m > 0) remove_tile_folder(tiles_dir);
    return 0;
}

const registration reg{"hydroflatten", "LAS files -> hydro-flattened DEM, breaklines and the specification's checks",
                       run_hydroflatten};

}  // namespace

}  // namespace lidarfx::cli
