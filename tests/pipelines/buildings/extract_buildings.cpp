// SPDX-License-Identifier: Apache-2.0
// extract_buildings and ground_model on tiny hand-made rasters: each step's rule, one case at a time.
#include <doctest/doctest.h>

#include "test_values.hpp"

#include <lidarfx/pipelines/buildings/extract_buildings.hpp>
#include <lidarfx/pipelines/buildings/ground_model.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

using namespace lidarfx;

namespace {

/// Flat ground at 100 m, 60 x 60 cells of 0.5 m, with a box of rows [r0, r1) x cols [c0, c1) at 100 + h.
raster<float> box_scene(std::ptrdiff_t r0, std::ptrdiff_t r1, std::ptrdiff_t c0, std::ptrdiff_t c1, float h)
{
    raster<float> z(60, 60, 100.0f);
    for (std::ptrdiff_t r = r0; r < r1; ++r)
        for (std::ptrdiff_t c = c0; c < c1; ++c) z(r, c) = 100.0f + h;
    return z;
}

/// A gable of `tilt` degrees over rows [10, 50) x cols [15, 45), ridge along the rows (north-south), eaves 6 m up.
raster<float> gable_scene(double tilt, double cell)
{
    raster<float> z(60, 60, 100.0f);
    const double slope = std::tan(tilt * 3.14159265358979 / 180.0);
    for (std::ptrdiff_t r = 10; r < 50; ++r) {
        for (std::ptrdiff_t c = 15; c < 45; ++c) {
            const double to_edge =
                std::min(static_cast<double>(c - 15) + 0.5, static_cast<double>(45 - c) - 0.5) * cell;
            z(r, c) = static_cast<float>(106.0 + slope * to_edge);
        }
    }
    return z;
}

/// The local grid of a raster of `cell`-metre cells: column 0 at x = 0, row 0's north edge at y = rows x cell.
grid local_grid(const raster<float>& z, double cell)
{
    return grid{0.0, static_cast<double>(z.rows()) * cell, cell, z.rows(), z.cols()};
}

}  // namespace

TEST_CASE("ground_model: the terrain under a box is the ground around it, and nDSM its height")
{
    const auto z = box_scene(20, 40, 20, 40, 8.0f);
    const auto gm = ground_model(z, 0.5);
    CHECK(gm.object_count == 1);
    CHECK(gm.in_hull(30, 30) == 1);
    CHECK(gm.in_hull(2, 2) == 0);
    CHECK(gm.edges(20, 30) == 1);  // the wall
    CHECK(gm.edges(30, 30) == 0);  // the middle of the flat roof
    CHECK(gm.ground(30, 30) == doctest::Approx(100.0));
    const auto h = ndsm(gm.surface, gm.ground);
    CHECK(h(30, 30) == doctest::Approx(8.0));
    CHECK(h(5, 5) == doctest::Approx(0.0));
}

TEST_CASE("ground_model: flat ground has no edges, holes are filled, all-NaN is refused")
{
    raster<float> z(10, 10, 5.0f);
    z(3, 3) = nan_f;
    const auto gm = ground_model(z, 1.0);
    CHECK(gm.object_count == 0);
    CHECK(gm.surface(3, 3) == doctest::Approx(5.0));
    CHECK(gm.ground(3, 3) == doctest::Approx(5.0));
    const raster<float> none(4, 4, nan_f);
    CHECK_THROWS_WITH_AS(ground_model(none, 1.0), doctest::Contains("no finite cell"), invalid_input);
    ground_model_options bad;
    bad.edge_angle_deg = 90;
    CHECK_THROWS_AS(ground_model(z, 1.0, bad), invalid_input);
}

TEST_CASE("ground_model: replace_ground takes a given terrain and fills its holes by IDW")
{
    const auto z = box_scene(20, 40, 16, 44, 7.0f);
    auto gm = ground_model(z, 0.5);
    raster<float> given(60, 60, 90.0f);
    given(30, 30) = nan_f;
    replace_ground(gm, given, 0.5);
    CHECK(gm.ground(0, 0) == 90.0f);
    CHECK(gm.ground(30, 30) == doctest::Approx(90.0));
    CHECK(gm.surface(30, 30) == 107.0f);  // the surface stays
    const raster<float> none(60, 60, nan_f);
    CHECK_THROWS_WITH_AS(replace_ground(gm, none, 0.5), doctest::Contains("no finite cell"), invalid_input);
    CHECK_THROWS_AS(replace_ground(gm, raster<float>(3, 3, 1.0f), 0.5), invalid_input);
}

