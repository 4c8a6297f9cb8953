// SPDX-License-Identifier: Apache-2.0
// join_roof_under_crowns: the roof hidden under an overhanging crown joins its building when the lowest of its
// cells' raised points lies on the roof's plane.
#include <doctest/doctest.h>

#include <lidarfx/pipelines/buildings/roof_under_crowns.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

using namespace lidarfx;

namespace {

/// A scene of the step: ids, the surface (DSM), local plane slopes of the building cells, and per cell the lowest
/// raised point, the points and the raised points.
struct crown_scene {
    raster<std::int32_t> id;
    raster<float> surface;
    local_planes_result planes;
    raster<float> lowest;
    raster<std::uint32_t> points, raised;

    crown_scene(std::ptrdiff_t rows, std::ptrdiff_t cols)
        : id(rows, cols),
          surface(rows, cols, 0.0f),
          planes{raster<float>(rows, cols, 0.0f), raster<float>(rows, cols, 0.0f), raster<float>(rows, cols, 0.0f)},
          lowest(rows, cols, std::numeric_limits<float>::quiet_NaN()),
          points(rows, cols, 10u),
          raised(rows, cols, 0u)
    {
    }
    /// Roof cells of building b on the plane z = z0 + a x + b y (x east = column, y north = -row; 1 m cells), every
    /// point raised and the lowest on the plane.
    void roof(std::int32_t b, double z0, double a, double slope_north, std::ptrdiff_t r0, std::ptrdiff_t r1,
              std::ptrdiff_t c0, std::ptrdiff_t c1)
    {
        for (std::ptrdiff_t r = r0; r <= r1; ++r)
            for (std::ptrdiff_t c = c0; c <= c1; ++c) {
                id(r, c) = b;
                surface(r, c) = static_cast<float>(plane_at(z0, a, slope_north, r, c));
                planes.a(r, c) = static_cast<float>(a), planes.b(r, c) = static_cast<float>(slope_north);
                lowest(r, c) = surface(r, c);
                raised(r, c) = points(r, c);
            }
    }
    static double plane_at(double z0, double a, double slope_north, std::ptrdiff_t r, std::ptrdiff_t c)
    {
        return z0 + a * static_cast<double>(c) - slope_north * static_cast<double>(r);
    }
    /// A cell under a crown: its highest return at crown_z, `raised` of its points raised, the lowest at low_z.
    void covered(std::ptrdiff_t r, std::ptrdiff_t c, double crown_z, double low_z, std::uint32_t raised_points = 10)
    {
        surface(r, c) = static_cast<float>(crown_z);
        lowest(r, c) = static_cast<float>(low_z);
        raised(r, c) = raised_points;
    }
    roof_under_crowns_result join(std::size_t count, const roof_under_crowns_options& opt = {})
    {
        return join_roof_under_crowns(id.view(), count, surface.view(), planes, lowest.view(), points.view(),
                                      raised.view(), 1.0, opt);
    }
};

}  // namespace

TEST_CASE("join_roof_under_crowns: a flat roof's strip under a crown joins; the crown beyond the wall does not")
{
    crown_scene s(10, 13);
    s.roof(1, 6.0, 0, 0, 2, 7, 2, 6);
    // Columns 7-9: the roof under a crown (foliage at 11 m, the lowest raised point on the roof, within 5 cm).
    for (std::ptrdiff_t r = 2; r <= 7; ++r)
        for (std::ptrdiff_t c = 7; c <= 9; ++c) s.covered(r, c, 11.0, 6.0 + 0.05 * ((r + c) % 2 ? 1 : -1));
    // Column 10, beyond the wall: a branch 2 m above the roof (all raised), the roof's height with the pulses that
    // pass the foliage ending on the ground (6 of 10 raised), and a cell without points.
    s.covered(2, 10, 11.0, 8.0);
    s.covered(3, 10, 11.0, 6.0, 6);
    s.covered(4, 10, 11.0, 6.0);
    s.points(4, 10) = 0, s.raised(4, 10) = 0;
    const roof_under_crowns_result got = s.join(1);
    CHECK(got.cells.size() == 18);
    for (std::ptrdiff_t r = 2; r <= 7; ++r)
        for (std::ptrdiff_t c = 7; c <= 9; ++c) {
            CHECK(s.id(r, c) == 1);
            CHECK(s.surface(r, c) == 6.0f);  // the roof's plane, not the crown or the return's noise
        }
    CHECK(s.id(2, 10) == 0);
    CHECK(s.id(3, 10) == 0);
    CHECK(s.id(4, 10) == 0);
    CHECK(s.surface(2, 10) == 11.0f);  // cells left out keep their surface
}

