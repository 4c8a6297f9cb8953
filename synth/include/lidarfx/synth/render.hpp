// SPDX-License-Identifier: Apache-2.0
// Turns a synthetic world (ground, water, trees, buildings, bridges) into scanned points and truth rasters.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "lidarfx/core/grid.hpp"
#include "lidarfx/core/las_class.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/synth/bucket_index.hpp"
#include "lidarfx/synth/noise.hpp"
#include "lidarfx/synth/point_set.hpp"
#include "lidarfx/synth/random.hpp"
#include "lidarfx/synth/roads.hpp"
#include "lidarfx/synth/roofs.hpp"
#include "lidarfx/synth/scan.hpp"
#include "lidarfx/synth/trees.hpp"
#include "lidarfx/synth/water.hpp"

namespace lidarfx::synth {

/// Holes in water smaller than this (m^2) count as water in scene_truth::water_filled, as the waterbody
/// method fills them (fill_small_islands, docs/waterbodies.md).
inline constexpr double island_fill_area_m2 = 200.0;

/// The truth of a synthetic scene, sampled at the centres of the cells of `g`.
struct scene_truth {
    grid g;                                     ///< truth grid: x0 = 0, y0 = size rounded up to whole cells
    raster<std::uint8_t> water;                 ///< 1 = water surface (islands of any size are 0; water under a
                                                ///< bridge deck is 1)
    raster<std::uint8_t> water_filled;          ///< water plus islands smaller than island_fill_area_m2
    raster<std::int32_t> building_id;           ///< footprint holding the cell centre, 1-based; 0 = none
    raster<std::int32_t> roof_plane_id;         ///< 1 + index into roof_planes of the face above the centre; 0 = none
                                                ///< (and 0 on a dormer, building_truth::dormers)
    raster<float> ground_z;                     ///< bare-earth elevation (water level on water), metres
    raster<float> water_z;                      ///< water surface elevation on water cells, NaN elsewhere
    raster<std::uint8_t> surface;               ///< las_class of the topmost surface above the cell centre
    std::vector<roof_plane_truth> roof_planes;  ///< every roof face, grouped by building in id order
    std::vector<std::vector<std::array<double, 2>>> footprints;  ///< per building id-1: closed counter-clockwise
                                                                 ///< ring (GeoJSON exterior), whole even where
                                                                 ///< it reaches past the scene's border
    std::vector<std::array<double, 4>> islands;                  ///< (x, y, radius_m, area_m2) of each island
};

/// Points and truth of a synthetic scene.
struct scene {
    point_set points;
    scene_truth truth;
};

/// What lies at a point beneath trees, buildings and bridges.
struct site_sample {
    double z = 0;                            ///< bare-earth or water surface elevation, metres
    std::uint8_t cover = las_class::ground;  ///< ground, road_surface or water
    std::int32_t water_body = -1;            ///< index of the waterbody, -1 on land
    double island_area_m2 = 0;               ///< area of the island holding the point; 0 if none
    double intensity = 100;                  ///< mean intensity of the land cover (unused on water)
};

namespace internal {

/// A synthetic world: `site(x, y)` gives the site_sample at a point (terrain, water, roads); trees,
/// buildings and bridge decks stand on top.
template <class Site>
struct world {
    double size_m = 640;
    std::uint64_t seed = 1;
    Site site;
    int water_bodies = 0;
    std::vector<tree> trees;
    std::vector<building_truth> buildings;
    std::vector<bridge_deck> bridges;
    std::vector<std::array<double, 4>> islands;
    water_returns water;
    scan_pattern scan;
};

/// Topmost object over a point.
struct top_hit {
    enum kind_t { none, bridge, building, tree } kind = none;
    std::int32_t index = -1;
    double height = 0;        ///< crown top above ground (trees)
    std::int32_t under = -1;  ///< trees: the building whose roof the crown covers here (tree::over_roofs); -1 none
};

/// Finds the object a pulse meets first: bridge decks, then roofs (unless a crown that may reach over roofs stands
/// above it), then the tallest crown.
class top_finder {
public:
    top_finder(double size_m, const std::vector<tree>& trees, const std::vector<building_truth>& buildings,
               const std::vector<bridge_deck>& bridges)
        : trees_(trees),
          buildings_(buildings),
          bridges_(bridges),
          tree_index_(size_m, 12.0),
          building_index_(size_m, 16.0)
    {
        for (std::size_t i = 0; i < trees.size(); ++i) {
            const auto& t = trees[i];
            tree_index_.insert(static_cast<std::int32_t>(i), t.x - t.crown_radius_m, t.y - t.crown_radius_m,
                               t.x + t.crown_radius_m, t.y + t.crown_radius_m);
        }
        for (std::size_t i = 0; i < buildings.size(); ++i) {
            const auto& b = buildings[i];
            const double r = b.bounding_radius();
            building_index_.insert(static_cast<std::int32_t>(i), b.x - r, b.y - r, b.x + r, b.y + r);
        }
    }

