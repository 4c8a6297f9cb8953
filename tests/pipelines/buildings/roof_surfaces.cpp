// SPDX-License-Identifier: Apache-2.0
// The surface steps of extract_buildings on a hand-made gable: grow_roof_surfaces, dissolve_small_surfaces,
// assign_remaining_cells, merge_roof_surfaces and number_roof_surfaces, one rule at a time.
#include <doctest/doctest.h>

#include <lidarfx/pipelines/buildings/grow_roof_surfaces.hpp>
#include <lidarfx/pipelines/buildings/local_planes.hpp>
#include <lidarfx/pipelines/buildings/merge_roof_surfaces.hpp>
#include <lidarfx/pipelines/buildings/number_roof_surfaces.hpp>

#include <cmath>
#include <cstdint>
#include <set>

using namespace lidarfx;

namespace {

constexpr double cell = 0.5;

/// A 30 x 30 raster with building 1 over rows [5, 25) x cols [5, 25): a gable of `tilt` degrees with its ridge
/// north-south (west face down to the west, east face down to the east), or flat at 10 m when tilt is 0.
void gable(double tilt, raster<float>& z, raster<std::int32_t>& id)
{
    z = raster<float>(30, 30, 0.0f);
    id = raster<std::int32_t>(30, 30, 0);
    const double slope = std::tan(tilt * 3.14159265358979 / 180.0);
    for (std::ptrdiff_t r = 5; r < 25; ++r)
        for (std::ptrdiff_t c = 5; c < 25; ++c) {
            const double to_edge = std::min(static_cast<double>(c - 5) + 0.5, static_cast<double>(25 - c) - 0.5) * cell;
            z(r, c) = static_cast<float>(10.0 + slope * to_edge);
            id(r, c) = 1;
        }
}

std::set<std::int32_t> ids_in(const raster<std::int32_t>& region, const raster<std::int32_t>& id)
{
    std::set<std::int32_t> s;
    for (std::ptrdiff_t i = 0; i < id.size(); ++i)
        if (id.data()[i] != 0) s.insert(region.data()[i]);
    return s;
}

}  // namespace

TEST_CASE("buildings/grow_roof_surfaces: a gable grows into two surfaces; every building cell gets one")
{
    raster<float> z;
    raster<std::int32_t> id;
    gable(30.0, z, id);
    const auto lp = local_planes(z, id, cell);
    auto regions = grow_roof_surfaces(z, id, lp, cell);
    CHECK(regions.count >= 2);
    CHECK(regions.region(15, 8) != regions.region(15, 21));
    CHECK(regions.core(15, 8) == 1);
    dissolve_small_surfaces(regions, z, id, 1, cell);
    assign_remaining_cells(regions, z, id, cell);
    const auto s = ids_in(regions.region, id);
    CHECK(s.count(0) == 0);  // every building cell has a surface
    CHECK(regions.region(0, 0) == 0);
    const auto sums = fit_roof_regions(regions, z, cell, false);
    double cells = 0;
    for (std::size_t g = 1; g < sums.size(); ++g) cells += sums[g].n;
    CHECK(cells == 400.0);
}

TEST_CASE("buildings/dissolve_small_surfaces: a building left without a surface becomes one surface")
{
    raster<float> z;
    raster<std::int32_t> id;
    gable(0.0, z, id);
    roof_regions regions{raster<std::int32_t>(30, 30), raster<std::uint8_t>(30, 30), 1};
    regions.region(10, 10) = 1;  // one cell: under min_surface_m2 (4 m^2 = 16 cells)
    regions.core(10, 10) = 1;
    dissolve_small_surfaces(regions, z, id, 1, cell);
    CHECK(regions.count == 1);
    CHECK(ids_in(regions.region, id) == std::set<std::int32_t>{1});
    CHECK(regions.core(10, 10) == 0);
}

TEST_CASE("buildings/merge_roof_surfaces: a flat roof cut in two merges; a gable's faces do not")
{
    raster<float> z;
    raster<std::int32_t> id;
    gable(0.0, z, id);
    roof_regions flat{raster<std::int32_t>(30, 30), raster<std::uint8_t>(30, 30), 2};
    for (std::ptrdiff_t r = 5; r < 25; ++r)
        for (std::ptrdiff_t c = 5; c < 25; ++c) {
            flat.region(r, c) = c < 15 ? 1 : 2;
            flat.core(r, c) = 1;
        }
    merge_roof_surfaces(flat, z, cell);
    CHECK(ids_in(flat.region, id) == std::set<std::int32_t>{1});

    gable(30.0, z, id);
    roof_regions faces = flat;
    for (std::ptrdiff_t r = 5; r < 25; ++r)
        for (std::ptrdiff_t c = 5; c < 25; ++c) faces.region(r, c) = c < 15 ? 1 : 2;
    faces.count = 2;
    merge_roof_surfaces(faces, z, cell);
    CHECK(ids_in(faces.region, id) == std::set<std::int32_t>{1, 2});
}

TEST_CASE("buildings/number_roof_surfaces: largest first; tilt, facing and areas of each plane")
{
    raster<float> z;
    raster<std::int32_t> id;
    gable(30.0, z, id);
    roof_regions faces{raster<std::int32_t>(30, 30), raster<std::uint8_t>(30, 30), 2};
    for (std::ptrdiff_t r = 5; r < 25; ++r)
        for (std::ptrdiff_t c = 5; c < 25; ++c) {
            faces.region(r, c) = c < 15 ? 2 : (r < 15 ? 1 : 2);  // region 2: the west face and half the east
            faces.core(r, c) = 1;
        }
    const auto n = number_roof_surfaces(faces, z, id, cell);
    REQUIRE(n.surfaces.size() == 2);
    CHECK(n.surfaces[0].horizontal_area_m2 == doctest::Approx(300 * cell * cell));
    CHECK(n.surfaces[1].horizontal_area_m2 == doctest::Approx(100 * cell * cell));
    CHECK(n.surface_id(20, 8) == 1);
    CHECK(n.surface_id(8, 20) == 2);
    CHECK(n.surface_id(0, 0) == 0);
    // Surface 2 is the north half of the east face alone: 30 deg, facing east (down-slope to the east).
    CHECK(n.surfaces[1].tilt_deg == doctest::Approx(30.0).epsilon(1e-4));
    CHECK(n.surfaces[1].azimuth_deg == doctest::Approx(90.0).epsilon(1e-4));
    CHECK(n.surfaces[1].area_m2 == doctest::Approx(n.surfaces[1].horizontal_area_m2 / std::cos(3.14159265358979 / 6)));
    CHECK(n.surfaces[1].building == 1);
}
