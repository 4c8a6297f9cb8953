// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include "io/quicklook.hpp"

#include <cmath>
#include <numbers>
#include <random>
#include <set>
#include <string>

using namespace lidarfx;
using namespace lidarfx::io;

namespace {

using rgb = std::array<std::uint8_t, 3>;

using io_test::pixel;

double luma(const rgb& c)
{
    return 0.299 * c[0] + 0.587 * c[1] + 0.114 * c[2];
}

/// Shade of a plane z = a*x + b*y (x east, y north) lit from azimuth/altitude: 255 * max(0, n . l).
int plane_shade(double a, double b, double azimuth_deg, double altitude_deg)
{
    const double d = std::numbers::pi / 180.0;
    const double l[3] = {std::sin(azimuth_deg * d) * std::cos(altitude_deg * d),
                         std::cos(azimuth_deg * d) * std::cos(altitude_deg * d), std::sin(altitude_deg * d)};
    const double dot = (-a * l[0] - b * l[1] + l[2]) / std::sqrt(a * a + b * b + 1);
    return static_cast<int>(std::lround(255 * std::max(0.0, dot)));
}

/// Textbook Horn gradient at an interior cell (a..i = the 3x3 window, row 0 north), then the same shading.
int horn_shade(raster_view<const float> z, std::ptrdiff_t r, std::ptrdiff_t c, double cell)
{
    const auto v = [&](int dr, int dc) { return static_cast<double>(z(r + dr, c + dc)); };
    const double dzdx = ((v(-1, 1) + 2 * v(0, 1) + v(1, 1)) - (v(-1, -1) + 2 * v(0, -1) + v(1, -1))) / (8 * cell);
    const double dzdn = ((v(-1, -1) + 2 * v(-1, 0) + v(-1, 1)) - (v(1, -1) + 2 * v(1, 0) + v(1, 1))) / (8 * cell);
    return plane_shade(dzdx, dzdn, 315, 45);
}

}  // namespace

TEST_CASE("io/ramp_color: viridis ends, NaN black, luminance rising with t")
{
    CHECK(ramp_color(0.0) == rgb{68, 1, 84});
    CHECK(ramp_color(1.0) == rgb{253, 231, 37});
    CHECK(ramp_color(0.5) == rgb{33, 144, 140});
    CHECK(ramp_color(-3.0) == ramp_color(0.0));
    CHECK(ramp_color(7.0) == ramp_color(1.0));
    CHECK(ramp_color(NAN) == rgb{0, 0, 0});
    double previous = -1;
    for (int i = 0; i <= 1000; ++i) {
        const double y = luma(ramp_color(i / 1000.0));
        CHECK(y >= previous - 0.6);  // rounding each channel to an integer moves luma by < 0.6
        previous = y;
    }
    CHECK(luma(ramp_color(1.0)) > luma(ramp_color(0.0)) + 150);
}

TEST_CASE("io/colorize: maps [min, max] onto the ramp, clamps outside, NaN black, strided views")
{
    raster<float> big(5, 9, 0.0f);
    auto v = big.view().window(1, 2, 3, 4);  // row_stride 9 > cols 4
    const float cells[3][4] = {{10, 15, 20, NAN}, {5, 25, 12.5f, 17.5f}, {10, 10, 20, 20}};
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) v(r, c) = cells[r][c];
    const auto img = colorize(v, 10, 20);
    CHECK(img.width == 4);
    CHECK(img.height == 3);
    REQUIRE(img.rgb.size() == 36);
    CHECK(pixel(img, 0, 0) == ramp_color(0));
    CHECK(pixel(img, 0, 1) == ramp_color(0.5));
    CHECK(pixel(img, 0, 2) == ramp_color(1));
    CHECK(pixel(img, 0, 3) == rgb{0, 0, 0});
    CHECK(pixel(img, 1, 0) == ramp_color(0));  // below min
    CHECK(pixel(img, 1, 1) == ramp_color(1));  // above max
    CHECK(pixel(img, 1, 2) == ramp_color(0.25));
    CHECK(pixel(img, 1, 3) == ramp_color(0.75));
    CHECK(colorize(raster<float>(v)).rgb == colorize(v).rgb);  // contiguous copy, same picture
    CHECK(colorize(v).rgb == colorize(v, 5, 25).rgb);          // automatic range = finite min and max

    const raster<float> flat(2, 2, 3.0f);
    CHECK(pixel(colorize(flat), 1, 1) == ramp_color(0.5));
    const raster<float> none(2, 3, NAN);
    const auto black = colorize(none);
    CHECK(std::all_of(black.rgb.begin(), black.rgb.end(), [](auto b) { return b == 0; }));
    CHECK_THROWS_WITH_AS(colorize(v, 2, 1), "colorize: min and max must be finite with min <= max", invalid_input);
    CHECK_THROWS_WITH_AS(colorize(raster<float>(0, 3)), "colorize: raster must not be empty", invalid_input);
}

