// SPDX-License-Identifier: Apache-2.0
// town_family: randomized synthetic towns from one seed (sizes, densities, roof kinds, tilts, orientations,
// trees beside roofs), with their truth, for testing building extraction on many towns.
#pragma once

#include <algorithm>
#include <cmath>
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
};

/// A family town with the density it was scanned at.
struct town_family_scene {
    scene town;                 ///< points and truth (building_id, roof_plane_id, roof_planes, footprints, surface)
    double density_per_m2 = 0;  ///< pulses per m^2 drawn for this town
    std::vector<tree> trees;    ///< the trees (crowns), for per-tree checks
};

/// A randomized town: gently rolling ground (2 m relief) without roads; 0.8-1.2 buildings per 1000 m^2 of
/// 8-18 m width, 1-2.2 times as long (at most 40 m), any orientation (uniform in [0, 180) deg), flat, shed,
/// gable or hip roofs (a quarter each; the first four take one kind each), tilts uniform in 5-55 deg, walls
/// 3-12 m, at least 3 m apart; trees (crown radius 2-5 m, 6-18 m tall) beside 60 % of the buildings with
/// crowns 0.5-4 m from the footprint's bounding circle, and scattered in the open. Deterministic from the
/// seed. @throws invalid_input on bad options (see scene_options).
inline town_family_scene town_family(const town_family_options& options = {})
{
    lidarfx::detail::require(options.min_density > 0 && options.min_density <= options.max_density, "town_family",
                             "densities must satisfy 0 < min_density <= max_density");
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
    return {internal::render(w, so), so.density_per_m2, w.trees};
}

}  // namespace lidarfx::synth