    top_hit at(double x, double y) const noexcept
    {
        for (std::size_t i = 0; i < bridges_.size(); ++i) {
            if (bridges_[i].span.contains(x, y)) return {top_hit::bridge, static_cast<std::int32_t>(i), 0};
        }
        for (const auto i : building_index_.at(x, y)) {
            const auto& b = buildings_[static_cast<std::size_t>(i)];
            if (!b.contains(x, y)) continue;
            top_hit over = tallest_crown(x, y, true);
            if (over.kind == top_hit::tree && over_z(over) > b.roof_at(x, y).z) {
                over.under = i;
                return over;
            }
            return {top_hit::building, i, 0};
        }
        return tallest_crown(x, y, false);
    }

private:
    /// The tallest crown over (x, y): all crowns, or only those that may reach over roofs.
    top_hit tallest_crown(double x, double y, bool over_roofs_only) const noexcept
    {
        top_hit best;
        double best_z = -std::numeric_limits<double>::infinity();
        for (const auto i : tree_index_.at(x, y)) {
            const auto& t = trees_[static_cast<std::size_t>(i)];
            if (over_roofs_only && !t.over_roofs) continue;
            const double h = t.crown_top(x, y);
            if (h > 0 && t.ground_z + h > best_z) {
                best_z = t.ground_z + h;
                best = {top_hit::tree, i, h};
            }
        }
        return best;
    }
    /// The elevation of a crown hit's surface.
    double over_z(const top_hit& hit) const noexcept
    {
        return trees_[static_cast<std::size_t>(hit.index)].ground_z + hit.height;
    }

