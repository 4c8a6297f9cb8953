// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include "cli/cli_common.hpp"
#include "cli/outputs.hpp"
#include "io/figure.hpp"
#include "io/quicklook.hpp"

#include <cmath>
#include <filesystem>
#include <string>

#include "io_test_survey.hpp"
#include "io_test_util.hpp"

using namespace lidarfx;
using namespace lidarfx::io;

namespace {

using rgb = std::array<std::uint8_t, 3>;

using io_test::pixel;

/// A rows x cols map whose cell (r, c) has colour (r, c, 7) (distinct per cell on small maps).
rgb_image cell_map(std::ptrdiff_t rows, std::ptrdiff_t cols)
{
    rgb_image m{cols, rows, {}};
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c)
            m.rgb.insert(m.rgb.end(), {static_cast<std::uint8_t>(r), static_cast<std::uint8_t>(c), 7});
    return m;
}

/// True when `img` holds, anywhere, the pixels of `text` drawn in black at `scale` on white.
bool holds_text(const rgb_image& img, const std::string& text, int scale)
{
    rgb_image stamp{text_width_px(text, scale), 7 * scale, {}};
    stamp.rgb.assign(static_cast<std::size_t>(stamp.width * stamp.height * 3), 255);
    draw_text(stamp, 0, 0, text, {0, 0, 0}, scale);
    for (std::ptrdiff_t r0 = 0; r0 + stamp.height <= img.height; ++r0)
        for (std::ptrdiff_t c0 = 0; c0 + stamp.width <= img.width; ++c0) {
            bool same = true;
            for (std::ptrdiff_t r = 0; r < stamp.height && same; ++r)
                for (std::ptrdiff_t c = 0; c < stamp.width && same; ++c)
                    same = (pixel(stamp, r, c) == rgb{0, 0, 0}) == (pixel(img, r0 + r, c0 + c) == rgb{0, 0, 0});
            if (same) return true;
        }
    return false;
}

}  // namespace

TEST_CASE("io/make_figure: a small grid is enlarged by whole pixels to a long side of at least 800")
{
    const rgb_image map = cell_map(23, 37);
    const figure fig = make_figure(map, {}, {.title = "test map", .cell_size = 2.0});
    const auto& at = fig.layout;
    CHECK(at.factor == 22);  // ceil(800 / 37)
    CHECK(37 * at.factor >= 800);
    CHECK(fig.image.width >= 37 * at.factor);
    CHECK(fig.image.height >= 23 * at.factor);
    // Nearest neighbour: every pixel of a cell's block has the cell's colour, no blending across cells.
    for (std::ptrdiff_t r = 0; r < 23 * at.factor; r += 5)
        for (std::ptrdiff_t c = 0; c < 37 * at.factor; c += 3) {
            const rgb want{static_cast<std::uint8_t>(r / at.factor), static_cast<std::uint8_t>(c / at.factor), 7};
            CHECK(pixel(fig.image, at.map_row + r, at.map_col + c) == want);
        }
    // A huge grid is never enlarged, a mid-size one is capped.
    CHECK(figure_factor(900, 1200) == 1);
    CHECK(figure_factor(3, 5) == 32);
    CHECK(figure_factor(400, 300) == 2);
}

TEST_CASE("io/make_figure: no-data cells are drawn in the no-data hatch, named in the legend")
{
    const rgb_image map = cell_map(10, 12);
    raster<std::uint8_t> no_data(10, 12, 0);
    no_data(4, 5) = 1;
    const figure fig = make_figure(map, no_data, {.title = "holes"});
    const auto& at = fig.layout;
    const std::ptrdiff_t f = at.factor;
    for (std::ptrdiff_t r = 4 * f; r < 5 * f; ++r)
        for (std::ptrdiff_t c = 5 * f; c < 6 * f; ++c) {
            const auto px = pixel(fig.image, at.map_row + r, at.map_col + c);
            CHECK(px == no_data_color(at.map_row + r, at.map_col + c));
            CHECK(is_no_data_color(px));
        }
    // Its neighbours keep their colour, and nothing else in the map is hatched or black.
    CHECK(pixel(fig.image, at.map_row + 4 * f, at.map_col + 4 * f) == rgb{4, 4, 7});
    CHECK(is_no_data_color(no_data_color(0, 0)));
    CHECK(no_data_color(0, 0) != no_data_color(0, 4));  // a hatch: two greys
    CHECK(holds_text(fig.image, "no data", 2));
    const auto nan_cells = non_finite_cells(raster<float>(2, 2, NAN));
    CHECK(nan_cells(1, 1) == 1);
}

TEST_CASE("io/make_figure: a categorical legend holds a swatch of each colour with its name")
{
    const rgb_image map = cell_map(20, 30);
    const std::vector<figure_key> key{{{40, 110, 255}, "true water"},
                                      {{230, 30, 30}, "false water"},
                                      {{250, 210, 0}, "missed water"},
                                      {{200, 200, 200}, "land"}};
    const figure fig = make_figure(map, {}, {.title = "agreement", .key = key});
    for (const auto& k : key) {
        CAPTURE(k.name);
        // A swatch: a solid block of the colour below the map (the map's cells hold other colours).
        std::ptrdiff_t count = 0;
        for (std::ptrdiff_t r = fig.layout.legend_row; r < fig.image.height; ++r)
            for (std::ptrdiff_t c = 0; c < fig.image.width; ++c) count += pixel(fig.image, r, c) == k.color;
        CHECK(count >= 18 * 12);
        CHECK(holds_text(fig.image, k.name, 2));
    }
    CHECK(holds_text(fig.image, "no data", 2));
}

