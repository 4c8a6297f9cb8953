// SPDX-License-Identifier: Apache-2.0
// split_party_walls: a contiguous block split where two roofs do not meet (a height step or a plane break along
// their party wall), never at a ridge, a hip or a valley, never into a chimney or a dormer.
#include <doctest/doctest.h>

#include <lidarfx/pipelines/buildings/extract_buildings.hpp>
#include <lidarfx/pipelines/buildings/party_walls.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <set>

using namespace lidarfx;

namespace {

/// A block of roofs drawn face by face: building ids, roof surfaces (every cell core) and heights, 1 m cells.
struct block_scene {
    raster<std::int32_t> id;
    roof_regions regions;
    raster<float> z;

    block_scene(std::ptrdiff_t rows, std::ptrdiff_t cols) : id(rows, cols), z(rows, cols, 0.0f)
    {
        regions.region = raster<std::int32_t>(rows, cols);
        regions.core = raster<std::uint8_t>(rows, cols, 1);
    }
    /// Roof face `surface` of building b over rows r0..r1, columns c0..c1 (inclusive): z = h + east x col + north
    /// x (-row), so east and north are the rise per metre eastwards and northwards.
    void face(std::int32_t b, std::int32_t surface, std::ptrdiff_t r0, std::ptrdiff_t r1, std::ptrdiff_t c0,
              std::ptrdiff_t c1, double h, double east = 0, double north = 0)
    {
        for (std::ptrdiff_t r = r0; r <= r1; ++r)
            for (std::ptrdiff_t c = c0; c <= c1; ++c) {
                id(r, c) = b;
                regions.region(r, c) = surface;
                z(r, c) = static_cast<float>(h + east * static_cast<double>(c) - north * static_cast<double>(r));
            }
        regions.count = std::max(regions.count, surface);
    }
    /// Heights of a gable over rows r0..r1, columns c0..c1: 10 m at its ridge (column ridge_col) falling 0.6 m per
    /// metre to either side. Its cells from column missed_from on are not core: a face the growth missed.
    void gable(std::ptrdiff_t r0, std::ptrdiff_t r1, std::ptrdiff_t c0, std::ptrdiff_t c1, double ridge_col,
               std::ptrdiff_t missed_from)
    {
        for (std::ptrdiff_t r = r0; r <= r1; ++r)
            for (std::ptrdiff_t c = c0; c <= c1; ++c) {
                z(r, c) = static_cast<float>(10.0 - 0.6 * std::abs(static_cast<double>(c) - ridge_col));
                if (c >= missed_from) regions.core(r, c) = 0;
            }
    }
    party_walls_result split(std::size_t count, const party_walls_options& opt = {})
    {
        return split_party_walls(id.view(), count, regions, z.view(), 1.0, opt);
    }
    std::set<std::int32_t> ids_in(std::ptrdiff_t r0, std::ptrdiff_t r1, std::ptrdiff_t c0, std::ptrdiff_t c1) const
    {
        std::set<std::int32_t> found;
        for (std::ptrdiff_t r = r0; r <= r1; ++r)
            for (std::ptrdiff_t c = c0; c <= c1; ++c) found.insert(id(r, c));
        return found;
    }
};

}  // namespace

TEST_CASE("split_party_walls: two terraced flat roofs 2.5 m apart in height are two buildings, the larger first")
{
    block_scene s(12, 22);
    s.face(1, 1, 1, 10, 1, 8, 8.0);    // 80 cells, low
    s.face(1, 2, 1, 10, 9, 20, 10.5);  // 120 cells, high
    const party_walls_result got = s.split(1);
    CHECK(got.count == 2);
    CHECK(got.split == 1);
    CHECK(s.ids_in(1, 10, 9, 20) == std::set<std::int32_t>{1});
    CHECK(s.ids_in(1, 10, 1, 8) == std::set<std::int32_t>{2});
    CHECK(s.id(0, 0) == 0);
}

TEST_CASE("split_party_walls: roofs at one height, or a step under min_step_m, stay one building")
{
    for (const double step : {0.0, 0.8}) {
        block_scene s(12, 22);
        s.face(1, 1, 1, 10, 1, 8, 8.0);
        s.face(1, 2, 1, 10, 9, 20, 8.0 + step);
        CHECK(s.split(1).count == 1);
        CHECK(s.ids_in(1, 10, 1, 20) == std::set<std::int32_t>{1});
    }
}

