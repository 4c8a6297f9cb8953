// SPDX-License-Identifier: Apache-2.0
#include "io/quicklook.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include <lidarfx/core/error.hpp>
#include <lidarfx/core/parallel.hpp>

namespace lidarfx::io {

namespace {

// viridis at t = 0, 1/8, ..., 1 (matplotlib, CC0).
constexpr std::array<std::array<std::uint8_t, 3>, 9> viridis{{{68, 1, 84},
                                                              {71, 45, 123},
                                                              {59, 82, 139},
                                                              {44, 114, 142},
                                                              {33, 144, 140},
                                                              {39, 173, 129},
                                                              {93, 200, 99},
                                                              {170, 220, 50},
                                                              {253, 231, 37}}};

rgb_image blank(std::ptrdiff_t rows, std::ptrdiff_t cols, const char* fn)
{
    detail::require(rows > 0 && cols > 0, fn, "raster must not be empty");
    return {cols, rows, std::vector<std::uint8_t>(static_cast<std::size_t>(rows * cols) * 3)};
}

void put(rgb_image& img, std::ptrdiff_t r, std::ptrdiff_t c, const std::array<std::uint8_t, 3>& rgb)
{
    std::copy(rgb.begin(), rgb.end(), img.rgb.begin() + (r * img.width + c) * 3);
}

}  // namespace

std::array<std::uint8_t, 3> ramp_color(double t) noexcept
{
    if (std::isnan(t)) return {0, 0, 0};
    const double u = std::clamp(t, 0.0, 1.0) * 8.0;
    const auto k = std::min<std::size_t>(7, static_cast<std::size_t>(u));
    const double f = u - static_cast<double>(k);
    std::array<std::uint8_t, 3> out{};
    for (std::size_t i = 0; i < 3; ++i) {
        const double v = (1.0 - f) * viridis[k][i] + f * viridis[k + 1][i];
        out[i] = static_cast<std::uint8_t>(std::lround(v));
    }
    return out;
}

rgb_image colorize(raster_view<const float> values, double min, double max)
{
    detail::require(std::isfinite(min) && std::isfinite(max) && min <= max, "colorize",
                    "min and max must be finite with min <= max");
    rgb_image img = blank(values.rows(), values.cols(), "colorize");
    const double span = max - min;
    for (std::ptrdiff_t r = 0; r < values.rows(); ++r) {
        const float* row = values.row(r);
        for (std::ptrdiff_t c = 0; c < values.cols(); ++c) {
            const double v = row[c];
            const double t = std::isnan(v) ? v : span > 0 ? (v - min) / span : 0.5;
            put(img, r, c, ramp_color(t));
        }
    }
    return img;
}

rgb_image colorize(raster_view<const float> values)
{
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::ptrdiff_t r = 0; r < values.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < values.cols(); ++c) {
            const double v = values(r, c);
            if (std::isfinite(v)) {
                lo = std::min(lo, v);
                hi = std::max(hi, v);
            }
        }
    }
    if (!(lo <= hi)) return blank(values.rows(), values.cols(), "colorize");  // no finite value: all black
    return colorize(values, lo, hi);
}

