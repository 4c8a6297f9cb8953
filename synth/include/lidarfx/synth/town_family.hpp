// SPDX-License-Identifier: Apache-2.0
// town_family: randomized synthetic towns from one seed (sizes, densities, roof kinds, tilts, orientations,
// trees beside roofs and over them, garages and sheds, terraced rows and semi-detached pairs, dormers, buildings cut by
// the survey's edge), with their truth, for testing building extraction on many towns.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
#include <utility>
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
    /// Terraced rows: rows of 3-6 houses standing side by side, touching at shared (party) walls, each house its
    /// own building (internal::add_house_rows), >= 0; 0 = none. A crowded town gets fewer.
    int terraced_rows = 0;
    /// Semi-detached pairs: rows of 2 touching houses, as terraced_rows, >= 0; 0 = none.
    int semi_detached_pairs = 0;
    /// Share of the gable and hip houses (not garages, sheds, row houses or edge buildings) that get 1-2 dormers on
    /// one or both long faces (internal::draw_dormers; a house whose face is too small or roof too flat gets none),
    /// in [0, 1]; 0 = none.
    double dormer_share = 0;
    /// Houses cut by the survey's edge: their footprints cross the town's border, the part outside is not scanned
    /// (internal::add_edge_buildings), >= 0; 0 = none. A crowded town gets fewer.
    int edge_buildings = 0;
    /// Share of the houses (not garages, sheds, row houses or edge buildings) that get a tree whose crown reaches
    /// 1-3 m over one of their walls, above the roof (internal::add_overhanging_trees), in [0, 1]; 0 = none.
    double overhanging_tree_share = 0;
};

/// Roofs of two touching houses differ by more than this along a party wall where the wall counts as a step, m.
inline constexpr double party_wall_step_m = 1.0;

/// The shared (party) wall of two touching houses of a terraced row or semi-detached pair, and the height step
/// of their roofs along it: the absolute difference of the two roofs (roof_at of each house, 0.05 m inside its
/// footprint) at 20 points evenly spread along the wall.
struct party_wall_truth {
    std::int32_t a = 0;      ///< building id of the house on the row's start side of the wall
    std::int32_t b = 0;      ///< building id of the house on the other side (b = a + 1)
    double step_share = 0;   ///< share of the samples whose roofs differ by more than party_wall_step_m, [0, 1]
    double mean_step_m = 0;  ///< mean absolute roof height difference over the samples, metres
};

/// A family town with the density it was scanned at.
struct town_family_scene {
    scene town;                 ///< points and truth (building_id, roof_plane_id, roof_planes, footprints, surface)
    double density_per_m2 = 0;  ///< pulses per m^2 drawn for this town
    std::vector<tree> trees;    ///< the trees (crowns), for per-tree checks
    std::vector<party_wall_truth> party_walls;  ///< every pair of touching houses (terraced rows, semi-detached
                                                ///< pairs), row by row, in order along each row
    std::vector<building_truth> buildings;      ///< every building as built (id order: buildings[i].id == i + 1), with
                                                ///< its dormers; edge buildings' footprints reach past the border
};

/// A randomized town: gently rolling ground (2 m relief) without roads; houses (0.4-0.6 per 1000 m^2) of
/// 8-18 m width, 1-2.2 times as long (at most 40 m), any orientation (uniform in [0, 180) deg), flat, shed,
/// gable or hip roofs (a quarter each; the first four take one kind each), tilts uniform in 5-55 deg, walls
/// 3-12 m, at least 3 m apart; trees (crown radius 2-5 m, 6-18 m tall) beside 60 % of the houses with
/// crowns 0.5-4 m from the footprint's bounding circle, and scattered in the open; then
/// small_buildings_per_house garages and sheds per house (internal::add_small_buildings), beside the houses
/// or in the open, clear of houses and crowns; then terraced_rows rows of 3-6 touching houses and
/// semi_detached_pairs pairs of 2 (internal::add_house_rows: any direction, frontages 5-8 m, one depth of
/// 8-12 m, the first house's walls 5-10 m and each next house's eave 1.2-3.0 m up or down from its neighbour's
/// 60 % of the time, else the same; flat, gable along or across the row, or shed roofs), clear of every building
/// and crown, with a party_wall_truth for every two touching houses. Deterministic from the seed; the garages and the
/// rows draw from their own random streams, so the houses and trees are those of the town without them, and the garages
/// those of the town without rows (their points' noise differs). Then edge_buildings houses cut by the town's
/// border (internal::add_edge_buildings) and, last, dormers on dormer_share of the gable and hip houses
/// (internal::draw_dormers) and trees overhanging overhanging_tree_share of the houses
/// (internal::add_overhanging_trees), each from its own random stream, so every other building stays as it was (with
/// these options 0 the town is the one without them, point for point). Houses are ids 1..n, garages and sheds follow,
/// then the row houses, row by row, then the edge buildings. @throws invalid_input on bad options (see
/// scene_options).
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

