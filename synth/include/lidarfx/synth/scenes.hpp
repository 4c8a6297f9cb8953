// SPDX-License-Identifier: Apache-2.0
// Deterministic synthetic airborne LiDAR scenes (lake, river, town) with their truth: the public entry.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/las_class.hpp"
#include "lidarfx/synth/noise.hpp"
#include "lidarfx/synth/point_set.hpp"
#include "lidarfx/synth/random.hpp"
#include "lidarfx/synth/render.hpp"
#include "lidarfx/synth/roads.hpp"
#include "lidarfx/synth/roofs.hpp"
#include "lidarfx/synth/trees.hpp"
#include "lidarfx/synth/water.hpp"

namespace lidarfx::synth {

/// Options shared by every scene.
struct scene_options {
    unsigned seed = 1;            ///< everything in the scene follows from it
    double size_m = 640;          ///< side of the square scene, metres (x and y from 0 to size_m), > 0
    double density_per_m2 = 2.0;  ///< pulses (first returns) per m^2, > 0
    double truth_cell_m = 2.0;    ///< cell of the truth rasters, metres, > 0
};

namespace internal {

inline void validate(const scene_options& o, const char* fn)
{
    lidarfx::detail::require_positive(o.size_m, fn, "size_m");
    lidarfx::detail::require_positive(o.density_per_m2, fn, "density_per_m2");
    lidarfx::detail::require_positive(o.truth_cell_m, fn, "truth_cell_m");
    const double pulses = o.size_m * o.size_m * o.density_per_m2;
    lidarfx::detail::require(pulses <= 1e9, fn, "size_m^2 * density_per_m2", "<= 1e9 pulses", pulses);
    const double cells = std::ceil(o.size_m / o.truth_cell_m) * std::ceil(o.size_m / o.truth_cell_m);
    lidarfx::detail::require(cells <= 2.5e8, fn, "(size_m / truth_cell_m)^2", "<= 2.5e8 truth cells", cells);
}

/// Land-cover intensity: grass, crops and bare soil of 66..164 varying over tens of metres.
inline double cover_intensity(const noise_field& cover, double x, double y)
{
    return std::clamp(115.0 + 110.0 * cover(x, y), 66.0, 164.0);
}

/// Asphalt intensity: 45..75, old and new patches along the road.
inline double road_intensity(const noise_field& cover, double x, double y)
{
    return std::clamp(60.0 + 40.0 * cover(y, x), 45.0, 75.0);
}

/// Shore profile: height of the land above the water level at `d_m` metres from the shoreline.
inline double bank_height(double d_m)
{
    return 0.3 + 0.6 * smoothstep(0.0, 4.0, d_m) + 0.02 * d_m;
}

/// The relief, micro-relief, land-cover and woodland fields every scene's ground uses.
struct ground_fields {
    noise_field relief, micro, cover, woods;
    ground_fields() = default;
    ground_fields(std::uint64_t seed, double relief_wavelength_m)
        : relief{hash64(seed, 1), relief_wavelength_m, 4, 0.45},
          micro{hash64(seed, 2), 12.0, 2, 0.5},
          cover{hash64(seed, 3), 70.0, 3, 0.5},
          woods{hash64(seed, 4), 160.0, 3, 0.5}
    {
    }
};

/// Where trees stand near water: never within crown radius + 1.5 m of the shore (no crown over the water)
/// nor within crown radius + road_gap_m of the road's edge; elsewhere with probability 0.55 within bank_m
/// of the water, `in_woods` where the woods field exceeds `woods_above`, and 0.03 in the open.
struct bank_trees {
    double bank_m = 30, woods_above = 0.2, in_woods = 0.7, road_gap_m = 1;

    double probability(double shore_m, double road_edge_m, double crown_radius_m, double woods) const
    {
        if (shore_m < crown_radius_m + 1.5 || road_edge_m < crown_radius_m + road_gap_m) return 0.0;
        if (shore_m < bank_m) return 0.55;
        return woods > woods_above ? in_woods : 0.03;
    }
};

/// Lake scene ground: rolling terrain bent down to the banks of each lake, flat lakes with islands, a road.
struct lake_site : ground_fields {
    noise_field coves;
    double base_z = 120, relief_m = 30, micro_m = 0.3;
    double coves_m = 5.0;               ///< amplitude of the small-scale shoreline wiggle, metres
    std::array<lake_outline, 2> lakes;  ///< the lake (0) and the pond (1)
    std::array<double, 2> levels{};     ///< water level of each
    std::vector<island_truth> islands;  ///< all in lake 0
    road_strip road;
    static constexpr double bank_m = 50;  ///< width of the band where the terrain bends to a bank

