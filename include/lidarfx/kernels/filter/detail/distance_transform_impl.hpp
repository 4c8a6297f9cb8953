// SPDX-License-Identifier: Apache-2.0
// Implementation of kernels/filter/distance_transform.hpp: the exact squared Euclidean distance as lower envelopes of
// parabolas, by rows then columns. Included at the end of distance_transform.hpp, after the declarations it defines;
// not a public header.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

namespace detail {

/// One row of the lower envelope of parabolas y = f[q] + (x - q)^2 over the finite f (Felzenszwalb and
/// Huttenlocher, "Distance transforms of sampled functions", 2012): out[x] = min_q f[q] + (x - q)^2, or
/// +infinity when every f is infinite. `site` and `from` are scratch of n and n + 1 entries. O(n).
inline void parabola_envelope(const double* f, std::ptrdiff_t n, float* out, std::vector<std::ptrdiff_t>& site,
                              std::vector<double>& from)
{
    site.resize(static_cast<std::size_t>(n));
    from.resize(static_cast<std::size_t>(n) + 1);
    std::ptrdiff_t k = -1;  // index of the rightmost parabola of the envelope
    for (std::ptrdiff_t q = 0; q < n; ++q) {
        if (!(f[q] < std::numeric_limits<double>::infinity())) continue;
        const double fq = f[q] + static_cast<double>(q) * static_cast<double>(q);
        double s = -std::numeric_limits<double>::infinity();
        while (k >= 0) {
            const std::ptrdiff_t v = site[static_cast<std::size_t>(k)];
            // Where the parabola at q starts to lie below the one at v.
            s = (fq - (f[v] + static_cast<double>(v) * static_cast<double>(v))) / (2.0 * static_cast<double>(q - v));
            if (s > from[static_cast<std::size_t>(k)]) break;
            --k;
        }
        ++k;
        site[static_cast<std::size_t>(k)] = q;
        from[static_cast<std::size_t>(k)] = k == 0 ? -std::numeric_limits<double>::infinity() : s;
        from[static_cast<std::size_t>(k) + 1] = std::numeric_limits<double>::infinity();
    }
    if (k < 0) {
        std::fill(out, out + n, no_feature_distance);
        return;
    }
    std::ptrdiff_t j = 0;
    for (std::ptrdiff_t x = 0; x < n; ++x) {
        while (from[static_cast<std::size_t>(j) + 1] < static_cast<double>(x)) ++j;
        const std::ptrdiff_t v = site[static_cast<std::size_t>(j)];
        const double dx = static_cast<double>(x - v);
        out[x] = static_cast<float>(dx * dx + f[v]);
    }
}

}  // namespace detail

inline raster<float> squared_distance_transform(raster_view<const std::uint8_t> features,
                                                const distance_transform_options& opt)
{
    constexpr const char* function = "squared_distance_transform";
    detail::check_execution(opt.run, function);
    const std::ptrdiff_t rows = features.rows(), cols = features.cols();
    raster<float> out(rows, cols, uninitialized);
    if (rows == 0 || cols == 0) {
        detail::report(opt.run.progress, 1.0, function);
        return out;
    }
    // Column pass: distance (in rows) to the nearest feature of the same column, down then up; kept in
    // `out` as float (row counts are far below 2^24) with +infinity for none.
    constexpr std::ptrdiff_t column_block = 256;
    const std::ptrdiff_t column_blocks = (cols + column_block - 1) / column_block;
    parallel_for_rows(column_blocks, 1, opt.run.threads, [&](std::ptrdiff_t b0, std::ptrdiff_t b1) {
        const std::ptrdiff_t c0 = b0 * column_block, c1 = std::min(cols, b1 * column_block);
        for (std::ptrdiff_t r = 0; r < rows; ++r) {
            const std::uint8_t* f = features.row(r);
            float* o = out.view().row(r);
            const float* above = r > 0 ? out.view().row(r - 1) : nullptr;
            for (std::ptrdiff_t c = c0; c < c1; ++c)
                o[c] = f[c] ? 0.0f : (above ? above[c] + 1.0f : no_feature_distance);
        }
        for (std::ptrdiff_t r = rows - 2; r >= 0; --r) {
            float* o = out.view().row(r);
            const float* below = out.view().row(r + 1);
            for (std::ptrdiff_t c = c0; c < c1; ++c) o[c] = std::min(o[c], below[c] + 1.0f);
        }
    });
    // Row pass: lower envelope of the parabolas (c - q)^2 + column distance(q)^2.
    parallel_for_rows(
        rows, 64, opt.run.threads,
        [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
            std::vector<double> f(static_cast<std::size_t>(cols)), from;
            std::vector<std::ptrdiff_t> site;
            for (std::ptrdiff_t r = r0; r < r1; ++r) {
                float* o = out.view().row(r);
                for (std::ptrdiff_t c = 0; c < cols; ++c) {
                    const double d = o[c];
                    f[static_cast<std::size_t>(c)] = d * d;
                }
                detail::parabola_envelope(f.data(), cols, o, site, from);
            }
        },
        opt.run.progress, function);
    return out;
}

}  // namespace lidarfx
