// SPDX-License-Identifier: Apache-2.0
// The pictures of docs/solar.md: cast shadows at several hours, sky view factor and the annual irradiation of a
// synthetic town (lidarfx::synth::town_scene), from the library alone.
// usage: lidarfx_solar_pictures OUT_DIR   (writes solar-shadow-HHh.png, solar-svf.png, solar-annual.png)
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>

#include <lidarfx/lidarfx.hpp>
#include <lidarfx/synth/scenes.hpp>

#include "io/figure.hpp"
#include "io/png.hpp"
#include "io/quicklook.hpp"

namespace {

constexpr double latitude_deg = 52.5, longitude_deg = 13.4;  // Berlin
constexpr int utc_offset_h = 1;                              // CET: local standard time = UTC + 1 h
constexpr double cell_m = 1.0;

// A figure of `m` with a colour bar over its finite range, 1 m cells.
void legend_png(const std::filesystem::path& path, const lidarfx::raster<float>& m, const std::string& title,
                const char* unit)
{
    const auto bar = lidarfx::io::finite_bar(m, unit);
    const auto fig =
        lidarfx::io::make_figure(lidarfx::io::colorize(m.view(), bar.min, bar.max), lidarfx::io::non_finite_cells(m),
                                 {.title = title, .cell_size = cell_m, .unit = "m", .bar = bar});
    lidarfx::io::write_png_rgb(path.string(), fig.image);
    std::cout << "wrote " << path.string() << " (" << bar.min << " .. " << bar.max << " " << unit << ")\n";
}

}  // namespace

int main(int argc, char** argv)
{
    if (argc != 2) {
        std::cerr << "usage: lidarfx_solar_pictures OUT_DIR\n";
        return 1;
    }
    const std::filesystem::path out = argv[1];
    std::filesystem::create_directories(out);

    // The town's surface model: highest return per 1 m cell, gaps filled by IDW (as lidarfx solar does).
    const auto sc = lidarfx::synth::town_scene({.seed = 1, .size_m = 240, .density_per_m2 = 4, .truth_cell_m = cell_m});
    const auto r = lidarfx::rasterize(sc.points.cloud(), sc.truth.g);
    const auto dsm = lidarfx::idw_fill(r.max_z, cell_m).filled;
    const auto shade = lidarfx::io::hillshade(dsm, cell_m);

    // Cast shadows on 21 June at 08, 11, 14 and 17 h local standard time: shadow cells tinted blue.
    namespace chr = std::chrono;
    for (const int hour : {8, 11, 14, 17}) {
        const chr::sys_seconds t = chr::sys_days{chr::year{2021} / chr::June / 21} + chr::hours{hour - utc_offset_h};
        const auto sun = lidarfx::sun_position(t, latitude_deg, longitude_deg);
        const auto lit = lidarfx::raylines_shadow(dsm, cell_m, sun.azimuth_deg, sun.elevation_deg);
        lidarfx::raster<std::uint8_t> shadow(lit.rows(), lit.cols(), 0);
        for (std::ptrdiff_t i = 0; i < lit.rows(); ++i)
            for (std::ptrdiff_t j = 0; j < lit.cols(); ++j) shadow(i, j) = lit(i, j) == 0 ? 1 : 0;
        char name[64];
        std::snprintf(name, sizeof name, "solar-shadow-%02dh.png", hour);
        char title[128];
        std::snprintf(title, sizeof title, "Cast shadows, 21 June %02d h CET (sun azimuth %.0f°, elevation %.0f°)",
                      hour, sun.azimuth_deg, sun.elevation_deg);
        const auto fig =
            lidarfx::io::make_figure(lidarfx::io::overlay_mask(shade, shadow), {},
                                     {.title = title,
                                      .cell_size = cell_m,
                                      .unit = "m",
                                      .key = {{{72, 144, 225}, "shadow"}, {{180, 180, 180}, "sunlit (hillshade)"}}});
        lidarfx::io::write_png_rgb((out / name).string(), fig.image);
        std::cout << "wrote " << (out / name).string() << " (sun azimuth " << sun.azimuth_deg << ", elevation "
                  << sun.elevation_deg << " deg)\n";
    }

    // Sky view factor and the annual irradiation of a clear-sky year.
    const auto res = lidarfx::irradiance_maps(
        dsm, cell_m, {.latitude_deg = latitude_deg, .longitude_deg = longitude_deg, .utc_offset_h = utc_offset_h},
        lidarfx::clear_sky_records(2021, latitude_deg, longitude_deg));
    legend_png(out / "solar-svf.png", res.sky_view_factor, "Sky view factor (SVF, 0..1)", "SVF");
    legend_png(out / "solar-annual.png", res.annual_kwh_m2, "Annual irradiation, clear-sky year (kWh/m²)", "kWh/m²");
    return 0;
}
