// SPDX-License-Identifier: Apache-2.0
// The pictures of docs/synthetic-scenes.md: the default lake, river and town scenes (seed 1), each picture a
// figure (title, scale bar, grid-north arrow, colour bar or legend, no data hatched).
// usage: lidarfx_synth_pictures OUT_DIR   (writes synth-{lake,river}-{intensity,dropouts,truth}.png and
//                                          synth-town-{height,closeup,planes}.png)
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <iostream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <lidarfx/lidarfx.hpp>
#include <lidarfx/synth/scenes.hpp>

#include "io/figure.hpp"
#include "io/png.hpp"
#include "io/quicklook.hpp"

namespace {

namespace io = lidarfx::io;
using rgb = std::array<std::uint8_t, 3>;

constexpr rgb water_blue{60, 110, 220}, water_dark{20, 40, 120}, land_red{220, 40, 40}, water_light{150, 190, 240},
    island_cyan{60, 210, 210}, tree_green{40, 150, 60}, road_grey{70, 70, 70}, deck_orange{240, 140, 30};

/// A picture of `rows` x `cols` cells whose colour is `color(r, c)`: a colour, or nothing for a grey `shade` cell.
io::rgb_image paint(const lidarfx::raster<std::uint8_t>& shade,
                    const std::function<std::optional<rgb>(std::ptrdiff_t, std::ptrdiff_t)>& color)
{
    io::rgb_image map{shade.cols(), shade.rows(), {}};
    map.rgb.reserve(static_cast<std::size_t>(shade.size()) * 3);
    for (std::ptrdiff_t r = 0; r < shade.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < shade.cols(); ++c) {
            const std::uint8_t g = shade(r, c);
            const rgb v = color(r, c).value_or(rgb{g, g, g});
            map.rgb.insert(map.rgb.end(), v.begin(), v.end());
        }
    }
    return map;
}

/// A colour bar from the 1st to the 99th percentile of the finite values (a few glints do not flatten the rest).
io::figure_bar percentile_bar(const lidarfx::raster<float>& values, std::string unit)
{
    std::vector<float> finite;
    for (const float v : values)
        if (std::isfinite(v)) finite.push_back(v);
    if (finite.empty()) return {0, 0, std::move(unit)};
    std::sort(finite.begin(), finite.end());
    const auto at = [&](double q) {
        return finite[static_cast<std::size_t>(q * static_cast<double>(finite.size() - 1))];
    };
    return {at(0.01), at(0.99), std::move(unit)};
}

void write(const std::filesystem::path& path, const io::figure& f)
{
    io::write_png_rgb(path.string(), f.image);
    std::cout << "wrote " << path.string() << " (" << f.image.width << " x " << f.image.height << ")\n";
}

/// The lake or river scene: mean intensity, dropouts and truth, at the truth grid's 2 m cells.
void water_pictures(const lidarfx::synth::scene& s, const std::string& name, const std::filesystem::path& out)
{
    const auto& t = s.truth;
    const double cell = t.g.cell;
    const auto pr = lidarfx::rasterize(s.points.cloud(), t.g);
    const auto shade = io::hillshade(t.ground_z, cell);

    lidarfx::raster<float> intensity = pr.mean_intensity;
    for (std::ptrdiff_t i = 0; i < intensity.size(); ++i)
        if (pr.count.data()[i] == 0) intensity.data()[i] = NAN;
    const io::figure_bar bar = percentile_bar(intensity, "mean intensity (1st-99th percentile)");
    write(out / ("synth-" + name + "-intensity.png"),
          io::make_figure(io::colorize(intensity, bar.min, bar.max), io::non_finite_cells(intensity),
                          {.title = name + ": mean intensity per " + std::to_string(int(cell)) + " m cell",
                           .cell_size = cell,
                           .bar = bar,
                           .no_data_name = "no return"}));

    const auto dropouts = paint(shade, [&](std::ptrdiff_t r, std::ptrdiff_t c) -> std::optional<rgb> {
        const bool water = t.water(r, c) != 0, dropout = pr.dropout(r, c) != 0;
        if (dropout) return water ? water_dark : land_red;
        if (water) return water_light;
        return std::nullopt;
    });
    write(out / ("synth-" + name + "-dropouts.png"), io::make_figure(dropouts, {},
                                                                     {.title = name + ": cells without a return",
                                                                      .cell_size = cell,
                                                                      .key = {{water_dark, "water, no return"},
                                                                              {land_red, "land, no return"},
                                                                              {water_light, "water with returns"},
                                                                              {{128, 128, 128}, "land (hillshade)"}}}));

    const auto truth = paint(shade, [&](std::ptrdiff_t r, std::ptrdiff_t c) -> std::optional<rgb> {
        const std::uint8_t surface = t.surface(r, c);
        if (surface == lidarfx::las_class::bridge_deck) return deck_orange;
        if (t.water(r, c)) return water_blue;
        if (t.water_filled(r, c)) return island_cyan;
        if (surface == lidarfx::las_class::high_vegetation) return tree_green;
        if (surface == lidarfx::las_class::road_surface) return road_grey;
        return std::nullopt;
    });
    std::vector<io::figure_key> key{
        {water_blue, "water"}, {island_cyan, "small island (filled)"}, {tree_green, "tree crown"}, {road_grey, "road"}};
    if (name == "river") key.push_back({deck_orange, "bridge deck"});
    key.push_back({{128, 128, 128}, "ground (hillshade)"});
    write(out / ("synth-" + name + "-truth.png"),
          io::make_figure(truth, {}, {.title = name + ": truth", .cell_size = cell, .key = key}));
}

