// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/synth/scenes.hpp>

#include "synth/scene_stats.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

using namespace synth_test;

namespace {

// Half-metre truth cells: roof faces are resolved finely enough to pick points well inside each face.
constexpr auto make_town = [] { return town_scene({.truth_cell_m = 0.5}); };  // built once (see once())
const scene& town()
{
    return once(make_town).s;
}
const cell_points& town_cells()
{
    return once(make_town).cells;
}

}  // namespace

TEST_CASE("synth/town_scene: 20-40 buildings with footprints, ids and faces consistent")
{
    const auto& t = town().truth;
    CHECK(t.g == grid{0.0, 640.0, 0.5, 1280, 1280});
    const auto buildings = t.footprints.size();
    CHECK(buildings >= 20);
    CHECK(buildings <= 40);
    std::set<std::int32_t> ids;
    for (const auto& plane : t.roof_planes) ids.insert(plane.building_id);
    CHECK(ids.size() == buildings);
    CHECK(*ids.begin() == 1);
    CHECK(*ids.rbegin() == static_cast<std::int32_t>(buildings));
    for (const auto& ring : t.footprints) {
        REQUIRE(ring.size() == 5);
        CHECK(ring.front() == ring.back());
    }
    // building_id is the footprint holding the cell centre; roof_plane_id belongs to that building.
    std::size_t wrong_id = 0, wrong_plane = 0, covered = 0;
    for (std::ptrdiff_t r = 0; r < t.g.rows; ++r) {
        for (std::ptrdiff_t c = 0; c < t.g.cols; ++c) {
            const auto [x, y] = t.g.center(r, c);
            const auto id = t.building_id(r, c);
            std::int32_t expected = 0;
            for (std::size_t b = 0; b < buildings && expected == 0; ++b) {
                const auto& ring = t.footprints[b];
                if (x < std::min({ring[0][0], ring[1][0], ring[2][0], ring[3][0]}) ||
                    x > std::max({ring[0][0], ring[1][0], ring[2][0], ring[3][0]}))
                    continue;
                if (inside_ring(ring, x, y)) expected = static_cast<std::int32_t>(b) + 1;
            }
            wrong_id += id != expected;
            const auto plane = t.roof_plane_id(r, c);
            wrong_plane += (plane == 0) != (id == 0) ||
                           (plane > 0 && t.roof_planes[static_cast<std::size_t>(plane - 1)].building_id != id);
            covered += id != 0;
            if (id != 0) wrong_plane += t.surface(r, c) != las_class::building;
        }
    }
    CHECK(wrong_id == 0);
    CHECK(wrong_plane == 0);
    CHECK(covered > 0);
}

TEST_CASE("synth/town_scene: roof points lie on the stated planes (tilt and azimuth within 1 degree)")
{
    const auto& s = town();
    const auto& t = s.truth;
    const auto& cells = town_cells();
    std::vector<std::vector<std::array<double, 3>>> on_plane(t.roof_planes.size());
    for (std::ptrdiff_t r = 0; r < t.g.rows; ++r) {
        for (std::ptrdiff_t c = 0; c < t.g.cols; ++c) {
            const auto id = t.roof_plane_id(r, c);
            if (id == 0) continue;
            // Cells whose 3x3 block is one face: their points lie at least 0.5 m inside the face.
            if (!block_all(t.g.rows, t.g.cols, r, c, [&](auto rr, auto cc) { return t.roof_plane_id(rr, cc) == id; }))
                continue;
            for (const auto i : cells.at(r, c)) {
                if (s.points.classification[i] == las_class::building)
                    on_plane[static_cast<std::size_t>(id - 1)].push_back({s.points.x[i], s.points.y[i], s.points.z[i]});
            }
        }
    }
    std::size_t checked = 0, tilt_off = 0, azimuth_off = 0, large_unchecked = 0;
    for (std::size_t k = 0; k < t.roof_planes.size(); ++k) {
        if (on_plane[k].size() < 20) {
            // Only small faces (hip ends of narrow houses) may lack 20 points well inside them.
            const double horizontal = t.roof_planes[k].area_m2 * std::cos(deg_to_rad(t.roof_planes[k].tilt_deg));
            large_unchecked += horizontal > 30.0;
            continue;
        }
        ++checked;
        const auto fit = fit_plane(on_plane[k]);
        const auto& truth = t.roof_planes[k];
        tilt_off += std::abs(fit.tilt_deg - truth.tilt_deg) > 1.0;
        // Azimuth is undefined on flat roofs (truth: tilt 0, azimuth 0).
        if (truth.tilt_deg > 0) azimuth_off += angle_difference(fit.azimuth_deg, truth.azimuth_deg) > 1.0;
    }
    CHECK(large_unchecked == 0);
    CHECK(checked >= t.roof_planes.size() * 3 / 4);
    CHECK(tilt_off == 0);
    CHECK(azimuth_off == 0);
}

