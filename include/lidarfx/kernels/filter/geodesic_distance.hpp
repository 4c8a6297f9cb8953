// SPDX-License-Identifier: Apache-2.0
// geodesic_distance: path lengths inside a mask from one cell (chamfer steps, Dijkstra).
// Implementation in detail/geodesic_distance_impl.hpp.
#pragma once

#include <cstddef>
#include <cstdint>

#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// Length, in metres, of the shortest path from cell (from_row, from_col) to every cell that stays on cells
/// with inside != 0, stepping between 8-neighbours: cell_m to a row or column neighbour, cell_m·√2 to a
/// diagonal one. Cells outside the mask or not reached are +inf; the start cell is 0. What a river's
/// cross-sections are cut from: cells at one distance from its upstream end lie across the channel.
/// Dijkstra's algorithm in double precision, written as float. O(n log n) in the n cells reached, memory of
/// the raster's size.
/// @throws invalid_input when the start cell lies outside the raster or outside the mask, or cell_m is not
/// finite and > 0.
inline raster<float> geodesic_distance(raster_view<const std::uint8_t> inside, std::ptrdiff_t from_row,
                                       std::ptrdiff_t from_col, double cell_m);

}  // namespace lidarfx

#include "lidarfx/kernels/filter/detail/geodesic_distance_impl.hpp"
