// SPDX-License-Identifier: Apache-2.0
// Quicklook pictures of rasters: colour ramp, hillshade, label colours and mask overlays (for PNG output).
#pragma once

#include <array>
#include <cstdint>

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
/// round(255 sin(altitude)) (180 at 45°); NaN cells give 0. Row 0 is north. O(cells).
/// @throws invalid_input if cell_m is not > 0, altitude_deg is outside [0, 90] or azimuth_deg not finite.
raster<std::uint8_t> hillshade(raster_view<const float> elevation, double cell_m, double azimuth_deg = 315.0,
                               double altitude_deg = 45.0);

/// A distinct, saturated colour for each label (label 0 = background is black); the colour depends on the
/// label alone (low-discrepancy hue, saturation and value sequences), so it is stable across pictures.
std::array<std::uint8_t, 3> label_color(std::int32_t label) noexcept;

/// Picture of a label raster (label_color per cell). O(cells). @throws invalid_input if empty.
rgb_image colorize_labels(raster_view<const std::int32_t> labels);

/// `grey` as a grey picture with the cells where mask != 0 tinted: out = (1 - opacity) * grey + opacity *
/// color. O(cells). @throws invalid_input on different shapes, an empty raster or opacity outside [0, 1].
rgb_image overlay_mask(raster_view<const std::uint8_t> grey, raster_view<const std::uint8_t> mask,
                       std::array<std::uint8_t, 3> color = {0, 120, 255}, double opacity = 0.6);

}  // namespace lidarfx::io
