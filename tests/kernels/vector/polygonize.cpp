// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/kernels/vector/polygonize.hpp>

#include <cmath>
#include <random>

using namespace lidarfx;

namespace {

double signed_area(const std::vector<std::array<double, 2>>& ring)
{
    double a = 0;
    for (std::size_t i = 0; i + 1 < ring.size(); ++i) a += ring[i][0] * ring[i + 1][1] - ring[i + 1][0] * ring[i][1];
    return a / 2;
}

}  // namespace

TEST_CASE("label/polygonize: a square with a hole, in world coordinates")
{
    raster<std::int32_t> l(5, 5, 0);
    for (int r = 1; r < 4; ++r)
        for (int c = 1; c < 4; ++c) l(r, c) = 7;
    l(2, 2) = 0;
    const grid g{100.0, 50.0, 2.0, 5, 5};
    const auto polys = polygonize(l, g);
    REQUIRE(polys.size() == 1);
    CHECK(polys[0].label == 7);
    REQUIRE(polys[0].polygons.size() == 1);
    const auto& rings = polys[0].polygons[0].rings;
    REQUIRE(rings.size() == 2);
    CHECK(rings[0].size() == 5);  // 4 corners + closing point
    CHECK(rings[0].front() == rings[0].back());
    CHECK(signed_area(rings[0]) == doctest::Approx(36.0));   // 3 x 3 cells of 4 m², counter-clockwise
    CHECK(signed_area(rings[1]) == doctest::Approx(-4.0));   // the hole, clockwise
    for (const auto& p : rings[0]) {
        CHECK((p[0] == 102.0 || p[0] == 108.0));
        CHECK((p[1] == 48.0 || p[1] == 42.0));
    }
}

TEST_CASE("label/polygonize: areas equal cell counts on random labels; corner contacts stay simple")
{
    std::mt19937 rng(11);
    for (int trial = 0; trial < 40; ++trial) {
        const std::ptrdiff_t rows = 1 + rng() % 20, cols = 1 + rng() % 20;
        raster<std::int32_t> l(rows, cols);
        for (auto& v : l) v = static_cast<std::int32_t>(rng() % 3);
        const grid g{0.0, 0.0, 1.5, rows, cols};
        std::vector<double> cells(3, 0);
        for (auto v : l) cells[static_cast<std::size_t>(v)] += 1;
        std::vector<double> area(3, 0);
        for (const auto& lp : polygonize(l, g)) {
            REQUIRE(lp.label > 0);
            for (const auto& poly : lp.polygons) {
                CHECK(signed_area(poly.rings[0]) > 0);
                for (std::size_t k = 0; k < poly.rings.size(); ++k) {
                    if (k > 0) CHECK(signed_area(poly.rings[k]) < 0);
                    area[static_cast<std::size_t>(lp.label)] += signed_area(poly.rings[k]);
                }
            }
        }
        for (int k = 1; k < 3; ++k) CHECK(area[static_cast<std::size_t>(k)] == doctest::Approx(cells[static_cast<std::size_t>(k)] * 2.25));
    }
    CHECK_THROWS_AS(polygonize(raster<std::int32_t>(2, 2), grid{0, 0, 1, 3, 2}), invalid_input);
}
