// SPDX-License-Identifier: Apache-2.0
#include "outputs.hpp"

#include <cmath>
#include <functional>
#include <iomanip>
#include <iostream>

#include <lidarfx/kernels/vector/polygonize.hpp>

#include "io/figure.hpp"
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

/// Pictures are made from rasters of at most this many cells on the long side: block reductions of the
/// survey's grid (factor 1 on grids up to this size), so that a picture costs little on any grid.
constexpr std::ptrdiff_t picture_max_side = 2048;

std::ptrdiff_t picture_factor(const grid& g)
{
    const std::ptrdiff_t side = std::max(g.rows, g.cols);
    return std::max<std::ptrdiff_t>(1, (side + picture_max_side - 1) / picture_max_side);
}

/// Blocks of f x f cells reduced to one: `reduce(values of the block's cells)`; f = 1 copies.
template <class T, class Reduce>
raster<T> block_reduce(raster_view<const T> v, std::ptrdiff_t f, Reduce reduce)
{
    if (f == 1) return raster<T>(v);
    raster<T> out((v.rows() + f - 1) / f, (v.cols() + f - 1) / f);
    std::vector<T> block;
    for (std::ptrdiff_t r = 0; r < out.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < out.cols(); ++c) {
            block.clear();
            for (std::ptrdiff_t rr = r * f; rr < std::min(v.rows(), (r + 1) * f); ++rr)
                for (std::ptrdiff_t cc = c * f; cc < std::min(v.cols(), (c + 1) * f); ++cc) block.push_back(v(rr, cc));
            out(r, c) = reduce(block);
        }
    }
    return out;
}

/// Lowest finite value of a block (NaN when none).
float finite_min(const std::vector<float>& block)
{
    float m = NAN;
    for (const float x : block)
        if (std::isfinite(x) && !(x >= m)) m = x;
    return m;
}

/// Mean of the finite values of a block (NaN when none).
float finite_mean(const std::vector<float>& block)
{
    double sum = 0;
    int n = 0;
    for (const float x : block)
        if (std::isfinite(x)) sum += x, ++n;
    return n ? static_cast<float>(sum / n) : NAN;
}

/// 1 when at least half of a block's cells are set.
std::uint8_t mostly_set(const std::vector<std::uint8_t>& block)
{
    std::size_t set = 0;
    for (const auto x : block) set += x != 0;
    return 2 * set >= block.size();
}

/// `z` with its NaN holes filled coarse to fine (pull-push): each coarser level holds the mean of the finite
/// cells of 2 x 2 blocks of the finer one, and a hole takes the value of its block at the first level
/// where that is finite. O(cells); for pictures only (the fill is blocky, never an interpolation).
raster<float> fill_holes_pull_push(raster<float> z)
{
    if (z.rows() <= 1 && z.cols() <= 1) return z;
    raster<float> coarse((z.rows() + 1) / 2, (z.cols() + 1) / 2);
    for (std::ptrdiff_t r = 0; r < coarse.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < coarse.cols(); ++c) {
            double sum = 0;
            int n = 0;
            for (std::ptrdiff_t rr = 2 * r; rr < std::min(z.rows(), 2 * r + 2); ++rr)
                for (std::ptrdiff_t cc = 2 * c; cc < std::min(z.cols(), 2 * c + 2); ++cc)
                    if (std::isfinite(z(rr, cc))) sum += z(rr, cc), ++n;
            coarse(r, c) = n ? static_cast<float>(sum / n) : NAN;
        }
    coarse = fill_holes_pull_push(std::move(coarse));
    for (std::ptrdiff_t r = 0; r < z.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < z.cols(); ++c)
            if (!std::isfinite(z(r, c))) z(r, c) = coarse(r / 2, c / 2);
    return z;
}

/// Elevation with dropout holes filled, for shaded pictures only: the picture grid's lowest returns (a block
/// reduction of the survey's grid, at most picture_max_side cells a side), holes filled coarse to fine. A
/// sparse survey (under a quarter of the picture's cells with returns) is shaded as it is: filling it would
/// show nothing real.
raster<float> picture_elevation(const rasterize_result& pr, std::ptrdiff_t f)
{
    auto z = block_reduce<float>(pr.min_z, f, finite_min);
    std::ptrdiff_t with_returns = 0;
    for (const auto v : z) with_returns += std::isfinite(v);
    if (4 * with_returns < z.size()) return z;
    return fill_holes_pull_push(std::move(z));
}

}  // namespace

height_unit file_height_unit(const survey& s)
{
    const bool vertical_written = s.crs_wkt.find("VERT") != std::string::npos;  // VERT_CS (WKT1), VERTCRS (WKT2)
    if (vertical_written) return {s.crs.vertical_unit_m, s.crs.vertical_unit};
    return {s.crs.horizontal_unit_m, s.crs.horizontal_unit};
}