TEST_CASE("io/hillshade: planes shade exactly everywhere (borders and NaN holes included)")
{
    std::mt19937 rng(31);
    std::uniform_real_distribution<double> slope(-1.5, 1.5);
    for (int trial = 0; trial < 40; ++trial) {
        const double a = slope(rng), b = slope(rng), cell = 0.5 + trial % 3;
        const std::ptrdiff_t rows = 1 + trial % 7, cols = 1 + (trial * 5) % 13;
        raster<float> z(rows, cols);
        for (std::ptrdiff_t r = 0; r < rows; ++r)
            for (std::ptrdiff_t c = 0; c < cols; ++c)  // y decreases with the row: row 0 is north
                z(r, c) =
                    static_cast<float>(100 + a * static_cast<double>(c) * cell - b * static_cast<double>(r) * cell);
        if (trial % 2 && rows * cols > 4) z(rows / 2, cols / 2) = NAN;
        const auto hs = hillshade(z, cell);
        const int expected = rows * cols == 1 ? 180 : plane_shade(a, b, 315, 45);
        for (std::ptrdiff_t r = 0; r < rows; ++r) {
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                if (std::isnan(z(r, c))) {
                    CHECK(hs(r, c) == 0);
                    continue;
                }
                // A single row or column has no gradient across it: only that axis is known.
                const int want =
                    rows == 1 || cols == 1 ? plane_shade(cols == 1 ? 0 : a, rows == 1 ? 0 : b, 315, 45) : expected;
                CHECK(std::abs(hs(r, c) - want) <= 1);  // float elevations move the shade by < 1 level
            }
        }
    }
    const raster<float> flat(4, 4, 7.0f);
    CHECK(hillshade(flat, 1.0)(2, 2) == 180);  // round(255 sin 45°)
    CHECK(hillshade(flat, 1.0, 0, 90)(0, 0) == 255);
    // Facing the light at 45° -> full light; facing away -> dark.
    raster<float> nw(3, 3), se(3, 3);
    for (std::ptrdiff_t r = 0; r < 3; ++r)
        for (std::ptrdiff_t c = 0; c < 3; ++c) {
            // Down-slope towards the north-west: z rises to the east and south, |grad| = 1.
            nw(r, c) = static_cast<float>(static_cast<double>(c + r) / std::numbers::sqrt2);
            se(r, c) = -nw(r, c);
        }
    CHECK(hillshade(nw, 1.0)(1, 1) == 255);
    CHECK(hillshade(se, 1.0)(1, 1) == 0);
}

TEST_CASE("io/hillshade: interior cells follow Horn's formula on random terrain; options are checked")
{
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 10.0f);
    raster<float> big(20, 31);
    for (auto& v : big) v = u(rng);
    const auto z = big.view().window(2, 3, 15, 25);
    const auto hs = hillshade(z, 2.0);
    CHECK(hs == hillshade(raster<float>(z), 2.0));
    for (std::ptrdiff_t r = 1; r + 1 < z.rows(); ++r)
        for (std::ptrdiff_t c = 1; c + 1 < z.cols(); ++c) CHECK(std::abs(hs(r, c) - horn_shade(z, r, c, 2.0)) <= 1);
    CHECK_THROWS_WITH_AS(hillshade(z, 0.0), "hillshade: cell_m must be finite and > 0 (got 0)", invalid_input);
    CHECK_THROWS_WITH_AS(hillshade(z, 1.0, 315, 91), "hillshade: altitude_deg must be in [0, 90] (got 91)",
                         invalid_input);
}

TEST_CASE("io/label_color: background black, distinct stable colours for labels")
{
    CHECK(label_color(0) == rgb{0, 0, 0});
    std::set<rgb> seen;
    for (std::int32_t label = 1; label <= 256; ++label) {
        const rgb c = label_color(label);
        CHECK(c != rgb{0, 0, 0});
        CHECK(luma(c) > 40);  // visible against the black background
        seen.insert(c);
        CHECK(label_color(label) == c);
    }
    CHECK(seen.size() == 256);
    // Consecutive labels (often adjacent regions) differ clearly.
    for (std::int32_t label = 1; label < 256; ++label) {
        const rgb a = label_color(label), b = label_color(label + 1);
        const int d = std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]);
        CHECK(d > 60);
    }
    raster<std::int32_t> labels(2, 3, 0);
    labels(0, 1) = 4;
    labels(1, 2) = 9;
    const auto img = colorize_labels(labels);
    CHECK(pixel(img, 0, 0) == rgb{0, 0, 0});
    CHECK(pixel(img, 0, 1) == label_color(4));
    CHECK(pixel(img, 1, 2) == label_color(9));
}