/// One house of a terraced row or semi-detached pair, as drawn before the row is placed.
struct row_house_plan {
    double frontage_m = 6;                         ///< width along the row, metres
    roof_kind_truth kind = roof_kind_truth::flat;  ///< flat, shed or gable (never hip)
    bool ridge_along_row = false;                  ///< a gable's ridge runs along the row (else across it)
    double tilt_deg = 0;                           ///< roof tilt, degrees (0 for flat)
    int shed_facing = 0;                           ///< facing of a shed roof, 0..3 (see building_truth)
    double intensity = 70;                         ///< mean intensity of the roof material
};

/// A terraced row or semi-detached pair before placement: houses side by side along one direction, one depth.
struct row_plan {
    double azimuth_deg = 0;              ///< direction of the row (first house to last), clockwise from north, [0, 180)
    double depth_m = 10;                 ///< depth of every house across the row, metres
    std::vector<row_house_plan> houses;  ///< in order along the row

    /// Length of the row: the sum of the frontages, metres.
    double length_m() const noexcept
    {
        double sum = 0;
        for (const auto& h : houses) sum += h.frontage_m;
        return sum;
    }
    /// Radius of the circle about the row's centre that encloses every house, metres.
    double bounding_radius() const noexcept { return 0.5 * std::hypot(length_m(), depth_m); }
};

/// A row house's frontage 5-8 m and roof: flat (20 %), gable with its ridge along the row (35 %) or across it
/// (30 %), both tilted 25-45 deg, or shed (15 %) tilted 5-20 deg, facing any of its four sides.
inline row_house_plan draw_row_house(rng& random)
{
    row_house_plan h;
    h.frontage_m = random.uniform(5.0, 8.0);
    const double kind = random.uniform(0.0, 1.0);
    h.kind = kind < 0.2 ? roof_kind_truth::flat : kind < 0.85 ? roof_kind_truth::gable : roof_kind_truth::shed;
    h.ridge_along_row = kind >= 0.2 && kind < 0.55;
    h.tilt_deg = h.kind == roof_kind_truth::flat   ? 0.0
                 : h.kind == roof_kind_truth::shed ? random.uniform(5.0, 20.0)
                                                   : random.uniform(25.0, 45.0);
    h.shed_facing = random.between(0, 3);
    h.intensity = random.uniform(40.0, 110.0);
    return h;
}

/// A row of `houses` houses: direction uniform in [0, 180) deg, depth 8-12 m, houses by draw_row_house.
inline row_plan draw_row(rng& random, int houses)
{
    row_plan row;
    row.azimuth_deg = random.uniform(0.0, 180.0);
    row.depth_m = random.uniform(8.0, 12.0);
    for (int k = 0; k < houses; ++k) row.houses.push_back(draw_row_house(random));
    return row;
}

/// A row house centred at (x, y), without id and eave. A gable's axis (u, along its ridge) runs along the row or
/// across it as planned, so its ridge may run along the footprint's short side (length_m < width_m: roof_at and
/// planes() take u as the ridge whatever the proportions; hips would not); flat and shed roofs take the longer
/// side as their axis.
inline building_truth row_house(const row_plan& row, const row_house_plan& house, double x, double y)
{
    const bool axis_along_row =
        house.kind == roof_kind_truth::gable ? house.ridge_along_row : house.frontage_m >= row.depth_m;
    building_truth b;
    b.x = x;
    b.y = y;
    b.axis_azimuth_deg = axis_along_row ? row.azimuth_deg : std::fmod(row.azimuth_deg + 90.0, 180.0);
    b.length_m = axis_along_row ? house.frontage_m : row.depth_m;
    b.width_m = axis_along_row ? row.depth_m : house.frontage_m;
    b.kind = house.kind;
    b.tilt_deg = house.tilt_deg;
    b.shed_facing = house.shed_facing;
    b.intensity = house.intensity;
    return b;
}