raster<std::uint8_t> hillshade(raster_view<const float> z, double cell_m, double azimuth_deg, double altitude_deg,
                               int threads)
{
    constexpr const char* fn = "hillshade";
    detail::require_positive(cell_m, fn, "cell_m");
    detail::require(std::isfinite(azimuth_deg), fn, "azimuth_deg", "finite", azimuth_deg);
    detail::require(altitude_deg >= 0 && altitude_deg <= 90, fn, "altitude_deg", "in [0, 90]", altitude_deg);
    const double deg = std::numbers::pi / 180.0;
    // Light direction in (east, north, up).
    const double lx = std::sin(azimuth_deg * deg) * std::cos(altitude_deg * deg);
    const double ly = std::cos(azimuth_deg * deg) * std::cos(altitude_deg * deg);
    const double lz = std::sin(altitude_deg * deg);
    const std::ptrdiff_t rows = z.rows(), cols = z.cols();
    raster<std::uint8_t> out(rows, cols, 0);
    const auto at = [&](std::ptrdiff_t r, std::ptrdiff_t c) {
        return r >= 0 && c >= 0 && r < rows && c < cols ? static_cast<double>(z(r, c)) : std::nan("");
    };
    // Difference along one axis at (r, c): central when both neighbours exist, else one-sided, else none.
    const auto diff = [](double before, double centre, double after, double& d) {
        const bool b = !std::isnan(before), a = !std::isnan(after);
        if (b && a)
            d = (after - before) / 2.0;
        else if (a)
            d = after - centre;
        else if (b)
            d = centre - before;
        return b || a;
    };
    // Rows are independent: blocks of them on `threads` threads.
    parallel_for_rows(rows, 64, threads, [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
        for (std::ptrdiff_t r = r0; r < r1; ++r) {
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                const double centre = at(r, c);
                if (std::isnan(centre)) continue;
                // Horn: weights 1, 2, 1 over the three rows (for d/dx) or columns (for d/dy) that have a difference.
                double sx = 0, wx = 0, sy = 0, wy = 0;
                for (int k = -1; k <= 1; ++k) {
                    const double w = k == 0 ? 2.0 : 1.0;
                    const double mid_x = at(r + k, c), mid_y = at(r, c + k);
                    double d = 0;
                    if (!std::isnan(mid_x) && diff(at(r + k, c - 1), mid_x, at(r + k, c + 1), d)) {
                        sx += w * d;
                        wx += w;
                    }
                    if (!std::isnan(mid_y) && diff(at(r - 1, c + k), mid_y, at(r + 1, c + k), d)) {
                        sy += w * d;
                        wy += w;
                    }
                }
                const double dzdx = wx > 0 ? sx / wx / cell_m : 0.0;
                const double dzdy = wy > 0 ? -sy / wy / cell_m : 0.0;  // rows grow southwards
                const double shade = (-dzdx * lx - dzdy * ly + lz) / std::sqrt(dzdx * dzdx + dzdy * dzdy + 1.0);
                out(r, c) = static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(shade, 0.0, 1.0)));
            }
        }
    });
    return out;
}

std::array<std::uint8_t, 3> cyclic_color(double t) noexcept
{
    if (std::isnan(t)) return {0, 0, 0};
    const double turn = t - std::floor(t);
    double h = (240.0 - 360.0 * turn) / 60.0;  // hue in sixths of the wheel, in (-2, 4]
    if (h < 0) h += 6.0;
    constexpr double s = 0.75, v = 0.95;
    const int sector = std::min(5, static_cast<int>(h));
    const double f = h - sector;
    const double p = v * (1 - s), q = v * (1 - s * f), u = v * (1 - s * (1 - f));
    const std::array<std::array<double, 3>, 6> rgb{{{v, u, p}, {q, v, p}, {p, v, u}, {p, q, v}, {u, p, v}, {v, p, q}}};
    std::array<std::uint8_t, 3> out{};
    for (std::size_t i = 0; i < 3; ++i) {
        out[i] = static_cast<std::uint8_t>(std::lround(255.0 * rgb[static_cast<std::size_t>(sector)][i]));
    }
    return out;
}

std::array<std::uint8_t, 3> azimuth_color(double azimuth_deg) noexcept
{
    return cyclic_color(azimuth_deg / 360.0);
}

rgb_image colorize_over_hillshade(raster_view<const float> values, double min, double max,
                                  raster_view<const float> elevation, double cell_m, color_ramp ramp)
{
    detail::require_same_shape(values, elevation, "colorize_over_hillshade", "values", "elevation");
    rgb_image img = colorize(values, min, max);
    if (ramp != ramp_color) {
        const double span = max - min;
        for (std::ptrdiff_t r = 0; r < values.rows(); ++r)
            for (std::ptrdiff_t c = 0; c < values.cols(); ++c)
                if (std::isfinite(values(r, c))) put(img, r, c, ramp(span > 0 ? (values(r, c) - min) / span : 0.5));
    }
    const raster<std::uint8_t> shade = hillshade(elevation, cell_m);
    for (std::ptrdiff_t r = 0; r < values.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < values.cols(); ++c)
            if (!std::isfinite(values(r, c))) {
                std::uint8_t* px = &img.rgb[static_cast<std::size_t>((r * img.width + c) * 3)];
                px[0] = px[1] = px[2] = static_cast<std::uint8_t>(shade(r, c) / 2);
            }
    return img;
}

