// SPDX-License-Identifier: Apache-2.0
// Figures: a map picture enlarged and framed with a title, a colour bar or legend, a scale bar and a north arrow.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <lidarfx/core/raster.hpp>

#include "io/png.hpp"

namespace lidarfx::io {

/// One swatch of a categorical legend: its colour and what it means ("water", "missed water").
struct figure_key {
    std::array<std::uint8_t, 3> color{};
    std::string name;
};

/// The legend of an azimuth map coloured by azimuth_color: the eight compass directions N, NE, ... NW (0°, 45°,
/// ... 315° clockwise from grid north), then the swatches `more`.
std::vector<figure_key> compass_key(const std::vector<figure_key>& more = {});

/// A colour bar for a continuous map coloured by ramp_color((v - min) / (max - min)).
struct figure_bar {
    double min = 0, max = 1;  ///< values at the left and right ends (finite, min <= max)
    std::string unit{};       ///< what the values are, with their unit ("kWh/m²", "height (ft)")
};

struct figure_options {
    std::string title{};                   ///< the top line: what the map shows, its file and units
    double cell_size = 1;                  ///< ground size of one map pixel in CRS units (> 0), for the scale bar
    std::string unit = "m";                ///< name of the CRS unit ("m", "ft", "US ft"), written on the scale bar
    std::optional<figure_bar> bar{};       ///< a colour bar (continuous maps) ...
    std::vector<figure_key> key{};         ///< ... and/or categorical swatches; "no data" is always appended
    std::string no_data_name = "no data";  ///< the name of the no-data swatch, always last in the legend
    std::ptrdiff_t min_long_side = 800;    ///< the map is enlarged until its long side reaches this (pixels)
    std::ptrdiff_t max_factor = 32;        ///< the largest enlargement (a huge grid is never enlarged)
};

/// Where the parts of a figure are, in pixels of its image (for tests and callers that draw more).
struct figure_layout {
    std::ptrdiff_t factor = 1;                ///< each map pixel became factor x factor pixels
    std::ptrdiff_t map_row = 0, map_col = 0;  ///< top-left pixel of the enlarged map
    std::ptrdiff_t title_row = 0, title_col = 0;
    std::ptrdiff_t scale_row = 0, scale_col = 0;  ///< top-left pixel of the scale bar
    std::ptrdiff_t scale_px = 0;                  ///< its length in pixels: round(scale_length / cell_size * factor)
    double scale_length = 0;                      ///< its labelled length in CRS units (1, 2 or 5 x 10^k)
    std::ptrdiff_t legend_row = 0;                ///< first row of the colour bar or legend
};

struct figure {
    rgb_image image;
    figure_layout layout;
};

/// The no-data colour at figure pixel (row, col): a light grey hatch (diagonal stripes of (150, 150, 150) on
/// (225, 225, 225), 3 pixels wide every 8), so unflown or empty cells read neither as land nor as a value.
std::array<std::uint8_t, 3> no_data_color(std::ptrdiff_t row, std::ptrdiff_t col) noexcept;

/// True when `color` is one of the two colours of the no-data hatch.
bool is_no_data_color(std::array<std::uint8_t, 3> color) noexcept;

/// 1 where `values` is NaN or infinite (no data), else 0. O(cells).
raster<std::uint8_t> non_finite_cells(raster_view<const float> values);

/// A colour bar over the range of the finite values of `values` (0 .. 0 when there are none).
figure_bar finite_bar(raster_view<const float> values, std::string unit);

/// The enlargement of a map of rows x cols pixels: the smallest integer factor that makes the long side at least
/// min_long_side, at most max_factor; 1 when the map is already that large.
std::ptrdiff_t figure_factor(std::ptrdiff_t rows, std::ptrdiff_t cols, std::ptrdiff_t min_long_side = 800,
                             std::ptrdiff_t max_factor = 32) noexcept;

/// The round scale bar length (1, 2 or 5 x 10^k CRS units) nearest below `target` (> 0).
double round_scale_length(double target) noexcept;

/// The short name of a CRS unit for pictures: "m" for a unit of 1 metre, "ft" for 0.3048 m, "US ft" for
/// 1200/3937 m, otherwise `name`.
std::string short_unit_name(double unit_m, const std::string& name);

/// A figure of `map`: the map enlarged by figure_factor (nearest neighbour, never blurred), cells where
/// `no_data` != 0 drawn in the no-data hatch (pass an empty view for none), framed in black on white with
/// the title above; below it a scale bar (a round length near a quarter of the map's width, labelled in
/// opt.unit) and an arrow labelled "grid north" (row 0 is north), then the colour bar (min and max under
/// its ends, the unit centred) and/or the legend swatches with their names, "no data" last. Text is the
/// built-in font at scale 2. O(pixels).
/// @throws invalid_input if the map is empty, no_data has another shape, cell_size is not > 0, or the bar's
/// min, max are not finite with min <= max.
figure make_figure(const rgb_image& map, raster_view<const std::uint8_t> no_data, const figure_options& opt);

}  // namespace lidarfx::io