TEST_CASE("split_party_walls: a steep gable's ridge and a hip's valley are not walls, at any misplaced boundary")
{
    // A 45 degree gable along the columns: the ridge between rows 5 and 6 is 1 m above either ridge row's centre
    // if the boundary is one cell off; the faces meet there all the same.
    for (const std::ptrdiff_t ridge_row : {5, 6}) {
        block_scene s(13, 20);
        s.face(1, 1, 1, ridge_row, 1, 18, 0.0, 0.0, 1.0);          // rises northwards... towards row 0
        s.face(1, 2, ridge_row + 1, 11, 1, 18, -12.0, 0.0, -1.0);  // rises southwards
        for (std::ptrdiff_t r = 1; r <= 11; ++r)                   // the true roof: ridge at row 5.5
            for (std::ptrdiff_t c = 1; c <= 18; ++c)
                s.z(r, c) = static_cast<float>(10.0 - std::abs(static_cast<double>(r) - 5.5));
        CHECK(s.split(1).count == 1);
    }
}

TEST_CASE("split_party_walls: a very steep gable whose ridge runs between cell centres is one building")
{
    // Slopes of 2 (63 degrees), the ridge at row 5.2: the cells beside it differ by 1.2 m and so do the planes at
    // the boundary's midpoint, yet the planes meet a fifth of a cell away.
    block_scene s(13, 20);
    s.face(1, 1, 1, 5, 1, 18, 0.0);
    s.face(1, 2, 6, 11, 1, 18, 0.0);
    for (std::ptrdiff_t r = 1; r <= 11; ++r)
        for (std::ptrdiff_t c = 1; c <= 18; ++c)
            s.z(r, c) = static_cast<float>(20.0 - 2.0 * std::abs(static_cast<double>(r) - 5.2));
    CHECK(s.split(1).count == 1);
}

TEST_CASE("split_party_walls: two terraced gables of the same pitch with eaves 1.5 m apart are two buildings")
{
    block_scene s(12, 24);
    for (int house = 0; house < 2; ++house) {
        const std::ptrdiff_t c0 = 1 + 11 * house, c1 = c0 + 10;
        const double eave = house == 0 ? 6.0 : 7.5;
        s.face(1, 2 * house + 1, 1, 5, c0, c1, 0.0);
        s.face(1, 2 * house + 2, 6, 10, c0, c1, 0.0);
        for (std::ptrdiff_t r = 1; r <= 10; ++r)
            for (std::ptrdiff_t c = c0; c <= c1; ++c)
                s.z(r, c) = static_cast<float>(eave + 0.7 * (5.0 - std::abs(static_cast<double>(r) - 5.5)));
    }
    const party_walls_result got = s.split(1);
    CHECK(got.count == 2);
    CHECK(s.ids_in(1, 10, 1, 11).size() == 1);
    CHECK(s.ids_in(1, 10, 12, 22).size() == 1);
    CHECK(s.id(3, 1) != s.id(3, 22));
}

TEST_CASE(
    "split_party_walls: a chimney, a dormer or an annex under min_part_m2 stays; a larger raised part is split off")
{
    block_scene s(14, 30);
    s.face(1, 1, 1, 12, 1, 28, 8.0);
    s.face(1, 2, 3, 5, 3, 5, 10.0);     // 9 cells, 2 m up: a chimney
    s.face(1, 3, 6, 10, 20, 24, 10.0);  // 25 cells, 2 m up: under the 30 m^2 of min_part_m2
    CHECK(s.split(1).count == 1);
    CHECK(s.ids_in(1, 12, 1, 28) == std::set<std::int32_t>{1});
    block_scene smaller_parts = s;
    CHECK(smaller_parts.split(1, {.min_part_m2 = 20}).count == 2);

    s.face(1, 3, 6, 11, 20, 25, 10.0);  // 36 cells, 2 m up: a building of its own
    const party_walls_result got = s.split(1);
    CHECK(got.count == 2);
    CHECK(s.ids_in(6, 11, 20, 25) == std::set<std::int32_t>{2});
    CHECK(s.ids_in(3, 5, 3, 5) == std::set<std::int32_t>{1});
}