std::array<std::uint8_t, 3> label_color(std::int32_t label) noexcept
{
    if (label == 0) return {0, 0, 0};
    // Additive recurrences with irrational steps spread hue, saturation and value evenly.
    const double n = static_cast<double>(static_cast<std::uint32_t>(label));
    const auto frac = [](double x) { return x - std::floor(x); };
    const double h = frac(n * 0.6180339887498949) * 6.0;
    const double s = 0.45 + 0.40 * frac(n * 0.7548776662466927);
    const double v = 0.80 + 0.20 * frac(n * 0.5698402909980532);
    const int sector = std::min(5, static_cast<int>(h));
    const double f = h - sector;
    const double p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
    const std::array<std::array<double, 3>, 6> rgb{{{v, t, p}, {q, v, p}, {p, v, t}, {p, q, v}, {t, p, v}, {v, p, q}}};
    std::array<std::uint8_t, 3> out{};
    for (std::size_t i = 0; i < 3; ++i) {
        out[i] = static_cast<std::uint8_t>(std::lround(255.0 * rgb[static_cast<std::size_t>(sector)][i]));
    }
    return out;
}

rgb_image colorize_labels(raster_view<const std::int32_t> labels)
{
    rgb_image img = blank(labels.rows(), labels.cols(), "colorize_labels");
    for (std::ptrdiff_t r = 0; r < labels.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < labels.cols(); ++c) put(img, r, c, label_color(labels(r, c)));
    }
    return img;
}

rgb_image overlay_mask(raster_view<const std::uint8_t> grey, raster_view<const std::uint8_t> mask,
                       std::array<std::uint8_t, 3> color, double opacity)
{
    constexpr const char* fn = "overlay_mask";
    detail::require_same_shape(grey, mask, fn, "grey", "mask");
    detail::require(opacity >= 0 && opacity <= 1, fn, "opacity", "in [0, 1]", opacity);
    rgb_image img = blank(grey.rows(), grey.cols(), fn);
    for (std::ptrdiff_t r = 0; r < grey.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < grey.cols(); ++c) {
            const double g = grey(r, c);
            std::array<std::uint8_t, 3> px{grey(r, c), grey(r, c), grey(r, c)};
            if (mask(r, c) != 0) {
                for (std::size_t i = 0; i < 3; ++i) {
                    px[i] = static_cast<std::uint8_t>(std::lround((1.0 - opacity) * g + opacity * color[i]));
                }
            }
            put(img, r, c, px);
        }
    }
    return img;
}

