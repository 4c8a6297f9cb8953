// SPDX-License-Identifier: Apache-2.0
// Implementation of measure_waterbodies (included at the end of pipelines/water/measure_waterbodies.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>
#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/grid.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/pipelines/water/water_rasters.hpp"

namespace lidarfx {

inline void measure_waterbodies(raster_view<std::int32_t> labels, std::vector<waterbody>& bodies,
                                const water_rasters& in, double cell_m)
{
    constexpr const char* fn = "measure_waterbodies";
    detail::validate(in, fn);
    detail::require_same_shape(labels, in.min_z, fn, "labels", "min_z");
    detail::require_positive(cell_m, fn, "cell_m");
    const std::ptrdiff_t rows = labels.rows(), cols = labels.cols();
    // Pass 1, per row: the labels' range by a vectorized min / max, then on a row that holds bodies their
    // cells, run by run (land passed over in blocks). Only the rows from first_row to last_row hold bodies.
    std::vector<std::size_t> size(bodies.size() + 1, 0);
    std::int32_t lowest = 0;
    std::ptrdiff_t first_row = rows, last_row = -1;
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        const std::int32_t* label = labels.row(r);
        const auto [low, high] = detail::row_label_range(label, cols);
        lowest = std::min(lowest, low);
        if (high <= 0) continue;
        if (size.size() <= static_cast<std::size_t>(high)) size.resize(static_cast<std::size_t>(high) + 1, 0);
        first_row = std::min(first_row, r);
        last_row = r;
        detail::for_each_run(label, cols, [&](std::int32_t l, std::ptrdiff_t start, std::ptrdiff_t end) {
            size[static_cast<std::size_t>(l)] += static_cast<std::size_t>(end - start);
        });
    }
    detail::require(lowest >= 0, fn, "labels", ">= 0", lowest);
    if (bodies.size() + 1 < size.size()) bodies.resize(size.size() - 1);
    std::vector<std::int32_t> order;
    for (std::size_t b = 1; b < size.size(); ++b)
        if (size[b] > 0) order.push_back(static_cast<std::int32_t>(b));
    std::stable_sort(order.begin(), order.end(), [&](auto a, auto b) {
        return size[static_cast<std::size_t>(a)] > size[static_cast<std::size_t>(b)];
    });
    std::vector<std::int32_t> relabel(size.size(), 0);
    for (std::size_t k = 0; k < order.size(); ++k)
        relabel[static_cast<std::size_t>(order[k])] = static_cast<std::int32_t>(k + 1);

    // One row-major pass gathers every body's extent, intensity and the heights for its water level.
    std::vector<waterbody> out(order.size());
    std::vector<double> intensity(order.size(), 0.0);
    std::vector<std::size_t> with_returns(order.size(), 0);
    std::vector<std::vector<float>> heights(order.size());
    std::vector<float*> height_end(order.size());  // written through pointers: the sums stay in registers
    for (std::size_t k = 0; k < order.size(); ++k) {
        auto& b = out[k];
        const auto& known = bodies[static_cast<std::size_t>(order[k] - 1)];
        b.label = static_cast<std::int32_t>(k + 1);
        b.seed = known.seed;
        b.theta_deg = known.theta_deg;
        b.stopped_by_ks = known.stopped_by_ks;
        b.box.row_min = rows;
        b.box.col_min = cols;
        heights[k].resize(size[static_cast<std::size_t>(order[k])]);  // at most one per cell, cut to length below
        height_end[k] = heights[k].data();
    }
    for (std::ptrdiff_t r = first_row; r <= last_row; ++r) {
        std::int32_t* label = labels.row(r);
        const std::uint8_t* dropout = in.dropout.row(r);
        const float* mean = in.mean_intensity.row(r);
        const float* low = in.min_z.row(r);
        // Run by run, land passed over in blocks: a run of one label is renumbered, counted and boxed at once;
        // its cells with returns add their intensity and height one by one.
        detail::for_each_run(label, cols, [&](std::int32_t old, std::ptrdiff_t start, std::ptrdiff_t c) {
            const std::int32_t l = relabel[static_cast<std::size_t>(old)];
            std::fill(label + start, label + c, l);
            const auto k = static_cast<std::size_t>(l - 1);
            auto& b = out[k];
            b.cells += static_cast<std::size_t>(c - start);
            b.box.row_min = std::min(b.box.row_min, r);
            b.box.row_max = r;
            b.box.col_min = std::min(b.box.col_min, start);
            b.box.col_max = std::max(b.box.col_max, c - 1);
            float* h = height_end[k];
            double sum = intensity[k];  // the same additions in the same order, in a register
            std::size_t returns = with_returns[k];
            for (std::ptrdiff_t x = start; x < c; ++x) {
                if (dropout[x]) continue;
                sum += mean[x];
                ++returns;
                *h = low[x];  // kept when finite; a slot below the body's cells so far, so inside its size
                h += std::isfinite(low[x]);
            }
            height_end[k] = h;
            intensity[k] = sum;
            with_returns[k] = returns;
        });
    }
    for (std::size_t k = 0; k < order.size(); ++k) {
        auto& b = out[k];
        b.area_m2 = static_cast<double>(b.cells) * cell_m * cell_m;
        b.mean_intensity = with_returns[k] ? intensity[k] / static_cast<double>(with_returns[k]) : NAN;
        b.dropout_fraction = b.cells ? 1.0 - static_cast<double>(with_returns[k]) / static_cast<double>(b.cells) : 0.0;
        heights[k].resize(static_cast<std::size_t>(height_end[k] - heights[k].data()));
        b.water_level_m = detail::median(heights[k]);
    }
    bodies = std::move(out);
}

}  // namespace lidarfx