    const std::vector<tree>& trees_;
    const std::vector<building_truth>& buildings_;
    const std::vector<bridge_deck>& bridges_;
    bucket_index tree_index_, building_index_;
};

/// Per-waterbody threshold of the patch field: the (1 - patch_share) quantile of the field over the
/// body, sampled on a fixed 4 m lattice (so the points do not depend on the truth cell size).
template <class Site>
std::vector<double> patch_thresholds(const world<Site>& w, const noise_field& patch)
{
    std::vector<std::vector<double>> values(static_cast<std::size_t>(w.water_bodies));
    const auto n = static_cast<long long>(std::ceil(w.size_m / 4.0));
    for (long long i = 0; i < n; ++i) {
        for (long long j = 0; j < n; ++j) {
            const double x = (static_cast<double>(j) + 0.5) * 4.0, y = (static_cast<double>(i) + 0.5) * 4.0;
            const auto s = w.site(x, y);
            if (s.water_body >= 0) values[static_cast<std::size_t>(s.water_body)].push_back(patch(x, y));
        }
    }
    std::vector<double> thresholds;
    for (auto& v : values) {
        if (v.empty() || w.water.patch_share <= 0) {
            thresholds.push_back(std::numeric_limits<double>::infinity());
            continue;
        }
        const auto k = static_cast<std::size_t>(std::clamp((1.0 - w.water.patch_share) * static_cast<double>(v.size()),
                                                           0.0, static_cast<double>(v.size() - 1)));
        std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
        thresholds.push_back(v[k]);
    }
    return thresholds;
}

/// Scans the world: see scan_square for the pulses and water_returns for what water does with them.
template <class Site>
point_set render_points(const world<Site>& w, double density_per_m2)
{
    constexpr std::uint64_t speck_tag = 0x59EC, patch_tag = 0x9A7C, returns_tag = 0x2E7;
    const top_finder top(w.size_m, w.trees, w.buildings, w.bridges);
    const noise_field patch{hash64(w.seed, patch_tag), w.water.patch_wavelength_m, 3, 0.5};
    const auto thresholds = patch_thresholds(w, patch);
    rng random(w.seed, returns_tag);
    point_set points;
    points.reserve(static_cast<std::size_t>(1.1 * w.size_m * w.size_m * density_per_m2));
    const auto noise = [&] { return 0.05 * random.triangular(); };  // +-5 cm, sd 2 cm

    scan_square(w.size_m, density_per_m2, hash64(w.seed, 0x5CA9), w.scan, [&](const pulse& p) {
        points.pulse_time_s = p.time_s;
        const double speck =
            hash_unit(w.seed, speck_tag,
                      static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(p.x / w.water.speck_cell_m))),
                      static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(p.y / w.water.speck_cell_m))));
        if (speck < w.water.speck_share_land) return;
        const top_hit hit = top.at(p.x, p.y);
        if (hit.kind == top_hit::bridge) {
            const auto& deck = w.bridges[static_cast<std::size_t>(hit.index)];
            points.push(p.x, p.y, deck.z + noise(), deck.intensity * (1.0 + 0.15 * random.triangular()), 1, 1,
                        las_class::bridge_deck);
            return;
        }
        if (hit.kind == top_hit::building) {
            const auto& b = w.buildings[static_cast<std::size_t>(hit.index)];
            points.push(p.x, p.y, b.roof_at(p.x, p.y).z + noise(), b.intensity * (1.0 + 0.1 * random.triangular()), 1,
                        1, las_class::building);
            return;
        }
        if (hit.kind == top_hit::tree && hit.under >= 0) {
            const auto& t = w.trees[static_cast<std::size_t>(hit.index)];
            const auto& b = w.buildings[static_cast<std::size_t>(hit.under)];
            crown_over_roof_returns(t, t.ground_z + hit.height, b.roof_at(p.x, p.y).z, b.intensity, random,
                                    [&](double z, double intensity, int rn, int nr, std::uint8_t cls) {
                                        points.push(p.x, p.y, z + noise(), intensity, rn, nr, cls);
                                    });
            return;
        }
        const site_sample s = w.site(p.x, p.y);
        if (hit.kind == top_hit::tree) {
            tree_returns(w.trees[static_cast<std::size_t>(hit.index)], hit.height, s.z, s.intensity, random,
                         [&](double z, double intensity, int rn, int nr, std::uint8_t cls) {
                             points.push(p.x, p.y, z + noise(), intensity, rn, nr, cls);
                         });
            return;
        }
        if (s.water_body >= 0) {
            if (speck < w.water.speck_share_water) return;
            // A little noise on the field makes patch borders ragged, as on real surveys.
            if (patch(p.x, p.y) + 0.03 * random.triangular() > thresholds[static_cast<std::size_t>(s.water_body)])
                return;
            if (random.chance(w.water.pulse_drop_probability(p.scan_angle_deg, w.scan.max_scan_angle_deg))) return;
            points.push(p.x, p.y, s.z + noise(), w.water.intensity(p.scan_angle_deg, random), 1, 1, las_class::water);
            return;
        }
        points.push(p.x, p.y, s.z + noise(), s.intensity * (1.0 + 0.1 * random.triangular()), 1, 1, s.cover);
    });
    return points;
}

