// SPDX-License-Identifier: Apache-2.0
// The roof outputs of `lidarfx roofs` and `lidarfx demo`: roof patches as a table, polygons and a picture.
#include "roof_outputs.hpp"

#include <cmath>
#include <cstdint>
#include <map>
#include <utility>

#include <lidarfx/lidarfx.hpp>

#include "io/figure.hpp"
#include "io/png.hpp"
#include "io/quicklook.hpp"
#include "io/tables.hpp"

namespace lidarfx::cli {
namespace {

// A figure of the patches: azimuth (clockwise from grid north) on a cyclic wheel, so 0 and 359 degrees look
// alike (north blue, east green, south yellow, west red-magenta), flat patches white, other cells a dim
// hillshade, suitable patches outlined in black, cells without a surface height as no data.
io::rgb_image patch_picture(const roof_suitability_result& r, const roof_output_frame& frame)
{
    raster<float> azimuth(r.patch_id.rows(), r.patch_id.cols(), NAN);
    std::map<std::int32_t, const roof_patch*> by_id;
    for (const roof_patch& p : r.patches) by_id[p.patch_id] = &p;
    for (std::ptrdiff_t y = 0; y < azimuth.rows(); ++y)
        for (std::ptrdiff_t x = 0; x < azimuth.cols(); ++x)
            if (const auto it = by_id.find(r.patch_id(y, x)); it != by_id.end() && !it->second->flat)
                azimuth(y, x) = static_cast<float>(it->second->azimuth_deg);
    io::rgb_image img =
        io::colorize_over_hillshade(azimuth.view(), 0.0, 360.0, frame.dsm, frame.cell_m, io::cyclic_color);
    const auto patch = [&](std::ptrdiff_t y, std::ptrdiff_t x) -> const roof_patch* {
        if (y < 0 || x < 0 || y >= azimuth.rows() || x >= azimuth.cols()) return nullptr;
        const auto it = by_id.find(r.patch_id(y, x));
        return it == by_id.end() ? nullptr : it->second;
    };
    const auto suitable = [&](std::ptrdiff_t y, std::ptrdiff_t x) {
        const roof_patch* p = patch(y, x);
        return p && p->suitable;
    };
    for (std::ptrdiff_t y = 0; y < azimuth.rows(); ++y)
        for (std::ptrdiff_t x = 0; x < azimuth.cols(); ++x) {
            std::uint8_t* px = &img.rgb[static_cast<std::size_t>((y * img.width + x) * 3)];
            if (const roof_patch* p = patch(y, x); p && p->flat) px[0] = px[1] = px[2] = 255;
            if (suitable(y, x) &&
                !(suitable(y - 1, x) && suitable(y + 1, x) && suitable(y, x - 1) && suitable(y, x + 1))) {
                px[0] = px[1] = px[2] = 0;  // the edge of a suitable patch
            }
        }
    const double unit_cell = frame.grid_crs.cell > 0 ? frame.grid_crs.cell : frame.cell_m / frame.unit_m;
    const auto fig = io::make_figure(
        img, io::non_finite_cells(frame.dsm),
        {.title = "roof_patches.png: roof patches by azimuth (clockwise from grid north)",
         .cell_size = unit_cell,
         .unit = io::short_unit_name(frame.unit_m, "units"),
         .key = io::compass_key(
             {{{255, 255, 255}, "flat"}, {{0, 0, 0}, "suitable patch edge"}, {{64, 64, 64}, "other (hillshade)"}})});
    return fig.image;
}

}  // namespace

std::vector<std::string> roof_patch_file_names(const output_formats& formats)
{
    std::vector<std::string> names;
    if (formats.csv) names.push_back("roof_patches.csv");
    for (auto& n : polygon_file_names("roof_patches", formats)) names.push_back(std::move(n));
    if (formats.png) names.push_back("roof_patches.png");
    return names;
}

void write_roof_patches(io::output_folder& out, const roof_suitability_result& r, const roof_output_frame& frame,
                        const output_formats& formats, std::span<const roof_patch_yield> yields)
{
    // Patches: centroids and outlines in the input's CRS units; areas in m2.
    std::vector<std::vector<io::table_value>> rows;
    for (const roof_patch& p : r.patches) {
        rows.push_back({p.building_id, p.patch_id, p.tilt_deg, p.azimuth_deg, p.area_m2, p.sloped_area_m2, p.kwp,
                        std::int64_t{p.suitable ? 1 : 0}, p.centroid_x / frame.unit_m, p.centroid_y / frame.unit_m,
                        std::int64_t{p.flat ? 1 : 0}, p.reason});
        if (!yields.empty()) {
            const roof_patch_yield& y = yields[rows.size() - 1];
            rows.back().push_back(y.annual_kwh_m2);
            rows.back().push_back(y.annual_kwh);
        }
    }
    // The columns in docs/pv.md.
    std::vector<io::csv_column> header{io::text_column("building_id"),
                                       io::text_column("patch_id"),
                                       io::degrees_column("tilt_deg"),
                                       io::degrees_column("azimuth_deg"),
                                       io::area_column("area_m2"),
                                       io::area_column("sloped_area_m2"),
                                       io::kwp_column("kwp"),
                                       io::text_column("suitable"),
                                       io::crs_column("centroid_x_crs"),
                                       io::crs_column("centroid_y_crs"),
                                       io::text_column("flat"),
                                       io::text_column("reason")};
    if (!yields.empty()) {
        header.push_back(io::kwh_m2_column("annual_kwh_m2"));
        header.push_back(io::kwh_column("annual_kwh"));
    }
    if (formats.csv) out.write("roof_patches.csv", [&](const std::string& path) { io::write_csv(path, header, rows); });
    std::map<std::int32_t, std::size_t> index_of;
    for (std::size_t i = 0; i < r.patches.size(); ++i) index_of[r.patches[i].patch_id] = i;
    std::vector<io::geojson_feature> features;
    for (const auto& lp : polygonize(r.patch_id, frame.grid_crs)) {
        const std::size_t i = index_of.at(lp.label);
        const roof_patch& p = r.patches[i];
        for (const auto& poly : lp.polygons) {
            features.push_back({poly.rings,
                                {{"building_id", p.building_id},
                                 {"patch_id", p.patch_id},
                                 {"tilt_deg", p.tilt_deg},
                                 {"azimuth_deg", p.azimuth_deg},
                                 {"area_m2", p.area_m2},
                                 {"sloped_area_m2", p.sloped_area_m2},
                                 {"kwp", p.kwp},
                                 {"suitable", p.suitable}}});
            if (!yields.empty()) {
                features.back().properties.emplace_back("annual_kwh_m2", yields[i].annual_kwh_m2);
                features.back().properties.emplace_back("annual_kwh", yields[i].annual_kwh);
            }
        }
    }
    write_polygons(out, "roof_patches", features, frame.crs_wkt, frame.epsg, formats);
    if (formats.png) {
        const io::rgb_image img = patch_picture(r, frame);
        out.write("roof_patches.png", [&](const std::string& path) { io::write_png_rgb(path, img); });
    }
    out.set_units_note(
        "areas in m2 (horizontal area_m2, sloped_area_m2), angles in degrees (azimuth clockwise from "
        "grid north), centroids and outlines in the input's CRS units");
}

}  // namespace lidarfx::cli
