// SPDX-License-Identifier: Apache-2.0
// The dissertation takes one convex hull per edge object with Boost.Geometry. convex_hull computes it in the
// header (exact integer monotone chain, so the library does not pull Boost.Geometry into every includer); here
// Boost.Geometry's convex_hull is the reference: same area and same vertex set on random and degenerate inputs.
#include <doctest/doctest.h>

#include <lidarfx/core/raster.hpp>
#include <lidarfx/kernels/vector/convex_hull.hpp>

#include <algorithm>
#include <array>
#include <random>
#include <set>
#include <vector>

#include <boost/geometry.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>

namespace {

namespace bg = boost::geometry;
using point = bg::model::d2::point_xy<double>;
using hull_cell = std::array<std::int64_t, 2>;

double area_of(const std::vector<hull_cell>& ring)
{
    double a2 = 0;
    for (std::size_t i = 0; i < ring.size(); ++i) {
        const auto& p = ring[i];
        const auto& q = ring[(i + 1) % ring.size()];
        a2 += static_cast<double>(p[0] * q[1] - q[0] * p[1]);
    }
    return a2 / 2;
}

}  // namespace

TEST_CASE("vector/convex_hull: equals Boost.Geometry's convex hull (area and vertices) on random point sets")
{
    std::mt19937 rng(2024);
    for (int trial = 0; trial < 300; ++trial) {
        const int spread = trial % 3 == 0 ? 3 : 40;  // small spreads give many collinear and repeated points
        std::uniform_int_distribution<std::int64_t> coord(-spread, spread);
        std::vector<hull_cell> pts(static_cast<std::size_t>(3 + trial % 60));
        for (auto& p : pts) p = {coord(rng), coord(rng)};
        const auto hull = lidarfx::convex_hull(pts);

        bg::model::multi_point<point> mp;
        for (const auto& p : pts) bg::append(mp, point(static_cast<double>(p[0]), static_cast<double>(p[1])));
        bg::model::polygon<point, false> ref;  // counter-clockwise, closed
        bg::convex_hull(mp, ref);
        INFO("trial ", trial, " points ", pts.size());
        CHECK(std::abs(area_of(hull)) == doctest::Approx(std::abs(bg::area(ref))));
        if (hull.size() >= 3) {
            CHECK(area_of(hull) > 0);  // counter-clockwise
            // Boost keeps only corners too (no collinear points on the boundary): the same vertex set.
            std::set<hull_cell> ours(hull.begin(), hull.end()), theirs;
            for (const auto& v : ref.outer())
                theirs.insert({static_cast<std::int64_t>(v.x()), static_cast<std::int64_t>(v.y())});
            CHECK(ours == theirs);
        }
    }
}

TEST_CASE("vector/convex_hull: one point, two points, a line")
{
    CHECK(lidarfx::convex_hull({{2, 3}}).size() == 1);
    CHECK(lidarfx::convex_hull({{2, 3}, {2, 3}, {5, 3}}).size() == 2);
    const auto line = lidarfx::convex_hull({{0, 0}, {1, 1}, {2, 2}, {3, 3}});
    CHECK(std::abs(area_of(line)) == 0.0);
}

TEST_CASE("vector/burn_convex: the cells whose centres lie inside or on the hull; a point; a segment")
{
    lidarfx::raster<std::uint8_t> m(6, 6, 0);
    lidarfx::burn_convex(lidarfx::convex_hull({{1, 1}, {4, 1}, {1, 4}}), m.view());  // triangle (col, row)
    int n = 0;
    for (std::ptrdiff_t r = 0; r < 6; ++r)
        for (std::ptrdiff_t c = 0; c < 6; ++c) {
            const bool inside = c >= 1 && r >= 1 && c + r <= 5;
            CHECK(m(r, c) == (inside ? 1 : 0));
            n += m(r, c);
        }
    CHECK(n == 10);
    lidarfx::raster<std::uint8_t> p(4, 4, 0);
    lidarfx::burn_convex({{2, 3}}, p.view());
    CHECK(p(3, 2) == 1);
    lidarfx::burn_convex({{0, 0}, {2, 2}}, p.view());  // the diagonal's cells
    CHECK((p(0, 0) == 1 && p(1, 1) == 1 && p(2, 2) == 1 && p(0, 1) == 0));
}