TEST_CASE("synth/town_scene: flat, shed, gable and hip roofs; rotations by 15-degree steps and arbitrary")
{
    const auto& t = town().truth;
    std::vector<std::vector<roof_plane_truth>> by_building(t.footprints.size());
    for (const auto& p : t.roof_planes) by_building[static_cast<std::size_t>(p.building_id - 1)].push_back(p);
    std::size_t flat = 0, shed = 0, gable = 0, hip = 0, stepped = 0, arbitrary = 0;
    for (const auto& planes : by_building) {
        if (planes.size() == 1) (planes[0].tilt_deg == 0 ? flat : shed) += 1;
        if (planes.size() == 2) ++gable;
        if (planes.size() == 4) ++hip;
        for (const auto& p : planes) {
            CHECK(p.tilt_deg >= 0);
            CHECK(p.tilt_deg <= 45);
        }
        if (planes[0].tilt_deg > 0) {
            const double steps = planes[0].azimuth_deg / 15.0;
            (std::abs(steps - std::round(steps)) < 1e-9 ? stepped : arbitrary) += 1;
        }
    }
    CHECK(flat > 0);
    CHECK(shed > 0);
    CHECK(gable > 0);
    CHECK(hip > 0);
    CHECK(flat + shed + gable + hip == t.footprints.size());
    CHECK(stepped > 0);
    CHECK(arbitrary > 0);
}

TEST_CASE("synth/town_scene: sloped areas match the counted faces; walls 3-15 m; roof intensities")
{
    const auto& s = town();
    const auto& t = s.truth;
    std::vector<double> cells_of(t.roof_planes.size(), 0);
    for (const auto id : t.roof_plane_id)
        if (id > 0) cells_of[static_cast<std::size_t>(id - 1)] += 1;
    std::size_t area_off = 0;
    for (std::size_t k = 0; k < t.roof_planes.size(); ++k) {
        const auto& p = t.roof_planes[k];
        const double horizontal = cells_of[k] * t.g.cell * t.g.cell;
        const double expected = p.area_m2 * std::cos(deg_to_rad(p.tilt_deg));
        // Counting 0.5 m cell centres: error about half a cell along the perimeter (< 10 % + 4 m^2 here).
        area_off += std::abs(horizontal - expected) > 0.1 * expected + 4.0;
    }
    CHECK(area_off == 0);
    // Eaves: the lowest roof return of each building stands 3-15 m above the ground under it.
    const auto& cells = town_cells();
    std::vector<double> lowest_roof(t.footprints.size(), 1e9), ground(t.footprints.size(), 0),
        ground_n(t.footprints.size(), 0);
    std::size_t roof_points = 0, roof_intensity_off = 0, multi_on_roofs = 0;
    for (std::ptrdiff_t r = 0; r < t.g.rows; ++r) {
        for (std::ptrdiff_t c = 0; c < t.g.cols; ++c) {
            const auto id = t.building_id(r, c);
            if (id == 0) continue;
            const auto b = static_cast<std::size_t>(id - 1);
            ground[b] += t.ground_z(r, c);
            ground_n[b] += 1;
            for (const auto i : cells.at(r, c)) {
                multi_on_roofs += s.points.number_of_returns[i] > 1;
                if (s.points.classification[i] != las_class::building) continue;
                ++roof_points;
                lowest_roof[b] = std::min(lowest_roof[b], s.points.z[i]);
                roof_intensity_off += s.points.intensity[i] < 30 || s.points.intensity[i] > 121;
            }
        }
    }
    CHECK(roof_points > 5000);
    CHECK(roof_intensity_off == 0);
    CHECK(multi_on_roofs == 0);  // trees never overhang roofs
    std::size_t wall_off = 0;
    for (std::size_t b = 0; b < t.footprints.size(); ++b) {
        const double wall = lowest_roof[b] - ground[b] / ground_n[b];
        // Ground varies by a few decimetres under a footprint; roof points carry +-5 cm noise.
        wall_off += wall < 3.0 - 0.5 || wall > 15.0 + 0.5;
    }
    CHECK(wall_off == 0);
}

TEST_CASE("synth/town_scene: trees near buildings; a road grid")
{
    const auto& s = town();
    const auto& t = s.truth;
    std::size_t tree_points = 0, road_cells = 0, tree_cells_near_buildings = 0;
    for (std::size_t i = 0; i < s.points.size(); ++i) tree_points += s.points.number_of_returns[i] > 1;
    for (std::ptrdiff_t r = 0; r < t.g.rows; ++r) {
        for (std::ptrdiff_t c = 0; c < t.g.cols; ++c) {
            road_cells += t.surface(r, c) == las_class::road_surface;
            if (t.surface(r, c) != las_class::high_vegetation) continue;
            bool near = false;
            for (std::ptrdiff_t dr = -20; dr <= 20 && !near; dr += 4)  // within 10 m
                for (std::ptrdiff_t dc = -20; dc <= 20 && !near; dc += 4)
                    near = t.g.contains(r + dr, c + dc) && t.building_id(r + dr, c + dc) != 0;
            tree_cells_near_buildings += near;
        }
    }
    CHECK(tree_points > 1000);
    CHECK(tree_cells_near_buildings > 500);
    // Four 10 m roads each way across 640 m, minus the crossings: about 4 * 2 * 6400 - 16 * 100 m^2.
    const double road_area = static_cast<double>(road_cells) * t.g.cell * t.g.cell;
    CHECK(road_area == doctest::Approx(8 * 6400.0 - 16 * 100.0).epsilon(0.02));
}
