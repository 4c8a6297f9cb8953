// SPDX-License-Identifier: Apache-2.0
// The pictures of docs/synthetic-scenes.md (water family): a grid of family scenes, lakes on top and rivers
// below (tuning seeds 1-4), and the two targeted cases, each a figure (title, scale bar, north arrow, legend) of
// the hillshaded lowest return with truth water found in blue (dark blue: cells without a return), red = water
// found on land, yellow = water missed.
// usage: lidarfx_water_family_pictures OUT_DIR   (writes water-family.png, water-cases.png)
#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <lidarfx/lidarfx.hpp>
#include <lidarfx/synth/water_cases.hpp>
#include <lidarfx/synth/water_family.hpp>

#include "io/figure.hpp"
#include "io/png.hpp"
#include "io/quicklook.hpp"

namespace {

using rgb = std::array<std::uint8_t, 3>;
constexpr rgb found_water{60, 110, 220}, found_no_return{20, 40, 120}, missed{240, 210, 40}, false_water{220, 40, 40};

/// One scene as a figure: the hillshaded lowest return (holes filled), truth water found in blue (dark blue:
/// cells without a return), water missed yellow, water found on land red; a title naming the scene.
lidarfx::io::rgb_image panel(const lidarfx::synth::water_family_scene& s, const std::string& title)
{
    const auto pr = lidarfx::rasterize(s.points.cloud(), s.g);
    const auto filled = lidarfx::idw_fill(pr.min_z, s.cell_m).filled;
    const auto shade = lidarfx::io::hillshade(filled, s.cell_m);
    const auto found = lidarfx::extract_waterbodies(pr);
    lidarfx::io::rgb_image map{s.g.cols, s.g.rows, {}};
    for (std::ptrdiff_t r = 0; r < s.g.rows; ++r) {
        for (std::ptrdiff_t c = 0; c < s.g.cols; ++c) {
            const std::uint8_t g = shade.view()(r, c);
            const bool truth = s.water_filled(r, c), hit = found.ran && found.water.view()(r, c);
            rgb color{g, g, g};
            if (truth && hit)
                color = pr.dropout(r, c) ? found_no_return : found_water;
            else if (truth)
                color = missed;
            else if (hit)
                color = false_water;
            map.rgb.insert(map.rgb.end(), color.begin(), color.end());
        }
    }
    return lidarfx::io::make_figure(map, {},
                                    {.title = title,
                                     .cell_size = s.cell_m,
                                     .unit = "m",
                                     .key = {{found_water, "water found"},
                                             {found_no_return, "found, no return"},
                                             {missed, "missed"},
                                             {false_water, "false water"}},
                                     .min_long_side = 200})
        .image;
}

/// The panels side by side, `columns` to a row, on white with 8 pixels between them.
lidarfx::io::rgb_image tiled(const std::vector<lidarfx::io::rgb_image>& panels, std::ptrdiff_t columns)
{
    std::ptrdiff_t cell_w = 0, cell_h = 0;
    for (const auto& p : panels) {
        cell_w = std::max(cell_w, p.width);
        cell_h = std::max(cell_h, p.height);
    }
    const auto rows = (static_cast<std::ptrdiff_t>(panels.size()) + columns - 1) / columns;
    const std::ptrdiff_t w = columns * (cell_w + 8) - 8, h = rows * (cell_h + 8) - 8;
    lidarfx::io::rgb_image out{w, h, std::vector<std::uint8_t>(static_cast<std::size_t>(w * h * 3), 255)};
    for (std::size_t k = 0; k < panels.size(); ++k) {
        const auto& p = panels[k];
        const std::ptrdiff_t r0 = static_cast<std::ptrdiff_t>(k) / columns * (cell_h + 8),
                             c0 = static_cast<std::ptrdiff_t>(k) % columns * (cell_w + 8);
        for (std::ptrdiff_t r = 0; r < p.height; ++r)
            std::copy_n(p.rgb.begin() + r * p.width * 3, p.width * 3, out.rgb.begin() + ((r0 + r) * w + c0) * 3);
    }
    return out;
}

}  // namespace

int main(int argc, char** argv)
{
    if (argc != 2) {
        std::cerr << "usage: lidarfx_water_family_pictures OUT_DIR\n";
        return 1;
    }
    const std::filesystem::path out = argv[1];
    std::filesystem::create_directories(out);
    using lidarfx::synth::water_family_kind;

    std::vector<lidarfx::io::rgb_image> family;
    for (const auto kind : {water_family_kind::lake, water_family_kind::river}) {
        for (unsigned seed = 1; seed <= 4; ++seed) {
            const auto s = lidarfx::synth::water_family({.seed = seed, .kind = kind});
            const bool lake = kind == water_family_kind::lake;
            char title[96];
            std::snprintf(title, sizeof title, "%s %u: %.0f m, %.3g pts/m², %.3g m cells", lake ? "lake" : "river",
                          seed, s.size_m, s.density_per_m2, s.cell_m);
            family.push_back(panel(s, title));
            std::cout << title << "\n";
        }
    }
    lidarfx::io::write_png_rgb((out / "water-family.png").string(), tiled(family, 4));

    const std::vector<lidarfx::io::rgb_image> cases{panel(lidarfx::synth::dropout_pond_scene(), "dropout pond"),
                                                    panel(lidarfx::synth::specular_river_scene(), "specular river")};
    lidarfx::io::write_png_rgb((out / "water-cases.png").string(), tiled(cases, 2));
    std::cout << "wrote " << (out / "water-family.png").string() << " and " << (out / "water-cases.png").string()
              << "\n";
    return 0;
}