TEST_CASE("join_roof_under_crowns: the roof's plane is carried under the crown, and stops past a ridge")
{
    // A roof rising east by 0.5 m a metre (26.6 deg), columns 1-5 open; columns 6-8 under a crown, their lowest
    // raised points a quarter metre below the plane at the centre (a cell's low side); column 9 falls again (the
    // other face of a ridge at column 8.5): 1.5 m below the plane carried on.
    crown_scene s(6, 11);
    s.roof(1, 3.0, 0.5, 0.0, 1, 4, 1, 5);
    for (std::ptrdiff_t r = 1; r <= 4; ++r) {
        for (std::ptrdiff_t c = 6; c <= 8; ++c) s.covered(r, c, 12.0, crown_scene::plane_at(3.0, 0.5, 0, r, c) - 0.25);
        s.covered(r, 9, 12.0, crown_scene::plane_at(3.0, 0.5, 0, r, 9) - 1.5);
    }
    CHECK(s.join(1).cells.size() == 12);
    for (std::ptrdiff_t r = 1; r <= 4; ++r) {
        for (std::ptrdiff_t c = 6; c <= 8; ++c) {
            CHECK(s.id(r, c) == 1);
            // The roof's plane carried on.
            CHECK(s.surface(r, c) == doctest::Approx(crown_scene::plane_at(3.0, 0.5, 0, r, c)).epsilon(1e-6));
        }
        CHECK(s.id(r, 9) == 0);
    }
    // No drift: lowest points falling 0.25 m a cell (a crown's underside, a slope) join only while they stay within
    // the tolerance of the roof's own plane, not of the cell joined before them.
    crown_scene d(5, 10);
    d.roof(1, 6.0, 0, 0, 1, 3, 1, 3);
    for (std::ptrdiff_t c = 4; c <= 8; ++c) d.covered(2, c, 12.0, 6.0 - 0.25 * static_cast<double>(c - 3));
    CHECK(d.join(1).cells.size() == 1);
    CHECK(d.id(2, 4) == 1);
    CHECK(d.id(2, 5) == 0);
    // The tolerance: a flat plane carried 0.35 m off joins with plane_tolerance_m 0.4, not with 0.3.
    for (const double tolerance : {0.3, 0.4}) {
        crown_scene t(5, 6);
        t.roof(1, 6.0, 0, 0, 1, 3, 1, 3);
        t.covered(2, 4, 10.0, 6.35);
        t.join(1, {.plane_tolerance_m = tolerance});
        CHECK(t.id(2, 4) == (tolerance > 0.35 ? 1 : 0));
    }
}

TEST_CASE("join_roof_under_crowns: a crown wider than max_reach_m keeps its far cells; 0 turns the step off")
{
    for (const double reach : {0.0, 2.0, 6.0}) {
        crown_scene s(5, 12);
        s.roof(1, 6.0, 0, 0, 1, 3, 1, 2);
        for (std::ptrdiff_t c = 3; c <= 10; ++c) s.covered(2, c, 11.0, 6.0);
        const auto got = s.join(1, {.max_reach_m = reach});
        CHECK(got.cells.size() == static_cast<std::size_t>(reach));
        CHECK(s.id(2, 3) == (reach > 0 ? 1 : 0));
        CHECK(s.id(2, 4) == (reach >= 2 ? 1 : 0));
        CHECK(s.id(2, 5) == (reach >= 3 ? 1 : 0));
    }
}

