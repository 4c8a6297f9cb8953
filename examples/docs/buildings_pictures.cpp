// SPDX-License-Identifier: Apache-2.0
// The pictures of docs/buildings.md: buildings extracted from a synthetic family town
// (lidarfx::synth::town_family, seed 4), their roof surfaces coloured by azimuth, and the annual energy of the
// roof patches and facade sub-patches of a clear-sky year, from the library alone.
// usage: lidarfx_buildings_pictures OUT_DIR
//        (writes buildings-extracted.png, buildings-roof-azimuth.png, buildings-energy.png)
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <limits>
#include <vector>

#include <lidarfx/lidarfx.hpp>
#include <lidarfx/synth/town_family.hpp>

#include "io/figure.hpp"
#include "io/png.hpp"
#include "io/quicklook.hpp"

namespace {

constexpr double latitude_deg = 52.5, longitude_deg = 13.4;  // Berlin, as the pictures of docs/solar.md
constexpr int utc_offset_h = 1;                              // CET: local standard time = UTC + 1 h
using rgb = std::array<std::uint8_t, 3>;

// The hillshade as a grey picture.
lidarfx::io::rgb_image grey_picture(const lidarfx::raster<std::uint8_t>& shade)
{
    lidarfx::io::rgb_image img{shade.cols(), shade.rows(), {}};
    img.rgb.reserve(static_cast<std::size_t>(shade.size()) * 3);
    for (const std::uint8_t v : shade) img.rgb.insert(img.rgb.end(), {v, v, v});
    return img;
}

void set_pixel(lidarfx::io::rgb_image& img, std::ptrdiff_t i, std::ptrdiff_t j, const rgb& c, double opacity = 1.0)
{
    auto* p = img.rgb.data() + (i * img.width + j) * 3;
    for (int k = 0; k < 3; ++k) p[k] = static_cast<std::uint8_t>(std::lround((1 - opacity) * p[k] + opacity * c[k]));
}

// True where a building cell has a 4-neighbour (or the raster border) outside its building: the outline cells.
bool on_outline(const lidarfx::raster<std::int32_t>& id, std::ptrdiff_t i, std::ptrdiff_t j)
{
    const std::int32_t b = id(i, j);
    if (b == 0) return false;
    constexpr std::array<std::array<int, 2>, 4> steps{{{-1, 0}, {1, 0}, {0, -1}, {0, 1}}};
    for (const auto& [di, dj] : steps) {
        const std::ptrdiff_t r = i + di, c = j + dj;
        if (r < 0 || c < 0 || r >= id.rows() || c >= id.cols() || id(r, c) != b) return true;
    }
    return false;
}

// Writes `img` as a figure of the town's 0.5 m grid.
void write(const std::filesystem::path& path, const lidarfx::io::rgb_image& img, lidarfx::io::figure_options opt,
           const char* what)
{
    opt.cell_size = 0.5;
    opt.unit = "m";
    lidarfx::io::write_png_rgb(path.string(), lidarfx::io::make_figure(img, {}, opt).image);
    std::cout << "wrote " << path.string() << " (" << what << ")\n";
}

}  // namespace

