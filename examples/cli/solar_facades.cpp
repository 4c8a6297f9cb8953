// SPDX-License-Identifier: Apache-2.0
#include "solar_facades.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>

#include <lidarfx/kernels/vector/polygonize.hpp>
#include <lidarfx/pipelines/buildings/extract_buildings.hpp>
#include <lidarfx/pipelines/buildings/surface_class_table.hpp>
#include <lidarfx/pipelines/buildings/surface_energy.hpp>

#include "io/figure.hpp"
#include "io/png.hpp"
#include "io/quicklook.hpp"
#include "io/tables.hpp"

namespace lidarfx::cli {
namespace {

constexpr const char* class_names[5] = {"north facade", "south facade", "east facade", "west facade", "rooftop"};

// Roof cells coloured by the energy of the quad patch they start, the ground cell in front of each wall by the
// mean of its sub-patches, the rest a dim hillshade; a colour bar in kWh/m2 below.
io::rgb_image energy_picture(const facade_run& run, const surface_energy_result& e)
{
    const std::ptrdiff_t rows = run.dsm.rows(), cols = run.dsm.cols();
    raster<float> energy(rows, cols, std::numeric_limits<float>::quiet_NaN());
    for (std::size_t i = 0; i < e.roofs.size(); ++i)
        energy(e.roofs[i].row, e.roofs[i].col) = static_cast<float>(e.roof_energy[i].annual_kwh_m2);
    std::map<std::pair<std::ptrdiff_t, std::ptrdiff_t>, std::pair<double, int>> walls;
    for (std::size_t i = 0; i < e.facades.size(); ++i) {
        auto& w = walls[{e.facades[i].front_row, e.facades[i].front_col}];
        w.first += e.facade_energy[i].annual_kwh_m2;
        ++w.second;
    }
    for (const auto& [cell, sum] : walls) energy(cell.first, cell.second) = static_cast<float>(sum.first / sum.second);
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c)
            if (std::isfinite(energy(r, c))) {
                lo = std::min(lo, static_cast<double>(energy(r, c)));
                hi = std::max(hi, static_cast<double>(energy(r, c)));
            }
    if (!(lo <= hi)) lo = hi = 0.0;
    const io::rgb_image img = io::colorize_over_hillshade(energy.view(), lo, hi, run.dsm, run.cell_m);
    const double unit_cell = run.grid_crs.cell > 0 ? run.grid_crs.cell : run.cell_m;
    return io::make_figure(img, io::non_finite_cells(run.dsm),
                           {.title = "buildings_energy.png: annual irradiation of roofs and walls (kWh/m²)",
                            .cell_size = unit_cell,
                            .unit = io::short_unit_name(run.cell_m / unit_cell, "units"),
                            .bar = io::figure_bar{lo, hi, "kWh/m² per year"},
                            .key = {{{64, 64, 64}, "ground (hillshade)"}}})
        .image;
}

}  // namespace

std::vector<std::string> facade_file_names(const output_formats& formats)
{
    std::vector<std::string> names = polygon_file_names("buildings", formats);
    for (const char* n : {"facade_patches.csv", "surface_table.csv", "bill_savings.csv"}) names.emplace_back(n);
    if (formats.png) names.push_back("buildings_energy.png");
    return names;
}

std::vector<std::string> facade_file_names(bool png)
{
    output_formats formats;
    formats.png = png;
    return facade_file_names(formats);
}

