// SPDX-License-Identifier: Apache-2.0
// Implementation of lake_level (included at the end of pipelines/water/lake_level.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "lidarfx/core/error.hpp"

namespace lidarfx {

namespace detail {

/// The element at position ⌊q · (n − 1)⌋ of the n sorted `values` (which it reorders); NaN when empty.
inline double quantile_in_place(std::vector<float>& values, double q)
{
    if (values.empty()) return NAN;
    const auto k = static_cast<std::ptrdiff_t>(std::floor(q * static_cast<double>(values.size() - 1)));
    std::nth_element(values.begin(), values.begin() + k, values.end());
    return values[static_cast<std::size_t>(k)];
}

/// The median as measure_waterbodies and water_levels take it: position n / 2 of the n sorted values.
inline double upper_median_in_place(std::vector<float>& values)
{
    if (values.empty()) return NAN;
    const auto k = static_cast<std::ptrdiff_t>(values.size() / 2);
    std::nth_element(values.begin(), values.begin() + k, values.end());
    return values[static_cast<std::size_t>(k)];
}

/// The median (position m / 2) of the m values inside the window [v, v + width] that holds the most of `values`
/// (which it sorts), v one of them, the lowest such window on ties; NaN when empty. O(n log n).
inline double densest_window_median(std::vector<float>& values, double width)
{
    if (values.empty()) return NAN;
    std::sort(values.begin(), values.end());
    std::size_t best_from = 0, best_count = 0;
    for (std::size_t from = 0, to = 0; from < values.size(); ++from) {
        to = std::max(to, from);
        while (to < values.size() && static_cast<double>(values[to]) <= static_cast<double>(values[from]) + width) ++to;
        if (to - from > best_count) {
            best_count = to - from;
            best_from = from;
        }
    }
    return values[best_from + best_count / 2];
}

/// Calls visit(r, c) once for every land cell (label 0) 8-adjacent to a cell of `label` inside `box`.
template <class Visit>
void for_each_shore_cell(raster_view<const std::int32_t> labels, std::int32_t label, const cell_box& box, Visit&& visit)
{
    const std::ptrdiff_t r0 = std::max<std::ptrdiff_t>(box.row_min - 1, 0),
                         c0 = std::max<std::ptrdiff_t>(box.col_min - 1, 0);
    const std::ptrdiff_t r1 = std::min(box.row_max + 1, labels.rows() - 1),
                         c1 = std::min(box.col_max + 1, labels.cols() - 1);
    for (std::ptrdiff_t r = r0; r <= r1; ++r)
        for (std::ptrdiff_t c = c0; c <= c1; ++c) {
            if (labels(r, c) != 0) continue;
            bool shore = false;
            for (std::ptrdiff_t rr = std::max<std::ptrdiff_t>(r - 1, 0);
                 rr <= std::min(r + 1, labels.rows() - 1) && !shore; ++rr)
                for (std::ptrdiff_t cc = std::max<std::ptrdiff_t>(c - 1, 0); cc <= std::min(c + 1, labels.cols() - 1);
                     ++cc)
                    if (labels(rr, cc) == label) {
                        shore = true;
                        break;
                    }
            if (shore) visit(r, c);
        }
}

inline void validate(const lake_level_options& opt, const char* fn)
{
    require(opt.shore_quantile >= 0 && opt.shore_quantile <= 1, fn, "shore_quantile", "in [0, 1]", opt.shore_quantile);
    require(opt.mode_window_m > 0, fn, "mode_window_m", "> 0", opt.mode_window_m);
    require(opt.below_shore_m >= 0 && std::isfinite(opt.below_shore_m), fn, "below_shore_m", "finite and >= 0",
            opt.below_shore_m);
}

inline void check_body_box(raster_view<const std::int32_t> labels, const cell_box& box, const char* fn)
{
    require(!box.empty() && box.row_min >= 0 && box.col_min >= 0 && box.row_max < labels.rows() &&
                box.col_max < labels.cols(),
            fn, "the box must be a non-empty box of cells inside the raster");
}

}  // namespace detail

inline lake_level_result lake_level(raster_view<const std::int32_t> labels, std::int32_t label, const cell_box& box,
                                    raster_view<const float> water_z, raster_view<const float> ground,
                                    const lake_level_options& opt)
{
    constexpr const char* fn = "lake_level";
    detail::require_same_shape(labels, water_z, fn, "labels", "water_z");
    detail::require_same_shape(labels, ground, fn, "labels", "ground");
    detail::validate(opt, fn);
    detail::check_body_box(labels, box, fn);
    std::vector<float> water, shore;
    for (std::ptrdiff_t r = box.row_min; r <= box.row_max; ++r)
        for (std::ptrdiff_t c = box.col_min; c <= box.col_max; ++c)
            if (labels(r, c) == label && std::isfinite(water_z(r, c))) water.push_back(water_z(r, c));
    detail::for_each_shore_cell(labels, label, box, [&](std::ptrdiff_t r, std::ptrdiff_t c) {
        if (std::isfinite(ground(r, c))) shore.push_back(ground(r, c));
    });
    lake_level_result out;
    out.returns = water.size();
    out.shore_cells = shore.size();
    out.returns_level_m = detail::densest_window_median(water, opt.mode_window_m);
    out.shore_low_m = detail::quantile_in_place(shore, opt.shore_quantile);
    const double below_shore = out.shore_low_m - opt.below_shore_m;
    if (std::isnan(out.returns_level_m))
        out.level_m = below_shore;
    else
        out.level_m = opt.cap_at_shore && !std::isnan(below_shore) ? std::min(out.returns_level_m, below_shore)
                                                                   : out.returns_level_m;
    return out;
}

}  // namespace lidarfx
