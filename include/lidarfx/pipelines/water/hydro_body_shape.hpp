// SPDX-License-Identifier: Apache-2.0
// hydro_body_shape: how long and how wide one waterbody is, along its longest path.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "lidarfx/core/grid.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// The size of one waterbody along the longest path inside it.
struct hydro_body_shape {
    double area_m2 = 0;   ///< cells · cell_m², m²
    double length_m = 0;  ///< length of the longest path inside the body (geodesic diameter) plus one cell, metres
    double width_m = 0;   ///< area_m2 / length_m: a river's mean (nominal) width, metres
    std::array<std::ptrdiff_t, 2> end_a{}, end_b{};  ///< (row, col) of the longest path's two ends
    /// length_m / width_m: about 1.6 for a round lake (the chamfer path of a raster disc), the length in widths for a
    /// river.
    double elongation() const noexcept { return width_m > 0 ? length_m / width_m : 0; }
};

/// The cells of `label` inside `box` as a mask of the box's size (1 = the body's cell).
inline raster<std::uint8_t> body_mask(raster_view<const std::int32_t> labels, std::int32_t label, const cell_box& box);

/// Shape of the body `label` of `labels` (its cells lie inside `box`, raster cells): its length is found by
/// the two-sweep rule on geodesic_distance inside the body (the cell farthest from the body's first cell in
/// row-major order is end_a, the cell farthest from end_a is end_b, ties to the first in row-major order), exact
/// for a channel without loops and within a few cells of the true geodesic diameter otherwise. cell_m in
/// metres. O(n log n) in the body's n cells, memory of the box.
/// @throws invalid_input on cell_m not finite and > 0, a box outside the raster or a label without a cell there.
inline hydro_body_shape measure_hydro_body_shape(raster_view<const std::int32_t> labels, std::int32_t label,
                                                 const cell_box& box, double cell_m);

}  // namespace lidarfx

#include "lidarfx/pipelines/water/detail/hydro_body_shape_impl.hpp"
