// SPDX-License-Identifier: Apache-2.0
// Implementation of kernels/stats/zonal_statistics.hpp: the largest label, and values grouped by label (a counting
// sort) before each statistic per group. Included at the end of zonal_statistics.hpp, after the declarations it
// defines; not a public header.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

namespace detail {

/// The largest label of a label raster (0 when empty). @throws invalid_input naming `fn` on a negative label.
template <raster_input Labels>
std::int64_t largest_label(const Labels& labels, const char* fn)
{
    std::int64_t top = 0;
    for (std::ptrdiff_t r = 0; r < labels.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < labels.cols(); ++c) {
            const auto k = static_cast<std::int64_t>(labels(r, c));
            detail::require(k >= 0, fn, "labels", ">= 0", k);
            top = std::max(top, k);
        }
    return top;
}

}  // namespace detail

template <raster_input Labels, raster_input Values>
std::vector<zone_statistics> zonal_statistics(const Labels& labels, const Values& values)
{
    constexpr const char* fn = "zonal_statistics";
    detail::require_same_shape(labels, values, fn, "labels", "values");
    const std::int64_t top = detail::largest_label(labels, fn);
    // Values grouped by label (counting sort), then every statistic per group.
    std::vector<std::size_t> start(static_cast<std::size_t>(top) + 2, 0);
    for (std::ptrdiff_t r = 0; r < labels.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < labels.cols(); ++c)
            if (std::isfinite(static_cast<double>(values(r, c)))) ++start[static_cast<std::size_t>(labels(r, c)) + 1];
    for (std::size_t k = 1; k < start.size(); ++k) start[k] += start[k - 1];
    std::vector<double> grouped(start.back());
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::ptrdiff_t r = 0; r < labels.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < labels.cols(); ++c) {
            const double v = static_cast<double>(values(r, c));
            if (std::isfinite(v)) grouped[fill[static_cast<std::size_t>(labels(r, c))]++] = v;
        }
    std::vector<zone_statistics> out(static_cast<std::size_t>(top) + 1);
    for (std::size_t k = 0; k < out.size(); ++k) {
        const auto first = grouped.begin() + static_cast<std::ptrdiff_t>(start[k]);
        const auto last = grouped.begin() + static_cast<std::ptrdiff_t>(start[k + 1]);
        zone_statistics& s = out[k];
        s.count = static_cast<std::size_t>(last - first);
        if (s.count == 0) continue;
        double sum = 0;
        for (auto it = first; it != last; ++it) sum += *it;
        s.mean = sum / static_cast<double>(s.count);
        double sq = 0;
        for (auto it = first; it != last; ++it) sq += (*it - s.mean) * (*it - s.mean);
        s.std = std::sqrt(sq / static_cast<double>(s.count));
        std::sort(first, last);
        s.min = *first;
        s.max = *(last - 1);
        const std::size_t h = s.count / 2;
        s.median = s.count % 2
                       ? first[static_cast<std::ptrdiff_t>(h)]
                       : 0.5 * (first[static_cast<std::ptrdiff_t>(h) - 1] + first[static_cast<std::ptrdiff_t>(h)]);
    }
    return out;
}

template <raster_input Labels, raster_input Angles>
std::vector<circular_zone_statistics> zonal_circular_statistics(const Labels& labels, const Angles& angles_deg,
                                                                const zonal_circular_statistics_options& opt)
{
    constexpr const char* fn = "zonal_circular_statistics";
    detail::require_same_shape(labels, angles_deg, fn, "labels", "angles_deg");
    const double bins_real = 360.0 / opt.bin_width_deg;
    const double bins_rounded = std::round(bins_real);
    detail::require(std::isfinite(bins_real) && std::fabs(bins_real - bins_rounded) < 1e-9 && bins_rounded >= 1 &&
                        bins_rounded <= 36000,
                    fn, "bin_width_deg", "360 / a whole number of bins in [1, 36000]", opt.bin_width_deg);
    const auto bins = static_cast<std::size_t>(bins_rounded);
    const std::int64_t top = detail::largest_label(labels, fn);
    const std::size_t zones = static_cast<std::size_t>(top) + 1;
    std::vector<std::uint32_t> hist(zones * bins, 0);
    std::vector<double> sum_sin(zones, 0.0), sum_cos(zones, 0.0);
    std::vector<std::size_t> count(zones, 0);
    constexpr double rad = std::numbers::pi / 180.0;
    for (std::ptrdiff_t r = 0; r < labels.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < labels.cols(); ++c) {
            const double a = static_cast<double>(angles_deg(r, c));
            if (!std::isfinite(a)) continue;
            const auto k = static_cast<std::size_t>(labels(r, c));
            double m = std::fmod(a, 360.0);
            if (m < 0) m += 360.0;
            auto b = static_cast<std::size_t>(std::floor(m / opt.bin_width_deg + 0.5));
            if (b >= bins) b -= bins;
            ++hist[k * bins + b];
            sum_sin[k] += std::sin(m * rad);
            sum_cos[k] += std::cos(m * rad);
            ++count[k];
        }
    std::vector<circular_zone_statistics> out(zones);
    for (std::size_t k = 0; k < zones; ++k) {
        circular_zone_statistics& s = out[k];
        s.count = count[k];
        const std::uint32_t* h = hist.data() + k * bins;
        if (opt.keep_histograms) s.histogram.assign(h, h + bins);
        if (s.count == 0) continue;
        const double length = std::hypot(sum_sin[k], sum_cos[k]);
        s.resultant_length = std::min(1.0, length / static_cast<double>(s.count));
        if (length > 1e-9 * static_cast<double>(s.count)) {
            double mean = std::atan2(sum_sin[k], sum_cos[k]) / rad;
            s.mean_deg = mean < 0 ? mean + 360.0 : mean;
        }
        const std::size_t best = static_cast<std::size_t>(std::max_element(h, h + bins) - h);  // first of the fullest
        s.mode_deg = static_cast<double>(best) * opt.bin_width_deg;
        s.mode_count = h[best];
    }
    return out;
}

}  // namespace lidarfx