/// Samples the truth rasters at the centres of a grid of `cell_m` cells covering [0, size_m]^2.
template <class Site>
scene_truth render_truth(const world<Site>& w, double cell_m)
{
    const auto n = static_cast<std::ptrdiff_t>(std::max(1.0, std::ceil(w.size_m / cell_m - 1e-9)));
    scene_truth t;
    t.g = grid{0.0, static_cast<double>(n) * cell_m, cell_m, n, n};
    t.water = raster<std::uint8_t>(n, n);
    t.water_filled = raster<std::uint8_t>(n, n);
    t.building_id = raster<std::int32_t>(n, n);
    t.roof_plane_id = raster<std::int32_t>(n, n);
    t.ground_z = raster<float>(n, n);
    t.water_z = raster<float>(n, n, std::numeric_limits<float>::quiet_NaN());
    t.surface = raster<std::uint8_t>(n, n);
    std::vector<std::int32_t> first_plane;
    for (const auto& b : w.buildings) {
        first_plane.push_back(static_cast<std::int32_t>(t.roof_planes.size()));
        const auto planes = b.planes();
        t.roof_planes.insert(t.roof_planes.end(), planes.begin(), planes.end());
        t.footprints.push_back(b.footprint());
    }
    t.islands = w.islands;
    const top_finder top(w.size_m, w.trees, w.buildings, w.bridges);
    for (std::ptrdiff_t r = 0; r < n; ++r) {
        for (std::ptrdiff_t c = 0; c < n; ++c) {
            const auto [x, y] = t.g.center(r, c);
            const site_sample s = w.site(x, y);
            const bool is_water = s.water_body >= 0;
            t.water(r, c) = is_water ? 1 : 0;
            t.water_filled(r, c) = is_water || (s.island_area_m2 > 0 && s.island_area_m2 < island_fill_area_m2);
            t.ground_z(r, c) = static_cast<float>(s.z);
            if (is_water) t.water_z(r, c) = static_cast<float>(s.z);
            t.surface(r, c) = s.cover;
            const top_hit hit = top.at(x, y);
            if (hit.kind == top_hit::bridge) t.surface(r, c) = las_class::bridge_deck;
            if (hit.kind == top_hit::tree) t.surface(r, c) = las_class::high_vegetation;
            if (hit.kind == top_hit::building || hit.under >= 0) {  // a roof, or a roof under a crown
                const auto i = static_cast<std::size_t>(hit.kind == top_hit::building ? hit.index : hit.under);
                if (hit.kind == top_hit::building) t.surface(r, c) = las_class::building;
                t.building_id(r, c) = w.buildings[i].id;
                const int face = w.buildings[i].roof_at(x, y).face;  // -1 on a dormer: no plane
                t.roof_plane_id(r, c) = face < 0 ? 0 : first_plane[i] + face + 1;
            }
        }
    }
    return t;
}

}  // namespace internal
/// Cells of a tree's visible crown (crown_top > 0 at the cell centre, outside every truth building of `t`) that
/// `found` marks as building (found != 0): a tree counts as reported as a building when they cover >= 2 m^2.
inline std::size_t crown_cells_in_buildings(const tree& tr, const scene_truth& t, const raster<std::int32_t>& found)
{
    const grid& g = t.g;
    const auto r0 =
        std::max<std::ptrdiff_t>(0, static_cast<std::ptrdiff_t>((g.y0 - tr.y - tr.crown_radius_m) / g.cell));
    const auto r1 =
        std::min<std::ptrdiff_t>(g.rows - 1, static_cast<std::ptrdiff_t>((g.y0 - tr.y + tr.crown_radius_m) / g.cell));
    const auto c0 =
        std::max<std::ptrdiff_t>(0, static_cast<std::ptrdiff_t>((tr.x - tr.crown_radius_m - g.x0) / g.cell));
    const auto c1 =
        std::min<std::ptrdiff_t>(g.cols - 1, static_cast<std::ptrdiff_t>((tr.x + tr.crown_radius_m - g.x0) / g.cell));
    std::size_t in_building = 0;
    for (std::ptrdiff_t r = r0; r <= r1; ++r) {
        for (std::ptrdiff_t c = c0; c <= c1; ++c) {
            const auto [x, y] = g.center(r, c);
            if (tr.crown_top(x, y) <= 0 || t.building_id(r, c) != 0) continue;
            in_building += found(r, c) != 0 ? 1 : 0;
        }
    }
    return in_building;
}

}  // namespace lidarfx::synth
