// SPDX-License-Identifier: Apache-2.0
#include "outputs.hpp"

#include <cmath>
#include <iomanip>
#include <iostream>

#include <lidarfx/kernels/vector/polygonize.hpp>
#include <lidarfx/kernels/interpolate/idw_fill.hpp>

#include "io/png.hpp"
#include "io/quicklook.hpp"
#include "io/tables.hpp"

namespace lidarfx::cli {

namespace {

/// A mask or count raster as floats, for the raster writers.
template <class T>
raster<float> as_float(raster_view<const T> m)
{
    raster<float> out(m.rows(), m.cols());
    for (std::ptrdiff_t r = 0; r < m.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < m.cols(); ++c) out(r, c) = static_cast<float>(m(r, c));
    return out;
}

/// Elevation with dropout holes filled, for shaded pictures only.
raster<float> picture_elevation(const point_rasters& pr)
{
    bool any = false;
    for (const auto v : pr.min_z) any |= std::isfinite(v);
    if (!any) return pr.min_z;
    return idw_fill(pr.min_z, idw_options{.k = 4, .cell_m = pr.g.cell}).filled;
}

}  // namespace

void print_survey(const survey& s)
{
    const auto& g = s.rasters.g;
    const double area = static_cast<double>(g.size()) * g.cell * g.cell;
    std::cout << "survey: " << s.files << " file(s), " << s.points << " points; grid " << g.rows << " x " << g.cols
              << " cells of " << g.cell << " m from (" << std::fixed << std::setprecision(2) << g.x0 << ", " << g.y0
              << ")" << std::defaultfloat << "; " << std::setprecision(3) << static_cast<double>(s.points) / area
              << " points/m2";
    if (s.epsg) std::cout << "; EPSG:" << s.epsg;
    std::cout << '\n';
    if (s.rasters.points_nan) std::cout << "  " << s.rasters.points_nan << " points with NaN coordinates ignored\n";
}

void write_point_rasters(const std::filesystem::path& dir, const survey& s)
{
    const auto& pr = s.rasters;
    write_raster(dir, "min_z", pr.min_z, pr.g, s.crs_wkt, s.epsg);
    write_raster(dir, "max_z", pr.max_z, pr.g, s.crs_wkt, s.epsg);
    write_raster(dir, "mean_intensity", pr.mean_intensity, pr.g, s.crs_wkt, s.epsg);
    write_raster(dir, "count", as_float<std::uint32_t>(pr.count), pr.g, s.crs_wkt, s.epsg);
    write_raster(dir, "dropout", as_float<std::uint8_t>(pr.dropout), pr.g, s.crs_wkt, s.epsg);
    const auto png = [&](const std::string& name, const io::rgb_image& img) {
        io::write_png_rgb((dir / name).string(), img);
        say_wrote(dir / name);
    };
    png("min_z.png", io::colorize(pr.min_z));
    png("mean_intensity.png", io::colorize(pr.mean_intensity));
    const auto grey = io::hillshade(picture_elevation(pr), pr.g.cell);
    png("dropout.png", io::overlay_mask(grey, pr.dropout, {255, 40, 40}, 0.8));
}

void write_waterbodies(const std::filesystem::path& dir, const survey& s, const extract_waterbodies_result& w)
{
    const auto& pr = s.rasters;
    const auto& g = pr.g;
    // No data: cells without any return within 2 cells that are not water (outside the survey, data gaps).
    raster<float> water(g.rows, g.cols), labels(g.rows, g.cols);
    for (std::ptrdiff_t r = 0; r < g.rows; ++r) {
        for (std::ptrdiff_t c = 0; c < g.cols; ++c) {
            labels(r, c) = static_cast<float>(w.labels(r, c));
            if (w.water(r, c)) {
                water(r, c) = 1.0f;
                continue;
            }
            bool data = false;
            for (std::ptrdiff_t rr = std::max<std::ptrdiff_t>(0, r - 2); rr <= std::min(g.rows - 1, r + 2) && !data; ++rr)
                for (std::ptrdiff_t cc = std::max<std::ptrdiff_t>(0, c - 2); cc <= std::min(g.cols - 1, c + 2); ++cc)
                    if (!pr.dropout(rr, cc)) {
                        data = true;
                        break;
                    }
            water(r, c) = data ? 0.0f : NAN;
        }
    }
    write_raster(dir, "water", water, g, s.crs_wkt, s.epsg);
    write_raster(dir, "waterbody_labels", labels, g, s.crs_wkt, s.epsg);

    const auto grey = io::hillshade(picture_elevation(pr), g.cell);
    io::write_png_rgb((dir / "water_overlay.png").string(), io::overlay_mask(grey, w.water, {30, 110, 255}, 0.65));
    say_wrote(dir / "water_overlay.png");

    std::vector<std::string> header{"label", "area_m2", "cells", "xmin", "ymin", "xmax", "ymax", "seed",
                                    "theta_deg", "stopped_by_ks", "mean_intensity", "water_level_m",
                                    "dropout_fraction"};
    std::vector<std::vector<io::table_value>> rows;
    for (const auto& b : w.bodies) {
        const bounds box = g.extent(b.box);
        rows.push_back({b.label, b.area_m2, b.cells, box.xmin, box.ymin, box.xmax, box.ymax, b.seed, b.theta_deg, b.stopped_by_ks,
                        b.mean_intensity, b.water_level_m, b.dropout_fraction});
    }
    io::write_csv((dir / "waterbodies.csv").string(), header, rows);
    say_wrote(dir / "waterbodies.csv");

    std::vector<io::geojson_feature> features;
    for (const auto& lp : polygonize(w.labels, g)) {
        const auto& b = w.bodies[static_cast<std::size_t>(lp.label - 1)];
        for (const auto& poly : lp.polygons) {
            features.push_back({poly.rings, {{"label", b.label}, {"area_m2", b.area_m2},
                                             {"water_level_m", b.water_level_m}, {"theta_deg", b.theta_deg}}});
        }
    }
    io::write_geojson((dir / "waterbodies.geojson").string(), features, s.epsg);
    say_wrote(dir / "waterbodies.geojson");
}

void print_diagnostics(const water_diagnostics& d)
{
    for (const auto& p : d.messages(water_severity::problem)) std::cout << "  problem: " << p << '\n';
    for (const auto& p : d.messages(water_severity::warning)) std::cout << "  note: " << p << '\n';
}

void print_waterbodies(const extract_waterbodies_result& w, std::size_t max_rows)
{
    double area = 0;
    for (const auto& b : w.bodies) area += b.area_m2;
    std::cout << "waterbodies: " << w.bodies.size() << " (" << std::fixed << std::setprecision(0) << area
              << " m2) from " << w.seeds_grown << " of " << w.seeds_found << " seeds\n";
    for (std::size_t i = 0; i < w.bodies.size() && i < max_rows; ++i) {
        const auto& b = w.bodies[i];
        std::cout << "  #" << b.label << "  " << std::setprecision(0) << b.area_m2 << " m2  level "
                  << std::setprecision(2) << b.water_level_m << " m  theta " << std::setprecision(1) << b.theta_deg
                  << " deg" << (b.stopped_by_ks ? " (KS stop)" : " (theta max)") << '\n';
    }
    if (w.bodies.size() > max_rows) std::cout << "  ... " << w.bodies.size() - max_rows << " more\n";
    std::cout << std::defaultfloat;
}

}  // namespace lidarfx::cli