std::string units_note(const survey& s)
{
    const std::string where = s.crs.source.empty() ? std::string("coordinates as read (no CRS: taken as metres)")
                                                   : "the CRS of the input, " + s.crs.describe();
    return "cell values (heights, levels) in metres, areas in m2; grids, bounding boxes and polygons in " + where;
}

void print_survey(const survey& s)
{
    const auto& g = s.rasters.g;
    const grid in_crs = to_crs_units(g, s);
    const double area = static_cast<double>(g.size()) * g.cell * g.cell;
    std::cout << "survey: " << s.files << " file(s), " << s.points << " points; grid " << g.rows << " x " << g.cols
              << " cells of " << g.cell << " m from (" << std::fixed << std::setprecision(2) << in_crs.x0 << ", "
              << in_crs.y0 << ")" << std::defaultfloat << "; " << std::setprecision(3)
              << static_cast<double>(s.points) / area << " points/m2";
    if (s.epsg) std::cout << "; EPSG:" << s.epsg;
    if (s.crs.horizontal_unit_m != 1 || s.crs.vertical_unit_m != 1) {
        std::cout << "; read in " << s.crs.horizontal_unit << " (z " << s.crs.vertical_unit << "), converted to metres";
    }
    std::cout << '\n';
    if (s.rasters.points_nan) {
        std::cout << "  " << s.rasters.points_nan << " points with NaN or infinite coordinates ignored\n";
    }
    if (s.rasters.points_outside) std::cout << "  " << s.rasters.points_outside << " points outside --crop ignored\n";
}

std::vector<std::string> point_raster_file_names(const output_formats& formats)
{
    std::vector<std::string> names;
    if (formats.png) names = {"min_z.png", "mean_intensity.png", "dropout.png"};
    for (const char* r : {"min_z", "max_z", "mean_intensity", "count", "dropout"}) {
        for (auto& n : raster_file_names(r, formats)) names.push_back(std::move(n));
    }
    return names;
}

std::vector<std::string> waterbody_file_names(const output_formats& formats)
{
    std::vector<std::string> names;
    if (formats.csv) names.push_back("waterbodies.csv");
    for (auto& n : polygon_file_names("waterbodies", formats)) names.push_back(std::move(n));
    if (formats.png) names.push_back("water_overlay.png");
    for (const char* r : {"water", "waterbody_labels"}) {
        for (auto& n : raster_file_names(r, formats)) names.push_back(std::move(n));
    }
    return names;
}