namespace {

// The printable ASCII characters ' ' (32) .. '~' (126), 7 rows of 5 columns each, bit 4 = left column.
constexpr std::array<std::array<std::uint8_t, 7>, 95> ascii_font{{
    {0, 0, 0, 0, 0, 0, 0},                                            // space
    {0b00100, 0b00100, 0b00100, 0b00100, 0b00100, 0, 0b00100},        // !
    {0b01010, 0b01010, 0b01010, 0, 0, 0, 0},                          // "
    {0b01010, 0b01010, 0b11111, 0b01010, 0b11111, 0b01010, 0b01010},  // #
    {0b00100, 0b01111, 0b10100, 0b01110, 0b00101, 0b11110, 0b00100},  // $
    {0b11000, 0b11001, 0b00010, 0b00100, 0b01000, 0b10011, 0b00011},  // %
    {0b01100, 0b10010, 0b10100, 0b01000, 0b10101, 0b10010, 0b01101},  // &
    {0b01100, 0b00100, 0b01000, 0, 0, 0, 0},                          // apostrophe
    {0b00010, 0b00100, 0b01000, 0b01000, 0b01000, 0b00100, 0b00010},  // (
    {0b01000, 0b00100, 0b00010, 0b00010, 0b00010, 0b00100, 0b01000},  // )
    {0, 0b00100, 0b10101, 0b01110, 0b10101, 0b00100, 0},              // *
    {0, 0b00100, 0b00100, 0b11111, 0b00100, 0b00100, 0},              // +
    {0, 0, 0, 0, 0b01100, 0b00100, 0b01000},                          // ,
    {0, 0, 0, 0b11111, 0, 0, 0},                                      // -
    {0, 0, 0, 0, 0, 0b01100, 0b01100},                                // .
    {0, 0b00001, 0b00010, 0b00100, 0b01000, 0b10000, 0},              // /
    {0b01110, 0b10001, 0b10011, 0b10101, 0b11001, 0b10001, 0b01110},  // 0
    {0b00100, 0b01100, 0b00100, 0b00100, 0b00100, 0b00100, 0b01110},  // 1
    {0b01110, 0b10001, 0b00001, 0b00010, 0b00100, 0b01000, 0b11111},  // 2
    {0b11111, 0b00010, 0b00100, 0b00010, 0b00001, 0b10001, 0b01110},  // 3
    {0b00010, 0b00110, 0b01010, 0b10010, 0b11111, 0b00010, 0b00010},  // 4
    {0b11111, 0b10000, 0b11110, 0b00001, 0b00001, 0b10001, 0b01110},  // 5
    {0b00110, 0b01000, 0b10000, 0b11110, 0b10001, 0b10001, 0b01110},  // 6
    {0b11111, 0b00001, 0b00010, 0b00100, 0b01000, 0b01000, 0b01000},  // 7
    {0b01110, 0b10001, 0b10001, 0b01110, 0b10001, 0b10001, 0b01110},  // 8
    {0b01110, 0b10001, 0b10001, 0b01111, 0b00001, 0b00010, 0b01100},  // 9
    {0, 0b01100, 0b01100, 0, 0b01100, 0b01100, 0},                    // :
    {0, 0b01100, 0b01100, 0, 0b01100, 0b00100, 0b01000},              // ;
    {0b00010, 0b00100, 0b01000, 0b10000, 0b01000, 0b00100, 0b00010},  // <
    {0, 0, 0b11111, 0, 0b11111, 0, 0},                                // =
    {0b01000, 0b00100, 0b00010, 0b00001, 0b00010, 0b00100, 0b01000},  // >
    {0b01110, 0b10001, 0b00001, 0b00010, 0b00100, 0, 0b00100},        // ?
    {0b01110, 0b10001, 0b00001, 0b01101, 0b10101, 0b10101, 0b01110},  // @
    {0b01110, 0b10001, 0b10001, 0b10001, 0b11111, 0b10001, 0b10001},  // A
    {0b11110, 0b10001, 0b10001, 0b11110, 0b10001, 0b10001, 0b11110},  // B
    {0b01110, 0b10001, 0b10000, 0b10000, 0b10000, 0b10001, 0b01110},  // C
    {0b11100, 0b10010, 0b10001, 0b10001, 0b10001, 0b10010, 0b11100},  // D
    {0b11111, 0b10000, 0b10000, 0b11110, 0b10000, 0b10000, 0b11111},  // E
    {0b11111, 0b10000, 0b10000, 0b11110, 0b10000, 0b10000, 0b10000},  // F
    {0b01110, 0b10001, 0b10000, 0b10111, 0b10001, 0b10001, 0b01111},  // G
    {0b10001, 0b10001, 0b10001, 0b11111, 0b10001, 0b10001, 0b10001},  // H
    {0b01110, 0b00100, 0b00100, 0b00100, 0b00100, 0b00100, 0b01110},  // I
    {0b00111, 0b00010, 0b00010, 0b00010, 0b00010, 0b10010, 0b01100},  // J
    {0b10001, 0b10010, 0b10100, 0b11000, 0b10100, 0b10010, 0b10001},  // K
    {0b10000, 0b10000, 0b10000, 0b10000, 0b10000, 0b10000, 0b11111},  // L
    {0b10001, 0b11011, 0b10101, 0b10101, 0b10001, 0b10001, 0b10001},  // M
    {0b10001, 0b10001, 0b11001, 0b10101, 0b10011, 0b10001, 0b10001},  // N
    {0b01110, 0b10001, 0b10001, 0b10001, 0b10001, 0b10001, 0b01110},  // O
    {0b11110, 0b10001, 0b10001, 0b11110, 0b10000, 0b10000, 0b10000},  // P
    {0b01110, 0b10001, 0b10001, 0b10001, 0b10101, 0b10010, 0b01101},  // Q
    {0b11110, 0b10001, 0b10001, 0b11110, 0b10100, 0b10010, 0b10001},  // R
    {0b01111, 0b10000, 0b10000, 0b01110, 0b00001, 0b00001, 0b11110},  // S
    {0b11111, 0b00100, 0b00100, 0b00100, 0b00100, 0b00100, 0b00100},  // T
    {0b10001, 0b10001, 0b10001, 0b10001, 0b10001, 0b10001, 0b01110},  // U
    {0b10001, 0b10001, 0b10001, 0b10001, 0b10001, 0b01010, 0b00100},  // V
    {0b10001, 0b10001, 0b10001, 0b10101, 0b10101, 0b10101, 0b01010},  // W
    {0b10001, 0b10001, 0b01010, 0b00100, 0b01010, 0b10001, 0b10001},  // X
    {0b10001, 0b10001, 0b10001, 0b01010, 0b00100, 0b00100, 0b00100},  // Y
    {0b11111, 0b00001, 0b00010, 0b00100, 0b01000, 0b10000, 0b11111},  // Z
    {0b01110, 0b01000, 0b01000, 0b01000, 0b01000, 0b01000, 0b01110},  // [
    {0, 0b10000, 0b01000, 0b00100, 0b00010, 0b00001, 0},              // backslash
    {0b01110, 0b00010, 0b00010, 0b00010, 0b00010, 0b00010, 0b01110},  // ]
    {0b00100, 0b01010, 0b10001, 0, 0, 0, 0},                          // ^
    {0, 0, 0, 0, 0, 0, 0b11111},                                      // _
    {0b01000, 0b00100, 0b00010, 0, 0, 0, 0},                          // `
    {0, 0, 0b01110, 0b00001, 0b01111, 0b10001, 0b01111},              // a
    {0b10000, 0b10000, 0b10110, 0b11001, 0b10001, 0b10001, 0b11110},  // b
    {0, 0, 0b01110, 0b10000, 0b10000, 0b10001, 0b01110},              // c
    {0b00001, 0b00001, 0b01101, 0b10011, 0b10001, 0b10001, 0b01111},  // d
    {0, 0, 0b01110, 0b10001, 0b11111, 0b10000, 0b01110},              // e
    {0b00110, 0b01001, 0b01000, 0b11100, 0b01000, 0b01000, 0b01000},  // f
    {0, 0b01111, 0b10001, 0b10001, 0b01111, 0b00001, 0b01110},        // g
    {0b10000, 0b10000, 0b10110, 0b11001, 0b10001, 0b10001, 0b10001},  // h
    {0b00100, 0, 0b01100, 0b00100, 0b00100, 0b00100, 0b01110},        // i
    {0b00010, 0, 0b00110, 0b00010, 0b00010, 0b10010, 0b01100},        // j
    {0b10000, 0b10000, 0b10010, 0b10100, 0b11000, 0b10100, 0b10010},  // k
    {0b01100, 0b00100, 0b00100, 0b00100, 0b00100, 0b00100, 0b01110},  // l
    {0, 0, 0b11010, 0b10101, 0b10101, 0b10001, 0b10001},              // m
    {0, 0, 0b10110, 0b11001, 0b10001, 0b10001, 0b10001},              // n
    {0, 0, 0b01110, 0b10001, 0b10001, 0b10001, 0b01110},              // o
    {0, 0, 0b11110, 0b10001, 0b11110, 0b10000, 0b10000},              // p
    {0, 0, 0b01101, 0b10011, 0b01111, 0b00001, 0b00001},              // q
    {0, 0, 0b10110, 0b11001, 0b10000, 0b10000, 0b10000},              // r
    {0, 0, 0b01110, 0b10000, 0b01110, 0b00001, 0b11110},              // s
    {0b01000, 0b01000, 0b11100, 0b01000, 0b01000, 0b01001, 0b00110},  // t
    {0, 0, 0b10001, 0b10001, 0b10001, 0b10011, 0b01101},              // u
    {0, 0, 0b10001, 0b10001, 0b10001, 0b01010, 0b00100},              // v
    {0, 0, 0b10001, 0b10001, 0b10101, 0b10101, 0b01010},              // w
    {0, 0, 0b10001, 0b01010, 0b00100, 0b01010, 0b10001},              // x
    {0, 0, 0b10001, 0b10001, 0b01111, 0b00001, 0b01110},              // y
    {0, 0, 0b11111, 0b00010, 0b00100, 0b01000, 0b11111},              // z
    {0b00010, 0b00100, 0b00100, 0b01000, 0b00100, 0b00100, 0b00010},  // {
    {0b00100, 0b00100, 0b00100, 0b00100, 0b00100, 0b00100, 0b00100},  // |
    {0b01000, 0b00100, 0b00100, 0b00010, 0b00100, 0b00100, 0b01000},  // }
    {0, 0, 0b01000, 0b10101, 0b00010, 0, 0},                          // ~
}};

}  // namespace

