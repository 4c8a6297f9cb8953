// SPDX-License-Identifier: Apache-2.0
// refine_building_rim: the one-cell rim of a building decided by the share of its points raised above the terrain;
// classified_building_parts: the parts of a vendor's building cells.
#include <doctest/doctest.h>

#include <lidarfx/pipelines/buildings/building_candidates.hpp>
#include <lidarfx/pipelines/buildings/building_rim.hpp>

#include <cstdint>
#include <random>
#include <vector>

using namespace lidarfx;

namespace {

/// A scene of the rim step: ids, surface heights, points and raised points per cell.
struct rim_scene {
    raster<std::int32_t> id;
    raster<float> z;
    raster<std::uint32_t> points, raised;

    rim_scene(std::ptrdiff_t rows, std::ptrdiff_t cols)
        : id(rows, cols), z(rows, cols, 0.0f), points(rows, cols, 10u), raised(rows, cols, 0u)
    {
    }
    /// A flat roof of building b, height h, rows r0..r1 and columns c0..c1 (inclusive), every point raised.
    void roof(std::int32_t b, float h, std::ptrdiff_t r0, std::ptrdiff_t r1, std::ptrdiff_t c0, std::ptrdiff_t c1)
    {
        for (std::ptrdiff_t r = r0; r <= r1; ++r)
            for (std::ptrdiff_t c = c0; c <= c1; ++c) id(r, c) = b, z(r, c) = h, raised(r, c) = points(r, c);
    }
    building_rim_result refine(std::size_t count, const building_rim_options& opt = {})
    {
        return refine_building_rim(id.view(), count, z.view(), points.view(), raised.view(), opt);
    }
};

}  // namespace

TEST_CASE("refine_building_rim: a wall's cell whose points lie mostly on the ground leaves the building")
{
    rim_scene s(8, 8);
    s.roof(1, 6.0f, 2, 5, 2, 5);
    s.raised(2, 3) = 4;  // 4 of 10 raised: the wall's foot holds most points
    s.raised(2, 4) = 5;  // half raised: stays
    s.raised(3, 3) = 0;  // inside the building (no neighbour outside): stays whatever its points
    const building_rim_result got = s.refine(1);
    CHECK(got.left == 1);
    CHECK(got.joined == 0);
    CHECK(s.id(2, 3) == 0);
    CHECK(s.id(2, 4) == 1);
    CHECK(s.id(3, 3) == 1);
}

TEST_CASE(
    "refine_building_rim: an eave cell of raised points at the roof's height joins; a crown or the ground does not")
{
    rim_scene s(8, 9);
    s.roof(1, 6.0f, 2, 5, 2, 5);
    // Beside the roof, column 6: an eave (raised, 0.3 m lower), a crown (raised, 2 m higher), a cell at the roof's
    // height with few raised points, and a cell without points.
    s.z(2, 6) = 5.7f, s.raised(2, 6) = 7;
    s.z(3, 6) = 8.0f, s.raised(3, 6) = 10;
    s.z(4, 6) = 6.0f, s.raised(4, 6) = 3;
    s.z(5, 6) = 6.0f, s.points(5, 6) = 0;
    // Two cells from the roof: no building beside it.
    s.z(2, 7) = 6.0f, s.raised(2, 7) = 10;
    const building_rim_result got = s.refine(1);
    CHECK(got.joined == 1);
    CHECK(s.id(2, 6) == 1);
    CHECK(s.id(3, 6) == 0);
    CHECK(s.id(4, 6) == 0);
    CHECK(s.id(5, 6) == 0);
    CHECK(s.id(2, 7) == 0);
    // join_height_m decides how far in height an eave may lie from the roof beside it.
    rim_scene t(8, 9);
    t.roof(1, 6.0f, 2, 5, 2, 5);
    t.z(2, 6) = 5.2f, t.raised(2, 6) = 10;
    t.refine(1);
    CHECK(t.id(2, 6) == 0);
    t.refine(1, {.join_height_m = 1.0});
    CHECK(t.id(2, 6) == 1);
}