void write_point_rasters(io::output_folder& dir, const survey& s, const output_formats& formats, int threads)
{
    const auto& pr = s.rasters;
    // A raster file speaks its CRS's units: placed in the files' CRS, heights in the vertical unit of the CRS the
    // file records (the horizontal unit when that CRS has no vertical part, as a reader of the file assumes).
    const grid g = to_crs_units(pr.g, s);
    const height_unit heights = file_height_unit(s);
    const double z_unit = heights.metres;
    const std::string z_unit_name = heights.name;
    const auto in_z_unit = [z_unit](const raster<float>& metres) {
        raster<float> out = metres;
        for (float& v : out) v = static_cast<float>(v / z_unit);
        return out;
    };
    const raster<float> min_z = z_unit == 1.0 ? raster<float>() : in_z_unit(pr.min_z);
    const raster<float> max_z = z_unit == 1.0 ? raster<float>() : in_z_unit(pr.max_z);
    dir.set_units_note("min_z and max_z in " + z_unit_name + "; " + units_note(s));
    // Every file is one job; the jobs run side by side (each writer is single-threaded).
    std::vector<std::function<void()>> jobs;
    const auto grid_file = [&](const char* name, const raster_view<const float>& values) {
        jobs.emplace_back([&, name, values] { write_raster(dir, name, values, g, s.crs_wkt, s.epsg, formats); });
    };
    grid_file("min_z", z_unit == 1.0 ? pr.min_z.view() : min_z.view());
    grid_file("max_z", z_unit == 1.0 ? pr.max_z.view() : max_z.view());
    // The library keeps 0 in cells without a return (the water steps skip them by their dropout flag); the file
    // says no data there, so a reader never averages a 0 that no return measured.
    raster<float> mean_intensity = pr.mean_intensity;
    for (std::ptrdiff_t i = 0; i < mean_intensity.size(); ++i)
        if (pr.count.data()[i] == 0) mean_intensity.data()[i] = NAN;
    grid_file("mean_intensity", mean_intensity);
    jobs.emplace_back(
        [&] { write_raster(dir, "count", as_float<std::uint32_t>(pr.count), g, s.crs_wkt, s.epsg, formats); });
    jobs.emplace_back(
        [&] { write_raster(dir, "dropout", as_float<std::uint8_t>(pr.dropout), g, s.crs_wkt, s.epsg, formats); });
    if (formats.png) {
        const auto f = picture_factor(pr.g);
        const std::string xy_unit = io::short_unit_name(s.crs.horizontal_unit_m, s.crs.horizontal_unit);
        const std::string z_short = io::short_unit_name(z_unit, z_unit_name);
        // A figure: the picture grid's cells (f x f survey cells each) in the CRS's unit, NaN cells as no data.
        const auto png = [&, f, xy_unit](const std::string& name, const io::rgb_image& map,
                                         raster_view<const std::uint8_t> no_data, io::figure_options opt) {
            opt.cell_size = g.cell * static_cast<double>(f);
            opt.unit = xy_unit;
            const io::figure fig = io::make_figure(map, no_data, opt);
            dir.write(name, [&](const std::string& path) { io::write_png_rgb(path, fig.image); });
        };
        jobs.emplace_back([&, png, f, z_short] {
            const auto z = block_reduce<float>(z_unit == 1.0 ? pr.min_z.view() : min_z.view(), f, finite_min);
            const auto bar = io::finite_bar(z, "lowest return height (" + z_short + ")");
            png("min_z.png", io::colorize(z, bar.min, bar.max), io::non_finite_cells(z),
                {.title = "min_z.png: lowest return per cell (" + z_short + ")",
                 .bar = bar,
                 .no_data_name = "no return"});
        });
        jobs.emplace_back([&, png, f] {
            raster<float> intensity = pr.mean_intensity;  // 0 where no return: no data in the picture
            for (std::ptrdiff_t i = 0; i < intensity.size(); ++i)
                if (pr.count.data()[i] == 0) intensity.data()[i] = NAN;
            const auto v = block_reduce<float>(intensity, f, finite_mean);
            const auto bar = io::finite_bar(v, "mean intensity (LAS units)");
            png("mean_intensity.png", io::colorize(v, bar.min, bar.max), io::non_finite_cells(v),
                {.title = "mean_intensity.png: mean return intensity per cell",
                 .bar = bar,
                 .no_data_name = "no return"});
        });
        jobs.emplace_back([&, png, f] {
            const auto z = picture_elevation(pr, f);
            const auto grey = io::hillshade(z, pr.g.cell * static_cast<double>(f));
            png("dropout.png",
                io::overlay_mask(grey, block_reduce<std::uint8_t>(pr.dropout, f, mostly_set), {255, 40, 40}, 0.8),
                io::non_finite_cells(z),
                {.title = "dropout.png: cells without returns over the terrain's hillshade",
                 .key = {{{230, 58, 58}, "dropout (no return)"}, {{128, 128, 128}, "returns (hillshade)"}},
                 .no_data_name = "no data to shade"});
        });
    }
    run_jobs(jobs, threads);
}

survey_waterbodies find_waterbodies(const survey& s, const extract_waterbodies_options& opt, double hull_radius_m)
{
    survey_waterbodies found{footprint_of(s, hull_radius_m, opt.run.threads), {}};
    std::size_t flown = 0, crossed = 0;
    for (const auto v : found.footprint) flown += v;
    if (!s.scan_covered.empty())
        for (std::ptrdiff_t i = 0; i < s.scan_covered.size(); ++i)
            crossed += s.scan_covered.data()[i] && s.rasters.dropout.data()[i];
    const auto cells = static_cast<double>(std::max<std::ptrdiff_t>(1, found.footprint.size()));
    std::cout << "footprint: " << std::fixed << std::setprecision(1) << 100.0 * static_cast<double>(flown) / cells
              << " % of the grid was flown (" << 100.0 * static_cast<double>(crossed) / cells
              << " % crossed by scan lines without a return); outside is no data\n"
              << std::defaultfloat;
    auto inputs = to_water_rasters(s.rasters);
    inputs.footprint = found.footprint;
    found.result = extract_waterbodies(inputs, s.rasters.g.cell, opt);
    return found;
}

