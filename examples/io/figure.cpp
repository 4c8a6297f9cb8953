// SPDX-License-Identifier: Apache-2.0
#include "io/figure.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

#include <lidarfx/core/error.hpp>

#include "io/quicklook.hpp"

namespace lidarfx::io {

namespace {

using rgb = std::array<std::uint8_t, 3>;
constexpr rgb black{0, 0, 0};
constexpr rgb hatch_dark{150, 150, 150}, hatch_light{225, 225, 225};

constexpr int text_scale = 2;
constexpr std::ptrdiff_t text_h = 7 * text_scale;  // height of a line of text
constexpr std::ptrdiff_t margin = 16;              // around the figure and between its parts
constexpr std::ptrdiff_t scale_row_h = 28;         // the scale bar and north arrow row
constexpr std::ptrdiff_t bar_h = 16;               // the colour bar
constexpr std::ptrdiff_t swatch_w = 20, swatch_gap = 8, entry_gap = 24;

void put(rgb_image& img, std::ptrdiff_t r, std::ptrdiff_t c, const rgb& color)
{
    if (r < 0 || c < 0 || r >= img.height || c >= img.width) return;
    std::copy(color.begin(), color.end(), img.rgb.begin() + (r * img.width + c) * 3);
}

void fill(rgb_image& img, std::ptrdiff_t r0, std::ptrdiff_t c0, std::ptrdiff_t h, std::ptrdiff_t w, const rgb& color)
{
    for (std::ptrdiff_t r = r0; r < r0 + h; ++r)
        for (std::ptrdiff_t c = c0; c < c0 + w; ++c) put(img, r, c, color);
}

void frame(rgb_image& img, std::ptrdiff_t r0, std::ptrdiff_t c0, std::ptrdiff_t h, std::ptrdiff_t w)
{
    fill(img, r0 - 1, c0 - 1, 1, w + 2, black);
    fill(img, r0 + h, c0 - 1, 1, w + 2, black);
    fill(img, r0 - 1, c0 - 1, h + 2, 1, black);
    fill(img, r0 - 1, c0 + w, h + 2, 1, black);
}

std::string number_text(double v)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", v);
    return buf;
}

std::ptrdiff_t text_w(const std::string& text)
{
    return text_width_px(text, text_scale);
}

/// Width of one legend entry: swatch, gap, name.
std::ptrdiff_t entry_w(const figure_key& k)
{
    return swatch_w + swatch_gap + text_w(k.name);
}

/// Rows of legend entries, each no wider than `width` (an entry wider than that gets a row of its own).
std::vector<std::vector<const figure_key*>> key_rows(const std::vector<figure_key>& key, std::ptrdiff_t width)
{
    std::vector<std::vector<const figure_key*>> rows;
    std::ptrdiff_t used = 0;
    for (const figure_key& k : key) {
        if (rows.empty() || used + entry_gap + entry_w(k) > width) {
            rows.emplace_back();
            used = -entry_gap;
        }
        rows.back().push_back(&k);
        used += entry_gap + entry_w(k);
    }
    return rows;
}

}  // namespace

std::array<std::uint8_t, 3> no_data_color(std::ptrdiff_t row, std::ptrdiff_t col) noexcept
{
    const std::ptrdiff_t d = ((row + col) % 8 + 8) % 8;
    return d < 3 ? hatch_dark : hatch_light;
}

bool is_no_data_color(std::array<std::uint8_t, 3> color) noexcept
{
    return color == hatch_dark || color == hatch_light;
}

raster<std::uint8_t> non_finite_cells(raster_view<const float> values)
{
    raster<std::uint8_t> out(values.rows(), values.cols(), 0);
    for (std::ptrdiff_t r = 0; r < values.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < values.cols(); ++c) out(r, c) = !std::isfinite(values(r, c));
    return out;
}

figure_bar finite_bar(raster_view<const float> values, std::string unit)
{
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::ptrdiff_t r = 0; r < values.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < values.cols(); ++c)
            if (const double v = values(r, c); std::isfinite(v)) {
                lo = std::min(lo, v);
                hi = std::max(hi, v);
            }
    if (!(lo <= hi)) lo = hi = 0.0;
    return {lo, hi, std::move(unit)};
}

