// SPDX-License-Identifier: Apache-2.0
// polygonize: outlines of labelled regions as polygons along cell edges (for GeoJSON and GIS export).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/grid.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"

namespace lidarfx {

/// A polygon of world coordinates: rings[0] is the exterior (counter-clockwise, x east, y north), the
/// others are holes (clockwise), as RFC 7946 GeoJSON orders them. Rings are closed (last point = first).
struct polygon {
    std::vector<std::vector<std::array<double, 2>>> rings;
};

/// The polygons of one label; a region whose parts touch only at corners gives several polygons.
struct label_polygons {
    std::int32_t label = 0;
    std::vector<polygon> polygons;
};

/// Options of polygonize.
struct polygonize_options {
    execution run = {};  ///< progress and cancellation (core/parallel.hpp); run.threads (>= 0) is ignored:
                         ///< polygonize runs on the caller's thread
};

namespace detail {

/// Twice the signed area of a closed ring of corners (row, col), in world axes (x = col, y = -row):
/// > 0 counter-clockwise.
inline long long ring_area2(const std::vector<std::array<std::ptrdiff_t, 2>>& ring)
{
    long long a = 0;
    for (std::size_t i = 0; i + 1 < ring.size(); ++i) {
        a += static_cast<long long>(ring[i][1]) * (-ring[i + 1][0]) -
             static_cast<long long>(ring[i + 1][1]) * (-ring[i][0]);
    }
    return a;
}

}  // namespace detail

/// Outlines every label > 0 of `labels` along cell edges and returns them in world coordinates of `g`,
/// sorted by label. Rings follow the region with the region on their left; where two cells of a label
/// touch only at a corner the outline separates there (parts become separate polygons or touch a hole at
/// a point), so every ring is simple. Collinear vertices are dropped. Each polygon is one 4-connected
/// part: its exterior ring (counter-clockwise, GeoJSON) then its holes (clockwise), rings of a label in
/// the raster order of their top-left corners. O(cells + boundary length · log(boundary length)).
/// @throws invalid_input if the labels' shape differs from the grid's or run.threads < 0; cancelled if
/// run.progress returns false.
template <raster_input Labels>
std::vector<label_polygons> polygonize(const Labels& labels, const grid& g, const polygonize_options& opt = {})
{
    constexpr const char* function = "polygonize";
    detail::require(labels.rows() == g.rows && labels.cols() == g.cols, function, "labels must have the grid's shape");
    detail::require(opt.run.threads >= 0, function, "run.threads", ">= 0", opt.run.threads);
    const auto& progress = opt.run.progress;
    const std::ptrdiff_t rows = labels.rows(), cols = labels.cols(), vcols = cols + 1;
    const auto label_at = [&](std::ptrdiff_t r, std::ptrdiff_t c) -> std::int64_t {
        return (r < 0 || c < 0 || r >= rows || c >= cols) ? 0 : static_cast<std::int64_t>(labels(r, c));
    };
    // Directed boundary edges (from vertex, to vertex) per label, vertex = row * vcols + col of a corner.
    struct edge {
        std::int64_t label;
        std::ptrdiff_t from, to;
    };
    std::vector<edge> edges;
    constexpr std::ptrdiff_t report_rows = 256;  // progress: first half over the rows scanned
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const auto l = label_at(r, c);
            if (l <= 0) continue;
            const auto v = [&](std::ptrdiff_t vr, std::ptrdiff_t vc) { return vr * vcols + vc; };
            if (label_at(r + 1, c) != l) edges.push_back({l, v(r + 1, c), v(r + 1, c + 1)});  // south side, east
            if (label_at(r, c + 1) != l) edges.push_back({l, v(r + 1, c + 1), v(r, c + 1)});  // east side, north
            if (label_at(r - 1, c) != l) edges.push_back({l, v(r, c + 1), v(r, c)});          // north side, west
            if (label_at(r, c - 1) != l) edges.push_back({l, v(r, c), v(r + 1, c)});          // west side, south
        }
        if ((r + 1) % report_rows == 0 || r + 1 == rows) {
            detail::report(progress, 0.5 * static_cast<double>(r + 1) / static_cast<double>(rows), function);
        }
    }
    std::sort(edges.begin(), edges.end(),
              [](const edge& a, const edge& b) { return a.label != b.label ? a.label < b.label : a.from < b.from; });

    std::vector<label_polygons> out;
    // Ring of each edge within its label (rings numbered in tracing order); npos = not traced yet.
    constexpr std::size_t npos = static_cast<std::size_t>(-1);
    std::vector<std::size_t> ring_of(edges.size(), npos);
    constexpr std::size_t report_edges = std::size_t{1} << 16;  // progress: second half over the edges
    std::size_t reported = 0;
    for (std::size_t begin = 0; begin < edges.size();) {
        std::size_t end = begin;
        while (end < edges.size() && edges[end].label == edges[begin].label) ++end;
        // Outgoing edges of a vertex sit next to each other (sorted by `from`): at most two per vertex.
        const auto outgoing = [&](std::ptrdiff_t vtx) {
            auto it = std::lower_bound(edges.begin() + static_cast<std::ptrdiff_t>(begin),
                                       edges.begin() + static_cast<std::ptrdiff_t>(end), vtx,
                                       [](const edge& e, std::ptrdiff_t x) { return e.from < x; });
            return static_cast<std::size_t>(it - edges.begin());
        };
        std::vector<std::vector<std::array<std::ptrdiff_t, 2>>> outers, holes;
        std::vector<std::size_t> owner;               // per ring: index in `outers` of the exterior of its part
        std::vector<std::size_t> hole_owner;          // per hole: the same, in `holes` order
        std::size_t west = begin, last_south = npos;  // sweep over the edges for the hole assignment
        std::size_t ring_id = 0;
        for (std::size_t e0 = begin; e0 < end; ++e0) {
            if (ring_of[e0] != npos) continue;
            // Every edge before e0 is traced, so e0.from is the ring's first vertex in raster order: its
            // top-left corner, a convex corner (never dropped as collinear).
            std::vector<std::array<std::ptrdiff_t, 2>> ring;
            std::size_t e = e0;
            while (ring_of[e] == npos) {
                ring_of[e] = ring_id;
                const auto from = edges[e].from, to = edges[e].to;
                ring.push_back({from / vcols, from % vcols});
                const std::array<std::ptrdiff_t, 2> dir{to / vcols - from / vcols, to % vcols - from % vcols};
                std::size_t next = outgoing(to), pick = next;
                if (next + 1 < end && edges[next + 1].from == to) {
                    // Pinch vertex: keep hugging the same cell, i.e. turn left (region side) in world axes.
                    for (std::size_t k = next; k < next + 2; ++k) {
                        const auto t = edges[k].to;
                        const std::array<std::ptrdiff_t, 2> d2{t / vcols - to / vcols, t % vcols - to % vcols};
                        // left turn in (x = col, y = -row): cross(dir, d2) > 0 with y flipped
                        const auto cross = dir[1] * (-d2[0]) - (-dir[0]) * d2[1];
                        if (cross > 0) pick = k;
                    }
                }
                e = pick;
            }
            ring.push_back(ring.front());
            // Drop collinear vertices (keep the closing point consistent).
            std::vector<std::array<std::ptrdiff_t, 2>> simple;
            const std::size_t n = ring.size() - 1;
            for (std::size_t i = 0; i < n; ++i) {
                const auto& a = ring[(i + n - 1) % n];
                const auto& b = ring[i];
                const auto& c = ring[(i + 1) % n];
                if ((b[0] - a[0]) * (c[1] - b[1]) != (b[1] - a[1]) * (c[0] - b[0])) simple.push_back(b);
            }
            simple.push_back(simple.front());
            if (detail::ring_area2(simple) > 0) {
                owner.push_back(outers.size());
                outers.push_back(std::move(simple));
            } else {
                // The cell above the hole's top-left corner belongs to the part the hole is cut from (its
                // edges have the part on their left). Its run of cells of this label in that row starts at a
                // west-side (southward) edge of a ring of the same part, traced earlier since that edge comes
                // first in raster order. Holes are met in raster order of their corners, so one forward
                // sweep over the edges finds every such edge: O(edges) for all holes of the label.
                const std::ptrdiff_t above = edges[e0].from - vcols;
                while (west < end && edges[west].from <= above) {
                    if (edges[west].to == edges[west].from + vcols) last_south = west;
                    ++west;
                }
                LIDARFX_ASSERT(last_south != npos && edges[last_south].from / vcols == above / vcols);
                const std::size_t part = owner[ring_of[last_south]];
                owner.push_back(part);
                hole_owner.push_back(part);
                holes.push_back(std::move(simple));
            }
            ++ring_id;
        }
        label_polygons lp;
        lp.label = static_cast<std::int32_t>(edges[begin].label);
        std::vector<polygon> polys(outers.size());
        const auto to_world = [&](const std::vector<std::array<std::ptrdiff_t, 2>>& ring) {
            std::vector<std::array<double, 2>> w;
            w.reserve(ring.size());
            for (const auto& p : ring) {
                w.push_back({g.x0 + static_cast<double>(p[1]) * g.cell, g.y0 - static_cast<double>(p[0]) * g.cell});
            }
            return w;
        };
        for (std::size_t k = 0; k < outers.size(); ++k) polys[k].rings.push_back(to_world(outers[k]));
        for (std::size_t h = 0; h < holes.size(); ++h) polys[hole_owner[h]].rings.push_back(to_world(holes[h]));
        lp.polygons = std::move(polys);
        out.push_back(std::move(lp));
        if (end - reported >= report_edges) {
            reported = end;
            detail::report(progress, 0.5 + 0.5 * static_cast<double>(end) / static_cast<double>(edges.size()),
                           function);
        }
        begin = end;
    }
    detail::report(progress, 1.0, function);
    return out;
}

}  // namespace lidarfx