std::array<std::uint8_t, 7> glyph_rows(char32_t ch) noexcept
{
    using g = std::array<std::uint8_t, 7>;
    if (ch >= 32 && ch <= 126) return ascii_font[ch - 32];
    if (ch == U'²') return g{0b01100, 0b10010, 0b00100, 0b01000, 0b11110, 0, 0};
    if (ch == U'°') return g{0b01100, 0b10010, 0b10010, 0b01100, 0, 0, 0};
    return g{0b11111, 0b10001, 0b10001, 0b10001, 0b10001, 0b10001, 0b11111};  // unknown: an empty box
}

namespace {

// The code points of UTF-8 `text` (1- and 2-byte sequences; longer ones become one unknown character each).
std::vector<char32_t> code_points(std::string_view text)
{
    std::vector<char32_t> out;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const auto b = static_cast<unsigned char>(text[i]);
        if (b < 0x80) {
            out.push_back(b);
        } else if ((b & 0xE0) == 0xC0 && i + 1 < text.size()) {
            out.push_back(static_cast<char32_t>(((b & 0x1F) << 6) | (static_cast<unsigned char>(text[i + 1]) & 0x3F)));
            ++i;
        } else {
            out.push_back(0xFFFD);
            while (i + 1 < text.size() && (static_cast<unsigned char>(text[i + 1]) & 0xC0) == 0x80) ++i;
        }
    }
    return out;
}

}  // namespace

