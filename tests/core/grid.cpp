// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/core/grid.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

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
    CHECK(g.cell_of(0.0, 10.0) == cell_index{0, 0});  // north-west corner
    CHECK(g.cell_of(1.0, 10.0) == cell_index{0, 1});  // west edge of column 1
    CHECK(g.cell_of(0.0, 9.0) == cell_index{1, 0});   // north edge of row 1
    CHECK(g.cell_of(10.0, 0.0) == cell_index{9, 9});  // far (south-east) corner -> last cell
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
    CHECK(g.cols == 4);  // 2..10, with 10 on the closed east edge
    CHECK(g.rows == 7);  // 20..6
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

TEST_CASE("core/grid: grids above 2^40 cells, or with extents that overflow, are refused")
{
    const std::ptrdiff_t big = std::ptrdiff_t{1} << 32, most = std::numeric_limits<std::ptrdiff_t>::max();
    CHECK_THROWS_WITH_AS((grid{0, 0, 1, big, big}.validate("f")),
                         "f: grid.rows x grid.cols must be <= 2^40 cells (got 4294967296 x 4294967296)", invalid_input);
    CHECK_THROWS_AS((grid{0, 0, 1, most, most}.validate()), invalid_input);
    CHECK_THROWS_AS((grid{0, 0, 1, 0, (std::ptrdiff_t{1} << 40) + 1}.validate()), invalid_input);
    CHECK_NOTHROW((grid{0, 0, 1, std::ptrdiff_t{1} << 20, std::ptrdiff_t{1} << 20}.validate()));
    CHECK_THROWS_AS((grid{0, 0, 1, std::ptrdiff_t{1} << 20, (std::ptrdiff_t{1} << 20) + 1}.validate()), invalid_input);
    // Tiny grids are valid: one cell, none.
    CHECK_NOTHROW((grid{5, 5, 0.5, 1, 1}.validate()));
    CHECK_NOTHROW((grid{5, 5, 0.5, 0, 0}.validate()));
    CHECK_NOTHROW((grid{5, 5, 0.5, 0, 7}.validate()));
    // A corner that is finite but an extent that is not.
    CHECK_THROWS_WITH_AS((grid{0, 0, 1e300, 1, std::ptrdiff_t{1} << 30}.validate("f")),
                         "f: grid extent (x0 + cols * cell, y0 - rows * cell) must be finite", invalid_input);

    const grid g{100.0, 200.0, 0.5, 40, 60};
    CHECK_THROWS_WITH_AS(g.window(0, 0, big, big),
                         "grid::window: nr x nc must be <= 2^40 cells (got 4294967296 x 4294967296)", invalid_input);
    CHECK_THROWS_AS((grid{0, 0, 1e290, 1, 1}.window(0, std::ptrdiff_t{1} << 62, 1, 1)), invalid_input);
    CHECK(g.window(2, 3, 0, 0).size() == 0);
}