int main(int argc, char** argv)
{
    if (argc != 2) {
        std::cerr << "usage: lidarfx_buildings_pictures OUT_DIR\n";
        return 1;
    }
    const std::filesystem::path out = argv[1];
    std::filesystem::create_directories(out);

    // A family town (200 m, 0.5 m cells): DSM = highest first return per cell, vegetation = cells with multiple
    // returns, as in tests/pipelines/buildings/extract_buildings_towns.cpp.
    const auto town = lidarfx::synth::town_family({.seed = 4});
    const auto& g = town.town.truth.g;
    lidarfx::rasterize_options first;
    first.returns = lidarfx::return_selection::first;
    const auto r = lidarfx::rasterize(town.town.points.cloud(), g, first);
    const auto b = lidarfx::extract_buildings(r.max_z, g, {}, r.multiple_returns);
    const auto dsm = lidarfx::idw_fill(r.max_z, g.cell).filled;
    const auto shade = lidarfx::io::hillshade(dsm, g.cell);
    std::cout << "town: " << dsm.rows() << " x " << dsm.cols() << " cells of " << g.cell << " m, "
              << town.density_per_m2 << " pulses/m², " << b.buildings.size() << " buildings, " << b.surfaces.size()
              << " roof surfaces\n";

    // (a) Buildings coloured by id over the hillshade, outlines black.
    auto img = grey_picture(shade);
    for (std::ptrdiff_t i = 0; i < dsm.rows(); ++i)
        for (std::ptrdiff_t j = 0; j < dsm.cols(); ++j) {
            const std::int32_t id = b.building_id(i, j);
            if (on_outline(b.building_id, i, j))
                set_pixel(img, i, j, {0, 0, 0});
            else if (id != 0)
                set_pixel(img, i, j, lidarfx::io::label_color(id), 0.6);
        }
    write(out / "buildings-extracted.png", img,
          {.title = "Extracted buildings, family town seed 4 (colour per building)",
           .key = {{lidarfx::io::label_color(1), "building (one colour each)"},
                   {{0, 0, 0}, "outline"},
                   {{180, 180, 180}, "ground, trees (hillshade)"}}},
          "buildings by id");

    // (b) Roof surfaces coloured by the down-slope azimuth of their plane; flat surfaces (tilt < 1 deg) white.
    img = grey_picture(shade);
    for (std::ptrdiff_t i = 0; i < dsm.rows(); ++i)
        for (std::ptrdiff_t j = 0; j < dsm.cols(); ++j) {
            const std::int32_t s = b.surface_id(i, j);
            if (on_outline(b.building_id, i, j))
                set_pixel(img, i, j, {0, 0, 0});
            else if (s != 0) {
                const auto& surf = b.surfaces[static_cast<std::size_t>(s - 1)];
                set_pixel(img, i, j,
                          surf.tilt_deg < 1.0 ? rgb{255, 255, 255} : lidarfx::io::azimuth_color(surf.azimuth_deg));
            }
        }
    namespace io = lidarfx::io;
    write(out / "buildings-roof-azimuth.png", img,
          {.title = "Roof surfaces by down-slope azimuth (clockwise from grid north)",
           .key = io::compass_key({{{255, 255, 255}, "flat (tilt < 1°)"}, {{0, 0, 0}, "building outline"}})},
          "roof surfaces by azimuth");

    // (c) Annual energy of a clear-sky year: each roof cell takes the mean of the roof patches (2 x 2 quads) it
    // belongs to; the edge cells the walls hang from take the mean over their facade sub-patches (all walls and
    // levels), drawn over the roof value.
    const auto e = lidarfx::surface_energy(
        dsm, b.building_id, g.cell,
        {.latitude_deg = latitude_deg, .longitude_deg = longitude_deg, .utc_offset_h = utc_offset_h},
        lidarfx::clear_sky_records(2021, latitude_deg, longitude_deg));
    lidarfx::raster<double> sum(dsm.rows(), dsm.cols(), 0.0), n(dsm.rows(), dsm.cols(), 0.0);
    for (std::size_t k = 0; k < e.roofs.size(); ++k)
        for (const auto& [di, dj] : std::array<std::array<int, 2>, 4>{{{0, 0}, {0, 1}, {1, 0}, {1, 1}}}) {
            sum(e.roofs[k].row + di, e.roofs[k].col + dj) += e.roof_energy[k].annual_kwh_m2;
            n(e.roofs[k].row + di, e.roofs[k].col + dj) += 1;
        }
    lidarfx::raster<double> wall_sum(dsm.rows(), dsm.cols(), 0.0), wall_n(dsm.rows(), dsm.cols(), 0.0);
    for (std::size_t k = 0; k < e.facades.size(); ++k) {
        wall_sum(e.facades[k].row, e.facades[k].col) += e.facade_energy[k].annual_kwh_m2;
        wall_n(e.facades[k].row, e.facades[k].col) += 1;
    }
    lidarfx::raster<float> energy(dsm.rows(), dsm.cols(), std::numeric_limits<float>::quiet_NaN());
    double lo = 1e300, hi = -1e300;
    for (std::ptrdiff_t i = 0; i < dsm.rows(); ++i)
        for (std::ptrdiff_t j = 0; j < dsm.cols(); ++j) {
            const double v = wall_n(i, j) > 0 ? wall_sum(i, j) / wall_n(i, j) : n(i, j) > 0 ? sum(i, j) / n(i, j) : NAN;
            if (std::isnan(v)) continue;
            energy(i, j) = static_cast<float>(v);
            lo = std::min(lo, v);
            hi = std::max(hi, v);
        }
    img = grey_picture(shade);
    const auto colours = lidarfx::io::colorize(energy.view(), lo, hi);
    for (std::ptrdiff_t i = 0; i < dsm.rows(); ++i)
        for (std::ptrdiff_t j = 0; j < dsm.cols(); ++j)
            if (std::isfinite(energy(i, j))) {
                const auto* c = colours.rgb.data() + (i * colours.width + j) * 3;
                set_pixel(img, i, j, {c[0], c[1], c[2]});
            }
    std::cout << e.roofs.size() << " roof patches, " << e.facades.size() << " facade sub-patches, GHI " << e.ghi_kwh_m2
              << " kWh/m², cells " << lo << " .. " << hi << " kWh/m²\n";
    // Enlarged (x2 on this 400-cell grid), so that the one-cell ring of facade values shows.
    write(out / "buildings-energy.png", img,
          {.title = "Annual irradiation of roof patches and facades, clear-sky year",
           .bar = lidarfx::io::figure_bar{lo, hi, "kWh/m² per year"},
           .key = {{{180, 180, 180}, "ground (hillshade)"}}},
          "annual energy of roofs and facades");
    return 0;
}