std::ptrdiff_t figure_factor(std::ptrdiff_t rows, std::ptrdiff_t cols, std::ptrdiff_t min_long_side,
                             std::ptrdiff_t max_factor) noexcept
{
    const std::ptrdiff_t side = std::max<std::ptrdiff_t>(1, std::max(rows, cols));
    return std::clamp<std::ptrdiff_t>((min_long_side + side - 1) / side, 1, std::max<std::ptrdiff_t>(1, max_factor));
}

double round_scale_length(double target) noexcept
{
    const double decade = std::pow(10.0, std::floor(std::log10(target)));
    for (const double m : {5.0, 2.0, 1.0})
        if (m * decade <= target * (1 + 1e-9)) return m * decade;
    return decade;
}

std::string short_unit_name(double unit_m, const std::string& name)
{
    if (unit_m == 1.0) return "m";
    if (std::abs(unit_m - 0.3048) < 1e-9) return "ft";
    if (std::abs(unit_m - 1200.0 / 3937.0) < 1e-9) return "US ft";
    return name;
}

figure make_figure(const rgb_image& map, raster_view<const std::uint8_t> no_data, const figure_options& opt)
{
    constexpr const char* fn = "make_figure";
    detail::require(
        map.width > 0 && map.height > 0 && map.rgb.size() == static_cast<std::size_t>(map.width * map.height * 3), fn,
        "map must not be empty and hold width * height * 3 bytes");
    detail::require(
        no_data.rows() * no_data.cols() == 0 || (no_data.rows() == map.height && no_data.cols() == map.width), fn,
        "no_data must be empty or have the map's shape");
    detail::require_positive(opt.cell_size, fn, "cell_size");
    if (opt.bar) {
        detail::require(std::isfinite(opt.bar->min) && std::isfinite(opt.bar->max) && opt.bar->min <= opt.bar->max, fn,
                        "the colour bar's min and max must be finite with min <= max");
    }
    figure out;
    figure_layout& at = out.layout;
    at.factor = figure_factor(map.height, map.width, opt.min_long_side, opt.max_factor);
    const std::ptrdiff_t f = at.factor, map_w = map.width * f, map_h = map.height * f;

    // Scale bar: a round length near a quarter of the map's width.
    at.scale_length = round_scale_length(static_cast<double>(map.width) * opt.cell_size / 4.0);
    at.scale_px = std::lround(at.scale_length / opt.cell_size * static_cast<double>(f));
    const std::string scale_text = number_text(at.scale_length) + " " + opt.unit;
    const std::string north_text = "grid north";
    const std::ptrdiff_t arrow_w = 14;
    const std::ptrdiff_t scale_need =
        at.scale_px + 10 + text_w(scale_text) + 2 * margin + text_w(north_text) + 8 + arrow_w;

    const std::string lo = opt.bar ? number_text(opt.bar->min) : "", hi = opt.bar ? number_text(opt.bar->max) : "";
    const std::string bar_unit = opt.bar ? opt.bar->unit : "";
    const std::ptrdiff_t bar_need = opt.bar ? 2 * std::max(text_w(lo), text_w(hi)) + text_w(bar_unit) + 2 * margin : 0;

    std::vector<figure_key> key = opt.key;
    key.push_back({hatch_light, opt.no_data_name});
    std::ptrdiff_t widest_entry = 0;
    for (const auto& k : key) widest_entry = std::max(widest_entry, entry_w(k));

    const std::ptrdiff_t content_w =
        std::max({map_w, text_w(opt.title), scale_need, bar_need, widest_entry, std::ptrdiff_t{400}});
    const auto rows_of_key = key_rows(key, content_w);

    at.title_row = margin;
    at.title_col = margin;
    at.map_row = at.title_row + text_h + margin;
    at.map_col = margin;
    at.scale_row = at.map_row + map_h + margin + 6;
    at.scale_col = margin;
    at.legend_row = at.scale_row + scale_row_h + margin;
    const std::ptrdiff_t bar_w = std::clamp<std::ptrdiff_t>(map_w, std::min<std::ptrdiff_t>(content_w, 300), content_w);
    const std::ptrdiff_t key_row0 = opt.bar ? at.legend_row + bar_h + 6 + text_h + margin : at.legend_row;
    const std::ptrdiff_t key_line_h = text_h + 8;
    const std::ptrdiff_t height = key_row0 + static_cast<std::ptrdiff_t>(rows_of_key.size()) * key_line_h + margin;
    const std::ptrdiff_t width = content_w + 2 * margin;

    rgb_image& img = out.image;
    img = {width, height, std::vector<std::uint8_t>(static_cast<std::size_t>(width * height) * 3, 255)};
    draw_text(img, at.title_row, at.title_col, opt.title, black, text_scale);

    // The map, nearest neighbour, no-data cells hatched.
    const bool has_no_data = no_data.rows() * no_data.cols() > 0;
    for (std::ptrdiff_t r = 0; r < map_h; ++r) {
        for (std::ptrdiff_t c = 0; c < map_w; ++c) {
            const std::ptrdiff_t mr = r / f, mc = c / f, fr = at.map_row + r, fc = at.map_col + c;
            if (has_no_data && no_data(mr, mc)) {
                put(img, fr, fc, no_data_color(fr, fc));
            } else {
                const auto* px = &map.rgb[static_cast<std::size_t>((mr * map.width + mc) * 3)];
                put(img, fr, fc, {px[0], px[1], px[2]});
            }
        }
    }
    frame(img, at.map_row, at.map_col, map_h, map_w);

    // Scale bar: a black bar with end ticks, its length written after it.
    fill(img, at.scale_row + 8, at.scale_col, 6, at.scale_px, black);
    fill(img, at.scale_row + 2, at.scale_col, 18, 2, black);
    fill(img, at.scale_row + 2, at.scale_col + at.scale_px - 2, 18, 2, black);
    draw_text(img, at.scale_row + 4, at.scale_col + at.scale_px + 10, scale_text, black, text_scale);

    // North arrow at the right: a triangle on a shaft pointing to row 0, "grid north" before it.
    const std::ptrdiff_t arrow_c = margin + content_w - arrow_w;
    for (std::ptrdiff_t r = 0; r < 14; ++r) {
        const std::ptrdiff_t half = r / 2;
        fill(img, at.scale_row + r, arrow_c + arrow_w / 2 - half, 1, 2 * half + 1, black);
    }
    fill(img, at.scale_row + 14, arrow_c + arrow_w / 2 - 1, scale_row_h - 14, 3, black);
    draw_text(img, at.scale_row + 8, arrow_c - 8 - text_w(north_text), north_text, black, text_scale);

    if (opt.bar) {
        for (std::ptrdiff_t c = 0; c < bar_w; ++c) {
            const double t = bar_w > 1 ? static_cast<double>(c) / static_cast<double>(bar_w - 1) : 0.5;
            fill(img, at.legend_row, margin + c, bar_h, 1, ramp_color(t));
        }
        frame(img, at.legend_row, margin, bar_h, bar_w);
        const std::ptrdiff_t text_row = at.legend_row + bar_h + 6;
        draw_text(img, text_row, margin, lo, black, text_scale);
        draw_text(img, text_row, margin + bar_w - text_w(hi), hi, black, text_scale);
        draw_text(img, text_row, margin + (bar_w - text_w(bar_unit)) / 2, bar_unit, black, text_scale);
    }

    std::ptrdiff_t row = key_row0;
    for (const auto& line : rows_of_key) {
        std::ptrdiff_t col = margin;
        for (const figure_key* k : line) {
            const bool is_no_data = k == &key.back();
            for (std::ptrdiff_t r = 0; r < text_h; ++r)
                for (std::ptrdiff_t c = 0; c < swatch_w; ++c)
                    put(img, row + r, col + c, is_no_data ? no_data_color(row + r, col + c) : k->color);
            frame(img, row, col, text_h, swatch_w);
            draw_text(img, row, col + swatch_w + swatch_gap, k->name, black, text_scale);
            col += entry_w(*k) + entry_gap;
        }
        row += key_line_h;
    }
    return out;
}

std::vector<figure_key> compass_key(const std::vector<figure_key>& more)
{
    std::vector<figure_key> key;
    const char* names[] = {"N 0°", "NE", "E 90°", "SE", "S 180°", "SW", "W 270°", "NW"};
    for (int i = 0; i < 8; ++i) key.push_back({azimuth_color(45.0 * i), names[i]});
    key.insert(key.end(), more.begin(), more.end());
    return key;
}

}  // namespace lidarfx::io