TEST_CASE("core/grid: snapped_grid refuses what it cannot represent, naming the bounds and cell_m")
{
    CHECK_THROWS_WITH_AS(snapped_grid({0, 0, 1, 1}, 1e-20),
                         "snapped_grid: cell_m must be >= 2^-36 x the largest |coordinate| of the bounds (got cell_m "
                         "9.9999999999999995e-21 for bounds (0, 0, 1, 1))",
                         invalid_input);
    CHECK_THROWS_WITH_AS(snapped_grid({0, 0, 1e7, 1e7}, 1e-3),
                         "snapped_grid: bounds (0, 0, 10000000, 10000000) at cell_m 0.001 need 10000000000 x "
                         "10000000000 cells, more than 2^40",
                         invalid_input);
    // LAS header bounds near 2^48 (a crafted file): refused, never a grid whose rows * cols wraps.
    const double far = std::ldexp(1.0, 48);
    CHECK_THROWS_AS(snapped_grid({-far, -far, far, far}, 1.0), invalid_input);
    CHECK_THROWS_AS(snapped_grid({0, 0, far, far}, 4096.0), invalid_input);  // fine lattice, 2^36 x 2^36 cells
    CHECK_THROWS_AS(snapped_grid({0, 0, std::numeric_limits<double>::infinity(), 1}, 1.0), invalid_input);
    CHECK_THROWS_AS(snapped_grid({0, 0, 1, 1}, std::numeric_limits<double>::infinity()), invalid_input);
    CHECK_THROWS_AS(snapped_grid({0, 0, 1, 1}, std::numeric_limits<double>::denorm_min()), invalid_input);
    CHECK_THROWS_WITH_AS(snapped_grid({2, 0, 1, 1}, 1.0),
                         "snapped_grid: bounds must be finite with min <= max (got bounds (2, 0, 1, 1))",
                         invalid_input);
    const double top = std::numeric_limits<double>::max();
    CHECK_THROWS_WITH_AS(snapped_grid({-top, 0, -top, 0}, 1e300),
                         "snapped_grid: bounds (-1.7976931348623157e+308, 0, -1.7976931348623157e+308, 0) at cell_m "
                         "1.0000000000000001e+300 give a grid beyond the double range",
                         invalid_input);
    CHECK_THROWS_AS(snapped_grid({-1e308, 0, 1e308, 0}, 1e300), invalid_input);  // xmax - x0 overflows
    const grid vast = snapped_grid({-1e303, -1e303, 1e303, 1e303}, 1e300);
    CHECK(vast.rows == 2000);
    CHECK(vast.cell_of(1e303, -1e303) == cell_index{1999, 1999});
    // At the limit: exactly 2^20 x 2^20 cells is a grid; the smallest cell of these bounds is accepted.
    const grid edge = snapped_grid({0, 0, 1048576, 1048576}, 1.0);
    CHECK(edge.rows == 1048576);
    CHECK(edge.cols == 1048576);
    CHECK_NOTHROW(edge.validate());
    CHECK_THROWS_AS(snapped_grid({0, 0, 1048576.5, 1048576}, 1.0), invalid_input);
    // One point at a tiny cell is one cell; a degenerate box at the origin has no scale to be small against.
    const grid dot = snapped_grid({0, 0, 0, 0}, 1e-300);
    CHECK(dot.rows == 1);
    CHECK(dot.cols == 1);
    CHECK(dot.cell_of(0, 0) == cell_index{0, 0});
}