void write_facade_outputs(io::output_folder& out, const facade_run& run)
{
    extract_buildings_options bopt;
    bopt.run = {.threads = run.threads, .progress = progress_bar("buildings")};
    const grid local{0.0, static_cast<double>(run.dsm.rows()) * run.cell_m, run.cell_m, run.dsm.rows(),
                     run.dsm.cols()};  // metres; the outlines below are polygonized on grid_crs
    const extract_buildings_result b =
        !run.classified_buildings.empty()
            ? extract_classified_buildings(run.dsm, local, run.ground, run.classified_buildings, bopt)
        : run.returns.points.empty()
            ? extract_buildings(run.dsm, local, run.ground, raster_view<const std::uint8_t>{}, bopt)
            : extract_buildings(run.dsm, local, run.ground, run.returns, bopt);
    // Roof and facade energy on the DSM: a roof found under an overhanging crown is left out of it (the DSM holds the
    // crown there, whose sun is not the roof's), as it was before that roof was found.
    raster<std::int32_t> energy_ids = b.building_id;
    std::size_t under_crowns = 0;
    for (std::ptrdiff_t i = 0; i < energy_ids.size(); ++i) {
        if (b.under_crowns.data()[i] == 0) continue;
        energy_ids.data()[i] = 0;
        ++under_crowns;
    }
    const surface_energy_result e =
        surface_energy(run.dsm, energy_ids, run.cell_m, run.site, run.records,
                       {.run = {.threads = run.threads, .progress = progress_bar("roofs and facades")}});

    // Outlines in the input's CRS units; heights and areas in metres.
    std::vector<io::geojson_feature> features;
    for (const auto& lp : polygonize(b.building_id, run.grid_crs)) {
        const building_record& rec = b.buildings[static_cast<std::size_t>(lp.label - 1)];
        for (const auto& poly : lp.polygons) {
            features.push_back({poly.rings,
                                {{"building_id", rec.id},
                                 {"ground_z", rec.ground_z},
                                 {"eave_z", rec.eave_z},
                                 {"ridge_z", rec.ridge_z},
                                 {"height_m", rec.ridge_z - rec.ground_z},
                                 {"roof_area_m2", rec.roof_area_horizontal_m2},
                                 {"roof_area_sloped_m2", rec.roof_area_sloped_m2},
                                 {"roof_surfaces", static_cast<std::int64_t>(rec.surfaces.size())},
                                 {"clipped", rec.clipped}}});
        }
    }
    write_polygons(out, "buildings", features, run.crs_wkt, run.epsg, run.formats);

    std::vector<std::vector<io::table_value>> rows;
    for (std::size_t i = 0; i < e.facades.size(); ++i) {
        const facade_patch& p = e.facades[i];
        const patch_energy& en = e.facade_energy[i];
        rows.push_back({p.building_id, p.wall_id, p.level, p.facing_azimuth_deg, p.height_m - p.bottom_m, p.area_m2,
                        en.annual_kwh_m2, en.quarter_kwh_m2_day[0], en.quarter_kwh_m2_day[1], en.quarter_kwh_m2_day[2],
                        en.quarter_kwh_m2_day[3]});
    }
    out.write("facade_patches.csv", [&](const std::string& path) {
        io::write_csv(
            path,
            {io::text_column("building_id"), io::text_column("patch_id"), io::text_column("level"),
             io::degrees_column("facing_azimuth_deg"), io::metres_column("height_m"), io::area_column("area_m2"),
             io::kwh_m2_column("annual_kwh_m2"), io::kwh_m2_column("q1_kwh_m2_day"), io::kwh_m2_column("q2_kwh_m2_day"),
             io::kwh_m2_column("q3_kwh_m2_day"), io::kwh_m2_column("q4_kwh_m2_day")},
            rows);
    });

    const auto table = surface_class_table(e);
    std::vector<std::vector<io::table_value>> t1, t2;
    for (const surface_class_row& r : table) {
        t1.push_back({class_names[static_cast<std::size_t>(r.kind)], r.quarter_kwh_m2_day[0], r.quarter_kwh_m2_day[1],
                      r.quarter_kwh_m2_day[2], r.quarter_kwh_m2_day[3], r.annual_kwh_m2, r.area_m2});
    }
    out.write("surface_table.csv", [&](const std::string& path) {
        io::write_csv(path,
                      {io::text_column("surface"), io::kwh_m2_column("jan_mar_kwh_m2_day"),
                       io::kwh_m2_column("apr_jun_kwh_m2_day"), io::kwh_m2_column("jul_sep_kwh_m2_day"),
                       io::kwh_m2_column("oct_dec_kwh_m2_day"), io::kwh_m2_column("annual_kwh_m2_yr"),
                       io::area_column("area_m2")},
                      t1);
    });
    for (const bill_savings_row& r : bill_savings(table)) {
        t2.push_back({class_names[static_cast<std::size_t>(r.kind)], r.quarter_per_day[0], r.quarter_per_day[1],
                      r.quarter_per_day[2], r.quarter_per_day[3], r.annual});
    }
    out.write("bill_savings.csv", [&](const std::string& path) {
        io::write_csv(path,
                      {io::text_column("surface"), io::money_column("jan_mar_savings_per_day"),
                       io::money_column("apr_jun_savings_per_day"), io::money_column("jul_sep_savings_per_day"),
                       io::money_column("oct_dec_savings_per_day"), io::money_column("annual_savings")},
                      t2);
    });
    if (run.png) {
        const io::rgb_image img = energy_picture(run, e);
        out.write("buildings_energy.png", [&](const std::string& path) { io::write_png_rgb(path, img); });
    }

    std::cout << std::fixed << std::setprecision(1) << "buildings: " << b.buildings.size() << ", roof patches "
              << e.roofs.size() << ", facade sub-patches " << e.facades.size() << "\n";
    if (under_crowns > 0)
        std::cout << "roof under overhanging crowns: " << under_crowns
                  << " cells, in the buildings' outlines and areas, not in roof energy (the DSM holds the crown)\n";
    for (const surface_class_row& r : table) {
        std::cout << "  " << std::setw(13) << class_names[static_cast<std::size_t>(r.kind)] << ": " << r.annual_kwh_m2
                  << " kWh/m2/yr over " << r.area_m2 << " m2\n";
    }
}

}  // namespace lidarfx::cli
