// SPDX-License-Identifier: Apache-2.0
// Implementation of azimuth_mode_select (pipelines/pv/azimuth_mode_select.hpp): plane counting on the smoothed
// aspect histogram, then the paper's swap and turn rules.
#pragma once
// Included at the end of its public header, which declares what is defined here.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "lidarfx/core/error.hpp"

namespace lidarfx {

namespace detail {

inline double wrap_deg(double a) noexcept
{
    double m = std::fmod(a, 360.0);
    return m < 0 ? m + 360.0 : m;
}

/// Smallest angle between two azimuths, degrees in [0, 180].
inline double azimuth_gap_deg(double a, double b) noexcept
{
    const double d = std::fabs(wrap_deg(a - b));
    return d > 180.0 ? 360.0 - d : d;
}

/// Number of major planes in a 1-degree circular histogram (see azimuth_mode_select_options).
inline int count_aspect_planes(std::span<const std::uint32_t> h, const azimuth_mode_select_options& o)
{
    const std::ptrdiff_t n = 360;
    double total = 0;
    for (const auto v : h) total += v;
    if (total <= 0) return 0;
    const auto at = [&](std::ptrdiff_t i) {
        return static_cast<double>(h[static_cast<std::size_t>(((i % n) + n) % n)]);
    };
    const auto half = static_cast<std::ptrdiff_t>(std::lround(o.smooth_deg));
    const auto wide = static_cast<std::ptrdiff_t>(std::lround(o.plane_halfwidth_deg));
    std::vector<double> smooth(static_cast<std::size_t>(n)), mass(static_cast<std::size_t>(n));
    for (std::ptrdiff_t i = 0; i < n; ++i) {
        double s = 0, m = 0;
        for (std::ptrdiff_t d = -half; d <= half; ++d) s += at(i + d);
        for (std::ptrdiff_t d = -wide; d <= wide; ++d) m += at(i + d);
        smooth[static_cast<std::size_t>(i)] = s;
        mass[static_cast<std::size_t>(i)] = m;
    }
    // Candidates: local maxima of the smoothed histogram (plateaus count once, at their first bin), largest
    // first; a candidate counts when it holds enough cells and lies far enough from every plane already kept.
    std::vector<std::ptrdiff_t> peaks;
    for (std::ptrdiff_t i = 0; i < n; ++i) {
        const double v = smooth[static_cast<std::size_t>(i)];
        const double prev = smooth[static_cast<std::size_t>((i + n - 1) % n)];
        const double next = smooth[static_cast<std::size_t>((i + 1) % n)];
        if (v > 0 && v > prev && v >= next) peaks.push_back(i);
    }
    std::stable_sort(peaks.begin(), peaks.end(), [&](std::ptrdiff_t a, std::ptrdiff_t b) {
        return smooth[static_cast<std::size_t>(a)] > smooth[static_cast<std::size_t>(b)];
    });
    std::vector<std::ptrdiff_t> kept;
    for (const std::ptrdiff_t p : peaks) {
        if (mass[static_cast<std::size_t>(p)] < o.min_plane_share * total) continue;
        const bool far = std::all_of(kept.begin(), kept.end(), [&](std::ptrdiff_t q) {
            return azimuth_gap_deg(static_cast<double>(p), static_cast<double>(q)) >= o.min_plane_separation_deg;
        });
        if (far) kept.push_back(p);
    }
    return static_cast<int>(kept.size());
}

}  // namespace detail

inline azimuth_selection azimuth_mode_select(std::span<const std::uint32_t> aspect_histogram,
                                             const azimuth_mode_select_options& opt)
{
    constexpr const char* fn = "azimuth_mode_select";
    detail::require(aspect_histogram.size() == 360, fn, "aspect_histogram", "360 one-degree bins",
                    aspect_histogram.size());
    detail::require(opt.window_deg >= 0 && opt.window_deg <= 180, fn, "window_deg", "in [0, 180]", opt.window_deg);
    detail::require(opt.four_plane_low_deg <= opt.four_plane_high_deg, fn, "four_plane_low_deg",
                    "<= four_plane_high_deg", opt.four_plane_low_deg);
    detail::require(opt.min_plane_share > 0 && opt.min_plane_share <= 1, fn, "min_plane_share", "in (0, 1]",
                    opt.min_plane_share);
    azimuth_selection s;
    const auto best = std::max_element(aspect_histogram.begin(), aspect_histogram.end());
    if (*best == 0) return s;
    s.mode_deg = static_cast<double>(best - aspect_histogram.begin());
    s.planes = detail::count_aspect_planes(aspect_histogram, opt);
    s.form = s.planes >= 5 ? roof_form::complex : static_cast<roof_form>(s.planes);
    if (s.planes > 4) {
        s.reason = azimuth_reason::too_many_planes;
        return s;
    }
    s.suitable = true;
    const auto has_aspect_near = [&](double a) {
        for (std::size_t k = 0; k < 360; ++k)
            if (aspect_histogram[k] > 0 && detail::azimuth_gap_deg(static_cast<double>(k), a) <= opt.window_deg)
                return true;
        return false;
    };
    const double m = s.mode_deg;
    const bool north_half = m > 270.0 || m < 90.0;
    const bool east_side = m >= opt.four_plane_low_deg && m <= opt.four_plane_high_deg;
    const bool may_lack_side = s.planes == 1 || s.planes == 3;
    s.azimuth_deg = m;
    s.reason = azimuth_reason::kept;
    if (north_half) {
        const double swapped = detail::wrap_deg(m + 180.0);
        if (may_lack_side && !has_aspect_near(swapped)) {
            s.reason = azimuth_reason::swap_abandoned;
        } else {
            s.azimuth_deg = swapped;
            s.reason = azimuth_reason::swapped;
        }
    } else if (east_side && s.planes >= 3) {
        std::uint64_t west = 0, east = 0;
        for (std::size_t k = 1; k < 180; ++k) east += aspect_histogram[k];
        for (std::size_t k = 181; k < 360; ++k) west += aspect_histogram[k];
        const double turned = detail::wrap_deg(m + 90.0);
        if (west <= east) {
            s.reason = azimuth_reason::kept_east;
        } else if (s.planes == 3 && !has_aspect_near(turned)) {
            s.reason = azimuth_reason::swap_abandoned;
        } else {
            s.azimuth_deg = turned;
            s.reason = azimuth_reason::turned_west;
        }
    }
    return s;
}

}  // namespace lidarfx