void write_waterbodies(io::output_folder& dir, const survey& s, const extract_waterbodies_result& w,
                       raster_view<const std::uint8_t> footprint, const output_formats& formats, int threads)
{
    const auto& pr = s.rasters;
    const auto& g = pr.g;
    const grid in_crs = to_crs_units(g, s);  // georeferenced in the files' CRS; areas and levels stay in metres
    dir.set_units_note(units_note(s));
    // The files are independent: they are written on `threads` threads, the longest (the picture) first.
    std::vector<std::function<void()>> jobs;
    if (formats.png) {
        jobs.push_back([&] {
            const auto f = picture_factor(g);
            // The longest job: its shading on every thread (the other jobs are short).
            const auto grey =
                io::hillshade(picture_elevation(pr, f), g.cell * static_cast<double>(f), 315.0, 45.0, threads);
            const auto overlay =
                io::overlay_mask(grey, block_reduce<std::uint8_t>(w.water, f, mostly_set), {30, 110, 255}, 0.65);
            auto unflown = block_reduce<std::uint8_t>(footprint, f, mostly_set);
            for (auto& v : unflown) v = !v;
            const io::figure fig =
                io::make_figure(overlay, unflown,
                                {.title = "water_overlay.png: waterbodies found, over the terrain's hillshade",
                                 .cell_size = in_crs.cell * static_cast<double>(f),
                                 .unit = io::short_unit_name(s.crs.horizontal_unit_m, s.crs.horizontal_unit),
                                 .key = {{{64, 116, 211}, "water"}, {{128, 128, 128}, "land (hillshade)"}},
                                 .no_data_name = "unflown (no data)"});
            dir.write("water_overlay.png", [&](const std::string& path) { io::write_png_rgb(path, fig.image); });
        });
    }
    jobs.push_back([&] {
        // No data: cells outside the footprint (nothing flown), and cells without any return within 2 cells
        // that are not water (data gaps).
        raster<float> water(g.rows, g.cols, uninitialized);
        for (std::ptrdiff_t r = 0; r < g.rows; ++r) {
            for (std::ptrdiff_t c = 0; c < g.cols; ++c) {
                if (!footprint(r, c) || w.water(r, c)) {
                    water(r, c) = footprint(r, c) ? 1.0f : NAN;
                    continue;
                }
                bool data = false;
                for (std::ptrdiff_t rr = std::max<std::ptrdiff_t>(0, r - 2); rr <= std::min(g.rows - 1, r + 2) && !data;
                     ++rr)
                    for (std::ptrdiff_t cc = std::max<std::ptrdiff_t>(0, c - 2); cc <= std::min(g.cols - 1, c + 2);
                         ++cc)
                        if (!pr.dropout(rr, cc)) {
                            data = true;
                            break;
                        }
                water(r, c) = data ? 0.0f : NAN;
            }
        }
        write_raster(dir, "water", water, in_crs, s.crs_wkt, s.epsg, formats);
    });
    jobs.push_back([&] {
        raster<float> labels(g.rows, g.cols, uninitialized);
        for (std::ptrdiff_t r = 0; r < g.rows; ++r)
            for (std::ptrdiff_t c = 0; c < g.cols; ++c)
                labels(r, c) = footprint(r, c) ? static_cast<float>(w.labels(r, c)) : NAN;
        write_raster(dir, "waterbody_labels", labels, in_crs, s.crs_wkt, s.epsg, formats);
    });
    jobs.push_back([&] {
        // Bounding boxes in the files' CRS unit; areas and levels in metres (the columns in docs/waterbodies.md).
        const std::vector<io::csv_column> header{
            io::text_column("label"),           io::area_column("area_m2"),
            io::text_column("cells"),           io::crs_column("xmin_crs"),
            io::crs_column("ymin_crs"),         io::crs_column("xmax_crs"),
            io::crs_column("ymax_crs"),         io::degrees_column("theta_deg"),
            io::text_column("stopped_by_ks"),   io::intensity_column("mean_intensity"),
            io::metres_column("water_level_m"), io::fraction_column("dropout_fraction")};
        std::vector<std::vector<io::table_value>> rows;
        for (const auto& b : w.bodies) {
            const bounds box = in_crs.extent(b.box);
            rows.push_back({b.label, b.area_m2, b.cells, box.xmin, box.ymin, box.xmax, box.ymax, b.theta_deg,
                            std::int64_t{b.stopped_by_ks ? 1 : 0}, b.mean_intensity, b.water_level_m,
                            b.dropout_fraction});
        }
        if (formats.csv)
            dir.write("waterbodies.csv", [&](const std::string& path) { io::write_csv(path, header, rows); });
    });
    jobs.push_back([&] {
        std::vector<io::geojson_feature> features;
        for (const auto& lp : polygonize(w.labels, in_crs)) {
            const auto& b = w.bodies[static_cast<std::size_t>(lp.label - 1)];
            for (const auto& poly : lp.polygons) {
                features.push_back({poly.rings,
                                    {{"label", b.label},
                                     {"area_m2", b.area_m2},
                                     {"water_level_m", b.water_level_m},
                                     {"theta_deg", b.theta_deg}}});
            }
        }
        write_polygons(dir, "waterbodies", features, s.crs_wkt, s.epsg, formats);
    });
    run_jobs(jobs, threads);
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
