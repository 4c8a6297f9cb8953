// SPDX-License-Identifier: Apache-2.0
// Randomized roof towns for rooftop PV tests: DSM, DTM and building-id rasters rendered directly from flat,
// shed, gable, hip and L-shaped roofs (any orientation, tilts 5-55 degrees) with dormers, chimneys and trees,
// and the truth of every roof plane.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/grid.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/synth/random.hpp"
#include "lidarfx/synth/roofs.hpp"

namespace lidarfx::synth {

/// Settings of roof_town. Distances in metres.
struct roof_town_options {
    std::uint64_t seed = 1;       ///< every random choice follows from it
    int buildings = 36;           ///< number of buildings, placed one per cell of a square lattice
    double spacing_m = 40.0;      ///< lattice pitch (>= 36: no two buildings or their trees touch)
    double cell_m = 1.0;          ///< raster cell size
    double density_per_m2 = 0.0;  ///< laser points per m^2; 0 = drawn per town in [1, 8]
    double noise_m = 0.05;        ///< standard deviation of the elevation noise per cell
    double tree_share = 0.35;     ///< share of buildings with a tree beside or over the roof
    double clutter_share = 0.6;   ///< share of pitched roofs with a dormer and/or a chimney
};

/// Roof kinds of the family (L-shaped = two gable wings meeting at a right angle, one valley between them).
enum class roof_town_kind : std::uint8_t { flat, shed, gable, hip, l_shaped };

/// One true roof plane: the part of a wing's face seen from above, dormers and chimneys taken out.
struct roof_town_plane {
    std::int32_t building_id = 0;
    std::int32_t plane_id = 0;  ///< 1.. over the town, as in roof_town::plane_id
    double tilt_deg = 0;        ///< 0 horizontal
    double azimuth_deg = 0;     ///< facing (down-slope) azimuth, clockwise from north; 0 for flat planes
    double area_m2 = 0;         ///< horizontal visible area (0.25 m supersampling)
    double sloped_area_m2 = 0;  ///< area_m2 / cos(tilt)
};

/// One building of the town.
struct roof_town_building {
    std::int32_t id = 0;
    roof_town_kind kind = roof_town_kind::gable;
    std::vector<building_truth> wings;  ///< one rectangle, or two for L-shaped roofs
    std::size_t cells = 0;              ///< cells of the building-id raster
    int dormers = 0, chimneys = 0, trees = 0;
};

/// A rendered town: rasters on `g` and the truth.
struct roof_town {
    grid g;
    raster<float> dsm;                 ///< highest of the laser samples of each cell plus noise
    raster<float> dtm;                 ///< the bare ground (exact)
    raster<std::int32_t> building_id;  ///< cell-centre rule on the wings' footprints; 0 outside
    raster<std::int32_t> plane_id;     ///< true plane at the cell centre; 0 outside, on dormers and chimneys
    std::vector<roof_town_plane> planes;
    std::vector<roof_town_building> buildings;
    double density_per_m2 = 0;
};

namespace detail_roof_town {

/// A box standing on a roof (dormer or chimney) in the local frame of a wing: |u - u0| <= hu, |v - v0| <= hv,
/// flat top at `top_z`.
struct roof_box {
    int wing = 0;
    double u0 = 0, v0 = 0, hu = 0, hv = 0, top_z = 0;
};

/// A tree: paraboloid crown of radius r whose top stands at top_z.
struct tree {
    double x = 0, y = 0, r = 0, top_z = 0, crown_depth = 0;
    double z_at(double px, double py) const noexcept
    {
        const double d2 = ((px - x) * (px - x) + (py - y) * (py - y)) / (r * r);
        return d2 >= 1 ? -1e30 : top_z - crown_depth * d2;
    }
};

struct house {
    roof_town_building b;
    std::vector<roof_box> boxes;
    std::vector<tree> trees;
    std::vector<std::int32_t> plane_of_face;  ///< wing * 4 + face -> plane id (0 = none yet)
};

/// Roof surface of a house at (x, y): elevation and face key (wing * 4 + face, -1 on a box, -2 outside).
struct hit {
    double z;
    int key;
};

inline hit roof_of(const house& h, double x, double y) noexcept
{
    hit best{-1e30, -2};
    for (std::size_t w = 0; w < h.b.wings.size(); ++w) {
        const building_truth& wing = h.b.wings[w];
        if (!wing.contains(x, y)) continue;
        const auto r = wing.roof_at(x, y);
        if (r.z > best.z) best = {r.z, static_cast<int>(w) * 4 + r.face};
    }
    if (best.key == -2) return best;
    for (const roof_box& box : h.boxes) {
        const auto [u, v] = h.b.wings[static_cast<std::size_t>(box.wing)].local(x, y);
        if (std::abs(u - box.u0) <= box.hu && std::abs(v - box.v0) <= box.hv && box.top_z > best.z)
            best = {box.top_z, -1};
    }
    return best;
}

inline double ground_z(double x, double y) noexcept
{
    return 50.0 + 0.01 * x - 0.006 * y;
}

inline double gaussian(rng& g) noexcept
{
    const double u1 = std::max(g.uniform(), 1e-300), u2 = g.uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * 3.14159265358979323846 * u2);
}

/// A random house centred at (cx, cy).
inline house make_house(rng& g, std::int32_t id, double cx, double cy, const roof_town_options& o)
{
    house h;
    h.b.id = id;
    const double kind_draw = g.uniform();
    h.b.kind = kind_draw < 0.15   ? roof_town_kind::flat
               : kind_draw < 0.33 ? roof_town_kind::shed
               : kind_draw < 0.63 ? roof_town_kind::gable
               : kind_draw < 0.83 ? roof_town_kind::hip
                                  : roof_town_kind::l_shaped;
    const double ground = ground_z(cx, cy);
    building_truth w;
    w.id = id;
    w.x = cx;
    w.y = cy;
    w.axis_azimuth_deg = g.uniform(0.0, 360.0);
    w.width_m = g.uniform(8.0, 13.0);
    w.length_m = std::min(24.0, w.width_m * g.uniform(1.05, 1.9));
    w.tilt_deg = g.uniform(5.0, 55.0);
    w.eave_z = ground + g.uniform(3.0, 10.0);
    w.shed_facing = g.between(0, 3);
    switch (h.b.kind) {
        case roof_town_kind::flat:
            w.kind = roof_kind_truth::flat;
            w.tilt_deg = 0;
            break;
        case roof_town_kind::shed:
            w.kind = roof_kind_truth::shed;
            break;
        case roof_town_kind::gable:
            w.kind = roof_kind_truth::gable;
            break;
        case roof_town_kind::hip:
            w.kind = roof_kind_truth::hip;
            break;
        case roof_town_kind::l_shaped:
            w.kind = roof_kind_truth::gable;
            break;
    }
    if (h.b.kind == roof_town_kind::hip) w.tilt_deg = g.uniform(15.0, 55.0);  // a 5-degree hip is not built
    h.b.wings.push_back(w);
    if (h.b.kind == roof_town_kind::l_shaped) {
        // Wing B spans u in [L/2 - w, L/2] and v in [0, w/2 + ext] of wing A: its ridge meets A's ridge, its
        // faces meet A's +v face in a valley (inner corner) and a hip (outer corner).
        building_truth& a = h.b.wings[0];
        a.length_m = g.uniform(14.0, 22.0);
        a.width_m = g.uniform(8.0, 11.0);
        a.tilt_deg = g.uniform(15.0, 55.0);
        const double ext = g.uniform(6.0, 10.0);
        building_truth b = a;
        b.length_m = 0.5 * a.width_m + ext;
        b.axis_azimuth_deg = std::fmod(a.axis_azimuth_deg + 90.0, 360.0);
        const double uc = 0.5 * a.length_m - 0.5 * a.width_m, vc = 0.5 * b.length_m;
        const double ar = deg_to_rad(a.axis_azimuth_deg);
        // u unit (sin, cos), v unit (cos, -sin) in (x east, y north); the L is then centred on the lattice cell.
        b.x = a.x + uc * std::sin(ar) + vc * std::cos(ar);
        b.y = a.y + uc * std::cos(ar) - vc * std::sin(ar);
        const double sx = -0.5 * uc * std::sin(ar) - 0.5 * vc * std::cos(ar),
                     sy = -0.5 * uc * std::cos(ar) + 0.5 * vc * std::sin(ar);
        a.x += sx;
        a.y += sy;
        b.x += sx;
        b.y += sy;
        h.b.wings.push_back(b);
    }
    // Clutter on pitched roofs: a chimney near the ridge and/or a dormer on one face.
    if (h.b.kind != roof_town_kind::flat && g.chance(o.clutter_share)) {
        const building_truth& a = h.b.wings[0];
        const double slope = std::tan(deg_to_rad(a.tilt_deg));
        if (g.chance(0.7)) {
            roof_box c;
            c.u0 = g.uniform(-0.3, 0.3) * a.length_m;
            c.v0 = g.uniform(-0.15, 0.15) * a.width_m;
            c.hu = c.hv = g.uniform(0.3, 0.5);
            c.top_z = a.eave_z + slope * 0.5 * a.width_m + g.uniform(0.8, 1.6);
            h.boxes.push_back(c);
            ++h.b.chimneys;
        }
        if (a.kind != roof_kind_truth::shed && a.width_m >= 9 && a.tilt_deg >= 25 && g.chance(0.6)) {
            roof_box d;
            const double side = g.chance(0.5) ? 1.0 : -1.0;
            d.u0 = g.uniform(-0.2, 0.2) * a.length_m;
            d.v0 = side * 0.25 * a.width_m;
            d.hu = g.uniform(0.9, 1.3);
            d.hv = g.uniform(0.7, 1.0);
            d.top_z = a.eave_z + slope * (0.5 * a.width_m - std::abs(d.v0) + d.hv) + 0.15;
            h.boxes.push_back(d);
            ++h.b.dormers;
        }
    }
    // A tree beside the house whose crown may reach over the roof edge.
    if (g.chance(o.tree_share)) {
        const building_truth& a = h.b.wings[0];
        tree t;
        t.r = g.uniform(2.0, 4.0);
        const double side = g.chance(0.5) ? 1.0 : -1.0;
        const double u = g.uniform(-0.4, 0.4) * a.length_m, v = side * (0.5 * a.width_m + t.r * g.uniform(0.5, 1.1));
        const double ar = deg_to_rad(a.axis_azimuth_deg);
        t.x = a.x + u * std::sin(ar) + v * std::cos(ar);
        t.y = a.y + u * std::cos(ar) - v * std::sin(ar);
        t.top_z = a.eave_z + g.uniform(-1.0, 5.0);
        t.crown_depth = t.r * g.uniform(0.8, 1.4);
        h.trees.push_back(t);
        ++h.b.trees;
    }
    return h;
}

}  // namespace detail_roof_town

