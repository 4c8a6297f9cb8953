// SPDX-License-Identifier: Apache-2.0
// Implementation of kernels/vector/burn_polygons.hpp: the row spans of each feature's rings (even-odd crossings at cell
// centres) and the burning of each feature. Included at the end of burn_polygons.hpp, after the declarations it
// defines; not a public header.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/grid.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/kernels/vector/polygonize.hpp"

namespace lidarfx {

namespace detail {

/// Cells of row r of `g` whose centre lies inside the parts (even-odd rule over all rings): appends column
/// intervals [c0, c1) to `spans`. An edge counts as crossed when (y_a > y) != (y_b > y) at the row's centre
/// line y, at x = its crossing; a centre counts as inside when an odd number of crossings lie at x < centre.
inline void burn_row_spans(const std::vector<polygon>& parts, const grid& g, std::ptrdiff_t r, std::vector<double>& xs,
                           std::vector<std::array<std::ptrdiff_t, 2>>& spans)
{
    const double y = g.center(r, 0)[1];
    xs.clear();
    for (const polygon& p : parts) {
        for (const auto& ring : p.rings) {
            const std::size_t n = ring.size();
            for (std::size_t i = 0; i < n; ++i) {
                const auto& a = ring[i];
                const auto& b = ring[(i + 1) % n];
                if ((a[1] > y) == (b[1] > y)) continue;
                xs.push_back(a[0] + (y - a[1]) * (b[0] - a[0]) / (b[1] - a[1]));
            }
        }
    }
    std::sort(xs.begin(), xs.end());
    for (std::size_t i = 0; i + 1 < xs.size(); i += 2) {
        // Centres x_c = x0 + (c + 0.5) cell with xs[i] < x_c <= xs[i + 1].
        const double lo = (xs[i] - g.x0) / g.cell - 0.5, hi = (xs[i + 1] - g.x0) / g.cell - 0.5;
        const double first = std::floor(lo) + 1.0, last = std::floor(hi);  // smallest c > lo, largest c <= hi
        const double c0 = std::max(first, 0.0), c1 = std::min(last + 1.0, static_cast<double>(g.cols));
        if (c0 < c1) spans.push_back({static_cast<std::ptrdiff_t>(c0), static_cast<std::ptrdiff_t>(c1)});
    }
}

}  // namespace detail

inline burn_result burn_polygons(std::span<const labelled_polygon> footprints, const grid& g)
{
    constexpr const char* fn = "burn_polygons";
    g.validate(fn);
    burn_result out{raster<std::int32_t>(g.rows, g.cols, 0), {}};
    out.footprints.reserve(footprints.size());
    std::vector<double> xs;
    std::vector<std::array<std::ptrdiff_t, 2>> spans;
    for (const labelled_polygon& f : footprints) {
        detail::require(f.label > 0, fn, "label", "> 0", f.label);
        burn_account acc{f.label, 0, 0, 0};
        double ymin = INFINITY, ymax = -INFINITY, xmin = INFINITY, xmax = -INFINITY;
        for (const polygon& p : f.parts) {
            for (const auto& ring : p.rings) {
                for (const auto& v : ring) {
                    detail::require(std::isfinite(v[0]) && std::isfinite(v[1]), fn,
                                    "every vertex finite; footprint label", "finite coordinates", f.label);
                    ymin = std::min(ymin, v[1]);
                    ymax = std::max(ymax, v[1]);
                    xmin = std::min(xmin, v[0]);
                    xmax = std::max(xmax, v[0]);
                }
            }
        }
        if (!(ymin <= ymax) || xmax < g.x0 || xmin > g.x1() || ymax < g.y1() || ymin > g.y0) {
            acc.outside = 1;
            out.footprints.push_back(acc);
            continue;
        }
        // Rows whose centre line y = y0 - (r + 0.5) cell lies within [ymin, ymax].
        const double r_lo = std::ceil((g.y0 - ymax) / g.cell - 0.5), r_hi = std::floor((g.y0 - ymin) / g.cell - 0.5);
        const auto r0 = static_cast<std::ptrdiff_t>(std::max(r_lo, 0.0));
        const auto r1 = static_cast<std::ptrdiff_t>(std::min(r_hi, static_cast<double>(g.rows - 1)));
        for (std::ptrdiff_t r = r0; r <= r1; ++r) {
            spans.clear();
            detail::burn_row_spans(f.parts, g, r, xs, spans);
            for (const auto& [c0, c1] : spans) {
                for (std::ptrdiff_t c = c0; c < c1; ++c) {
                    std::int32_t& cell = out.labels(r, c);
                    if (cell == 0) {
                        cell = f.label;
                        ++acc.cells;
                    } else {
                        ++acc.contested;
                    }
                }
            }
        }
        out.footprints.push_back(acc);
    }
    return out;
}

}  // namespace lidarfx