TEST_CASE("refine_building_rim: no cell joins through a wall's cell that leaves, and other ids are left alone")
{
    rim_scene s(10, 10);
    s.roof(1, 6.0f, 3, 7, 2, 7);
    for (std::ptrdiff_t c = 2; c <= 7; ++c) s.raised(3, c) = 2;  // the north row: a wall's cells, they leave
    for (std::ptrdiff_t c = 2; c <= 7; ++c)
        s.z(2, c) = 6.0f, s.raised(2, c) = 10;  // beyond it, at the roof's height: touches only leaving cells
    s.id(8, 4) = 5, s.z(8, 4) = 6.0f, s.raised(8, 4) = 10;  // an id beyond count under the south edge, raised
    const building_rim_result got = s.refine(1);
    for (std::ptrdiff_t c = 2; c <= 7; ++c) {
        CHECK(s.id(3, c) == 0);
        CHECK(s.id(2, c) == 0);
    }
    CHECK(s.id(8, 4) == 5);
    CHECK(got.left == 6);
    CHECK(got.joined == 0);
}

TEST_CASE("refine_building_rim: a cell across a corner joins only beside a cell of the building across an edge")
{
    rim_scene s(8, 8);
    s.roof(1, 6.0f, 2, 5, 2, 5);
    s.z(1, 1) = 6.0f, s.raised(1, 1) = 10;  // the corner alone: would touch the building at a corner only
    s.z(6, 6) = 6.0f, s.raised(6, 6) = 10;  // the opposite corner, with the cell above it joining across an edge
    s.z(6, 5) = 6.0f, s.raised(6, 5) = 10;
    s.refine(1);
    CHECK(s.id(1, 1) == 0);
    CHECK(s.id(6, 5) == 1);
    CHECK(s.id(6, 6) == 1);
}

TEST_CASE("refine_building_rim: between two buildings a cell takes the one closest in height")
{
    // A closer building across a corner does not keep a cell from the building across an edge.
    rim_scene e(8, 9);
    e.roof(1, 6.0f, 1, 3, 1, 3);  // across a corner of (4, 4), 0.1 m away
    e.roof(2, 6.4f, 4, 6, 5, 7);  // across an edge of (4, 4), 0.3 m away
    e.z(4, 4) = 6.1f, e.raised(4, 4) = 10;
    e.refine(2);
    CHECK(e.id(4, 4) == 2);

    rim_scene s(6, 9);
    s.roof(1, 6.0f, 1, 4, 1, 3);
    s.roof(2, 6.4f, 1, 4, 5, 7);
    s.z(2, 4) = 6.3f, s.raised(2, 4) = 10;  // 0.3 m from building 1, 0.1 m from building 2
    s.z(3, 4) = 6.2f, s.raised(3, 4) = 10;  // 0.2 m from both: the lower id
    s.refine(2);
    CHECK(s.id(2, 4) == 2);
    CHECK(s.id(3, 4) == 1);
}

TEST_CASE("refine_building_rim: a cell cut off by the leaving cells leaves; a building keeps its last cell")
{
    rim_scene s(9, 9);
    s.roof(1, 6.0f, 2, 6, 2, 6);
    s.roof(1, 6.0f, 1, 1, 4, 4);  // one cell above the roof's edge, held by (2, 4) only
    s.raised(2, 4) = 2;           // (2, 4) is a wall's cell: it leaves, and (1, 4) is cut off
    const building_rim_result got = s.refine(1);
    CHECK(s.id(2, 4) == 0);
    CHECK(s.id(1, 4) == 0);
    CHECK(got.left == 2);

    rim_scene tiny(5, 5);
    tiny.roof(1, 6.0f, 2, 2, 2, 2);
    tiny.raised(2, 2) = 0;
    tiny.refine(1);
    CHECK(tiny.id(2, 2) == 1);
}