    double terrain(double x, double y) const { return base_z + relief_m * relief(x, y); }

    /// Terrain bent to the lake banks (no micro relief), given the shore distance to each lake.
    double banked(double x, double y, const std::array<double, 2>& shore) const
    {
        double z = terrain(x, y);
        for (std::size_t j = 0; j < 2; ++j) {
            if (shore[j] < bank_m) {
                const double bank = levels[j] + bank_height(std::max(0.0, shore[j]));
                z = bank + smoothstep(0.0, bank_m, shore[j]) * (z - bank);
            }
        }
        return z;
    }

    /// Distance to the shore of each lake (negative inside): the outline's radial distance plus a small
    /// wiggle (coves and points tens of metres long; gentle enough never to cut off a pool or a spit).
    std::array<double, 2> shores(double x, double y) const
    {
        const double wiggle = coves_m * coves(x, y);
        return {lakes[0].shore_distance(x, y) + wiggle, lakes[1].shore_distance(x, y) + wiggle};
    }

    site_sample operator()(double x, double y) const
    {
        const auto shore = shores(x, y);
        for (std::size_t j = 0; j < 2; ++j) {
            if (shore[j] > 0) continue;
            for (const auto& isl : islands) {
                const double h = j == 0 ? isl.height_above_water(x, y) : -1.0;
                if (h >= 0) return {levels[j] + h, las_class::ground, -1, isl.area_m2(), 150.0};
            }
            return {levels[j], las_class::water, static_cast<std::int32_t>(j), 0.0, 0.0};
        }
        const auto [along, across] = road.local(x, y);
        if (std::abs(across) <= 0.5 * road.width_m) {
            const auto p = road.world(along, 0.0);
            return {banked(p[0], p[1], shores(p[0], p[1])), las_class::road_surface, -1, 0.0,
                    road_intensity(cover, x, y)};
        }
        const double z =
            banked(x, y, shore) + micro_m * micro(x, y) * smoothstep(0.0, 10.0, std::min(shore[0], shore[1]));
        return {z, las_class::ground, -1, 0.0, cover_intensity(cover, x, y)};
    }
};

/// River scene ground: a valley falling eastwards along a meandering river, and a road on embankments
/// that climbs to a bridge deck.
struct river_site : ground_fields {
    double size_m = 640;
    river_channel channel;
    road_strip road;  ///< infinite road through the bridge; along = 0 at the deck centre
    double deck_half_length_m = 30;
    double deck_z = 0;
    static constexpr double ramp_slope = 0.06, embankment_slope = 0.5;

    /// Valley floor and sides at (x, y) (no micro relief, no road), given the point's offset from the
    /// channel's centre line and the water width there.
    double valley(double x, double y, double offset, double width) const
    {
        const double s = std::abs(offset), d = s - 0.5 * width;
        return channel.level(x) + bank_height(d) + 12.0 * smoothstep(0.1 * size_m, 0.45 * size_m, s) +
               2.5 * (relief(x, y) + 1.0) * smoothstep(5.0, 40.0, d);
    }

    site_sample operator()(double x, double y) const
    {
        const double offset = channel.offset(x, y), width = channel.width(x);
        const double d = std::abs(offset) - 0.5 * width;
        if (d <= 0) return {channel.level(x), las_class::water, 0, 0.0, 0.0};
        double z = valley(x, y, offset, width) + 0.2 * micro(x, y) * smoothstep(0.0, 10.0, d);
        const auto [along, across] = road.local(x, y);
        const double off_road = std::abs(across) - 0.5 * road.width_m;
        // Beyond 30 m from the road no embankment (at most a deck height, 1:2) reaches the ground.
        if (std::abs(along) > deck_half_length_m && off_road < 30.0) {
            const auto p = road.world(along, 0.0);
            const double natural = valley(p[0], p[1], channel.offset(p[0], p[1]), channel.width(p[0]));
            const double road_z = std::max(natural, deck_z - ramp_slope * (std::abs(along) - deck_half_length_m));
            if (off_road <= 0) return {road_z, las_class::road_surface, -1, 0.0, road_intensity(cover, x, y)};
            z = std::max(z, road_z - embankment_slope * off_road);
        }
        return {z, las_class::ground, -1, 0.0, cover_intensity(cover, x, y)};
    }
};

/// Town scene ground: gently undulating, with a grid of roads.
struct town_site : ground_fields {
    double base_z = 50, relief_m = 2.0;
    std::vector<road_strip> roads;

