// SPDX-License-Identifier: Apache-2.0
// Reference angular filter (one atan per neighbour, in double) and random/strided raster helpers for tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <random>

#include <lidarfx/core/raster.hpp>
#include <lidarfx/core/raster_view.hpp>

namespace reference {

/// rows x cols cells uniform in [lo, hi), each NaN with probability nan_share.
inline lidarfx::raster<float> random_raster(std::mt19937& rng, std::ptrdiff_t rows, std::ptrdiff_t cols,
                                            double lo = 0.0, double hi = 10.0, double nan_share = 0.0)
{
    std::uniform_real_distribution<double> value(lo, hi);
    std::bernoulli_distribution hole(nan_share);
    lidarfx::raster<float> z(rows, cols);
    for (auto& v : z) v = hole(rng) ? std::numeric_limits<float>::quiet_NaN() : static_cast<float>(value(rng));
    return z;
}

/// A copy of `src` inside a larger raster whose margin holds `poison`; window(margin, margin, rows, cols) of
/// the result is a strided view (row_stride > cols) of the same cells. A kernel that reads outside its view
/// picks up the poison and gives different results.
template <class T>
lidarfx::raster<T> with_margin(const lidarfx::raster<T>& src, std::ptrdiff_t margin, T poison)
{
    lidarfx::raster<T> big(src.rows() + 2 * margin, src.cols() + 2 * margin + 3, poison);
    for (std::ptrdiff_t r = 0; r < src.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < src.cols(); ++c) big(r + margin, c + margin) = src(r, c);
    return big;
}

/// The strided view of the cells `with_margin` copied.
template <class T>
lidarfx::raster_view<const T> inner(const lidarfx::raster<T>& big, std::ptrdiff_t margin, std::ptrdiff_t rows,
                                    std::ptrdiff_t cols)
{
    return big.view().window(margin, margin, rows, cols);
}

/// Angular filter by definition: for each cell, the largest atan(|dz| / distance) over every non-NaN
/// neighbour in the clipped (2r+1)^2 window, in degrees; NaN centre -> NaN, no valid neighbour -> 0.
inline lidarfx::raster<float> angular_filter(lidarfx::raster_view<const float> z, double cell, int radius)
{
    lidarfx::raster<float> out(z.rows(), z.cols());
    for (std::ptrdiff_t r = 0; r < z.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < z.cols(); ++c) {
            const double zp = z(r, c);
            if (std::isnan(zp)) {
                out(r, c) = std::numeric_limits<float>::quiet_NaN();
                continue;
            }
            double best = 0.0;
            for (std::ptrdiff_t dr = -radius; dr <= radius; ++dr) {
                for (std::ptrdiff_t dc = -radius; dc <= radius; ++dc) {
                    const std::ptrdiff_t rr = r + dr, cc = c + dc;
                    if ((dr == 0 && dc == 0) || rr < 0 || rr >= z.rows() || cc < 0 || cc >= z.cols()) continue;
                    const double zq = z(rr, cc);
                    if (std::isnan(zq)) continue;
                    const double distance = cell * std::hypot(static_cast<double>(dr), static_cast<double>(dc));
                    best = std::max(best, std::atan(std::fabs(zq - zp) / distance));
                }
            }
            out(r, c) = static_cast<float>(best * 180.0 / std::numbers::pi);
        }
    }
    return out;
}

}  // namespace reference
