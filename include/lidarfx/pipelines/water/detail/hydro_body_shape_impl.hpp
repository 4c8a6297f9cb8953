// SPDX-License-Identifier: Apache-2.0
// Implementation of hydro_body_shape (included at the end of pipelines/water/hydro_body_shape.hpp).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>

#include "lidarfx/core/error.hpp"
#include "lidarfx/kernels/filter/geodesic_distance.hpp"

namespace lidarfx {

namespace detail {

/// The cell of largest finite value in `distance` (the first in row-major order on ties), and that value.
inline std::pair<std::array<std::ptrdiff_t, 2>, float> farthest_cell(const raster<float>& distance)
{
    std::array<std::ptrdiff_t, 2> at{-1, -1};
    float best = -1;
    for (std::ptrdiff_t r = 0; r < distance.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < distance.cols(); ++c)
            if (const float d = distance(r, c); std::isfinite(d) && d > best) {
                best = d;
                at = {r, c};
            }
    return {at, best};
}

}  // namespace detail

inline raster<std::uint8_t> body_mask(raster_view<const std::int32_t> labels, std::int32_t label, const cell_box& box)
{
    detail::require(!box.empty() && box.row_min >= 0 && box.col_min >= 0 && box.row_max < labels.rows() &&
                        box.col_max < labels.cols(),
                    "body_mask", "the box must be a non-empty box of cells inside the raster");
    raster<std::uint8_t> mask(box.rows(), box.cols(), 0);
    for (std::ptrdiff_t r = 0; r < box.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < box.cols(); ++c) mask(r, c) = labels(box.row_min + r, box.col_min + c) == label;
    return mask;
}

inline hydro_body_shape measure_hydro_body_shape(raster_view<const std::int32_t> labels, std::int32_t label,
                                                 const cell_box& box, double cell_m)
{
    constexpr const char* fn = "measure_hydro_body_shape";
    detail::require_positive(cell_m, fn, "cell_m");
    const raster<std::uint8_t> mask = body_mask(labels, label, box);
    std::size_t cells = 0;
    std::array<std::ptrdiff_t, 2> first{-1, -1};
    for (std::ptrdiff_t r = 0; r < mask.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < mask.cols(); ++c)
            if (mask(r, c)) {
                if (cells++ == 0) first = {r, c};
            }
    detail::require(cells > 0, fn, "the label has no cell inside the box");
    const auto a = detail::farthest_cell(geodesic_distance(mask, first[0], first[1], cell_m)).first;
    const auto [b, diameter] = detail::farthest_cell(geodesic_distance(mask, a[0], a[1], cell_m));
    hydro_body_shape s;
    s.area_m2 = static_cast<double>(cells) * cell_m * cell_m;
    s.length_m = static_cast<double>(diameter) + cell_m;
    s.width_m = s.area_m2 / s.length_m;
    s.end_a = {box.row_min + a[0], box.col_min + a[1]};
    s.end_b = {box.row_min + b[0], box.col_min + b[1]};
    return s;
}

}  // namespace lidarfx