std::ptrdiff_t text_width_px(std::string_view text, int scale) noexcept
{
    const auto n = static_cast<std::ptrdiff_t>(code_points(text).size());
    return n == 0 ? 0 : (6 * n - 1) * scale;
}

void draw_text(rgb_image& img, std::ptrdiff_t row, std::ptrdiff_t col, std::string_view text,
               std::array<std::uint8_t, 3> color, int scale)
{
    detail::require(scale >= 1, "draw_text", "scale", ">= 1", scale);
    std::ptrdiff_t x = col;
    for (const char32_t ch : code_points(text)) {
        const auto rows = glyph_rows(ch);
        for (std::ptrdiff_t gr = 0; gr < 7; ++gr) {
            for (std::ptrdiff_t gc = 0; gc < 5; ++gc) {
                if (((rows[static_cast<std::size_t>(gr)] >> (4 - gc)) & 1) == 0) continue;
                for (std::ptrdiff_t dr = 0; dr < scale; ++dr) {
                    for (std::ptrdiff_t dc = 0; dc < scale; ++dc) {
                        const std::ptrdiff_t r = row + gr * scale + dr, c = x + gc * scale + dc;
                        if (r >= 0 && c >= 0 && r < img.height && c < img.width) put(img, r, c, color);
                    }
                }
            }
        }
        x += 6 * scale;
    }
}

}  // namespace lidarfx::io