TEST_CASE("split_party_walls: a roof face the growth missed, given to the neighbour's roof, joins its own house")
{
    // House A: a gable with its ridge between columns 3 and 4 (rows 1-12, columns 1-6), eaves 8.5 m, ridge 9.7 m.
    // Its west face is a surface; its east face was never grown, and its cells were given to the surface of B, a
    // flat roof at 4.5 m that wraps round it (columns 7-20, and row 13 under A). The east face touches B along
    // more cell pairs than it touches its own west face, but only at the ridge do the heights meet.
    block_scene s(15, 22);
    s.face(1, 2, 1, 12, 7, 20, 4.5);
    s.face(1, 2, 13, 13, 1, 6, 4.5);
    s.face(1, 1, 1, 12, 1, 3, 0.0);
    s.face(1, 2, 1, 12, 4, 6, 0.0);
    s.gable(1, 12, 1, 6, 3.5, 4);
    const party_walls_result got = s.split(1);
    CHECK(got.count == 2);
    CHECK(s.ids_in(1, 12, 7, 20) == std::set<std::int32_t>{1});
    CHECK(s.ids_in(13, 13, 1, 6) == std::set<std::int32_t>{1});
    CHECK(s.ids_in(1, 12, 1, 6) == std::set<std::int32_t>{2});
    // The east face's cells now belong to a surface of their own house: the west face's.
    CHECK(s.regions.region(5, 5) == 1);
    CHECK(s.regions.region(5, 10) == 2);
}

TEST_CASE("split_party_walls: roofs whose planes stand apart stay one building where the cells do not step")
{
    // Flat roofs at 8 m (columns 1-10) and 9.5 m (columns 12-20). Column 11 was given to the high roof: rows 1-3
    // at its height (a step of 1.5 m to the low roof), rows 4-10 at 8.6 m, loose (off its plane by more than half
    // a step) and nearer the low roof in height. The planes call the surfaces' boundary a wall; yet between the
    // pieces they leave, the heights step along rows 1-3 only (of rows 1-10): one building.
    block_scene s(12, 22);
    s.face(1, 1, 1, 10, 1, 10, 8.0);
    s.face(1, 2, 1, 10, 11, 20, 9.5);
    for (std::ptrdiff_t r = 1; r <= 10; ++r) {
        s.regions.core(r, 11) = 0;
        if (r > 3) s.z(r, 11) = 8.6f;
    }
    CHECK(s.split(1).count == 1);
    CHECK(s.ids_in(1, 10, 1, 20) == std::set<std::int32_t>{1});
}

TEST_CASE("split_party_walls: a boundary is a wall only when at least min_wall_share of it steps")
{
    // Two flat roofs 1.5 m apart whose boundary cells on the high side (not core: they do not move the plane) step
    // along rows 1-4 only, of rows 1-10: 40 % of the boundary. Rows 5-10 lie 1 m above the low roof there, half
    // a step_m below their own plane: given to it, and no step.
    block_scene s(12, 22);
    s.face(1, 1, 1, 10, 1, 10, 8.0);
    s.face(1, 2, 1, 10, 11, 20, 9.5);
    for (std::ptrdiff_t r = 1; r <= 10; ++r) {
        s.regions.core(r, 11) = 0;
        if (r > 4) s.z(r, 11) = 9.0f;
    }
    block_scene t = s;
    CHECK(s.split(1).count == 1);
    party_walls_options lenient;
    lenient.min_wall_share = 0.3;
    CHECK(t.split(1, lenient).count == 2);
}

TEST_CASE("split_party_walls: after a split every building is numbered by area; a building without walls is whole")
{
    block_scene s(12, 34);
    s.face(1, 1, 1, 10, 1, 8, 8.0);
    s.face(1, 2, 1, 10, 9, 16, 11.0);
    s.face(2, 3, 1, 10, 20, 32, 9.0);  // 130 cells: the largest, one surface
    const party_walls_result got = s.split(2);
    CHECK(got.count == 3);
    CHECK(got.split == 1);
    CHECK(s.ids_in(1, 10, 20, 32) == std::set<std::int32_t>{1});
    CHECK(s.ids_in(1, 10, 1, 8) == std::set<std::int32_t>{2});  // 80 cells, the earlier first cell of two
    CHECK(s.ids_in(1, 10, 9, 16) == std::set<std::int32_t>{3});
}

