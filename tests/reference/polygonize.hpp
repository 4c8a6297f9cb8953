// SPDX-License-Identifier: Apache-2.0
// Reference polygonize: the first implementation, whose hole assignment tests every hole against every
// exterior ring of its label with an even-odd test (quadratic). Same rings, same order as polygonize.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <lidarfx/core/grid.hpp>
#include <lidarfx/kernels/vector/polygonize.hpp>

namespace reference {

inline long long ring_area2(const std::vector<std::array<std::ptrdiff_t, 2>>& ring)  // twice the signed area
{
    long long a = 0;
    for (std::size_t i = 0; i + 1 < ring.size(); ++i) {
        // (x, y) = (col, -row)
        a += static_cast<long long>(ring[i][1]) * (-ring[i + 1][0]) -
             static_cast<long long>(ring[i + 1][1]) * (-ring[i][0]);
    }
    return a;
}

/// Even-odd test of point (x, y) (in corner units, x = col, y = -row) against a closed ring.
inline bool inside(const std::vector<std::array<std::ptrdiff_t, 2>>& ring, double x, double y)
{
    bool in = false;
    for (std::size_t i = 0, j = ring.size() - 2; i + 1 < ring.size(); j = i++) {
        const double xi = static_cast<double>(ring[i][1]), yi = -static_cast<double>(ring[i][0]);
        const double xj = static_cast<double>(ring[j][1]), yj = -static_cast<double>(ring[j][0]);
        if ((yi > y) != (yj > y) && x < (xj - xi) * (y - yi) / (yj - yi) + xi) in = !in;
    }
    return in;
}

/// Outlines of every label > 0 as lidarfx::polygonize gives them; each hole goes to the smallest exterior
/// ring of its label that contains the midpoint of the hole's first edge.
template <class Labels>
std::vector<lidarfx::label_polygons> polygonize_quadratic(const Labels& labels, const lidarfx::grid& g)
{
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
    }
    std::sort(edges.begin(), edges.end(),
              [](const edge& a, const edge& b) { return a.label != b.label ? a.label < b.label : a.from < b.from; });

    std::vector<lidarfx::label_polygons> out;
    std::vector<std::uint8_t> used(edges.size(), 0);
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
        for (std::size_t e0 = begin; e0 < end; ++e0) {
            if (used[e0]) continue;
            std::vector<std::array<std::ptrdiff_t, 2>> ring;
            std::size_t e = e0;
            while (!used[e]) {
                used[e] = 1;
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
            (ring_area2(simple) > 0 ? outers : holes).push_back(std::move(simple));
        }
        lidarfx::label_polygons lp;
        lp.label = static_cast<std::int32_t>(edges[begin].label);
        std::vector<lidarfx::polygon> polys(outers.size());
        const auto to_world = [&](const std::vector<std::array<std::ptrdiff_t, 2>>& ring) {
            std::vector<std::array<double, 2>> w;
            w.reserve(ring.size());
            for (const auto& p : ring) {
                w.push_back({g.x0 + static_cast<double>(p[1]) * g.cell, g.y0 - static_cast<double>(p[0]) * g.cell});
            }
            return w;
        };
        for (std::size_t k = 0; k < outers.size(); ++k) polys[k].rings.push_back(to_world(outers[k]));
        for (const auto& h : holes) {
            // The midpoint of a hole edge is never a vertex of another ring; the smallest containing exterior owns it.
            const double x = 0.5 * static_cast<double>(h[0][1] + h[1][1]),
                         y = -0.5 * static_cast<double>(h[0][0] + h[1][0]);
            std::size_t best = outers.size();
            long long best_area = 0;
            for (std::size_t k = 0; k < outers.size(); ++k) {
                if (!inside(outers[k], x, y)) continue;
                const auto a = ring_area2(outers[k]);
                if (best == outers.size() || a < best_area) {
                    best = k;
                    best_area = a;
                }
            }
            if (best < outers.size()) polys[best].rings.push_back(to_world(h));
        }
        lp.polygons = std::move(polys);
        out.push_back(std::move(lp));
        begin = end;
    }
    return out;
}

}  // namespace reference