/// The houses of `row` with the row's centre at (x, y), touching: neighbours' centres are half their frontages
/// apart along the row, so they share a wall and no ground between them.
inline std::vector<building_truth> lay_out_row(const row_plan& row, double x, double y)
{
    const double a = deg_to_rad(row.azimuth_deg), ex = std::sin(a), ey = std::cos(a);
    std::vector<building_truth> houses;
    double start = -0.5 * row.length_m();
    for (const auto& h : row.houses) {
        const double along = start + 0.5 * h.frontage_m;
        houses.push_back(row_house(row, h, x + along * ex, y + along * ey));
        start += h.frontage_m;
    }
    return houses;
}

/// Where a row may stand: its bounding circle (radius_m about (x, y)) 3 m from every building's, and every house's
/// bounding circle 0.4 m from every crown. (The caller keeps the circle 4 m inside the town.)
inline bool row_fits(const std::vector<building_truth>& houses, double x, double y, double radius_m,
                     const std::vector<building_truth>& buildings, const std::vector<tree>& trees)
{
    const bool clear_of_buildings = std::all_of(buildings.begin(), buildings.end(), [&](const building_truth& o) {
        return std::hypot(o.x - x, o.y - y) > o.bounding_radius() + radius_m + 3;
    });
    return clear_of_buildings && std::all_of(houses.begin(), houses.end(), [&](const building_truth& h) {
               return std::all_of(trees.begin(), trees.end(), [&](const tree& t) {
                   return std::hypot(t.x - h.x, t.y - h.y) > t.crown_radius_m + h.bounding_radius() + 0.4;
               });
           });
}

/// Sets the eaves of a placed row: the first house's walls 5-10 m above the terrain at its centre; each next
/// house steps 1.2-3.0 m up or down from its neighbour's eave with probability 0.6 (up when down would leave
/// walls under 3 m), else keeps the neighbour's eave; walls are never under 3 m at a house's centre.
template <class Site>
void draw_row_eaves(const world<Site>& w, rng& random, std::vector<building_truth>& houses)
{
    for (std::size_t k = 0; k < houses.size(); ++k) {
        building_truth& b = houses[k];
        const double ground = w.site.terrain(b.x, b.y);
        if (k == 0) {
            b.eave_z = ground + random.uniform(5.0, 10.0);
            continue;
        }
        const double previous = houses[k - 1].eave_z;
        b.eave_z = previous;
        if (random.chance(0.6)) {
            const double step = random.uniform(1.2, 3.0);
            const bool down = random.chance(0.5) && previous - step >= ground + 3.0;
            b.eave_z = down ? previous - step : previous + step;
        }
        b.eave_z = std::max(b.eave_z, ground + 3.0);
    }
}

/// Full extent of b's footprint along the unit direction (ex, ey), metres.
inline double extent_along(const building_truth& b, double ex, double ey) noexcept
{
    const double a = deg_to_rad(b.axis_azimuth_deg);
    const double along_u = std::abs(ex * std::sin(a) + ey * std::cos(a));
    const double along_v = std::abs(ex * std::cos(a) - ey * std::sin(a));
    return b.length_m * along_u + b.width_m * along_v;
}

/// The party wall of two touching houses whose sides are parallel or perpendicular to the line through their
/// centres (as in a row, a's wall against b's wall): the roofs' absolute height difference at 20 points evenly
/// spread along the wall, each house sampled 0.05 m inside its footprint (party_wall_truth).
inline party_wall_truth measure_party_wall(const building_truth& a, const building_truth& b)
{
    constexpr int samples = 20;
    constexpr double inset_m = 0.05;
    const double distance = std::hypot(b.x - a.x, b.y - a.y);
    const double ex = (b.x - a.x) / distance, ey = (b.y - a.y) / distance;  // across the wall, a to b
    const double half_a = 0.5 * extent_along(a, ex, ey),
                 wall_m = std::min(extent_along(a, ey, -ex), extent_along(b, ey, -ex));
    const double wx = a.x + half_a * ex, wy = a.y + half_a * ey;
    int steps = 0;
    double step_sum_m = 0;
    for (int k = 0; k < samples; ++k) {
        const double along = wall_m * ((k + 0.5) / samples - 0.5);
        const double px = wx + along * ey, py = wy - along * ex;
        const double step = std::abs(a.roof_at(px - inset_m * ex, py - inset_m * ey).z -
                                     b.roof_at(px + inset_m * ex, py + inset_m * ey).z);
        steps += step > party_wall_step_m ? 1 : 0;
        step_sum_m += step;
    }
    return {a.id, b.id, static_cast<double>(steps) / samples, step_sum_m / samples};
}