    double terrain(double x, double y) const { return base_z + relief_m * relief(x, y); }

    site_sample operator()(double x, double y) const
    {
        for (const auto& road : roads) {
            const auto [along, across] = road.local(x, y);
            if (std::abs(across) <= 0.5 * road.width_m) {
                const auto p = road.world(along, 0.0);
                return {terrain(p[0], p[1]), las_class::road_surface, -1, 0.0, road_intensity(cover, x, y)};
            }
        }
        return {terrain(x, y) + 0.1 * micro(x, y), las_class::ground, -1, 0.0, cover_intensity(cover, x, y)};
    }
};

template <class Site>
scene render(const world<Site>& w, const scene_options& o)
{
    return {render_points(w, o.density_per_m2), render_truth(w, o.truth_cell_m)};
}

/// An empty world of the scene's size, its seed derived from the options' seed and the scene's tag, its
/// ground fields seeded. @throws invalid_input on bad options (see validate).
template <class Site>
world<Site> new_world(const scene_options& o, const char* fn, std::uint64_t tag, double relief_wavelength_m)
{
    validate(o, fn);
    world<Site> w;
    w.size_m = o.size_m;
    w.seed = hash64(o.seed, tag);
    static_cast<ground_fields&>(w.site) = ground_fields(w.seed, relief_wavelength_m);
    return w;
}

/// Trees scattered over the world (see scatter_trees), standing on its ground.
template <class Site, class Probability>
std::vector<tree> site_trees(const world<Site>& w, rng& random, double spacing_m, const tree_size& sizes,
                             Probability&& probability)
{
    return scatter_trees(random, w.size_m, spacing_m, sizes, probability,
                         [&](double x, double y) { return w.site(x, y).z; });
}

/// Trees beside buildings: for each building in order, with probability `chance` 1..3 trees whose crowns
/// stand gap_min_m..gap_max_m outside its bounding circle in a random direction, kept where
/// fits(x, y, crown_radius) holds; ground_z from ground(x, y). Draws from `random` in a fixed order.
template <class Fits, class Ground>
std::vector<tree> trees_beside_buildings(const std::vector<building_truth>& buildings, rng& random,
                                         const tree_size& sizes, double chance, double gap_min_m, double gap_max_m,
                                         Fits&& fits, Ground&& ground)
{
    std::vector<tree> out;
    for (const auto& b : buildings) {
        const int count = random.chance(chance) ? random.between(1, 3) : 0;
        for (int k = 0; k < count; ++k) {
            tree t;
            const double angle = random.uniform(0.0, 2 * std::numbers::pi);
            t.crown_radius_m = random.uniform(sizes.min_radius_m, sizes.max_radius_m);
            const double distance = b.bounding_radius() + t.crown_radius_m + random.uniform(gap_min_m, gap_max_m);
            t.x = b.x + distance * std::sin(angle);
            t.y = b.y + distance * std::cos(angle);
            t.height_m = random.uniform(sizes.min_height_m, sizes.max_height_m);
            t.crown_base_m = std::max(1.5, t.height_m * random.uniform(0.25, 0.5));
            t.intensity = random.uniform(sizes.min_intensity, sizes.max_intensity);
            if (!fits(t.x, t.y, t.crown_radius_m)) continue;
            t.ground_z = ground(t.x, t.y);
            out.push_back(t);
        }
    }
    return out;
}

}  // namespace internal

/// Lake scene: rolling terrain (about 30 m of relief over 640 m) with one large irregular lake (mean
/// radius 0.22 size) and a pond (0.06 size), flat water below banks that rise 0.3 m at the shoreline and
/// then bend into the terrain over 50 m; 2-3 islands of 300-900 m^2 and 3-5 rocks of 40-100 m^2 in the
/// lake; trees along the banks, in woods and on the large islands; a road across the south. Water
/// returns follow water_returns (dropout patches covering 40 % of each waterbody, single-cell dropouts,
/// weak returns with a few specular glints near nadir). Truth: water (islands are land), water_filled
/// (islands under island_fill_area_m2 are water), ground_z, surface, islands. See
/// docs/synthetic-scenes.md. About 0.3 s per million points (Release, one core).
/// @throws invalid_input if size_m, density_per_m2 or truth_cell_m is not finite and > 0, or the scene
/// would exceed 1e9 pulses or 2.5e8 truth cells.
inline scene lake_scene(const scene_options& options = {})
{
    auto w = internal::new_world<internal::lake_site>(options, "lake_scene", 0x1A4E, 320.0);
    const double S = w.size_m;
    rng random(w.seed, 10);
    auto& site = w.site;
    site.coves = noise_field{hash64(w.seed, 5), 45.0, 2, 0.5};
    site.lakes[0] = lake_outline::random(random, S * (0.45 + 0.03 * random.triangular()),
                                         S * (0.58 + 0.03 * random.triangular()), 0.22 * S, 0.38);
    site.lakes[1] = lake_outline::random(random, S * (0.84 + 0.02 * random.triangular()),
                                         S * (0.24 + 0.02 * random.triangular()), 0.06 * S, 0.25);
    // Each level lies 1 m below the lowest terrain within the bank band, so the banks rise everywhere.
    for (std::size_t j = 0; j < 2; ++j) {
        const auto& lake = site.lakes[j];
        double lowest = std::numeric_limits<double>::infinity();
        for (int a = 0; a < 72; ++a) {  // every 5 degrees
            const double theta = a * (std::numbers::pi / 36), c = std::cos(theta), s = std::sin(theta);
            const double r0 = lake.radius_toward(c, s);
            for (double d = 0; d <= internal::lake_site::bank_m; d += 5.0)
                lowest = std::min(lowest, site.terrain(lake.x + (r0 + d) * c, lake.y + (r0 + d) * s));
        }
        site.levels[j] = lowest - 1.0;
    }
    site.road = road_strip{0.0, S * 0.06, 90.0 + 2.0 * random.triangular(), 7.0};

    const auto place_islands = [&](int count, double min_area, double max_area, double min_h, double max_h) {
        const auto& lake = site.lakes[0];
        for (int k = 0; k < count; ++k) {
            for (int attempt = 0; attempt < 300; ++attempt) {
                const double area = random.uniform(min_area, max_area), r = std::sqrt(area / std::numbers::pi);
                const double x = lake.x + random.uniform(-1.0, 1.0) * lake.max_radius();
                const double y = lake.y + random.uniform(-1.0, 1.0) * lake.max_radius();
                if (lake.shore_distance(x, y) > -(r + 12.0)) continue;
                const bool clear = std::all_of(site.islands.begin(), site.islands.end(), [&](const island_truth& o) {
                    return std::hypot(o.x - x, o.y - y) > o.radius_m + r + 12.0;
                });
                if (!clear) continue;
                site.islands.push_back({x, y, r, random.uniform(min_h, max_h)});
                w.islands.push_back({x, y, r, site.islands.back().area_m2()});
                break;
            }
        }
    };
    place_islands(random.between(2, 3), 300.0, 900.0, 1.5, 3.5);
    place_islands(random.between(3, 5), 40.0, 100.0, 0.3, 1.2);
    w.water_bodies = 2;

    rng tree_random(w.seed, 11);
    w.trees = internal::site_trees(w, tree_random, 7.0, tree_size{}, [&](double x, double y, double rc) {
        for (const auto& isl : site.islands) {
            const double rho = std::hypot(x - isl.x, y - isl.y);
            if (rho < isl.radius_m + rc + 1.5)
                return isl.area_m2() >= island_fill_area_m2 && rho + rc + 1.0 <= isl.radius_m ? 0.35 : 0.0;
        }
        const auto shores = site.shores(x, y);
        return internal::bank_trees{}.probability(std::min(shores[0], shores[1]), site.road.edge_distance(x, y), rc,
                                                  site.woods(x, y));
    });
    return internal::render(w, options);
}

/// River scene: a river 15-40 m wide meandering west to east, its level falling 1.5 m per 640 m, in a
/// valley whose banks rise 0.3 m at the water's edge; trees along the banks and in woods; a road on
/// embankments climbing at 6 % to a flat bridge deck 5.5-7.5 m above the water, crossing where the river
/// runs straightest east-west. Truth: water (the water under the deck is water), water_z, ground_z
/// (the ground under the deck, not the deck), surface (17 on the deck). See docs/synthetic-scenes.md.
/// @throws invalid_input as lake_scene.
inline scene river_scene(const scene_options& options = {})
{
    auto w = internal::new_world<internal::river_site>(options, "river_scene", 0x71FE, 260.0);
    const double S = w.size_m;
    rng random(w.seed, 10);
    auto& site = w.site;
    site.size_m = S;
    auto& ch = site.channel;
    constexpr double two_pi = river_channel::two_pi;
    ch.y_mid = S * (0.5 + 0.03 * random.triangular());
    ch.meander_amplitude_m = {0.11 * S * random.uniform(0.8, 1.2), 0.02 * S * random.uniform(0.5, 1.5)};
    ch.meander_wavelength_m = {S * random.uniform(0.6, 0.8), S * random.uniform(0.25, 0.35)};
    ch.meander_phase = {random.uniform(0.0, two_pi), random.uniform(0.0, two_pi)};
    ch.width_wavelength_m = {0.45 * S, 0.21 * S};
    ch.width_phase = {random.uniform(0.0, two_pi), random.uniform(0.0, two_pi)};
    ch.level_west_z = 40.0 + 2.0 * random.triangular();
    w.water_bodies = 1;

    // The bridge crosses where the channel runs closest to east-west, its axis square to the channel.
    double xb = 0.6 * S;
    for (double x = 0.45 * S; x <= 0.75 * S; x += 0.5) {
        if (std::abs(ch.centre_slope(x)) < std::abs(ch.centre_slope(xb))) xb = x;
    }
    road_strip axis{xb, ch.centre_y(xb), rad_to_deg(std::atan2(-ch.centre_slope(xb), 1.0)), 7.0};
    const auto last_water = [&](double direction) {
        double last = 0;
        for (double t = 0; t < 0.5 * S && t < last + 20.0; t += 0.5) {
            const auto p = axis.world(direction * t, 0.0);
            if (std::abs(ch.offset(p[0], p[1])) <= 0.5 * ch.width(p[0])) last = t;
        }
        return last;
    };
    const double ahead = last_water(1.0) + 12.0, behind = last_water(-1.0) + 12.0;
    const auto centre = axis.world(0.5 * (ahead - behind), 0.0);
    site.road = road_strip{centre[0], centre[1], axis.azimuth_deg, 7.0};
    site.deck_half_length_m = 0.5 * (ahead + behind);
    site.deck_z = ch.level(xb) + random.uniform(5.5, 7.5);
    w.bridges.push_back({road_strip{centre[0], centre[1], axis.azimuth_deg, 8.0, site.deck_half_length_m}, site.deck_z,
                         random.uniform(60.0, 100.0)});

    rng tree_random(w.seed, 11);
    w.trees = internal::site_trees(w, tree_random, 7.0, tree_size{}, [&](double x, double y, double rc) {
        // Wider clearance from the road: its embankments.
        const internal::bank_trees rules{.bank_m = 25, .woods_above = 0.25, .in_woods = 0.6, .road_gap_m = 10};
        return rules.probability(std::abs(ch.offset(x, y)) - 0.5 * ch.width(x), site.road.edge_distance(x, y), rc,
                                 site.woods(x, y));
    });
    return internal::render(w, options);
}

/// Town scene: gently undulating ground (about 2 m of relief) with a grid of 10 m roads every ~160 m,
/// 20-40 buildings per 640 m x 640 m (scaled by area) along the streets, on rectangular footprints 8-16 m
/// wide and up to 32 m long, rotated by multiples of 15 degrees or by arbitrary angles, with flat (20 %),
/// shed (20 %), gable (35 %) and hip (25 %) roofs (at least one of each), walls 3-15 m high, roof
/// intensity 36-121; trees next to some buildings and a few in the open. Truth: building_id, roof_plane_id, footprints,
/// roof_planes (tilt, facing azimuth clockwise from north, sloped area). See docs/synthetic-scenes.md.
/// @throws invalid_input as lake_scene.
inline scene town_scene(const scene_options& options = {})
{
    auto w = internal::new_world<internal::town_site>(options, "town_scene", 0x70AB, 300.0);
    const double S = w.size_m;
    rng random(w.seed, 10);
    auto& site = w.site;
    const int road_count = std::max(1, static_cast<int>(std::lround(S / 160.0)));
    for (int k = 0; k < road_count; ++k) {
        const double p = (k + 0.5) * S / road_count;
        site.roads.push_back(road_strip{p, 0.5 * S, 0.0, 10.0});
        site.roads.push_back(road_strip{0.5 * S, p, 90.0, 10.0});
    }
    const auto road_clearance = [&](double x, double y) {
        double nearest = std::numeric_limits<double>::infinity();
        for (const auto& road : site.roads) nearest = std::min(nearest, road.edge_distance(x, y));
        return nearest;
    };

    const auto target = static_cast<int>(std::lround((20 + random.between(0, 20)) * (S / 640.0) * (S / 640.0)));
    const auto first_kind = static_cast<std::size_t>(random.below(4));
    for (int attempt = 0; attempt < 400 * std::max(1, target) && static_cast<int>(w.buildings.size()) < target;
         ++attempt) {
        building_truth b;
        b.width_m = random.uniform(8.0, 16.0);
        b.length_m = std::min(32.0, b.width_m * random.uniform(1.0, 2.0));
        b.axis_azimuth_deg = random.chance(0.5) ? 15.0 * random.between(0, 11) : random.uniform(0.0, 180.0);
        // The first four buildings take one roof kind each (in a random order), so every town has all four.
        const double kind = w.buildings.size() < 4
                                ? (static_cast<double>((first_kind + w.buildings.size()) % 4) + 0.5) / 4.0
                                : random.uniform();
        b.kind = kind < 0.2    ? roof_kind_truth::flat
                 : kind < 0.4  ? roof_kind_truth::shed
                 : kind < 0.75 ? roof_kind_truth::gable
                               : roof_kind_truth::hip;
        b.tilt_deg = b.kind == roof_kind_truth::flat    ? 0.0
                     : b.kind == roof_kind_truth::shed  ? random.uniform(5.0, 25.0)
                     : b.kind == roof_kind_truth::gable ? random.uniform(20.0, 45.0)
                                                        : random.uniform(20.0, 40.0);
        b.shed_facing = random.between(0, 3);
        const double wall = b.kind == roof_kind_truth::flat ? random.uniform(3.0, 15.0) : random.uniform(3.0, 9.0);
        b.intensity = random.uniform(40.0, 110.0);
        // Houses front onto the streets: set back 4-12 m from the edge of a random road.
        const double r = b.bounding_radius();
        const auto& street = site.roads[static_cast<std::size_t>(random.below(site.roads.size()))];
        const double setback = 0.5 * street.width_m + 4.0 + r + random.uniform(0.0, 8.0);
        const auto spot = street.world(random.uniform(-0.5 * S, 0.5 * S), random.chance(0.5) ? setback : -setback);
        b.x = spot[0];
        b.y = spot[1];
        if (b.x < r + 4 || b.y < r + 4 || b.x > S - r - 4 || b.y > S - r - 4) continue;
        if (road_clearance(b.x, b.y) < r + 4) continue;
        const bool clear = std::all_of(w.buildings.begin(), w.buildings.end(), [&](const building_truth& o) {
            return std::hypot(o.x - b.x, o.y - b.y) > o.bounding_radius() + r + 4;
        });
        if (!clear) continue;
        b.id = static_cast<std::int32_t>(w.buildings.size()) + 1;
        b.eave_z = site.terrain(b.x, b.y) + wall;
        w.buildings.push_back(b);
    }

    // Trees never overhang roofs or roads, so every roof point belongs to its roof.
    const auto tree_fits = [&](double x, double y, double rc) {
        if (x < 0 || y < 0 || x > S || y > S || road_clearance(x, y) < rc + 1.0) return false;
        return std::all_of(w.buildings.begin(), w.buildings.end(), [&](const building_truth& o) {
            return std::hypot(o.x - x, o.y - y) > o.bounding_radius() + rc + 1.0;
        });
    };
    rng tree_random(w.seed, 11);
    const tree_size sizes{.min_radius_m = 2.0, .max_radius_m = 4.5, .min_height_m = 6.0, .max_height_m = 16.0};
    const auto beside = internal::trees_beside_buildings(w.buildings, tree_random, sizes, 0.4, 1.5, 6.0, tree_fits,
                                                         [&](double x, double y) { return site(x, y).z; });
    w.trees.insert(w.trees.end(), beside.begin(), beside.end());
    const auto park = internal::site_trees(
        w, tree_random, 9.0, sizes, [&](double x, double y, double rc) { return tree_fits(x, y, rc) ? 0.03 : 0.0; });
    w.trees.insert(w.trees.end(), park.begin(), park.end());
    return internal::render(w, options);
}

}  // namespace lidarfx::synth
