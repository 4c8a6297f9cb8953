// SPDX-License-Identifier: Apache-2.0
// Implementation of kernels/vector/polygonize.hpp: collect the labels' directed boundary edges, trace each ring,
// drop collinear corners, and give each hole to the part it is cut from. Included at the end of polygonize.hpp,
// after the declarations it defines; not a public header.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/grid.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"

namespace lidarfx {

namespace detail {

/// A directed boundary edge of a label: key = from * 4 + direction, `from` the corner (row * vcols + col) the
/// edge leaves; directions 0 east, 1 north, 2 west, 3 south (counter-clockwise in world axes). Edges run with
/// the region on their left.
struct boundary_edge {
    std::int64_t label;
    std::int64_t key;
    std::ptrdiff_t from() const noexcept { return static_cast<std::ptrdiff_t>(key >> 2); }
    int dir() const noexcept { return static_cast<int>(key & 3); }
};

/// A ring's corners as (row, col) of the corner grid.
using corner_ring = std::vector<std::array<std::ptrdiff_t, 2>>;

/// Twice the signed area of a closed ring of corners (row, col), in world axes (x = col, y = -row):
/// > 0 counter-clockwise.
inline long long ring_area2(const corner_ring& ring)
{
    long long a = 0;
    for (std::size_t i = 0; i + 1 < ring.size(); ++i) {
        a += static_cast<long long>(ring[i][1]) * (-ring[i + 1][0]) -
             static_cast<long long>(ring[i + 1][1]) * (-ring[i][0]);
    }
    return a;
}

/// The boundary edges of every label > 0, sorted by label, then by corner (a corner's outgoing edges, at most
/// two of a label, sit side by side). Progress: 0 to 0.5 over the rows scanned.
template <class Labels>
std::vector<boundary_edge> boundary_edges(const Labels& labels, const progress_callback& progress, const char* function)
{
    const std::ptrdiff_t rows = labels.rows(), cols = labels.cols(), vcols = cols + 1;
    const auto label_at = [&](std::ptrdiff_t r, std::ptrdiff_t c) -> std::int64_t {
        return (r < 0 || c < 0 || r >= rows || c >= cols) ? 0 : static_cast<std::int64_t>(labels(r, c));
    };
    const auto key = [&](std::ptrdiff_t vr, std::ptrdiff_t vc, int dir) {
        return static_cast<std::int64_t>(vr * vcols + vc) * 4 + dir;
    };
    std::vector<boundary_edge> edges;
    constexpr std::ptrdiff_t report_rows = 256;
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const auto l = label_at(r, c);
            if (l <= 0) continue;
            if (label_at(r + 1, c) != l) edges.push_back({l, key(r + 1, c, 0)});      // south side, east
            if (label_at(r, c + 1) != l) edges.push_back({l, key(r + 1, c + 1, 1)});  // east side, north
            if (label_at(r - 1, c) != l) edges.push_back({l, key(r, c + 1, 2)});      // north side, west
            if (label_at(r, c - 1) != l) edges.push_back({l, key(r, c, 3)});          // west side, south
        }
        if ((r + 1) % report_rows == 0 || r + 1 == rows) {
            report(progress, 0.5 * static_cast<double>(r + 1) / static_cast<double>(rows), function);
        }
    }
    std::sort(edges.begin(), edges.end(), [](const boundary_edge& a, const boundary_edge& b) {
        return a.label != b.label ? a.label < b.label : a.key < b.key;
    });
    return edges;
}

/// The edges [begin, end) of one label, sorted by key, with the state of tracing them into rings.
struct label_edges {
    static constexpr std::size_t npos = static_cast<std::size_t>(-1);

    const std::vector<boundary_edge>& edges;
    std::size_t begin, end;
    std::ptrdiff_t vcols;               ///< corners per row: cols + 1
    std::vector<std::size_t>& ring_of;  ///< per edge: its ring within the label (tracing order); npos = not traced
    std::size_t west = 0, last_south = npos;  ///< sweep over the edges for the hole assignment (part_above)

    /// First edge of the label leaving corner `vtx`, galloping from edge `near`: a step along a row of corners
    /// lands next to `near`, a step across rows one row of edges away. O(log distance).
    std::size_t outgoing(std::ptrdiff_t vtx, std::size_t near) const
    {
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
                                         [](const boundary_edge& e, std::int64_t x) { return e.key < x; });
        return static_cast<std::size_t>(it - edges.begin());
    }

    /// Traces the ring that starts with untraced edge e0, numbering its edges `ring_id`, into `ring` (its
    /// corners in order, not closed). Every edge before e0 is traced, so e0's corner is the ring's first in
    /// raster order: its top-left corner, a convex corner (never dropped as collinear).
    void trace_ring(std::size_t e0, std::size_t ring_id, corner_ring& ring)
    {
        const std::array<std::ptrdiff_t, 4> step{1, -vcols, -1, vcols};
        ring.clear();
        std::size_t e = e0;
        while (ring_of[e] == npos) {
            ring_of[e] = ring_id;
            const auto from = edges[e].from();
            const int dir = edges[e].dir();
            const auto to = from + step[static_cast<std::size_t>(dir)];
            ring.push_back({from / vcols, from % vcols});
            std::size_t next = outgoing(to, e);
            if (next + 1 < end && edges[next + 1].from() == to) {
                // Pinch corner (two cells of the label touch only there): keep hugging the same cell, i.e.
                // turn left (region side); the other edge turns right.
                if (edges[next].dir() != ((dir + 1) & 3)) ++next;
            }
            e = next;
        }
    }

    /// The ring (in tracing order) of a part's ring that holds the cell above the top-left corner of the hole
    /// starting at edge e0. That cell belongs to the part the hole is cut from (its edges have the part on
    /// their left). Its run of cells of this label in that row starts at a west-side (southward) edge of a
    /// ring of the same part, traced earlier since that edge comes first in raster order. Holes are met in
    /// raster order of their corners, so one forward sweep over the edges finds every such edge: O(edges)
    /// for all holes of the label.
    std::size_t ring_above(std::size_t e0)
    {
        const std::ptrdiff_t above = edges[e0].from() - vcols;
        while (west < end && edges[west].from() <= above) {
            if (edges[west].dir() == 3) last_south = west;
            ++west;
        }
        LIDARFX_ASSERT(last_south != npos && edges[last_south].from() / vcols == above / vcols);
        return ring_of[last_south];
    }
};