/// Adds `count` rows of min_houses-max_houses touching houses to w, after every other building, and the truth of
/// their party walls to `walls` (row_plan, draw_row, lay_out_row, draw_row_eaves, measure_party_wall). Each row
/// is drawn once (so placed rows keep the drawn sizes), then placed: its bounding circle 4 m inside the town and
/// 3 m from every other building's, its houses 0.4 m from every crown; up to 200 places each, a row that finds
/// none is left out (a crowded town gets fewer). Ids continue after w's buildings. Draws only from `random`.
template <class Site>
void add_house_rows(world<Site>& w, rng& random, int count, int min_houses, int max_houses,
                    std::vector<party_wall_truth>& walls)
{
    for (int k = 0; k < count; ++k) {
        const row_plan row = draw_row(random, random.between(min_houses, max_houses));
        const double r = row.bounding_radius();
        if (w.size_m - 2 * r - 8 <= 0) continue;
        for (int attempt = 0; attempt < 200; ++attempt) {
            const double x = random.uniform(r + 4, w.size_m - r - 4), y = random.uniform(r + 4, w.size_m - r - 4);
            auto houses = lay_out_row(row, x, y);
            if (!row_fits(houses, x, y, r, w.buildings, w.trees)) continue;
            draw_row_eaves(w, random, houses);
            const std::size_t first = w.buildings.size();
            for (auto& b : houses) {
                b.id = static_cast<std::int32_t>(w.buildings.size()) + 1;
                w.buildings.push_back(b);
            }
            for (std::size_t i = first; i + 1 < w.buildings.size(); ++i)
                walls.push_back(measure_party_wall(w.buildings[i], w.buildings[i + 1]));
            break;
        }
    }
}

/// Dormers on house b (a gable or hip; faces 0 and 1, see dormer_truth), all of one size: 1.5-3 m wide along the
/// ridge, fronts 0.5-1 m in from the eave, each front standing 0.8-1.5 m above the roof; the top is flat (half the
/// time, when the depth that gives the step is 1.5-2.5 m) or a shed 1.5-2.5 m deep falling towards the eave, and
/// meets the roof at the dormer's back; the step is drawn up to what a 2.5 m deep dormer makes on the roof. One face
/// (either) or both, 1-2 dormers on each (2 at least 1 m apart), at least 0.5 m from the ridge and 1 m from the
/// gable ends (a hip's hip lines, measured along the ridge). Returns false and leaves b as it was when a face is too
/// small or the roof too flat for a 0.8 m step (tilt under 17.7 deg). Draws only from `random`.
inline bool draw_dormers(building_truth& b, rng& random)
{
    const double slope = std::tan(deg_to_rad(b.tilt_deg));
    // The step a dormer at most 2.5 m deep can make on this roof bounds the step drawn.
    const double hu = 0.5 * random.uniform(1.5, 3.0), step = random.uniform(0.8, std::min(1.5, 2.5 * slope)),
                 setback = random.uniform(0.5, 1.0), shed_depth = random.uniform(1.5, 2.5);
    const bool want_flat = random.chance(0.5);
    const int faces = random.between(0, 2);  // face 0, face 1, or both
    const std::array<int, 2> counts{random.between(1, 2), random.between(1, 2)};
    if (2.5 * slope < 0.8) return false;
    const double flat_depth = step / slope;
    const bool flat = want_flat && flat_depth >= 1.5;
    const double depth = flat ? flat_depth : std::max(shed_depth, flat_depth);
    const double front = 0.5 * b.width_m - setback, back = front - depth;
    if (back < 0.5) return false;
    const double room = b.kind == roof_kind_truth::hip ? 0.5 * (b.length_m - b.width_m) + back - 1.0 - hu
                                                       : 0.5 * b.length_m - 1.0 - hu;  // |u0| may reach this
    if (room < 0) return false;
    const double top_z = b.eave_z + slope * (0.5 * b.width_m - back);
    const double drop = flat ? 0.0 : std::max(0.0, slope * depth - step);
    std::vector<dormer_truth> dormers;
    for (int face = 0; face < 2; ++face) {
        if (faces != 2 && faces != face) continue;
        const double v0 = (face == 0 ? 1.0 : -1.0) * (back + 0.5 * depth);
        const auto add = [&](double u0) { dormers.push_back({u0, v0, hu, 0.5 * depth, top_z, drop}); };
        if (counts[static_cast<std::size_t>(face)] == 2 && room >= hu + 0.5) {
            const double apart = random.uniform(hu + 0.5, room), shift = random.uniform(apart - room, room - apart);
            add(shift - apart);
            add(shift + apart);
        } else {
            add(random.uniform(-room, room));
        }
    }
    b.dormers = std::move(dormers);
    return true;
}