TEST_CASE("core/grid: one rounding rule - every point of the bounds lands in the snapped grid (property)")
{
    // snapped_grid sizes the grid with the very expressions cell_of tests, so corners, edges and the
    // interior of the bounds always land, whatever the rounding; before, a maximum on a lattice line could
    // fall a hair outside (bounds 1000..1010 at 0.32 m: (y0 - ymin) / cell = 32.000000000000028 > 32 rows).
    const unsigned seed = 20250611;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const std::vector<double> centres{0.0, 1000.0, 2.2e6, 2.5e5, 5.1e6, -7.3e5, -3.0e6};
    const std::vector<double> nice_cells{0.01, 0.14, 0.25, 0.5, 0.59, 1.0, 1.01, 1.18, 2.0, 0.32, 0.64, 5.0};
    long checked_points = 0;
    for (int trial = 0; trial < 6000; ++trial) {
        CAPTURE(seed);
        CAPTURE(trial);
        const double cell = trial % 3 == 0   ? nice_cells[static_cast<std::size_t>(trial / 3) % nice_cells.size()]
                            : trial % 3 == 1 ? std::round(1 + u(rng) * 499) / 100  // 0.01 .. 5 in steps of 0.01
                                             : 0.01 + u(rng) * 4.99;
        const double cx = centres[static_cast<std::size_t>(trial) % centres.size()];
        const double cy = centres[static_cast<std::size_t>(trial / 7) % centres.size()];
        const double w = trial % 11 == 0 ? 0.0 : u(rng) * 2000, h = trial % 13 == 0 ? 0.0 : u(rng) * 2000;
        bounds b{cx + u(rng) * 1000, cy + u(rng) * 1000, 0, 0};
        b.xmax = b.xmin + w;
        b.ymax = b.ymin + h;
        switch (trial % 5) {
            case 1:  // bounds on lattice lines, computed as k * cell (as a header written from a grid would hold)
                b = {std::floor(b.xmin / cell) * cell, std::floor(b.ymin / cell) * cell,
                     std::ceil(b.xmax / cell) * cell, std::ceil(b.ymax / cell) * cell};
                break;
            case 2:  // minimum on a lattice line, the maximum a whole number of cells further (summed, not multiplied)
                b.xmin = std::round(b.xmin / cell) * cell;
                b.ymin = std::round(b.ymin / cell) * cell;
                b.xmax = b.xmin + std::round(w / cell) * cell;
                b.ymax = b.ymin + std::round(h / cell) * cell;
                break;
            case 3:  // decimal bounds (centimetres), as LAS scales make them
                b = {std::round(b.xmin * 100) / 100, std::round(b.ymin * 100) / 100, std::round(b.xmax * 100) / 100,
                     std::round(b.ymax * 100) / 100};
                break;
            default:
                break;
        }
        CAPTURE(cell);
        CAPTURE(b.xmin);
        CAPTURE(b.ymin);
        CAPTURE(b.xmax);
        CAPTURE(b.ymax);
        const grid g = snapped_grid(b, cell);
        REQUIRE_NOTHROW(g.validate());
        // Corners on the lattice, and the grid is the smallest such: the next lattice line east (south) of the
        // corner lies past xmin (ymax), and one row or column less would lose a point.
        CHECK(std::abs(g.x0 / cell - std::round(g.x0 / cell)) < 1e-6);
        CHECK(std::abs(g.y0 / cell - std::round(g.y0 / cell)) < 1e-6);
        CHECK((std::round(g.x0 / cell) + 1) * cell > b.xmin);
        CHECK((std::round(g.y0 / cell) - 1) * cell < b.ymax);
        CHECK((g.cols == 1 || g.to_cell_coords(b.xmax, b.ymin).col > static_cast<double>(g.cols - 1)));
        CHECK((g.rows == 1 || g.to_cell_coords(b.xmax, b.ymin).row > static_cast<double>(g.rows - 1)));

        std::vector<std::array<double, 2>> points{
            {b.xmin, b.ymin}, {b.xmin, b.ymax}, {b.xmax, b.ymin}, {b.xmax, b.ymax}};
        for (int k = 0; k < 8; ++k) {
            const double t = u(rng);
            points.push_back({b.xmin + t * (b.xmax - b.xmin), b.ymin});  // south and north edges
            points.push_back({b.xmin + t * (b.xmax - b.xmin), b.ymax});
            points.push_back({b.xmin, b.ymin + t * (b.ymax - b.ymin)});  // west and east edges
            points.push_back({b.xmax, b.ymin + t * (b.ymax - b.ymin)});
            points.push_back({b.xmin + u(rng) * (b.xmax - b.xmin), b.ymin + u(rng) * (b.ymax - b.ymin)});
            // On an interior lattice line (kept inside the bounds).
            const double lx =
                std::clamp(g.x0 + std::floor(u(rng) * static_cast<double>(g.cols)) * cell, b.xmin, b.xmax);
            const double ly =
                std::clamp(g.y0 - std::floor(u(rng) * static_cast<double>(g.rows)) * cell, b.ymin, b.ymax);
            points.push_back({lx, ly});
        }
        for (const auto& item : points) {
            const auto& x = std::get<0>(item);
            const auto& y = std::get<1>(item);
            CAPTURE(x);
            CAPTURE(y);
            const auto at = g.cell_of(x, y);
            REQUIRE(at);
            CHECK(g.contains(at->row, at->col));
            ++checked_points;
        }
    }
    CHECK(checked_points == 6000 * 52);
}

TEST_CASE("core/grid: every cell size from 0.01 to 5 m covers bounds 1000..1010 x 2000..2010")
{
    const bounds b{1000, 2000, 1010, 2010};
    for (int k = 1; k <= 500; ++k) {
        const double cell = k / 100.0;
        CAPTURE(cell);
        const grid g = snapped_grid(b, cell);
        CHECK(g.cell_of(b.xmax, b.ymin));
        CHECK(g.cell_of(b.xmin, b.ymax));
        CHECK(g.cell_of(b.xmax, b.ymax));
        CHECK(g.cell_of(b.xmin, b.ymin));
    }
    // The cases the old sizing lost: (y0 - ymin) / cell came out a hair above the row count.
    const grid g = snapped_grid(b, 0.32);
    CHECK(g.y0 == 2010.24);
    CHECK(g.rows == 33);  // 32 rows reach down to 2000.0000000000000089 in exact arithmetic, just short of 2000
    CHECK(g.cell_of(1005, 2000) == cell_index{32, 15});
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
    CHECK_THROWS_WITH_AS(from_gdal({0, 1, 0.1, 0, 0, -1}, 2, 2), "from_gdal: rotated geotransforms are not supported",
                         invalid_input);
    CHECK_THROWS_AS(from_gdal({0, 1, 0, 0, 0, 1}, 2, 2), invalid_input);
    CHECK_THROWS_AS(from_gdal({0, 1, 0, 0, 0, -2}, 2, 2), invalid_input);
    CHECK_THROWS_WITH_AS((grid{0, 0, -1, 1, 1}.validate("f")), "f: grid.cell must be finite and > 0 (got -1)",
                         invalid_input);
}