TEST_CASE("refine_building_rim: the result does not depend on the order of the cells (a transposed scene)")
{
    std::mt19937 rng(20261206);
    for (int trial = 0; trial < 30; ++trial) {
        rim_scene s(24, 24), t(24, 24);
        std::uniform_int_distribution<int> pos(1, 16), len(2, 6), share(0, 10);
        for (std::int32_t b = 1; b <= 3; ++b) {
            const int r0 = pos(rng), c0 = pos(rng), h = len(rng), w = len(rng);
            s.roof(b, 5.0f + static_cast<float>(b) * 0.2f, r0, r0 + h, c0, c0 + w);
        }
        for (std::ptrdiff_t r = 0; r < 24; ++r)
            for (std::ptrdiff_t c = 0; c < 24; ++c) {
                if (s.id(r, c) == 0) s.z(r, c) = 5.0f + 0.1f * static_cast<float>(share(rng));
                s.raised(r, c) = static_cast<std::uint32_t>(share(rng));
            }
        for (std::ptrdiff_t r = 0; r < 24; ++r)
            for (std::ptrdiff_t c = 0; c < 24; ++c)
                t.id(c, r) = s.id(r, c), t.z(c, r) = s.z(r, c), t.points(c, r) = s.points(r, c),
                        t.raised(c, r) = s.raised(r, c);
        const building_rim_result a = s.refine(3), b = t.refine(3);
        CHECK(a.joined == b.joined);
        CHECK(a.left == b.left);
        for (std::ptrdiff_t r = 0; r < 24; ++r)
            for (std::ptrdiff_t c = 0; c < 24; ++c) CHECK(t.id(c, r) == s.id(r, c));
    }
}

TEST_CASE("refine_building_rim: options, shapes and counts out of range are refused")
{
    rim_scene s(4, 4);
    CHECK_THROWS_AS(s.refine(1, {.min_raised_share = 0.0}), invalid_input);
    CHECK_THROWS_AS(s.refine(1, {.min_raised_share = 1.5}), invalid_input);
    CHECK_THROWS_AS(s.refine(1, {.join_height_m = -0.1}), invalid_input);
    s.raised(1, 1) = 11;  // more raised points than points
    CHECK_THROWS_AS(s.refine(1), invalid_input);
    raster<float> z(4, 5);
    CHECK_THROWS_AS(refine_building_rim(s.id.view(), 1, z.view(), s.points.view(), s.raised.view()), invalid_input);
}

TEST_CASE("drop_small_pieces: pieces under the minimum go; the buildings left are numbered by area")
{
    raster<std::int32_t> id(6, 12);
    // Building 1: a piece of 4 cells and a piece of 1; building 2: 6 cells; building 3: 2 cells.
    for (std::ptrdiff_t c = 0; c < 4; ++c) id(0, c) = 1;
    id(2, 0) = 1;
    for (std::ptrdiff_t c = 5; c < 11; ++c) id(4, c) = 2;
    id(2, 8) = 3, id(2, 9) = 3;
    id(5, 0) = 7;  // an id beyond count: left as it is
    const std::size_t kept = detail::drop_small_pieces(id.view(), 3, 3);
    CHECK(kept == 2);
    CHECK(id(4, 5) == 1);  // the largest building is now 1
    CHECK(id(0, 0) == 2);
    CHECK(id(2, 0) == 0);
    CHECK(id(2, 8) == 0);
    CHECK(id(5, 0) == 7);
}

TEST_CASE("classified_building_parts: the mask's parts, holes and parts under the minimum as for candidates")
{
    raster<std::uint8_t> cells(12, 20);
    for (std::ptrdiff_t r = 1; r <= 8; ++r)
        for (std::ptrdiff_t c = 1; c <= 8; ++c) cells(r, c) = 1;  // 64 cells with a hole of 4
    for (std::ptrdiff_t r = 4; r <= 5; ++r)
        for (std::ptrdiff_t c = 4; c <= 5; ++c) cells(r, c) = 0;
    for (std::ptrdiff_t r = 1; r <= 10; ++r)
        for (std::ptrdiff_t c = 11; c <= 17; ++c) cells(r, c) = 1;  // 70 cells: the largest
    cells(11, 1) = cells(11, 2) = 1;                                // 2 cells: under the minimum
    const building_candidates_result parts = classified_building_parts(cells, 1.0, {.min_area_m2 = 15.0});
    CHECK(parts.count == 2);
    CHECK(parts.building_id(5, 14) == 1);
    CHECK(parts.building_id(1, 1) == 2);
    CHECK(parts.building_id(4, 4) == 2);  // the hole of 4 m^2 filled
    CHECK(parts.building_id(11, 1) == 0);
    const building_candidates_result big_holes = classified_building_parts(cells, 1.0, {.min_area_m2 = 4.0});
    CHECK(big_holes.building_id(4, 4) == 0);  // a hole of the minimum stays a courtyard
    CHECK(big_holes.count == 2);
    CHECK_THROWS_AS(classified_building_parts(cells, 0.0), invalid_input);
}