/// Adds `count` houses cut by the town's border to w, after every other building: footprints 8-14 m x 8-20 m, any
/// direction, flat, shed (tilted 5-20 deg), gable or hip (15-45 deg) roofs, a quarter each, walls 3-9 m above the
/// terrain at the centre; on a random side, the centre 1-4 m inside the border (and at least 1 m less than half the
/// footprint's extent across the border, so at least 1 m of it lies outside), 4 m plus the bounding radius from the
/// other sides; the bounding circle 3 m from every other building's and 0.4 m from every crown. Up to 200 tries
/// each; a house that finds no place is left out. Ids continue after w's buildings. Draws only from `random`.
template <class Site>
void add_edge_buildings(world<Site>& w, rng& random, int count)
{
    const double S = w.size_m;
    for (int k = 0; k < count; ++k) {
        for (int attempt = 0; attempt < 200; ++attempt) {
            building_truth b;
            b.width_m = random.uniform(8.0, 14.0);
            b.length_m = std::max(b.width_m, random.uniform(8.0, 20.0));
            b.axis_azimuth_deg = random.uniform(0.0, 180.0);
            b.kind = static_cast<roof_kind_truth>(random.between(0, 3));
            b.tilt_deg = b.kind == roof_kind_truth::flat   ? 0.0
                         : b.kind == roof_kind_truth::shed ? random.uniform(5.0, 20.0)
                                                           : random.uniform(15.0, 45.0);
            b.shed_facing = random.between(0, 3);
            b.intensity = random.uniform(40.0, 110.0);
            const int side = random.between(0, 3);  // west, east, south, north
            const double nx = side == 0 ? -1.0 : side == 1 ? 1.0 : 0.0, ny = side == 2 ? -1.0 : side == 3 ? 1.0 : 0.0;
            const double half = 0.5 * extent_along(b, nx, ny);  // >= 4 m: half the width at least
            const double inside = random.uniform(1.0, std::min(4.0, half - 1.0));
            const double r = b.bounding_radius();
            if (S - 2 * r - 8 <= 0) continue;
            const double along = random.uniform(r + 4, S - r - 4);
            b.x = side == 0 ? inside : side == 1 ? S - inside : along;
            b.y = side == 2 ? inside : side == 3 ? S - inside : along;
            const bool clear = std::all_of(w.buildings.begin(), w.buildings.end(), [&](const building_truth& o) {
                return std::hypot(o.x - b.x, o.y - b.y) > o.bounding_radius() + r + 3;
            });
            const bool clear_of_trees = std::all_of(w.trees.begin(), w.trees.end(), [&](const tree& t) {
                return std::hypot(t.x - b.x, t.y - b.y) > t.crown_radius_m + r + 0.4;
            });
            if (!clear || !clear_of_trees) continue;
            b.id = static_cast<std::int32_t>(w.buildings.size()) + 1;
            b.eave_z = w.site.terrain(b.x, b.y) + random.uniform(3.0, 9.0);
            w.buildings.push_back(b);
            break;
        }
    }
}