TEST_CASE("split_party_walls: a building is split by its own walls only, whatever another building holds")
{
    // Building 1: a flat roof at 10 m whose row 6 (a parapet, 2 m higher) was given to it (not core): loose
    // cells that cut the roof in two. It has no wall, so it stays whole, whether or not building 2 far away is
    // a terrace with a 2.5 m step; so does building 3, in two parts apart.
    for (const bool terrace : {false, true}) {
        block_scene s(22, 40);
        s.face(1, 1, 1, 10, 1, 12, 10.0);
        for (std::ptrdiff_t c = 1; c <= 12; ++c) {
            s.z(6, c) = 12.0f;
            s.regions.core(6, c) = 0;
        }
        s.face(2, 2, 1, 10, 20, 28, 8.0);
        s.face(2, 3, 1, 10, 29, 38, terrace ? 10.5 : 8.0);
        s.face(3, 4, 13, 16, 1, 12, 6.0);
        s.face(3, 5, 18, 21, 1, 12, 6.0);
        const party_walls_result got = s.split(3);
        CHECK(got.count == (terrace ? 4u : 3u));
        CHECK(s.ids_in(1, 10, 1, 12).size() == 1);
        CHECK(s.id(13, 1) == s.id(21, 12));
        CHECK(s.id(13, 1) != s.id(2, 2));
    }
}

TEST_CASE("split_party_walls: a part apart from a split block stays with the block's largest building")
{
    block_scene s(20, 20);
    s.face(1, 1, 1, 10, 1, 8, 8.0);    // 80 cells
    s.face(1, 2, 1, 10, 9, 18, 10.5);  // 100 cells: the largest
    s.face(1, 3, 14, 17, 1, 12, 6.0);  // 48 cells, touching neither
    const party_walls_result got = s.split(1);
    CHECK(got.count == 2);
    CHECK(s.id(15, 5) == s.id(5, 12));
    CHECK(s.id(5, 2) != s.id(5, 12));
}

TEST_CASE("split_party_walls: a surface spread over two buildings never joins them")
{
    // Buildings 1 and 2, two columns apart, each a terrace of a low and a high roof; the low halves share region
    // 1 and the high halves region 2 (ids a caller may hand over): four buildings, none spanning the gap.
    block_scene s(12, 30);
    s.face(1, 1, 1, 10, 1, 5, 8.0);
    s.face(1, 2, 1, 10, 6, 10, 11.0);
    s.face(2, 1, 1, 10, 13, 17, 8.0);
    s.face(2, 2, 1, 10, 18, 22, 11.0);
    const party_walls_result got = s.split(2, {.min_part_m2 = 20});
    CHECK(got.count == 4);
    CHECK(s.ids_in(1, 10, 1, 22).size() == 5);  // four buildings and the gap's 0
}

TEST_CASE("split_party_walls: every building keeps a roof surface, and cells outside the split keep theirs")
{
    // House A: a gable over columns 1-8 (ridge between columns 4 and 5), rows 1-12; its west face is surface 1,
    // its east face (48 cells, not core) was given to surface 2, the flat roof of B at 4.5 m (columns 9-11 and
    // row 13: 47 core cells). The east face is most of surface 2's cells, yet surface 2 is B's roof: B keeps it.
    block_scene s(15, 20);
    s.face(1, 2, 1, 12, 9, 11, 4.5);
    s.face(1, 2, 13, 13, 1, 11, 4.5);
    s.face(1, 1, 1, 12, 1, 4, 0.0);
    s.face(1, 2, 1, 12, 5, 8, 0.0);
    s.gable(1, 12, 1, 8, 4.5, 5);
    s.face(2, 3, 1, 6, 15, 18, 7.0);  // building 2: no wall; its cell (6, 18) has no surface and keeps none
    s.regions.region(6, 18) = 0;
    const party_walls_result got = s.split(2);
    REQUIRE(got.split == 1);
    CHECK(s.id(5, 2) == s.id(5, 7));  // A whole
    CHECK(s.id(5, 2) != s.id(5, 10));
    CHECK(s.regions.region(5, 10) == 2);  // B's roof
    CHECK(s.regions.region(5, 7) == 1);   // A's east face joined A's west face
    CHECK(s.regions.region(6, 18) == 0);
    std::map<std::int32_t, std::set<std::int32_t>> buildings_of_surface;
    for (std::ptrdiff_t r = 0; r < 15; ++r)
        for (std::ptrdiff_t c = 0; c < 20; ++c)
            if (s.regions.region(r, c) > 0) buildings_of_surface[s.regions.region(r, c)].insert(s.id(r, c));
    std::set<std::int32_t> surfaced;
    for (const auto& [surface, buildings] : buildings_of_surface) {
        CHECK(buildings.size() == 1);
        surfaced.insert(*buildings.begin());
    }
    CHECK(surfaced.size() == got.count);
}