TEST_CASE("io/make_figure: the scale bar is its labelled length over the cell size times the factor")
{
    for (const double cell : {0.5, 1.0, 2.0, 3.0, 0.3048}) {
        CAPTURE(cell);
        const rgb_image map = cell_map(23, 37);
        const figure fig = make_figure(map, {}, {.title = "scale", .cell_size = cell, .unit = "ft"});
        const auto& at = fig.layout;
        // A round length (1, 2 or 5 x 10^k) near a quarter of the map's width.
        const double mantissa = at.scale_length / std::pow(10.0, std::floor(std::log10(at.scale_length) + 1e-9));
        CHECK((std::abs(mantissa - 1) < 1e-9 || std::abs(mantissa - 2) < 1e-9 || std::abs(mantissa - 5) < 1e-9));
        CHECK(at.scale_length <= 37 * cell / 4 * (1 + 1e-9));
        CHECK(at.scale_length > 37 * cell / 4 / 2.5);
        // Measure the black bar on its middle row.
        const std::ptrdiff_t row = at.scale_row + 10;
        std::ptrdiff_t len = 0;
        while (pixel(fig.image, row, at.scale_col + len) == rgb{0, 0, 0}) ++len;
        CHECK(std::abs(static_cast<double>(len) - at.scale_length / cell * static_cast<double>(at.factor)) <= 0.5);
        char label[32];
        std::snprintf(label, sizeof label, "%.4g ft", at.scale_length);
        CHECK(holds_text(fig.image, label, 2));
        CHECK(holds_text(fig.image, "grid north", 2));
    }
    CHECK(round_scale_length(9.9) == 5);
    CHECK(round_scale_length(250) == 200);
    CHECK(round_scale_length(0.7) == doctest::Approx(0.5));
    CHECK(short_unit_name(0.3048, "foot") == "ft");
    CHECK(short_unit_name(1.0, "metre") == "m");
}

TEST_CASE("io/make_figure: the title and the colour bar's range and unit are drawn")
{
    const rgb_image map = cell_map(30, 20);
    const std::string title = "min_z.png: lowest return (m), EPSG:32613";
    const figure fig = make_figure(map, {}, {.title = title, .bar = figure_bar{12.5, 47, "height (m)"}});
    CHECK(holds_text(fig.image, title, 2));
    // The title sits where the layout says.
    rgb_image stamp{fig.image.width, fig.image.height, std::vector<std::uint8_t>(fig.image.rgb.size(), 255)};
    draw_text(stamp, fig.layout.title_row, fig.layout.title_col, title, {0, 0, 0}, 2);
    for (std::ptrdiff_t c = 0; c < text_width_px(title, 2); ++c)
        for (std::ptrdiff_t r = 0; r < 14; ++r) {
            const auto rr = fig.layout.title_row + r, cc = fig.layout.title_col + c;
            CHECK(pixel(fig.image, rr, cc) == pixel(stamp, rr, cc));
        }
    CHECK(holds_text(fig.image, "12.5", 2));
    CHECK(holds_text(fig.image, "47", 2));
    CHECK(holds_text(fig.image, "height (m)", 2));
    // The bar runs the ramp from left to right.
    CHECK(pixel(fig.image, fig.layout.legend_row + 8, 16) == ramp_color(0.0));
    CHECK_THROWS_AS(make_figure(map, {}, {.cell_size = 0}), invalid_input);
    CHECK_THROWS_AS(make_figure(map, raster<std::uint8_t>(2, 2), {}), invalid_input);
    CHECK_THROWS_AS(make_figure(map, {}, {.bar = figure_bar{2, 1, ""}}), invalid_input);
}

TEST_CASE("io/make_figure: the program's point-raster pictures are figures (long side >= 800 px on a 40 x 30 grid)")
{
    const cli::survey s = io_test::small_survey();
    io_test::temp_dir dir;
    const auto out = std::filesystem::path(dir.file("png"));
    {
        io::output_folder folder(out);
        cli::output_formats formats;
        formats.asc = formats.tif = false;
        cli::write_point_rasters(folder, s, formats, 1);
        folder.commit("test");
    }
    const auto be32 = [](const std::vector<std::uint8_t>& b, std::size_t at) {
        return (std::uint32_t{b[at]} << 24) | (std::uint32_t{b[at + 1]} << 16) | (std::uint32_t{b[at + 2]} << 8) |
               std::uint32_t{b[at + 3]};
    };
    for (const char* name : {"min_z.png", "mean_intensity.png", "dropout.png"}) {
        CAPTURE(name);
        const auto bytes = io_test::read_bytes((out / name).string());
        REQUIRE(bytes.size() > 24);
        const auto width = be32(bytes, 16), height = be32(bytes, 20);  // IHDR
        CHECK(width >= 40 * 20);                                       // 40 columns enlarged 20 times, plus the frame
        CHECK(height >= 30 * 20);                                      // 30 rows, plus title, scale bar and legend
    }
}

TEST_CASE("io/compass_key: the eight compass swatches in azimuth colours, clockwise from north, then the others")
{
    const auto key = compass_key({{{255, 255, 255}, "flat"}});
    REQUIRE(key.size() == 9);
    for (int i = 0; i < 8; ++i) CHECK(key[static_cast<std::size_t>(i)].color == azimuth_color(45.0 * i));
    CHECK(key[0].name == "N 0°");
    CHECK(key[4].name == "S 180°");
    CHECK(key[8].name == "flat");
}