/// `ring` without its collinear corners, closed (last corner = first), into `simple`.
inline void drop_collinear(const corner_ring& ring, corner_ring& simple)
{
    simple.clear();
    const std::size_t n = ring.size();
    for (std::size_t i = 0; i < n; ++i) {
        const auto& a = ring[(i + n - 1) % n];
        const auto& b = ring[i];
        const auto& c = ring[(i + 1) % n];
        if ((b[0] - a[0]) * (c[1] - b[1]) != (b[1] - a[1]) * (c[0] - b[0])) simple.push_back(b);
    }
    simple.push_back(simple.front());
}

/// A ring of corners in world coordinates of `g`.
inline std::vector<std::array<double, 2>> corners_to_world(const corner_ring& corners, const grid& g)
{
    std::vector<std::array<double, 2>> w;
    w.reserve(corners.size());
    for (const auto& p : corners) w.push_back(g.to_world(static_cast<double>(p[0]), static_cast<double>(p[1])));
    return w;
}

/// Progress of the ring tracing: 0.5 to 1 over the edges traced, reported every 2^16 edges.
struct tracing_progress {
    const progress_callback& progress;
    const char* function;
    std::size_t total;
    std::size_t traced = 0, reported = 0;

    void add(std::size_t edges)
    {
        traced += edges;
        if (traced - reported >= (std::size_t{1} << 16)) {
            reported = traced;
            report(progress, 0.5 + 0.5 * static_cast<double>(traced) / static_cast<double>(total), function);
        }
    }
};

/// The polygons of one label: each exterior ring (counter-clockwise) starts a polygon, each hole (clockwise)
/// joins the polygon of the part it is cut from; rings in the raster order of their top-left corners.
inline label_polygons label_outlines(label_edges& le, const grid& g, tracing_progress& tracking)
{
    std::vector<std::vector<std::array<double, 2>>> outers, holes;
    std::vector<std::size_t> owner;       // per ring: index in `outers` of the exterior of its part
    std::vector<std::size_t> hole_owner;  // per hole: the same, in `holes` order
    corner_ring ring, simple;
    std::size_t ring_id = 0;
    for (std::size_t e0 = le.begin; e0 < le.end; ++e0) {
        if (le.ring_of[e0] != label_edges::npos) continue;
        le.trace_ring(e0, ring_id, ring);
        drop_collinear(ring, simple);
        if (ring_area2(simple) > 0) {
            owner.push_back(outers.size());
            outers.push_back(corners_to_world(simple, g));
        } else {
            const std::size_t part = owner[le.ring_above(e0)];
            owner.push_back(part);
            hole_owner.push_back(part);
            holes.push_back(corners_to_world(simple, g));
        }
        ++ring_id;
        tracking.add(ring.size());
    }
    label_polygons lp;
    lp.label = static_cast<std::int32_t>(le.edges[le.begin].label);
    lp.polygons.resize(outers.size());
    for (std::size_t k = 0; k < outers.size(); ++k) lp.polygons[k].rings.push_back(std::move(outers[k]));
    for (std::size_t h = 0; h < holes.size(); ++h) lp.polygons[hole_owner[h]].rings.push_back(std::move(holes[h]));
    return lp;
}

}  // namespace detail

template <raster_input Labels>
std::vector<label_polygons> polygonize(const Labels& labels, const grid& g, const polygonize_options& opt)
{
    constexpr const char* function = "polygonize";
    detail::require(labels.rows() == g.rows && labels.cols() == g.cols, function, "labels must have the grid's shape");
    detail::require(opt.run.threads >= 0, function, "run.threads", ">= 0", opt.run.threads);
    const std::vector<detail::boundary_edge> edges = detail::boundary_edges(labels, opt.run.progress, function);
    std::vector<std::size_t> ring_of(edges.size(), detail::label_edges::npos);
    detail::tracing_progress tracking{opt.run.progress, function, edges.size()};
    std::vector<label_polygons> out;
    for (std::size_t begin = 0; begin < edges.size();) {
        std::size_t end = begin;
        while (end < edges.size() && edges[end].label == edges[begin].label) ++end;
        detail::label_edges le{edges, begin, end, labels.cols() + 1, ring_of, begin};
        out.push_back(detail::label_outlines(le, g, tracking));
        begin = end;
    }
    detail::report(opt.run.progress, 1.0, function);
    return out;
}

}  // namespace lidarfx