TEST_CASE("split_party_walls: ids beyond the counts and bad options throw")
{
    block_scene s(12, 34);
    s.face(1, 1, 1, 10, 1, 8, 8.0);
    s.face(1, 2, 1, 10, 9, 16, 11.0);
    block_scene beyond = s;
    beyond.id(0, 33) = 7;
    CHECK_THROWS_AS(beyond.split(1), invalid_input);
    block_scene bad_region = s;
    bad_region.regions.region(0, 33) = 9;
    CHECK_THROWS_AS(bad_region.split(1), invalid_input);
    party_walls_options bad;
    bad.min_step_m = 0;
    CHECK_THROWS_AS(s.split(1, bad), invalid_input);
    bad = {};
    bad.min_wall_share = 1.5;
    CHECK_THROWS_AS(s.split(1, bad), invalid_input);
    bad = {};
    bad.min_part_m2 = -1;
    CHECK_THROWS_AS(s.split(1, bad), invalid_input);
    raster<float> wrong(3, 3);
    CHECK_THROWS_AS(split_party_walls(s.id.view(), 1, s.regions, wrong.view(), 1.0), invalid_input);
    // An infinite step never splits and changes nothing.
    block_scene same = s;
    CHECK(same.split(1, {.min_step_m = std::numeric_limits<double>::infinity()}).count == 1);
    CHECK(same.id == s.id);
    CHECK(same.regions.region == s.regions.region);
}

TEST_CASE("extract_buildings: a terrace of three flat-roofed houses 2 m apart in height is three buildings")
{
    // 1 m cells; flat ground at 0; houses 8 x 10 m side by side at eaves 6, 8 and 6 m.
    const std::ptrdiff_t rows = 30, cols = 44;
    raster<float> dsm(rows, cols, 0.0f), ground(rows, cols, 0.0f);
    const double heights[3] = {6.0, 8.0, 6.0};
    for (int house = 0; house < 3; ++house)
        for (std::ptrdiff_t r = 10; r < 20; ++r)
            for (std::ptrdiff_t c = 10 + 8 * house; c < 18 + 8 * house; ++c)
                dsm(r, c) = static_cast<float>(heights[house]);
    const grid g{0.0, static_cast<double>(rows), 1.0, rows, cols};
    const extract_buildings_result split = extract_buildings(dsm, g, ground.view());
    REQUIRE(split.buildings.size() == 3);
    CHECK(split.building_id(15, 12) != split.building_id(15, 20));
    CHECK(split.building_id(15, 20) != split.building_id(15, 30));
    CHECK(split.building_id(15, 12) != split.building_id(15, 30));
    // Each roof surface lies in one building, and each building has a surface.
    std::map<std::int32_t, std::set<std::int32_t>> buildings_of_surface;
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c)
            if (split.surface_id(r, c) > 0)
                buildings_of_surface[split.surface_id(r, c)].insert(split.building_id(r, c));
    for (const auto& [surface, buildings] : buildings_of_surface) CHECK(buildings.size() == 1);
    for (const building_record& b : split.buildings) CHECK(!b.surfaces.empty());

    extract_buildings_options whole;
    whole.party_walls.min_step_m = std::numeric_limits<double>::infinity();
    const extract_buildings_result block =
        extract_buildings(dsm, g, ground.view(), raster_view<const std::uint8_t>{}, whole);
    CHECK(block.buildings.size() == 1);
}