TEST_CASE("io/overlay_mask: tints masked cells over the grey picture")
{
    raster<std::uint8_t> grey(2, 2, 100), mask(2, 2, 0);
    mask(1, 0) = 1;
    const auto img = overlay_mask(grey, mask, {0, 120, 255}, 0.5);
    CHECK(pixel(img, 0, 0) == rgb{100, 100, 100});
    CHECK(pixel(img, 1, 0) == rgb{50, 110, 178});  // round(0.5 * 100 + 0.5 * colour)
    CHECK(pixel(overlay_mask(grey, mask, {9, 8, 7}, 1.0), 1, 0) == rgb{9, 8, 7});
    CHECK(overlay_mask(grey, mask, {9, 8, 7}, 0.0).rgb == std::vector<std::uint8_t>(12, 100));
    CHECK_THROWS_WITH_AS(overlay_mask(grey, raster<std::uint8_t>(2, 3)),
                         "overlay_mask: grey and mask must have the same shape (got 2x2 and 2x3)", invalid_input);
    CHECK_THROWS_WITH_AS(overlay_mask(grey, mask, {0, 0, 0}, 1.5), "overlay_mask: opacity must be in [0, 1] (got 1.5)",
                         invalid_input);
}

TEST_CASE("io/draw_text: the built-in font draws each digit's bitmap, the same bytes every time")
{
    // '1' has 10 lit font pixels: 1 + 2 + 1 + 1 + 1 + 1 + 3.
    rgb_image one{8, 9, std::vector<std::uint8_t>(8 * 9 * 3, 255)};
    draw_text(one, 1, 2, "1", {0, 0, 0});
    int lit = 0;
    for (std::ptrdiff_t r = 0; r < one.height; ++r)
        for (std::ptrdiff_t c = 0; c < one.width; ++c) lit += pixel(one, r, c) == rgb{0, 0, 0};
    CHECK(lit == 10);
    CHECK(pixel(one, 1, 4) == rgb{0, 0, 0});  // top of the stem: glyph column 2, row 0
    CHECK(pixel(one, 7, 3) == rgb{0, 0, 0});  // foot: glyph row 6, columns 1..3
    CHECK(pixel(one, 7, 2) == rgb{255, 255, 255});
    CHECK(pixel(one, 1, 2) == rgb{255, 255, 255});

    // Every digit is drawn from its own bitmap, pixel for pixel, at scale 1 and as blocks at scale 2.
    std::set<std::string> pictures;  // the bytes of each digit's picture
    for (char d = '0'; d <= '9'; ++d) {
        const std::string text(1, d);
        for (int scale : {1, 2}) {
            const auto bytes = static_cast<std::size_t>(35 * scale * scale) * 3;
            rgb_image img{5 * scale, 7 * scale, std::vector<std::uint8_t>(bytes, 0)};
            draw_text(img, 0, 0, text, {200, 100, 50}, scale);
            const auto rows = glyph_rows(static_cast<char32_t>(d));
            for (std::ptrdiff_t r = 0; r < img.height; ++r)
                for (std::ptrdiff_t c = 0; c < img.width; ++c) {
                    const bool on = (rows[static_cast<std::size_t>(r / scale)] >> (4 - c / scale)) & 1;
                    CHECK(pixel(img, r, c) == (on ? rgb{200, 100, 50} : rgb{0, 0, 0}));
                }
            if (scale == 1) pictures.insert(std::string(img.rgb.begin(), img.rgb.end()));
            rgb_image again{img.width, img.height, std::vector<std::uint8_t>(img.rgb.size(), 0)};
            draw_text(again, 0, 0, text, {200, 100, 50}, scale);
            CHECK(again.rgb == img.rgb);
        }
    }
    CHECK(pictures.size() == 10);  // ten different digits

    CHECK(text_width_px("", 1) == 0);
    CHECK(text_width_px("12", 1) == 11);
    CHECK(text_width_px("kWh/m²", 2) == (6 * 6 - 1) * 2);  // "²" is one character
    CHECK(glyph_rows(U'²') != glyph_rows(U'2'));
    CHECK(glyph_rows(U'é') == glyph_rows(U'€'));  // unknown characters: the same empty box
    CHECK(glyph_rows(U'é') != glyph_rows(U' '));
    rgb_image edge{3, 3, std::vector<std::uint8_t>(27, 0)};
    draw_text(edge, -2, -2, "8", {9, 9, 9});   // partly outside: clipped, no crash
    CHECK(pixel(edge, 0, 0) == rgb{0, 0, 0});  // glyph row 2 (10001), column 2: off
    CHECK(pixel(edge, 1, 0) == rgb{9, 9, 9});  // glyph row 3 (01110), column 2: on
    CHECK_THROWS_AS(draw_text(edge, 0, 0, "1", {0, 0, 0}, 0), invalid_input);
}