TEST_CASE("ground_model: the run argument drives threads, progress and cancellation, never the result")
{
    const auto z = box_scene(20, 40, 20, 40, 8.0f);
    const auto plain = ground_model(z, 0.5);
    std::vector<double> calls;
    const auto reported = ground_model(z, 0.5, {}, {.threads = 3, .progress = [&calls](double f) {
                                                        calls.push_back(f);
                                                        return true;
                                                    }});
    CHECK(calls == std::vector<double>{0.3, 0.5, 1.0});
    CHECK(reported.ground == plain.ground);
    CHECK(reported.in_hull == plain.in_hull);
    int stopped = 0;
    const execution cancel{.threads = 1, .progress = [&stopped](double) {
                               ++stopped;
                               return false;
                           }};
    CHECK_THROWS_WITH_AS(ground_model(z, 0.5, {}, cancel), "ground_model: cancelled", cancelled);
    CHECK(stopped == 1);
    auto terrain = ground_model(z, 0.5);
    CHECK_THROWS_WITH_AS(replace_ground(terrain, raster<float>(60, 60, 90.0f), 0.5, {}, {.threads = -1}),
                         doctest::Contains("run.threads"), invalid_input);
    CHECK_THROWS_WITH_AS(ground_model(z, 0.5, {}, {.threads = -1}), doctest::Contains("run.threads"), invalid_input);
}

TEST_CASE("extract_buildings: one box building: footprint, heights, one flat surface, outline")
{
    const auto z = box_scene(20, 40, 16, 44, 7.0f);  // 10 m x 14 m = 140 m^2
    const auto b = extract_buildings(z, local_grid(z, 0.5));
    REQUIRE(b.buildings.size() == 1);
    REQUIRE(b.surfaces.size() == 1);
    std::size_t cells = 0, wrong = 0;
    for (std::ptrdiff_t r = 0; r < 60; ++r) {
        for (std::ptrdiff_t c = 0; c < 60; ++c) {
            const bool truth = r >= 20 && r < 40 && c >= 16 && c < 44;
            cells += b.building_id(r, c) == 1;
            wrong += (b.building_id(r, c) == 1) != truth;
        }
    }
    CHECK(cells == 560);
    CHECK(wrong == 0);
    const auto& rec = b.buildings[0];
    CHECK(rec.ground_z == doctest::Approx(100.0));
    CHECK(rec.eave_z == doctest::Approx(107.0));
    CHECK(rec.ridge_z == doctest::Approx(107.0));
    CHECK(rec.roof_area_horizontal_m2 == doctest::Approx(140.0));
    CHECK(b.surfaces[0].tilt_deg < 0.5);
    CHECK(b.surfaces[0].building == 1);
    REQUIRE(rec.outline.size() == 1);
    CHECK(rec.outline[0].rings[0].size() == 5);  // a rectangle, closed
    CHECK(rec.outline[0].rings[0][0] == rec.outline[0].rings[0][4]);
}

TEST_CASE("extract_buildings: a gable becomes two surfaces of the right tilt and facing")
{
    for (const double tilt : {15.0, 30.0, 50.0}) {
        CAPTURE(tilt);
        const auto z = gable_scene(tilt, 0.5);
        const auto b = extract_buildings(z, local_grid(z, 0.5));
        REQUIRE(b.buildings.size() == 1);
        REQUIRE(b.surfaces.size() == 2);
        for (const auto& s : b.surfaces) {
            CHECK(std::abs(s.tilt_deg - tilt) < 2.0);
            CHECK(s.area_m2 == doctest::Approx(s.horizontal_area_m2 / std::cos(s.tilt_deg * 3.14159265358979 / 180)));
        }
        // The west face (columns < 30) slopes down to the west: azimuth 270; the east face 90.
        const auto west = b.surface_id(30, 20), east = b.surface_id(30, 40);
        REQUIRE(west != east);
        CHECK(b.surfaces[static_cast<std::size_t>(west - 1)].azimuth_deg == doctest::Approx(270.0).epsilon(0.01));
        CHECK(b.surfaces[static_cast<std::size_t>(east - 1)].azimuth_deg == doctest::Approx(90.0).epsilon(0.01));
        CHECK(b.buildings[0].ridge_z - b.buildings[0].eave_z > 0.8 * 7.0 * std::tan(tilt * 3.14159265358979 / 180.0));
    }
}

