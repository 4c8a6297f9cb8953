// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/core/grid.hpp>

#include <cmath>
#include <random>

using namespace lidarfx;

TEST_CASE("core/grid: cell centres follow the north-up convention")
{
    const grid g{100.0, 500.0, 2.0, 10, 20};
    const auto [x, y] = g.center(0, 0);
    CHECK(x == 101.0);
    CHECK(y == 499.0);
    const auto [x2, y2] = g.center(9, 19);
    CHECK(x2 == 139.0);
    CHECK(y2 == 481.0);
    CHECK(g.x1() == 140.0);
    CHECK(g.y1() == 480.0);
    CHECK(g.extent() == bounds{100.0, 480.0, 140.0, 500.0});
}

TEST_CASE("core/grid: world <-> cell round trips on random points")
{
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int trial = 0; trial < 200; ++trial) {
        const grid g{1e5 * u(rng), 1e6 * u(rng), 0.25 + 4 * u(rng), 1 + static_cast<std::ptrdiff_t>(50 * u(rng)),
                     1 + static_cast<std::ptrdiff_t>(50 * u(rng))};
        const std::ptrdiff_t r = static_cast<std::ptrdiff_t>(u(rng) * static_cast<double>(g.rows));
        const std::ptrdiff_t c = static_cast<std::ptrdiff_t>(u(rng) * static_cast<double>(g.cols));
        const auto [x, y] = g.center(r, c);
        const auto idx = g.cell_of(x, y);
        REQUIRE(idx);
        CHECK(idx->row == r);
        CHECK(idx->col == c);
        const cell_coords rc = g.to_cell_coords(x, y);
        CHECK(rc.row == doctest::Approx(static_cast<double>(r) + 0.5));
        CHECK(rc.col == doctest::Approx(static_cast<double>(c) + 0.5));
        const auto [wx, wy] = g.to_world(rc);
        CHECK(wx == doctest::Approx(x));  // exact up to rounding of a few flops
        CHECK(wy == doctest::Approx(y));
    }
}

TEST_CASE("core/grid: cell boxes grow cell by cell and map to the world rectangle of their outer edges")
{
    cell_box b;
    CHECK(b.empty());
    CHECK(b.rows() == 0);
    b.extend(3, 5);
    CHECK(b == cell_box{3, 5, 3, 5});
    b.extend(1, 7);
    b.extend(4, 2);
    CHECK(b == cell_box{1, 2, 4, 7});
    CHECK(b.rows() == 4);
    CHECK(b.cols() == 6);
    const grid g{100.0, 50.0, 2.0, 10, 10};
    CHECK(g.extent(b) == bounds{104.0, 40.0, 116.0, 48.0});
    CHECK(g.extent(cell_box{0, 0, 9, 9}) == g.extent());
}

TEST_CASE("core/grid: edges belong to cells as documented; outside and NaN are nowhere")
{
    const grid g{0.0, 10.0, 1.0, 10, 10};
    CHECK(g.cell_of(0.0, 10.0) == cell_index{0, 0});   // north-west corner
    CHECK(g.cell_of(1.0, 10.0) == cell_index{0, 1});   // west edge of column 1
    CHECK(g.cell_of(0.0, 9.0) == cell_index{1, 0});    // north edge of row 1
    CHECK(g.cell_of(10.0, 0.0) == cell_index{9, 9});   // far (south-east) corner -> last cell
    CHECK(g.cell_of(10.0, 5.5) == cell_index{4, 9});
    CHECK_FALSE(g.cell_of(10.0 + 1e-9, 5.0));
    CHECK_FALSE(g.cell_of(-1e-9, 5.0));
    CHECK_FALSE(g.cell_of(5.0, 10.0 + 1e-9));
    CHECK_FALSE(g.cell_of(NAN, 5.0));
    CHECK_FALSE(grid{0, 0, 1, 0, 0}.cell_of(0, 0));
}

TEST_CASE("core/grid: snapped grids sit on multiples of the cell and cover the bounds")
{
    const auto g = snapped_grid({3.2, 7.9, 10.0, 20.0}, 2.0);
    CHECK(g.x0 == 2.0);
    CHECK(g.y0 == 20.0);
    CHECK(g.cols == 4);   // 2..10, with 10 on the closed east edge
    CHECK(g.rows == 7);   // 20..6
    CHECK(g.cell_of(10.0, 7.9));
    CHECK(g.cell_of(3.2, 20.0));
    const auto one = snapped_grid({4.0, 4.0, 4.0, 4.0}, 2.0);
    CHECK(one.rows == 1);
    CHECK(one.cols == 1);
    CHECK(one.cell_of(4.0, 4.0));
    CHECK_THROWS_WITH_AS(snapped_grid({0, 0, 1, 1}, 0.0), "snapped_grid: cell_m must be finite and > 0 (got 0)",
                         invalid_input);
    CHECK_THROWS_AS(snapped_grid({0, 0, NAN, 1}, 1.0), invalid_input);
    CHECK_THROWS_AS(snapped_grid({2, 0, 1, 1}, 1.0), invalid_input);
}

TEST_CASE("core/grid: windows keep the lattice; alignment and offsets")
{
    const grid g{100.0, 200.0, 0.5, 40, 60};
    const grid w = g.window(4, 6, 10, 12);
    CHECK(w.x0 == 103.0);
    CHECK(w.y0 == 198.0);
    CHECK(w.rows == 10);
    CHECK(aligned(g, w));
    CHECK(offset_of(g, w) == cell_index{4, 6});
    CHECK(offset_of(g, g.window(-2, -3, 1, 1)) == cell_index{-2, -3});
    CHECK_FALSE(aligned(g, grid{100.25, 200.0, 0.5, 1, 1}));
    CHECK_FALSE(aligned(g, grid{100.0, 200.0, 1.0, 1, 1}));
    CHECK_THROWS_AS(offset_of(g, grid{100.1, 200.0, 0.5, 1, 1}), invalid_input);
    CHECK_THROWS_AS(g.window(0, 0, -1, 2), invalid_input);
}

TEST_CASE("core/grid: GDAL geotransforms round-trip and bad ones are refused")
{
    const grid g{500000.0, 4100000.0, 2.0, 30, 40};
    CHECK(from_gdal(to_gdal(g), 30, 40) == g);
    CHECK_THROWS_WITH_AS(from_gdal({0, 1, 0.1, 0, 0, -1}, 2, 2),
                         "from_gdal: rotated geotransforms are not supported", invalid_input);
    CHECK_THROWS_AS(from_gdal({0, 1, 0, 0, 0, 1}, 2, 2), invalid_input);
    CHECK_THROWS_AS(from_gdal({0, 1, 0, 0, 0, -2}, 2, 2), invalid_input);
    CHECK_THROWS_WITH_AS((grid{0, 0, -1, 1, 1}.validate("f")), "f: grid.cell must be finite and > 0 (got -1)",
                         invalid_input);
}