/// Heights above the truth's ground of the highest return per cell, over a hillshade of the ground; roads dark.
io::rgb_image heights_over_ground(const lidarfx::synth::scene& s, const lidarfx::grid& g,
                                  const lidarfx::raster<float>& ground, const lidarfx::raster<std::uint8_t>& surface,
                                  float top_m)
{
    const auto pr = lidarfx::rasterize(s.points.cloud(), g);
    lidarfx::raster<float> height(g.rows, g.cols, NAN);
    for (std::ptrdiff_t r = 0; r < g.rows; ++r)
        for (std::ptrdiff_t c = 0; c < g.cols; ++c)
            if (std::isfinite(pr.max_z(r, c)) && pr.max_z(r, c) - ground(r, c) > 0.5f)
                height(r, c) = pr.max_z(r, c) - ground(r, c);
    io::rgb_image map = io::colorize_over_hillshade(height, 0.0, top_m, ground, g.cell);
    for (std::ptrdiff_t i = 0; i < surface.size(); ++i) {
        if (surface.data()[i] == lidarfx::las_class::road_surface && !std::isfinite(height.data()[i])) {
            std::copy(road_grey.begin(), road_grey.end(), map.rgb.begin() + 3 * i);
        }
    }
    return map;
}

/// `r` rows and `c` columns of `src` from (r0, c0).
template <class T>
lidarfx::raster<T> window(const lidarfx::raster<T>& src, std::ptrdiff_t r0, std::ptrdiff_t c0, std::ptrdiff_t rows,
                          std::ptrdiff_t cols)
{
    lidarfx::raster<T> out(rows, cols);
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c) out(r, c) = src(r0 + r, c0 + c);
    return out;
}

/// The town: heights above ground at 2 m, and the 200 m x 200 m window with the most roof cells at 1 m.
void town_pictures(const std::filesystem::path& out)
{
    const auto whole = lidarfx::synth::town_scene();
    const auto& t = whole.truth;
    constexpr float top_m = 20;
    const io::figure_bar bar{0, top_m, "height above ground (m)"};
    write(out / "synth-town-height.png",
          io::make_figure(heights_over_ground(whole, t.g, t.ground_z, t.surface, top_m), {},
                          {.title = "town: heights above ground, 2 m cells",
                           .cell_size = t.g.cell,
                           .bar = bar,
                           .key = {{road_grey, "road"}}}));

    const auto fine = lidarfx::synth::town_scene({.truth_cell_m = 1.0});
    const auto& f = fine.truth;
    const std::ptrdiff_t side = 200, step = 20;
    std::ptrdiff_t best_r = 0, best_c = 0, best = -1;
    for (std::ptrdiff_t r0 = 0; r0 + side <= f.g.rows; r0 += step) {
        for (std::ptrdiff_t c0 = 0; c0 + side <= f.g.cols; c0 += step) {
            std::ptrdiff_t roofs = 0;
            for (std::ptrdiff_t r = r0; r < r0 + side; ++r)
                for (std::ptrdiff_t c = c0; c < c0 + side; ++c) roofs += f.roof_plane_id(r, c) != 0;
            if (roofs > best) best = roofs, best_r = r0, best_c = c0;
        }
    }
    lidarfx::grid g = f.g;
    g.x0 += static_cast<double>(best_c) * g.cell;
    g.y0 -= static_cast<double>(best_r) * g.cell;
    g.rows = g.cols = side;
    const auto ground = window(f.ground_z, best_r, best_c, side, side);
    const std::string where =
        " (x " + std::to_string(static_cast<int>(g.x0)) + "-" + std::to_string(static_cast<int>(g.x0) + 200) +
        " m, y " + std::to_string(static_cast<int>(g.y0) - 200) + "-" + std::to_string(static_cast<int>(g.y0)) + " m)";
    write(
        out / "synth-town-closeup.png",
        io::make_figure(heights_over_ground(fine, g, ground, window(f.surface, best_r, best_c, side, side), top_m), {},
                        {.title = "town close-up, 1 m cells" + where,
                         .cell_size = g.cell,
                         .bar = bar,
                         .key = {{road_grey, "road"}}}));

    const auto faces = window(f.roof_plane_id, best_r, best_c, side, side);
    const auto shade = io::hillshade(ground, g.cell);
    const auto planes = paint(shade, [&](std::ptrdiff_t r, std::ptrdiff_t c) -> std::optional<rgb> {
        if (faces(r, c) == 0) return std::nullopt;
        return io::label_color(faces(r, c));
    });
    write(out / "synth-town-planes.png",
          io::make_figure(
              planes, {},
              {.title = "town close-up: roof faces (truth roof_plane_id)" + where,
               .cell_size = g.cell,
               .key = {{io::label_color(1), "one colour per roof face"}, {{128, 128, 128}, "ground (hillshade)"}}}));
}

}  // namespace

int main(int argc, char** argv)
{
    if (argc != 2) {
        std::cerr << "usage: lidarfx_synth_pictures OUT_DIR\n";
        return 1;
    }
    const std::filesystem::path out = argv[1];
    std::filesystem::create_directories(out);
    water_pictures(lidarfx::synth::lake_scene(), "lake", out);
    water_pictures(lidarfx::synth::river_scene(), "river", out);
    town_pictures(out);
    return 0;
}
