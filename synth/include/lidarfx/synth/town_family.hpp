// SPDX-License-Identifier: Apache-2.0
// town_family: randomized synthetic towns from one seed (sizes, densities, roof kinds, tilts, orientations,
// trees beside roofs, garages and sheds), with their truth, for testing building extraction on many towns.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <vector>

#include "lidarfx/synth/scenes.hpp"

namespace lidarfx::synth {

/// Settings of a family town. Everything else follows from `seed`.
struct town_family_options {
    unsigned seed = 1;          ///< the town
    double size_m = 200;        ///< side of the square town, metres, > 0
    double truth_cell_m = 0.5;  ///< cell of the truth rasters, metres, > 0
    double min_density = 1.0;   ///< pulses per m^2 are drawn uniformly in [min_density, max_density]
    double max_density = 8.0;
    /// Garages and sheds (20-42 m^2 footprints, 2.6-3.0 m eaves, flat, shed, gable or hip roofs) per house: the
    /// town gets round(houses x this) of them, >= 0; 0 = none.
    double small_buildings_per_house = 0.15;
};

/// A family town with the density it was scanned at.
struct town_family_scene {
    scene town;                 ///< points and truth (building_id, roof_plane_id, roof_planes, footprints, surface)
    double density_per_m2 = 0;  ///< pulses per m^2 drawn for this town
    std::vector<tree> trees;    ///< the trees (crowns), for per-tree checks
};

/// A randomized town: gently rolling ground (2 m relief) without roads; houses (0.4-0.6 per 1000 m^2) of
/// 8-18 m width, 1-2.2 times as long (at most 40 m), any orientation (uniform in [0, 180) deg), flat, shed,
/// gable or hip roofs (a quarter each; the first four take one kind each), tilts uniform in 5-55 deg, walls
/// 3-12 m, at least 3 m apart; trees (crown radius 2-5 m, 6-18 m tall) beside 60 % of the houses with
/// crowns 0.5-4 m from the footprint's bounding circle, and scattered in the open; then
/// small_buildings_per_house garages and sheds per house (internal::add_small_buildings), beside the houses
/// or in the open, clear of houses and crowns. Deterministic from the seed; the garages draw from their own
/// random stream, so the houses and trees are those of the town without them (their points' noise differs).
/// Houses are ids 1..n, garages and sheds follow. @throws invalid_input on bad options (see scene_options).
inline town_family_scene town_family(const town_family_options& options = {});

namespace internal {

/// Where a small building may stand: inside the town with a 4 m margin, its bounding circle `gap_m` from every
/// building's (but `beside`, whose gap was drawn) and 0.4 m from every crown.
inline bool small_building_fits(const building_truth& b, const std::vector<building_truth>& buildings,
                                const std::vector<tree>& trees, double size_m, const building_truth* beside,
                                double gap_m)
{
    const double r = b.bounding_radius();
    if (b.x < r + 4 || b.y < r + 4 || b.x > size_m - r - 4 || b.y > size_m - r - 4) return false;
    const bool clear_of_buildings = std::all_of(buildings.begin(), buildings.end(), [&](const building_truth& o) {
        return &o == beside || std::hypot(o.x - b.x, o.y - b.y) > o.bounding_radius() + r + gap_m;
    });
    return clear_of_buildings && std::all_of(trees.begin(), trees.end(), [&](const tree& t) {
               return std::hypot(t.x - b.x, t.y - b.y) > t.crown_radius_m + r + 0.4;
           });
}

/// Adds `count` garages and sheds to w (after its houses and trees, which they avoid): footprints 4-6 m x
/// 5-7 m (20-42 m^2), eaves 2.6-3.0 m above the ground at their centre; flat roofs (30 %), sheds tilted
/// 5-20 deg (20 %), gables (35 %) and hips (15 %) tilted 20-45 deg: faces 2-3 m deep, hip ends down to about
/// 4 m^2. 70 % stand beside a random house, parallel to it, their bounding circle 2-5 m from the house's; the
/// rest anywhere in the open, any orientation. Every one keeps its bounding circle 2 m from the other
/// buildings' and 0.4 m from every crown; up to 200 tries each (a crowded town gets fewer). Draws only from
/// `random`.
template <class Site>
void add_small_buildings(world<Site>& w, rng& random, int count)
{
    const std::size_t houses = w.buildings.size();
    for (int k = 0; k < count; ++k) {
        for (int attempt = 0; attempt < 200; ++attempt) {
            building_truth b;
            b.width_m = random.uniform(4.0, 6.0);
            b.length_m = std::max(b.width_m, random.uniform(5.0, 7.0));
            const double kind = random.uniform(0.0, 1.0);
            b.kind = kind < 0.3    ? roof_kind_truth::flat
                     : kind < 0.5  ? roof_kind_truth::shed
                     : kind < 0.85 ? roof_kind_truth::gable
                                   : roof_kind_truth::hip;
            b.tilt_deg = b.kind == roof_kind_truth::flat   ? 0.0
                         : b.kind == roof_kind_truth::shed ? random.uniform(5.0, 20.0)
                                                           : random.uniform(20.0, 45.0);
            b.shed_facing = random.between(0, 3);
            b.intensity = random.uniform(40.0, 110.0);
            const double eave_m = random.uniform(2.6, 3.0);
            const building_truth* beside = nullptr;
            if (houses > 0 && random.chance(0.7)) {
                beside = &w.buildings[static_cast<std::size_t>(random.between(0, static_cast<int>(houses) - 1))];
                const double angle = random.uniform(0.0, 2 * std::numbers::pi);
                const double distance = beside->bounding_radius() + b.bounding_radius() + random.uniform(2.0, 5.0);
                b.x = beside->x + distance * std::sin(angle);
                b.y = beside->y + distance * std::cos(angle);
                b.axis_azimuth_deg = beside->axis_azimuth_deg;
            } else {
                b.x = random.uniform(0.0, w.size_m);
                b.y = random.uniform(0.0, w.size_m);
                b.axis_azimuth_deg = random.uniform(0.0, 180.0);
            }
            if (!small_building_fits(b, w.buildings, w.trees, w.size_m, beside, 2.0)) continue;
            b.id = static_cast<std::int32_t>(w.buildings.size()) + 1;
            b.eave_z = w.site.terrain(b.x, b.y) + eave_m;
            w.buildings.push_back(b);
            break;
        }
    }
}

}  // namespace internal

inline town_family_scene town_family(const town_family_options& options)
{
    lidarfx::detail::require(options.min_density > 0 && options.min_density <= options.max_density, "town_family",
                             "densities must satisfy 0 < min_density <= max_density");
    lidarfx::detail::require(options.small_buildings_per_house >= 0 && options.small_buildings_per_house < 1e6,
                             "town_family", "small_buildings_per_house must be finite and >= 0");
    rng pick(hash64(options.seed, 0xFA31), 1);
    scene_options so;
    so.seed = options.seed;
    so.size_m = options.size_m;
    so.truth_cell_m = options.truth_cell_m;
    so.density_per_m2 = pick.uniform(options.min_density, options.max_density);
    auto w = internal::new_world<internal::town_site>(so, "town_family", 0xFA31, 250.0);
    const double S = w.size_m;
    rng random(w.seed, 10);
    const auto target = static_cast<int>(std::lround(S * S / 1000.0 * random.uniform(0.8, 1.2) * 0.5));
    for (int attempt = 0; attempt < 400 * std::max(1, target) && static_cast<int>(w.buildings.size()) < target;
         ++attempt) {
        building_truth b;
        b.width_m = random.uniform(8.0, 18.0);
        b.length_m = std::min(40.0, b.width_m * random.uniform(1.0, 2.2));
        b.axis_azimuth_deg = random.uniform(0.0, 180.0);
        const auto kind = w.buildings.size() < 4 ? static_cast<int>(w.buildings.size()) : random.between(0, 3);
        b.kind = static_cast<roof_kind_truth>(kind);
        b.tilt_deg = b.kind == roof_kind_truth::flat ? 0.0 : random.uniform(5.0, 55.0);
        b.shed_facing = random.between(0, 3);
        b.intensity = random.uniform(40.0, 110.0);
        const double r = b.bounding_radius();
        b.x = random.uniform(r + 4, S - r - 4);
        b.y = random.uniform(r + 4, S - r - 4);
        if (S - 2 * r - 8 <= 0) continue;
        const bool clear = std::all_of(w.buildings.begin(), w.buildings.end(), [&](const building_truth& o) {
            return std::hypot(o.x - b.x, o.y - b.y) > o.bounding_radius() + r + 3;
        });
        if (!clear) continue;
        b.id = static_cast<std::int32_t>(w.buildings.size()) + 1;
        b.eave_z = w.site.terrain(b.x, b.y) + random.uniform(3.0, 12.0);
        w.buildings.push_back(b);
    }
    const auto tree_fits = [&](double x, double y, double rc) {
        if (x < 0 || y < 0 || x > S || y > S) return false;
        return std::all_of(w.buildings.begin(), w.buildings.end(), [&](const building_truth& o) {
            return std::hypot(o.x - x, o.y - y) > o.bounding_radius() + rc + 0.4;
        });
    };
    rng tree_random(w.seed, 11);
    const tree_size sizes{.min_radius_m = 2.0, .max_radius_m = 5.0, .min_height_m = 6.0, .max_height_m = 18.0};
    const auto beside = internal::trees_beside_buildings(w.buildings, tree_random, sizes, 0.6, 0.5, 4.0, tree_fits,
                                                         [&](double x, double y) { return w.site(x, y).z; });
    w.trees.insert(w.trees.end(), beside.begin(), beside.end());
    const auto park = internal::site_trees(
        w, tree_random, 12.0, sizes, [&](double x, double y, double rc) { return tree_fits(x, y, rc) ? 0.15 : 0.0; });
    w.trees.insert(w.trees.end(), park.begin(), park.end());
    rng small_random(w.seed, 12);
    const auto houses = static_cast<double>(w.buildings.size());
    internal::add_small_buildings(w, small_random,
                                  static_cast<int>(std::lround(houses * options.small_buildings_per_house)));
    return {internal::render(w, so), so.density_per_m2, w.trees};
}

}  // namespace lidarfx::synth