TEST_CASE("join_roof_under_crowns: between two buildings a cell takes the plane that fits best, then the lowest id")
{
    crown_scene s(5, 9);
    s.roof(1, 6.0, 0, 0, 1, 3, 1, 3);
    s.roof(2, 6.25, 0, 0, 1, 3, 5, 7);
    s.covered(1, 4, 11.0, 6.1875);  // 0.1875 from 1, 0.0625 from 2
    s.covered(2, 4, 11.0, 6.125);   // 0.125 from either: the lowest id
    s.join(2);
    CHECK(s.id(1, 4) == 2);
    CHECK(s.id(2, 4) == 1);
    // Ids beyond count keep their cells and take none.
    crown_scene t(5, 9);
    t.roof(1, 6.0, 0, 0, 1, 3, 1, 3);
    t.roof(7, 6.0, 0, 0, 1, 3, 6, 7);
    t.covered(2, 4, 11.0, 6.0);
    t.covered(2, 5, 11.0, 6.0);
    CHECK(t.join(1).cells.size() == 2);
    CHECK(t.id(2, 4) == 1);
    CHECK(t.id(2, 5) == 1);  // joined from building 1 in the second round, not from 7
    CHECK(t.id(2, 6) == 7);
}

TEST_CASE("join_roof_under_crowns: a scene and its transpose give transposed buildings and surfaces")
{
    std::mt19937 rng(20261207);
    std::uniform_real_distribution<double> u(0, 1);
    std::size_t joined_in_all = 0;
    for (int trial = 0; trial < 30; ++trial) {
        const std::ptrdiff_t n = 14, m = 11;
        crown_scene s(n, m);
        for (int b = 1; b <= 3; ++b) {
            const auto r0 = static_cast<std::ptrdiff_t>(u(rng) * (n - 4)),
                       c0 = static_cast<std::ptrdiff_t>(u(rng) * (m - 4));
            s.roof(b, 4 + 4 * u(rng), u(rng) - 0.5, u(rng) - 0.5, r0, r0 + 2, c0, c0 + 2);
        }
        for (std::ptrdiff_t r = 0; r < n; ++r)
            for (std::ptrdiff_t c = 0; c < m; ++c)
                if (s.id(r, c) == 0 && u(rng) < 0.7) s.covered(r, c, 14.0, 3 + 6 * u(rng), u(rng) < 0.8 ? 10 : 8);
        // Transposed: row r, column c becomes row c, column r; x' = -y and y' = -x, so a' = -b and b' = -a.
        crown_scene t(m, n);
        for (std::ptrdiff_t r = 0; r < n; ++r)
            for (std::ptrdiff_t c = 0; c < m; ++c) {
                t.id(c, r) = s.id(r, c), t.surface(c, r) = s.surface(r, c), t.lowest(c, r) = s.lowest(r, c);
                t.points(c, r) = s.points(r, c), t.raised(c, r) = s.raised(r, c);
                t.planes.a(c, r) = -s.planes.b(r, c), t.planes.b(c, r) = -s.planes.a(r, c);
            }
        const auto joined = s.join(3, {.plane_tolerance_m = 1.0});
        CHECK(t.join(3, {.plane_tolerance_m = 1.0}).cells.size() == joined.cells.size());
        bool same = true;
        for (std::ptrdiff_t r = 0; r < n; ++r)
            for (std::ptrdiff_t c = 0; c < m; ++c)
                same = same && t.id(c, r) == s.id(r, c) && t.surface(c, r) == s.surface(r, c);
        CHECK(same);
        joined_in_all += joined.cells.size();
    }
    CHECK(joined_in_all > 30);  // the scenes join cells: the comparison is not of untouched rasters
}

TEST_CASE("join_roof_under_crowns: shapes, counts and options out of range are refused")
{
    crown_scene s(4, 4);
    CHECK_THROWS_AS(s.join(1, {.plane_tolerance_m = -1}), invalid_input);
    CHECK_THROWS_AS(s.join(1, {.max_reach_m = std::nan("")}), invalid_input);
    CHECK_THROWS_AS(s.join(1, {.min_raised_share = 0}), invalid_input);
    CHECK_THROWS_AS(s.join(1, {.min_raised_share = 1.5}), invalid_input);
    s.raised(1, 1) = 11;  // more raised points than points
    CHECK_THROWS_AS(s.join(1), invalid_input);
    s.raised(1, 1) = 0;
    raster<float> wrong(4, 5);
    CHECK_THROWS_AS(join_roof_under_crowns(s.id.view(), 1, s.surface.view(), s.planes, wrong.view(), s.points.view(),
                                           s.raised.view(), 1.0),
                    invalid_input);
    CHECK_THROWS_AS(join_roof_under_crowns(s.id.view(), 1, s.surface.view(), s.planes, s.lowest.view(), s.points.view(),
                                           s.raised.view(), 0.0),
                    invalid_input);
}
