// SPDX-License-Identifier: Apache-2.0
// Implementation of measure_waterbodies (included at the end of pipelines/water/measure_waterbodies.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>
#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/grid.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/parallel_bands.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/pipelines/water/water_rasters.hpp"

namespace lidarfx {

inline void measure_waterbodies(raster_view<std::int32_t> labels, std::vector<waterbody>& bodies,
                                const water_rasters& in, double cell_m, const execution& run)
{
    constexpr const char* fn = "measure_waterbodies";
    detail::validate(in, fn);
    detail::require_same_shape(labels, in.min_z, fn, "labels", "min_z");
    detail::require_positive(cell_m, fn, "cell_m");
    detail::check_execution(run, fn);
    const std::ptrdiff_t rows = labels.rows(), cols = labels.cols();
    // Both passes run in bands of rows on run.threads threads, each band with results of its own merged in band
    // order after: the same result for any thread count.
    constexpr std::ptrdiff_t band_rows = 256;
    // Pass 1, per row: the labels' range by a vectorized min / max, then on a row that holds bodies their
    // cells, run by run (land passed over in blocks).
    struct band_sizes {
        std::vector<std::size_t> size;
        std::int32_t lowest = 0;
    };
    const auto sizes = parallel_bands(rows, band_rows, run.threads, [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
        band_sizes band;
        for (std::ptrdiff_t r = r0; r < r1; ++r) {
            const std::int32_t* label = labels.row(r);
            const auto [low, high] = detail::row_label_range(label, cols);
            band.lowest = std::min(band.lowest, low);
            if (high <= 0) continue;
            if (band.size.size() <= static_cast<std::size_t>(high))
                band.size.resize(static_cast<std::size_t>(high) + 1, 0);
            detail::for_each_run(label, cols, [&](std::int32_t l, std::ptrdiff_t start, std::ptrdiff_t end) {
                band.size[static_cast<std::size_t>(l)] += static_cast<std::size_t>(end - start);
            });
        }
        return band;
    });
    std::vector<std::size_t> size(bodies.size() + 1, 0);
    std::int32_t lowest = 0;
    for (const auto& band : sizes) {
        lowest = std::min(lowest, band.lowest);
        if (size.size() < band.size.size()) size.resize(band.size.size(), 0);
        for (std::size_t l = 0; l < band.size.size(); ++l) size[l] += band.size[l];
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

    // Pass 2 renumbers the labels and notes each run of one body: its row and columns, the sum of its
    // intensities and its returns; its finite heights go to the band's buffer, in raster order.
    struct body_run {
        std::ptrdiff_t row, from, to;
        std::size_t body, returns, heights;
        double intensity;
    };
    struct band_runs {
        std::vector<body_run> runs;
        std::unique_ptr<float[]> heights;  // room for every cell of the band, touched only where written
    };
    const auto found = parallel_bands(rows, band_rows, run.threads, [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
        band_runs band;
        std::size_t used = 0;
        for (std::ptrdiff_t r = r0; r < r1; ++r) {
            std::int32_t* label = labels.row(r);
            const std::uint8_t* dropout = in.dropout.row(r);
            const float* mean = in.mean_intensity.row(r);
            const float* low = in.min_z.row(r);
            detail::for_each_run(label, cols, [&](std::int32_t old, std::ptrdiff_t start, std::ptrdiff_t c) {
                const std::int32_t l = relabel[static_cast<std::size_t>(old)];
                std::fill(label + start, label + c, l);
                if (!band.heights) band.heights.reset(new float[static_cast<std::size_t>((r1 - r) * cols)]);
                float* h = band.heights.get() + used;
                const float* first = h;
                double sum = 0;
                std::size_t returns = 0;
                for (std::ptrdiff_t x = start; x < c; ++x) {
                    if (dropout[x]) continue;
                    sum += mean[x];
                    ++returns;
                    *h = low[x];  // kept when finite
                    h += std::isfinite(low[x]);
                }
                const auto kept = static_cast<std::size_t>(h - first);
                band.runs.push_back({r, start, c, static_cast<std::size_t>(l - 1), returns, kept, sum});
                used += kept;
            });
        }
        return band;
    });
    // The runs in raster order make each body's extent, intensity and heights.
    std::vector<waterbody> out(order.size());
    std::vector<double> intensity(order.size(), 0.0);
    std::vector<std::size_t> with_returns(order.size(), 0), heights_of(order.size() + 1, 0);
    for (std::size_t k = 0; k < order.size(); ++k) {
        auto& b = out[k];
        const auto& known = bodies[static_cast<std::size_t>(order[k] - 1)];
        b.label = static_cast<std::int32_t>(k + 1);
        b.seed = known.seed;
        b.theta_deg = known.theta_deg;
        b.stopped_by_ks = known.stopped_by_ks;
        b.box.row_min = rows;
        b.box.col_min = cols;
    }
    for (const auto& band : found) {
        for (const auto& run_of : band.runs) {
            auto& b = out[run_of.body];
            b.cells += static_cast<std::size_t>(run_of.to - run_of.from);
            b.box.row_min = std::min(b.box.row_min, run_of.row);
            b.box.row_max = run_of.row;
            b.box.col_min = std::min(b.box.col_min, run_of.from);
            b.box.col_max = std::max(b.box.col_max, run_of.to - 1);
            intensity[run_of.body] += run_of.intensity;
            with_returns[run_of.body] += run_of.returns;
            heights_of[run_of.body + 1] += run_of.heights;
        }
    }
    // Every body's heights in one buffer, body k's at [heights_of[k], heights_of[k + 1]), in raster order.
    for (std::size_t k = 1; k < heights_of.size(); ++k) heights_of[k] += heights_of[k - 1];
    std::vector<float> heights(heights_of.back());
    std::vector<std::size_t> next(heights_of.begin(), heights_of.end() - 1);
    for (const auto& band : found) {
        const float* from = band.heights.get();
        for (const auto& run_of : band.runs) {
            std::copy(from, from + run_of.heights, heights.begin() + static_cast<std::ptrdiff_t>(next[run_of.body]));
            next[run_of.body] += run_of.heights;
            from += run_of.heights;
        }
    }
    parallel_for_rows(
        static_cast<std::ptrdiff_t>(order.size()), 16, run.threads, [&](std::ptrdiff_t k0, std::ptrdiff_t k1) {
            for (auto k = static_cast<std::size_t>(k0); k < static_cast<std::size_t>(k1); ++k) {
                auto& b = out[k];
                b.area_m2 = static_cast<double>(b.cells) * cell_m * cell_m;
                b.mean_intensity = with_returns[k] ? intensity[k] / static_cast<double>(with_returns[k]) : NAN;
                b.dropout_fraction =
                    b.cells ? 1.0 - static_cast<double>(with_returns[k]) / static_cast<double>(b.cells) : 0.0;
                b.water_level_m =
                    detail::median(std::span<float>(heights).subspan(heights_of[k], heights_of[k + 1] - heights_of[k]));
            }
        });
    bodies = std::move(out);
}

}  // namespace lidarfx
