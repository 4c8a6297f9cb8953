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
    // Directed boundary edges per label: key = from * 4 + direction, `from` the corner (row * vcols + col)
    // the edge leaves; directions 0 east, 1 north, 2 west, 3 south (counter-clockwise in world axes).
    struct edge {
        std::int64_t label;
        std::int64_t key;
    };
    const std::array<std::ptrdiff_t, 4> step{1, -vcols, -1, vcols};
    const auto from_of = [](const edge& e) { return static_cast<std::ptrdiff_t>(e.key >> 2); };
    const auto dir_of = [](const edge& e) { return static_cast<int>(e.key & 3); };
    std::vector<edge> edges;
    constexpr std::ptrdiff_t report_rows = 256;  // progress: first half over the rows scanned
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const auto l = label_at(r, c);
            if (l <= 0) continue;
            const auto key = [&](std::ptrdiff_t vr, std::ptrdiff_t vc, int dir) {
                return static_cast<std::int64_t>(vr * vcols + vc) * 4 + dir;
            };
            if (label_at(r + 1, c) != l) edges.push_back({l, key(r + 1, c, 0)});      // south side, east
            if (label_at(r, c + 1) != l) edges.push_back({l, key(r + 1, c + 1, 1)});  // east side, north
            if (label_at(r - 1, c) != l) edges.push_back({l, key(r, c + 1, 2)});      // north side, west
            if (label_at(r, c - 1) != l) edges.push_back({l, key(r, c, 3)});          // west side, south
        }
        if ((r + 1) % report_rows == 0 || r + 1 == rows) {
            detail::report(progress, 0.5 * static_cast<double>(r + 1) / static_cast<double>(rows), function);
        }
    }
    // By label, then by corner: a corner's outgoing edges (at most two of a label) sit side by side.
    std::sort(edges.begin(), edges.end(),
              [](const edge& a, const edge& b) { return a.label != b.label ? a.label < b.label : a.key < b.key; });

    std::vector<label_polygons> out;
    // Ring of each edge within its label (rings numbered in tracing order); npos = not traced yet.
    constexpr std::size_t npos = static_cast<std::size_t>(-1);
    std::vector<std::size_t> ring_of(edges.size(), npos);
    constexpr std::size_t report_edges = std::size_t{1} << 16;  // progress: second half over the edges
    std::size_t traced = 0, reported = 0;
    std::vector<std::array<std::ptrdiff_t, 2>> ring, simple;  // scratch: one ring's corners (row, col)
    const auto to_world = [&](const std::vector<std::array<std::ptrdiff_t, 2>>& corners) {
        std::vector<std::array<double, 2>> w;
        w.reserve(corners.size());
        for (const auto& p : corners) {
            w.push_back(g.to_world(static_cast<double>(p[0]), static_cast<double>(p[1])));
        }
        return w;
    };
    for (std::size_t begin = 0; begin < edges.size();) {
        std::size_t end = begin;
        while (end < edges.size() && edges[end].label == edges[begin].label) ++end;
        // First edge of the label leaving corner `vtx`, galloping from edge `near`: a step along a row of
        // corners lands next to `near`, a step across rows one row of edges away. O(log distance).
        const auto outgoing = [&](std::ptrdiff_t vtx, std::size_t near) {
            const std::int64_t k = static_cast<std::int64_t>(vtx) * 4;
            std::size_t lo = near, hi = near, stride = 1;  // the answer lies in [lo, hi]
            if (edges[near].key < k) {
                lo = hi = near + 1;
                while (hi < end && edges[hi].key < k) {
                    lo = hi + 1;
                    hi = std::min(end, hi + stride);
                    stride *= 2;
                }
            } else {
                while (lo > begin && edges[lo - 1].key >= k) {
                    hi = lo - 1;
                    lo = lo - begin > stride ? lo - stride : begin;
                    stride *= 2;
                }
            }
            const auto it = std::lower_bound(edges.begin() + static_cast<std::ptrdiff_t>(lo),
                                             edges.begin() + static_cast<std::ptrdiff_t>(hi), k,
                                             [](const edge& e, std::int64_t x) { return e.key < x; });
            return static_cast<std::size_t>(it - edges.begin());
        };
        std::vector<std::vector<std::array<double, 2>>> outers, holes;
        std::vector<std::size_t> owner;               // per ring: index in `outers` of the exterior of its part
        std::vector<std::size_t> hole_owner;          // per hole: the same, in `holes` order
        std::size_t west = begin, last_south = npos;  // sweep over the edges for the hole assignment
        std::size_t ring_id = 0;
        for (std::size_t e0 = begin; e0 < end; ++e0) {
            if (ring_of[e0] != npos) continue;
            // Every edge before e0 is traced, so e0's corner is the ring's first in raster order: its
            // top-left corner, a convex corner (never dropped as collinear).
            ring.clear();
            std::size_t e = e0;
            while (ring_of[e] == npos) {
                ring_of[e] = ring_id;
                const auto from = from_of(edges[e]);
                const int dir = dir_of(edges[e]);
                const auto to = from + step[static_cast<std::size_t>(dir)];
                ring.push_back({from / vcols, from % vcols});
                std::size_t next = outgoing(to, e);
                if (next + 1 < end && from_of(edges[next + 1]) == to) {
                    // Pinch corner (two cells of the label touch only there): keep hugging the same cell, i.e.
                    // turn left (region side); the other edge turns right.
                    if (dir_of(edges[next]) != ((dir + 1) & 3)) ++next;
                }
                e = next;
            }
            traced += ring.size();
            // Drop collinear corners.
            simple.clear();
            const std::size_t n = ring.size();
            for (std::size_t i = 0; i < n; ++i) {
                const auto& a = ring[(i + n - 1) % n];
                const auto& b = ring[i];
                const auto& c = ring[(i + 1) % n];
                if ((b[0] - a[0]) * (c[1] - b[1]) != (b[1] - a[1]) * (c[0] - b[0])) simple.push_back(b);
            }
            simple.push_back(simple.front());
            if (detail::ring_area2(simple) > 0) {
                owner.push_back(outers.size());
                outers.push_back(to_world(simple));
            } else {
                // The cell above the hole's top-left corner belongs to the part the hole is cut from (its
                // edges have the part on their left). Its run of cells of this label in that row starts at a
                // west-side (southward) edge of a ring of the same part, traced earlier since that edge comes
                // first in raster order. Holes are met in raster order of their corners, so one forward
                // sweep over the edges finds every such edge: O(edges) for all holes of the label.
                const std::ptrdiff_t above = from_of(edges[e0]) - vcols;
                while (west < end && from_of(edges[west]) <= above) {
                    if (dir_of(edges[west]) == 3) last_south = west;
                    ++west;
                }
                LIDARFX_ASSERT(last_south != npos && from_of(edges[last_south]) / vcols == above / vcols);
                const std::size_t part = owner[ring_of[last_south]];
                owner.push_back(part);
                hole_owner.push_back(part);
                holes.push_back(to_world(simple));
            }
            ++ring_id;
            if (traced - reported >= report_edges) {
                reported = traced;
                detail::report(progress, 0.5 + 0.5 * static_cast<double>(traced) / static_cast<double>(edges.size()),
                               function);
            }
        }
        label_polygons lp;
        lp.label = static_cast<std::int32_t>(edges[begin].label);
        lp.polygons.resize(outers.size());
        for (std::size_t k = 0; k < outers.size(); ++k) lp.polygons[k].rings.push_back(std::move(outers[k]));
        for (std::size_t h = 0; h < holes.size(); ++h) lp.polygons[hole_owner[h]].rings.push_back(std::move(holes[h]));
        out.push_back(std::move(lp));
        begin = end;
    }
    detail::report(progress, 1.0, function);
    return out;
}

}  // namespace lidarfx