TEST_CASE("extract_buildings: vegetation cells and small objects are no buildings")
{
    const auto z = box_scene(20, 40, 16, 44, 7.0f);
    raster<std::uint8_t> veg(60, 60, 0);
    for (std::ptrdiff_t r = 20; r < 40; ++r)
        for (std::ptrdiff_t c = 16; c < 44; ++c) veg(r, c) = 1;
    CHECK(extract_buildings(z, local_grid(z, 0.5), {}, veg).buildings.empty());
    const auto shed = box_scene(20, 30, 20, 30, 3.0f);  // 5 m x 5 m = 25 m^2, 3 m high: a garage or shed
    CHECK(extract_buildings(shed, local_grid(shed, 0.5)).buildings.size() == 1);
    const auto small = box_scene(20, 27, 20, 27, 7.0f);  // 3.5 m x 3.5 m = 12.25 m^2 < 15 m^2
    CHECK(extract_buildings(small, local_grid(small, 0.5)).buildings.empty());
    extract_buildings_options opt;
    opt.candidates.min_area_m2 = 10;
    CHECK(extract_buildings(small, local_grid(small, 0.5), opt).buildings.size() == 1);
}

TEST_CASE("extract_buildings: empty raster, all NaN, one cell, same result for any thread count")
{
    const raster<float> empty(0, 0);
    CHECK(extract_buildings(empty, local_grid(empty, 1.0)).buildings.empty());
    const raster<float> none(5, 5, nan_f);
    CHECK_THROWS_WITH_AS(extract_buildings(none, local_grid(none, 1.0)), doctest::Contains("no finite cell"),
                         invalid_input);
    const raster<float> one(1, 1, 3.0f);
    const auto b1 = extract_buildings(one, local_grid(one, 1.0));
    CHECK(b1.buildings.empty());
    CHECK(b1.ground(0, 0) == 3.0f);
    CHECK_THROWS_AS(extract_buildings(one, local_grid(one, 0.0)), invalid_input);

    const auto z = gable_scene(35.0, 0.5);
    extract_buildings_options many;
    many.run.threads = 3;
    const auto a = extract_buildings(z, local_grid(z, 0.5)), b = extract_buildings(z, local_grid(z, 0.5), many);
    CHECK(a.building_id.size() == b.building_id.size());
    bool same = true;
    for (std::ptrdiff_t i = 0; i < a.building_id.size(); ++i) {
        same = same && a.building_id.data()[i] == b.building_id.data()[i] &&
               a.surface_id.data()[i] == b.surface_id.data()[i];
    }
    CHECK(same);
}

TEST_CASE("extract_buildings: a building cut by the raster's border is kept and flagged as clipped")
{
    raster<float> z = box_scene(20, 36, 24, 40, 7.0f);  // 8 m x 8 m inside the raster
    for (std::ptrdiff_t r = 44; r < 60; ++r)            // one cut by the south border
        for (std::ptrdiff_t c = 10; c < 30; ++c) z(r, c) = 108.0f;
    const auto b = extract_buildings(z, local_grid(z, 0.5));
    REQUIRE(b.buildings.size() == 2);
    const std::int32_t inner = b.building_id(28, 32), south = b.building_id(55, 20);
    REQUIRE(inner > 0);
    REQUIRE(south > 0);
    CHECK(!b.buildings[static_cast<std::size_t>(inner - 1)].clipped);
    CHECK(b.buildings[static_cast<std::size_t>(south - 1)].clipped);
    CHECK(b.buildings[static_cast<std::size_t>(south - 1)].roof_area_horizontal_m2 == doctest::Approx(16 * 20 * 0.25));
}