/// Adds to w a tree overhanging each of the first `houses` buildings with probability `share`: a crown of radius
/// 2.5-5 m whose edge reaches 1 m to min(3 m, radius - 0.5 m) over one of the footprint's four walls (at a random
/// place along it, 1 m from its corners), its stem outside the footprint; the crown's base 0.5-2 m above the
/// highest roof under the crown (dormers included), its top 3-8 m above the base; tree::over_roofs set. The crown
/// must stay 2 m inside the town and 0.4 m from every other building's bounding circle; up to 20 tries per house,
/// one that finds no place gets none. Draws only from `random`.
template <class Site>
void add_overhanging_trees(world<Site>& w, rng& random, std::size_t houses, double share)
{
    const double S = w.size_m;
    for (std::size_t i = 0; i < houses; ++i) {
        if (!random.chance(share)) continue;
        const building_truth& b = w.buildings[i];
        for (int attempt = 0; attempt < 20; ++attempt) {
            tree t;
            t.crown_radius_m = random.uniform(2.5, 5.0);
            const double over = random.uniform(1.0, std::min(3.0, t.crown_radius_m - 0.5));
            const int side = random.between(0, 3);  // +v, -v (long walls), +u, -u (short walls)
            const bool long_wall = side < 2;
            const double half_along = 0.5 * (long_wall ? b.length_m : b.width_m) - 1.0;
            const double along = random.uniform(-half_along, half_along);
            const double out = 0.5 * (long_wall ? b.width_m : b.length_m) + t.crown_radius_m - over;
            const double sign = side % 2 == 0 ? 1.0 : -1.0;
            const double pu = long_wall ? along : sign * out, pv = long_wall ? sign * out : along;
            // local() is a reflection-rotation that is its own inverse.
            const double a = deg_to_rad(b.axis_azimuth_deg), su = std::sin(a), cu = std::cos(a);
            t.x = b.x + pu * su + pv * cu;
            t.y = b.y + pu * cu - pv * su;
            const double rc = t.crown_radius_m;
            if (t.x < rc + 2 || t.y < rc + 2 || t.x > S - rc - 2 || t.y > S - rc - 2) continue;
            const bool clear = std::all_of(w.buildings.begin(), w.buildings.end(), [&](const building_truth& o) {
                return o.id == b.id || std::hypot(o.x - t.x, o.y - t.y) > o.bounding_radius() + rc + 0.4;
            });
            if (!clear) continue;
            double roof_top = -std::numeric_limits<double>::infinity();
            for (double dy = -rc; dy <= rc; dy += 0.25) {
                for (double dx = -rc; dx <= rc; dx += 0.25) {
                    if (dx * dx + dy * dy > rc * rc || !b.contains(t.x + dx, t.y + dy)) continue;
                    roof_top = std::max(roof_top, b.roof_at(t.x + dx, t.y + dy).z);
                }
            }
            if (!std::isfinite(roof_top)) continue;
            t.ground_z = w.site(t.x, t.y).z;
            t.crown_base_m = roof_top + random.uniform(0.5, 2.0) - t.ground_z;
            t.height_m = t.crown_base_m + random.uniform(3.0, 8.0);
            t.intensity = random.uniform(50.0, 140.0);
            t.over_roofs = true;
            w.trees.push_back(t);
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
    lidarfx::detail::require(options.terraced_rows >= 0 && options.semi_detached_pairs >= 0, "town_family",
                             "terraced_rows and semi_detached_pairs must be >= 0");
    lidarfx::detail::require(options.dormer_share >= 0 && options.dormer_share <= 1, "town_family",
                             "dormer_share must be in [0, 1]");
    lidarfx::detail::require(options.edge_buildings >= 0, "town_family", "edge_buildings must be >= 0");
    lidarfx::detail::require(options.overhanging_tree_share >= 0 && options.overhanging_tree_share <= 1, "town_family",
                             "overhanging_tree_share must be in [0, 1]");
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
    rng block_random(w.seed, 13);
    std::vector<party_wall_truth> walls;
    internal::add_house_rows(w, block_random, options.terraced_rows, 3, 6, walls);
    internal::add_house_rows(w, block_random, options.semi_detached_pairs, 2, 2, walls);
    rng edge_random(w.seed, 15);
    internal::add_edge_buildings(w, edge_random, options.edge_buildings);
    if (options.dormer_share > 0) {
        rng dormer_random(w.seed, 14);
        for (std::size_t i = 0; i < static_cast<std::size_t>(houses); ++i) {
            building_truth& b = w.buildings[i];
            if (b.kind != roof_kind_truth::gable && b.kind != roof_kind_truth::hip) continue;
            if (dormer_random.chance(options.dormer_share)) internal::draw_dormers(b, dormer_random);
        }
    }
    if (options.overhanging_tree_share > 0) {
        rng overhang_random(w.seed, 16);
        internal::add_overhanging_trees(w, overhang_random, static_cast<std::size_t>(houses),
                                        options.overhanging_tree_share);
    }
    auto town = internal::render(w, so);
    return {std::move(town), so.density_per_m2, w.trees, std::move(walls), std::move(w.buildings)};
}

}  // namespace lidarfx::synth
