// SPDX-License-Identifier: Apache-2.0
// Quicklook pictures of rasters: colour ramps (viridis, cyclic), hillshade, label colours, mask overlays and a
// 5x7 bitmap font; io/figure.hpp frames them for PNG output.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

#include <lidarfx/core/raster.hpp>

#include "io/png.hpp"

namespace lidarfx::io {

/// The perceptual colour of t in [0, 1] on the viridis ramp (dark purple -> blue -> green -> yellow):
/// linear interpolation between 9 anchors of matplotlib's viridis; luminance rises monotonically with t.
/// t is clamped to [0, 1]; NaN gives black.
std::array<std::uint8_t, 3> ramp_color(double t) noexcept;

/// Colours each cell of `values` by ramp_color((v - min) / (max - min)); values outside [min, max] take the
/// end colours, NaN cells are black. When min == max every finite cell takes the middle colour. O(cells).
/// @throws invalid_input if min or max is not finite or min > max, or `values` is empty.
rgb_image colorize(raster_view<const float> values, double min, double max);

/// colorize over the range of the finite values (all black when there are none).
rgb_image colorize(raster_view<const float> values);

/// Hillshade of an elevation raster, 0..255: 255 * max(0, n . l), n the unit surface normal from the
/// gradient, l the unit vector towards a light at `azimuth_deg` (clockwise from north) and `altitude_deg`
/// above the horizon. Gradients are Horn's 3x3 weighted differences; at borders and next to NaN cells the
/// missing side is dropped (one-sided differences), so planes shade exactly everywhere. A flat cell gets
/// round(255 sin(altitude)) (180 at 45°); NaN cells give 0. Row 0 is north. O(cells), blocks of rows on
/// `threads` threads (0 = all cores).
/// @throws invalid_input if cell_m is not > 0, altitude_deg is outside [0, 90] or azimuth_deg not finite.
raster<std::uint8_t> hillshade(raster_view<const float> elevation, double cell_m, double azimuth_deg = 315.0,
                               double altitude_deg = 45.0, int threads = 1);

/// The colour of t on a cyclic hue wheel (period 1: t and t + 1 give the same colour, and t -> 1 meets t = 0
/// smoothly): hue = 240° - 360° t at saturation 0.75, value 0.95, so t = 0 is blue, 0.25 green, 0.5 yellow,
/// 0.75 red-magenta. For angles, where 0° and 360° are one direction. NaN gives black.
std::array<std::uint8_t, 3> cyclic_color(double t) noexcept;

/// cyclic_color(azimuth_deg / 360): azimuth clockwise from grid north; north blue, east green, south yellow,
/// west red-magenta; 0° and 359.9° are (nearly) the same colour.
std::array<std::uint8_t, 3> azimuth_color(double azimuth_deg) noexcept;

/// The colour function of a map: t in [0, 1] -> colour (ramp_color, or cyclic_color for angles).
using color_ramp = std::array<std::uint8_t, 3> (*)(double) noexcept;

/// colorize(values, min, max) where `values` is finite (through `ramp`); elsewhere a dim grey hillshade of
/// `elevation` (half of hillshade(elevation, cell_m)), so coloured cells stand on the terrain. @throws as
/// colorize and hillshade, and invalid_input if the shapes differ.
rgb_image colorize_over_hillshade(raster_view<const float> values, double min, double max,
                                  raster_view<const float> elevation, double cell_m, color_ramp ramp = ramp_color);

/// A distinct, saturated colour for each label (label 0 = background is black); the colour depends on the
/// label alone (low-discrepancy hue, saturation and value sequences), so it is stable across pictures.
std::array<std::uint8_t, 3> label_color(std::int32_t label) noexcept;

/// Picture of a label raster (label_color per cell). O(cells). @throws invalid_input if empty.
rgb_image colorize_labels(raster_view<const std::int32_t> labels);

/// `grey` as a grey picture with the cells where mask != 0 tinted: out = (1 - opacity) * grey + opacity *
/// color. O(cells). @throws invalid_input on different shapes, an empty raster or opacity outside [0, 1].
rgb_image overlay_mask(raster_view<const std::uint8_t> grey, raster_view<const std::uint8_t> mask,
                       std::array<std::uint8_t, 3> color = {0, 120, 255}, double opacity = 0.6);

/// Pixels of one glyph of the built-in 5x7 bitmap font (7 rows of 5 columns, bit 4 = left column). It covers
/// printable ASCII (' ' .. '~': letters of both cases, digits, punctuation), the superscript "²" and the
/// degree sign "°"; any other character is an empty box, space is blank. A constexpr table, no font file.
std::array<std::uint8_t, 7> glyph_rows(char32_t ch) noexcept;

/// Width in pixels of `text` (UTF-8) drawn by draw_text at `scale`: 6 * scale per character (5 columns of
/// the glyph + 1 of spacing), minus the last spacing; 0 for empty text.
std::ptrdiff_t text_width_px(std::string_view text, int scale) noexcept;

/// Draws `text` (UTF-8) with the built-in font into `img`, its top-left corner at (row, col), each font pixel
/// a scale x scale block of `color`; pixels outside the picture are skipped. Deterministic: the same call gives
/// the same bytes on every platform. @throws invalid_input if scale < 1.
void draw_text(rgb_image& img, std::ptrdiff_t row, std::ptrdiff_t col, std::string_view text,
               std::array<std::uint8_t, 3> color, int scale = 1);

}  // namespace lidarfx::io