/// A randomized town of `buildings` houses on a jittered square lattice, rendered on a north-up grid of
/// cell_m cells: each cell gets n = max(1, Poisson(density)) laser samples at hashed positions inside it, the
/// DSM is the highest sample (ground, roof, dormer, chimney or tree crown) plus Gaussian noise, the DTM the
/// exact ground. Roof kinds: flat 15 %, shed 18 %, gable 30 %, hip 20 %, L-shaped 17 %; axes at any
/// azimuth; tilts 5-55 degrees (hip and L 15-55); eaves 3-10 m above ground. Truth: the building-id and
/// plane-id rasters (cell-centre rule) and every plane's tilt, facing azimuth and visible area.
/// @throws invalid_input on a non-positive count, spacing below 36 m, or cell_m not in (0, 4].
inline roof_town make_roof_town(const roof_town_options& o = {})
{
    constexpr const char* fn = "make_roof_town";
    lidarfx::detail::require(o.buildings > 0, fn, "buildings", "> 0", o.buildings);
    lidarfx::detail::require(o.spacing_m >= 36.0, fn, "spacing_m", ">= 36", o.spacing_m);
    lidarfx::detail::require(o.cell_m > 0 && o.cell_m <= 4.0, fn, "cell_m", "in (0, 4]", o.cell_m);
    using namespace detail_roof_town;
    rng g(o.seed, 0x200F);
    roof_town t;
    t.density_per_m2 = o.density_per_m2 > 0 ? o.density_per_m2 : g.uniform(1.0, 8.0);
    const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(o.buildings))));
    const double extent = side * o.spacing_m;
    const auto n = static_cast<std::ptrdiff_t>(std::ceil(extent / o.cell_m));
    t.g = grid{0.0, extent, o.cell_m, n, n};
    t.dsm = raster<float>(n, n);
    t.dtm = raster<float>(n, n);
    t.building_id = raster<std::int32_t>(n, n, 0);
    t.plane_id = raster<std::int32_t>(n, n, 0);
    std::vector<house> houses;
    for (int k = 0; k < o.buildings; ++k) {
        const double cx = (k % side + 0.5) * o.spacing_m + g.uniform(-2.0, 2.0);
        const double cy = extent - (k / side + 0.5) * o.spacing_m + g.uniform(-2.0, 2.0);
        houses.push_back(make_house(g, k + 1, cx, cy, o));
    }
    // Samples of cell (r, c): hashed positions, so every object renders the same samples and the DSM is the
    // maximum over objects of each object's maximum over the samples.
    const double mean_samples = t.density_per_m2 * o.cell_m * o.cell_m;
    const auto sample_count = [&](std::ptrdiff_t r, std::ptrdiff_t c) {
        // Poisson by inversion from one hashed uniform.
        const double u = hash_unit(o.seed, 0x5A11, static_cast<std::uint64_t>(r), static_cast<std::uint64_t>(c));
        double p = std::exp(-mean_samples), cdf = p;
        int k = 0;
        while (u > cdf && k < 64) {
            ++k;
            p *= mean_samples / k;
            cdf += p;
        }
        return std::max(1, k);
    };
    const auto sample_at = [&](std::ptrdiff_t r, std::ptrdiff_t c, int s) {
        const double ux =
            hash_unit(o.seed, 0x5A12, static_cast<std::uint64_t>(r * n + c), static_cast<std::uint64_t>(s));
        const double uy =
            hash_unit(o.seed, 0x5A13, static_cast<std::uint64_t>(r * n + c), static_cast<std::uint64_t>(s));
        return std::array<double, 2>{t.g.x0 + (static_cast<double>(c) + ux) * o.cell_m,
                                     t.g.y0 - (static_cast<double>(r) + uy) * o.cell_m};
    };
    for (std::ptrdiff_t r = 0; r < n; ++r)
        for (std::ptrdiff_t c = 0; c < n; ++c) {
            const auto [x, y] = t.g.center(r, c);
            t.dtm(r, c) = static_cast<float>(ground_z(x, y));
            double top = -1e30;
            const int m = sample_count(r, c);
            for (int s = 0; s < m; ++s) {
                const auto p = sample_at(r, c, s);
                top = std::max(top, ground_z(p[0], p[1]));
            }
            t.dsm(r, c) = static_cast<float>(top);
        }
    std::int32_t next_plane = 1;
    for (house& h : houses) {
        double reach = 0;
        for (const auto& w : h.b.wings)
            reach = std::max(reach, std::hypot(w.x - h.b.wings[0].x, w.y - h.b.wings[0].y) + w.bounding_radius());
        for (const auto& tr : h.trees)
            reach = std::max(reach, std::hypot(tr.x - h.b.wings[0].x, tr.y - h.b.wings[0].y) + tr.r);
        const double cx = h.b.wings[0].x, cy = h.b.wings[0].y;
        const auto r0 = std::max<std::ptrdiff_t>(0, static_cast<std::ptrdiff_t>((t.g.y0 - cy - reach) / o.cell_m) - 1);
        const auto r1 =
            std::min<std::ptrdiff_t>(n - 1, static_cast<std::ptrdiff_t>((t.g.y0 - cy + reach) / o.cell_m) + 1);
        const auto c0 = std::max<std::ptrdiff_t>(0, static_cast<std::ptrdiff_t>((cx - reach - t.g.x0) / o.cell_m) - 1);
        const auto c1 =
            std::min<std::ptrdiff_t>(n - 1, static_cast<std::ptrdiff_t>((cx + reach - t.g.x0) / o.cell_m) + 1);
        h.plane_of_face.assign(h.b.wings.size() * 4, 0);
        for (std::ptrdiff_t r = r0; r <= r1; ++r)
            for (std::ptrdiff_t c = c0; c <= c1; ++c) {
                double top = t.dsm(r, c);
                const int m = sample_count(r, c);
                for (int s = 0; s < m; ++s) {
                    const auto p = sample_at(r, c, s);
                    top = std::max(top, roof_of(h, p[0], p[1]).z);
                    for (const auto& tr : h.trees) top = std::max(top, tr.z_at(p[0], p[1]));
                }
                t.dsm(r, c) = static_cast<float>(top);
                const auto [x, y] = t.g.center(r, c);
                const hit at = roof_of(h, x, y);
                if (at.key == -2) continue;
                t.building_id(r, c) = h.b.id;
                ++h.b.cells;
                if (at.key >= 0) {
                    auto& pid = h.plane_of_face[static_cast<std::size_t>(at.key)];
                    if (pid == 0) pid = next_plane++;
                    t.plane_id(r, c) = pid;
                }
            }
        // Visible area of each face by 0.25 m supersampling of the wings' extent.
        std::vector<double> area(h.plane_of_face.size(), 0.0);
        const double step = 0.25;
        for (double y = cy - reach; y <= cy + reach; y += step)
            for (double x = cx - reach; x <= cx + reach; x += step) {
                const hit at = roof_of(h, x + 0.5 * step, y + 0.5 * step);
                if (at.key >= 0) area[static_cast<std::size_t>(at.key)] += step * step;
            }
        for (std::size_t key = 0; key < area.size(); ++key) {
            if (area[key] <= 0) continue;
            auto& pid = h.plane_of_face[key];
            if (pid == 0) pid = next_plane++;  // a sliver no cell centre hit
            const building_truth& wing = h.b.wings[key / 4];
            const auto faces = wing.planes();
            const roof_plane_truth& face = faces[std::min(key % 4, faces.size() - 1)];
            roof_town_plane p;
            p.building_id = h.b.id;
            p.plane_id = pid;
            p.tilt_deg = face.tilt_deg;
            p.azimuth_deg = face.azimuth_deg;
            p.area_m2 = area[key];
            p.sloped_area_m2 = area[key] / std::cos(deg_to_rad(face.tilt_deg));
            t.planes.push_back(p);
        }
        t.buildings.push_back(h.b);
    }
    std::sort(t.planes.begin(), t.planes.end(), [](const auto& a, const auto& b) { return a.plane_id < b.plane_id; });
    rng noise(o.seed, 0x2011);
    for (std::ptrdiff_t r = 0; r < n; ++r)
        for (std::ptrdiff_t c = 0; c < n; ++c) t.dsm(r, c) += static_cast<float>(o.noise_m * gaussian(noise));
    return t;
}

}  // namespace lidarfx::synth
