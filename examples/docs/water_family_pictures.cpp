// SPDX-License-Identifier: Apache-2.0
// The pictures of docs/synthetic-scenes.md (water family): a grid of family scenes, lakes on top and rivers
// below (tuning seeds 1-4), and the two targeted cases, each as the hillshaded lowest return with truth water
// in blue (dark blue: cells without a return) and what extract_waterbodies found marked: red = water found
// on land, yellow = water missed.
// usage: lidarfx_water_family_pictures OUT_DIR   (writes water-family.png, water-cases.png)
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <lidarfx/lidarfx.hpp>
#include <lidarfx/synth/water_cases.hpp>
#include <lidarfx/synth/water_family.hpp>

#include "io/png.hpp"
#include "io/quicklook.hpp"

namespace {

constexpr std::ptrdiff_t tile = 200;  // pixels per scene side

/// Draws one scene into `img` at (x0, y0), nearest-neighbour scaled to tile x tile pixels.
void draw(lidarfx::io::rgb_image& img, std::ptrdiff_t x0, std::ptrdiff_t y0,
          const lidarfx::synth::water_family_scene& s)
{
    const auto pr = lidarfx::rasterize(s.points.cloud(), s.g);
    const auto filled = lidarfx::idw_fill(pr.min_z, s.cell_m).filled;
    const auto shade = lidarfx::io::hillshade(filled, s.cell_m);
    const auto found = lidarfx::extract_waterbodies(pr);
    for (std::ptrdiff_t py = 0; py < tile; ++py) {
        for (std::ptrdiff_t px = 0; px < tile; ++px) {
            const std::ptrdiff_t r = py * s.g.rows / tile, c = px * s.g.cols / tile;
            const int g = shade.view()(r, c);
            const bool truth = s.water_filled(r, c), hit = found.ran && found.water.view()(r, c);
            std::array<int, 3> rgb{g, g, g};
            if (truth && hit)
                rgb = pr.dropout(r, c) ? std::array<int, 3>{20, 40, 120} : std::array<int, 3>{60, 110, 220};
            else if (truth)
                rgb = {240, 210, 40};
            else if (hit)
                rgb = {220, 40, 40};
            auto* p = &img.rgb[static_cast<std::size_t>(((y0 + py) * img.width + x0 + px) * 3)];
            for (int k = 0; k < 3; ++k) p[k] = static_cast<std::uint8_t>(rgb[static_cast<std::size_t>(k)]);
        }
    }
}

lidarfx::io::rgb_image blank(std::ptrdiff_t cols, std::ptrdiff_t rows)
{
    const std::ptrdiff_t w = cols * (tile + 4) + 4, h = rows * (tile + 4) + 4;
    return {w, h, std::vector<std::uint8_t>(static_cast<std::size_t>(w * h * 3), 255)};
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

    auto grid = blank(4, 2);
    for (unsigned seed = 1; seed <= 4; ++seed) {
        for (const auto kind : {water_family_kind::lake, water_family_kind::river}) {
            const auto s = lidarfx::synth::water_family({.seed = seed, .kind = kind});
            const std::ptrdiff_t row = kind == water_family_kind::lake ? 0 : 1;
            draw(grid, 4 + (seed - 1) * (tile + 4), 4 + row * (tile + 4), s);
            std::cout << (row ? "river " : "lake ") << seed << ": " << s.size_m << " m, " << s.density_per_m2
                      << " pts/m2, cell " << s.cell_m << " m\n";
        }
    }
    lidarfx::io::write_png_rgb((out / "water-family.png").string(), grid);

    auto cases = blank(2, 1);
    draw(cases, 4, 4, lidarfx::synth::dropout_pond_scene());
    draw(cases, 4 + tile + 4, 4, lidarfx::synth::specular_river_scene());
    lidarfx::io::write_png_rgb((out / "water-cases.png").string(), cases);
    std::cout << "wrote " << (out / "water-family.png").string() << " and " << (out / "water-cases.png").string()
              << "\n";
    return 0;
}
