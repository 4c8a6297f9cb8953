// SPDX-License-Identifier: Apache-2.0
#include "elevation_input.hpp"

#include <cmath>
#include <iostream>
#include <utility>

#include "io/ascii_grid.hpp"
#include "io/geotiff.hpp"

namespace lidarfx::cli {

namespace {

/// Metres per unit of the unit option `--option` (m, ft, us-ft) and the unit's name; {0, ""} when not given.
std::pair<double, std::string> unit_option(const arguments& a, const std::string& option)
{
    if (!a.has(option)) return {0.0, ""};
    const std::string u = a.text(option, "");
    if (u == "m") return {io::metre_m, "metre"};
    if (u == "ft") return {io::international_foot_m, "foot"};
    if (u == "us-ft") return {io::us_survey_foot_m, "US survey foot"};
    throw usage_error("--" + option + " must be m, ft (international foot) or us-ft (US survey foot) (got " + u + ")");
}

bool is_ascii_grid(const std::string& path)
{
    return has_extension(path, ".asc");
}

/// Refuses a raster format this lidarfx cannot read (anything but ESRI ASCII without GDAL).
void require_reader(const std::string& path)
{
    if (is_ascii_grid(path) || io::geotiff_available()) return;
    throw usage_error(path +
                      ": rasters other than ESRI ASCII are read through GDAL, and this lidarfx was built without "
                      "it: convert it (gdal_translate -of AAIGrid " +
                      path +
                      " DSM.asc; the .prj GDAL writes beside it keeps the CRS) or install libgdal-dev and "
                      "rebuild");
}

}  // namespace

bool is_point_cloud_path(const std::string& path)
{
    return has_extension(path, ".las") || has_extension(path, ".laz");
}

io::survey_crs raster_crs(const std::string& path, const arguments& a)
{
    require_reader(path);
    const bool ascii = is_ascii_grid(path);
    // Where the CRS comes from, for messages: the .prj beside an ESRI ASCII grid, the file itself otherwise.
    const std::string source = ascii ? io::prj_path_of(path) : path;
    const std::string wkt = ascii ? io::read_prj_beside(path) : io::read_geotiff_crs(path);
    io::survey_crs crs = io::crs_of_wkt(wkt);
    for (const auto& w : crs.warnings) std::cerr << "lidarfx: warning: " << source << ": " << w << '\n';
    if (crs.geographic) {
        throw usage_error(path + ": x and y are longitude and latitude in degrees (" + crs.describe() + ", from " +
                          source +
                          "), but cells, heights and areas are measured in metres. Reproject it to a projected CRS "
                          "first, e.g. gdalwarp -t_srs EPSG:<the UTM zone's code> " +
                          path + " OUT.tif");
    }
    if (!io::crs_understood(crs.wkt)) crs.wkt.clear();
    const auto [xy_m, xy_name] = unit_option(a, "xy-unit");
    const auto [z_m, z_name] = unit_option(a, "z-unit");
    if (crs.source.empty()) {  // no CRS: the units are what the user says
        if (xy_m == 0 || z_m == 0) {
            const std::string why = !ascii        ? "the file states no CRS"
                                    : wkt.empty() ? "no " + source + " beside it"
                                                  : source + " names no CRS";
            const std::string fix =
                ascii ? "put the grid's CRS beside it (gdalsrsinfo -o wkt_esri EPSG:<code> > " + source + ")"
                      : "give the file its CRS (gdal_edit.py -a_srs EPSG:<code> " + path + ")";
            throw usage_error(path + ": the units of this raster are unknown (" + why +
                              "): state them with --xy-unit m|ft|us-ft and --z-unit m|ft|us-ft, or " + fix);
        }
        crs.horizontal_unit_m = xy_m;
        crs.horizontal_unit = xy_name;
        crs.vertical_unit_m = z_m;
        crs.vertical_unit = z_name;
        return crs;
    }
    const auto differs = [](double given, double m) { return given != 0 && std::abs(given - m) > 1e-12 * m; };
    if (differs(xy_m, crs.horizontal_unit_m) || differs(z_m, crs.vertical_unit_m)) {
        throw usage_error(path + ": --xy-unit/--z-unit disagree with its CRS in " + source + " (" + crs.describe() +
                          ", z in " + crs.vertical_unit + "): leave them out or fix the CRS");
    }
    return crs;
}

grid raster_file_grid(const std::string& path)
{
    require_reader(path);
    return is_ascii_grid(path) ? io::read_ascii_grid_header(path).g : io::read_geotiff_grid(path);
}

elevation_raster read_elevation_raster(const std::string& path, const io::survey_crs& crs)
{
    require_reader(path);
    elevation_raster out;
    std::size_t non_finite = 0;
    if (is_ascii_grid(path)) {
        out.values = io::read_ascii_grid(path, out.file_grid, &non_finite);
    } else {
        io::geotiff_raster t = io::read_geotiff(path);
        out.values = std::move(t.values);
        out.file_grid = t.g;
        non_finite = t.non_finite_cells;
    }
    report_non_finite_heights(path, non_finite);
    if (crs.vertical_unit_m != 1.0) {
        for (float& v : out.values) v = static_cast<float>(v * crs.vertical_unit_m);
    }
    out.g = out.file_grid;
    out.g.x0 *= crs.horizontal_unit_m;
    out.g.y0 *= crs.horizontal_unit_m;
    out.g.cell *= crs.horizontal_unit_m;
    return out;
}

}  // namespace lidarfx::cli
