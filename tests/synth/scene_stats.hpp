// SPDX-License-Identifier: Apache-2.0
// Test helpers for the synthetic scenes: points grouped by truth cell, components, plane fits, comparisons.
#pragma once

#include <lidarfx/synth/scenes.hpp>

#include "reference/components.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <span>
#include <utility>
#include <vector>

namespace synth_test {

using namespace lidarfx;
using namespace lidarfx::synth;

/// Indices of the points in each cell of a grid (compressed rows: cell k holds index[start[k]..start[k+1])).
struct cell_points {
    grid g;
    std::vector<std::size_t> start, index;

    std::span<const std::size_t> at(std::ptrdiff_t r, std::ptrdiff_t c) const
    {
        const auto k = static_cast<std::size_t>(r * g.cols + c);
        return {index.data() + start[k], start[k + 1] - start[k]};
    }
    std::size_t count(std::ptrdiff_t r, std::ptrdiff_t c) const { return at(r, c).size(); }
};

inline cell_points group_by_cell(const point_set& p, const grid& g)
{
    cell_points out{g, std::vector<std::size_t>(static_cast<std::size_t>(g.size()) + 1, 0), {}};
    std::vector<std::size_t> cell_of(p.size(), static_cast<std::size_t>(-1));
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (const auto c = g.cell_of(p.x[i], p.y[i])) {
            cell_of[i] = static_cast<std::size_t>(c->row * g.cols + c->col);
            ++out.start[cell_of[i] + 1];
        }
    }
    for (std::size_t k = 1; k < out.start.size(); ++k) out.start[k] += out.start[k - 1];
    out.index.resize(out.start.back());
    std::vector<std::size_t> fill(out.start.begin(), out.start.end() - 1);
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (cell_of[i] != static_cast<std::size_t>(-1)) out.index[fill[cell_of[i]]++] = i;
    }
    return out;
}

/// A scene with its points grouped by truth cell, built once per test file.
struct indexed_scene {
    scene s;
    cell_points cells;
};

inline indexed_scene indexed(scene s)
{
    auto cells = group_by_cell(s.points, s.truth.g);
    return {std::move(s), std::move(cells)};
}

/// The scene `make()` returns, indexed, built on first use and kept: each lambda type has its own.
template <class Make>
const indexed_scene& once(Make make)
{
    static const indexed_scene kept = indexed(make());
    return kept;
}

/// 8-connected components of the cells where mask != 0 (plain breadth-first reference): labels from 1,
/// sizes[label], sizes[0] = background cells.
inline components components8(const raster<std::uint8_t>& mask)
{
    return reference::flood_label(mask, connectivity::eight);
}

/// Size of the largest component (0 when there is none).
inline std::size_t largest(const components& parts)
{
    return parts.sizes.size() < 2 ? 0 : *std::max_element(parts.sizes.begin() + 1, parts.sizes.end());
}

/// True when every cell of the 3x3 block around (r, c) is inside the raster and satisfies pred(r, c).
template <class Pred>
bool block_all(std::ptrdiff_t rows, std::ptrdiff_t cols, std::ptrdiff_t r, std::ptrdiff_t c, Pred&& pred)
{
    if (r < 1 || c < 1 || r + 1 >= rows || c + 1 >= cols) return false;
    for (std::ptrdiff_t dr = -1; dr <= 1; ++dr) {
        for (std::ptrdiff_t dc = -1; dc <= 1; ++dc) {
            if (!pred(r + dr, c + dc)) return false;
        }
    }
    return true;
}

/// Bitwise equality of rasters (NaN cells equal when their bits are).
template <class T>
bool same_bits(const raster<T>& a, const raster<T>& b)
{
    return a.rows() == b.rows() && a.cols() == b.cols() &&
           std::memcmp(a.data(), b.data(), static_cast<std::size_t>(a.size()) * sizeof(T)) == 0;
}

inline bool same_planes(const std::vector<roof_plane_truth>& a, const std::vector<roof_plane_truth>& b)
{
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        if (a[i].building_id != b[i].building_id || a[i].tilt_deg != b[i].tilt_deg ||
            a[i].azimuth_deg != b[i].azimuth_deg || a[i].area_m2 != b[i].area_m2)
            return false;
    }
    return true;
}

inline bool same_truth(const scene_truth& a, const scene_truth& b)
{
    return a.g == b.g && same_bits(a.water, b.water) && same_bits(a.water_filled, b.water_filled) &&
           same_bits(a.building_id, b.building_id) && same_bits(a.roof_plane_id, b.roof_plane_id) &&
           same_bits(a.ground_z, b.ground_z) && same_bits(a.water_z, b.water_z) && same_bits(a.surface, b.surface) &&
           same_planes(a.roof_planes, b.roof_planes) && a.footprints == b.footprints && a.islands == b.islands;
}

/// Least-squares plane z = z0 + b (x - x0) + c (y - y0): tilt and down-slope azimuth (clockwise from north).
struct plane_fit {
    double tilt_deg = 0, azimuth_deg = 0;
    std::size_t n = 0;
};

inline plane_fit fit_plane(const std::vector<std::array<double, 3>>& pts)
{
    plane_fit fit;
    fit.n = pts.size();
    if (pts.size() < 3) return fit;
    double mx = 0, my = 0, mz = 0;
    for (const auto& p : pts) mx += p[0], my += p[1], mz += p[2];
    const auto n = static_cast<double>(pts.size());
    mx /= n, my /= n, mz /= n;
    double sxx = 0, sxy = 0, syy = 0, sxz = 0, syz = 0;
    for (const auto& p : pts) {
        const double dx = p[0] - mx, dy = p[1] - my, dz = p[2] - mz;
        sxx += dx * dx, sxy += dx * dy, syy += dy * dy, sxz += dx * dz, syz += dy * dz;
    }
    const double det = sxx * syy - sxy * sxy;
    const double b = (sxz * syy - syz * sxy) / det, c = (syz * sxx - sxz * sxy) / det;
    fit.tilt_deg = rad_to_deg(std::atan(std::hypot(b, c)));
    fit.azimuth_deg = std::fmod(rad_to_deg(std::atan2(-b, -c)) + 360.0, 360.0);
    return fit;
}

/// Smallest absolute difference of two angles, degrees (0..180).
inline double angle_difference(double a, double b)
{
    const double d = std::fmod(std::abs(a - b), 360.0);
    return d > 180.0 ? 360.0 - d : d;
}

/// Even-odd point-in-polygon test on a closed ring.
inline bool inside_ring(const std::vector<std::array<double, 2>>& ring, double x, double y)
{
    bool inside = false;
    for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
        const auto& a = ring[i];
        const auto& b = ring[j];
        if ((a[1] > y) != (b[1] > y) && x < (b[0] - a[0]) * (y - a[1]) / (b[1] - a[1]) + a[0]) inside = !inside;
    }
    return inside;
}

}  // namespace synth_test