TEST_CASE("io/glyph_rows: every printable ASCII character, ² and ° have their own glyph")
{
    const auto box = glyph_rows(U'é');
    std::set<std::array<std::uint8_t, 7>> seen;
    for (char32_t ch = U'!'; ch <= U'~'; ++ch) {
        CAPTURE(static_cast<int>(ch));
        const auto g = glyph_rows(ch);
        CHECK(g != box);
        CHECK(g != glyph_rows(U' '));
        for (const auto row : g) CHECK(row < 32);  // 5 columns
        seen.insert(g);
    }
    seen.insert(glyph_rows(U'²'));
    seen.insert(glyph_rows(U'°'));
    CHECK(seen.size() == 94 + 2);  // no two characters look the same
    // Upper and lower case differ, and a word draws as its letters side by side.
    CHECK(glyph_rows(U'a') != glyph_rows(U'A'));
    rgb_image word{23, 7, std::vector<std::uint8_t>(23 * 7 * 3, 0)};
    draw_text(word, 0, 0, "Ab,", {255, 255, 255});
    for (std::ptrdiff_t r = 0; r < 7; ++r)
        for (std::ptrdiff_t c = 0; c < 5; ++c) {
            const auto lit = [&](char32_t ch) {
                return ((glyph_rows(ch)[static_cast<std::size_t>(r)] >> (4 - c)) & 1) != 0;
            };
            CHECK((pixel(word, r, c)[0] == 255) == lit(U'A'));
            CHECK((pixel(word, r, c + 6)[0] == 255) == lit(U'b'));
            CHECK((pixel(word, r, c + 12)[0] == 255) == lit(U','));
        }
}

TEST_CASE("io/azimuth_color: a cyclic wheel, 0 and 359.9 degrees alike, opposite directions far apart")
{
    const auto distance = [](const rgb& a, const rgb& b) {
        return std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]);
    };
    CHECK(distance(azimuth_color(0.0), azimuth_color(359.9)) <= 3);
    CHECK(azimuth_color(0.0) == azimuth_color(360.0));
    CHECK(azimuth_color(-90.0) == azimuth_color(270.0));
    CHECK(distance(azimuth_color(90.0), azimuth_color(270.0)) > 200);
    CHECK(distance(azimuth_color(0.0), azimuth_color(180.0)) > 200);
    // Neighbouring directions are near: no jump anywhere on the wheel.
    for (int a = 0; a < 360; ++a) {
        CAPTURE(a);
        CHECK(distance(azimuth_color(a), azimuth_color(a + 1)) <= 16);
    }
    const rgb north = azimuth_color(0.0);
    CHECK(north[2] > north[0]);  // north is blue
    CHECK(cyclic_color(std::nan("")) == rgb{0, 0, 0});
}

TEST_CASE("io/colorize_over_hillshade: finite cells as colorize, the others a dim hillshade of the terrain")
{
    raster<float> z(6, 7);
    for (std::ptrdiff_t r = 0; r < 6; ++r)
        for (std::ptrdiff_t c = 0; c < 7; ++c)
            z(r, c) = static_cast<float>(0.7 * static_cast<double>(c) - 0.3 * static_cast<double>(r));
    raster<float> v(6, 7, NAN);
    v(1, 2) = 3.0f;
    v(4, 5) = 8.0f;
    const rgb_image img = colorize_over_hillshade(v.view(), 0.0, 10.0, z.view(), 1.0);
    const rgb_image colours = colorize(v.view(), 0.0, 10.0);
    const raster<std::uint8_t> shade = hillshade(z.view(), 1.0);
    for (std::ptrdiff_t r = 0; r < 6; ++r)
        for (std::ptrdiff_t c = 0; c < 7; ++c) {
            const auto at = static_cast<std::size_t>((r * 7 + c) * 3);
            const rgb got{img.rgb[at], img.rgb[at + 1], img.rgb[at + 2]};
            const auto grey = static_cast<std::uint8_t>(shade(r, c) / 2);
            const rgb want = std::isnan(v(r, c)) ? rgb{grey, grey, grey}
                                                 : rgb{colours.rgb[at], colours.rgb[at + 1], colours.rgb[at + 2]};
            INFO("cell ", r, ",", c);
            CHECK(got == want);
        }
    CHECK_THROWS_AS(colorize_over_hillshade(v.view(), 0.0, 10.0, raster<float>(2, 2).view(), 1.0), invalid_input);
}
