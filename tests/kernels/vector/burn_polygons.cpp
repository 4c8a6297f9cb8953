// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/kernels/vector/burn_polygons.hpp>
#include <lidarfx/kernels/vector/polygonize.hpp>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

using namespace lidarfx;

namespace {

using ring_t = std::vector<std::array<double, 2>>;

/// Even-odd point-in-polygon by the half-open crossing rule, straight from the definition.
bool contains(const std::vector<polygon>& parts, double x, double y)
{
    bool inside = false;
    for (const polygon& p : parts)
        for (const ring_t& ring : p.rings)
            for (std::size_t i = 0, n = ring.size(); i < n; ++i) {
                const auto& a = ring[i];
                const auto& b = ring[(i + 1) % n];
                if ((a[1] > y) == (b[1] > y)) continue;
                if (a[0] + (y - a[1]) * (b[0] - a[0]) / (b[1] - a[1]) < x) inside = !inside;
            }
    return inside;
}

/// A star-shaped ring around (cx, cy) with `n` vertices at radii in [r0, r1], counter-clockwise.
ring_t star(std::mt19937& rng, double cx, double cy, double r0, double r1, int n)
{
    std::uniform_real_distribution<double> radius(r0, r1);
    ring_t ring;
    for (int i = 0; i < n; ++i) {
        const double a = 2 * std::numbers::pi * i / n;
        const double r = radius(rng);
        ring.push_back({cx + r * std::cos(a), cy + r * std::sin(a)});
    }
    return ring;
}

polygon box(double x0, double y0, double x1, double y1)
{
    return {{{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}, {x0, y0}}}};
}

}  // namespace

TEST_CASE("vector/burn_polygons: a cell is labelled iff its centre is inside (random stars with holes)")
{
    std::mt19937 rng(1301);
    const grid g{.x0 = 1000.25, .y0 = 5000.75, .cell = 0.5, .rows = 90, .cols = 110};
    std::vector<labelled_polygon> fs;
    for (int k = 1; k <= 12; ++k) {
        std::uniform_real_distribution<double> x(g.x0 - 5, g.x1() + 5), y(g.y1() - 5, g.y0 + 5);
        const double cx = x(rng), cy = y(rng);
        polygon p{{star(rng, cx, cy, 6, 14, 3 + k)}};
        if (k % 3 == 0) p.rings.push_back(star(rng, cx, cy, 1.5, 4, 7));  // a hole
        fs.push_back({k, {p}});
    }
    const burn_result got = burn_polygons(fs, g);
    std::vector<std::size_t> cells(fs.size(), 0), contested(fs.size(), 0);
    for (std::ptrdiff_t r = 0; r < g.rows; ++r)
        for (std::ptrdiff_t c = 0; c < g.cols; ++c) {
            const auto [cx, cy] = g.center(r, c);
            std::int32_t want = 0;
            for (std::size_t i = 0; i < fs.size(); ++i) {
                if (!contains(fs[i].parts, cx, cy)) continue;
                if (want == 0) {
                    want = fs[i].label;
                    ++cells[i];
                } else {
                    ++contested[i];
                }
            }
            INFO("cell ", r, ",", c);
            REQUIRE(got.labels(r, c) == want);
        }
    REQUIRE(got.footprints.size() == fs.size());
    for (std::size_t i = 0; i < fs.size(); ++i) {
        CHECK(got.footprints[i].label == fs[i].label);
        CHECK(got.footprints[i].cells == cells[i]);
        CHECK(got.footprints[i].contested == contested[i]);
    }
}

TEST_CASE("vector/burn_polygons: burning polygonize's outlines gives the labels back")
{
    std::mt19937 rng(1302);
    const grid g{.x0 = -20, .y0 = 40, .cell = 2, .rows = 37, .cols = 29};
    for (int trial = 0; trial < 20; ++trial) {
        raster<std::int32_t> labels(g.rows, g.cols, 0);
        std::uniform_int_distribution<int> label(0, 4);
        for (std::ptrdiff_t r = 0; r < g.rows; ++r)
            for (std::ptrdiff_t c = 0; c < g.cols; ++c)
                labels(r, c) = (r / 4 + c / 5 + trial) % 3 == 0 ? 0 : label(rng);
        std::vector<labelled_polygon> fs;
        for (const label_polygons& lp : polygonize(labels, g)) fs.push_back({lp.label, lp.polygons});
        const burn_result back = burn_polygons(fs, g);
        INFO("trial ", trial);
        CHECK(std::equal(back.labels.data(), back.labels.data() + g.size(), labels.data()));
        for (const burn_account& a : back.footprints) CHECK(a.contested == 0);
    }
}

TEST_CASE("vector/burn_polygons: footprints sharing an edge through cell centres never share a cell")
{
    // Vertical shared edge at x = 5.5 (a column of centres) and horizontal at y = 4.5 (a row of centres).
    const grid g{.x0 = 0, .y0 = 10, .cell = 1, .rows = 10, .cols = 10};
    const std::vector<labelled_polygon> fs{
        {1, {box(1.5, 4.5, 5.5, 8.5)}}, {2, {box(5.5, 4.5, 8.5, 8.5)}}, {3, {box(1.5, 1.5, 8.5, 4.5)}}};
    const burn_result b = burn_polygons(fs, g);
    std::size_t total = 0;
    for (const auto& a : b.footprints) {
        CHECK(a.contested == 0);
        total += a.cells;
    }
    // Centres 2..8 by x and 2..8 by y lie in the union (7 x 7 = 49 cells), every one owned once.
    CHECK(total == 49);
    CHECK(b.labels(10 - 1 - 5, 5) ==
          1);  // centre (5.5, 4.5) on both shared edges: west of x = 5.5 is 1, north of y = 4.5
    CHECK(b.labels(10 - 1 - 5, 6) == 2);
}

TEST_CASE("vector/burn_polygons: holes stay empty, parts of one footprint all burn, overlaps are counted")
{
    const grid g{.x0 = 0, .y0 = 20, .cell = 1, .rows = 20, .cols = 20};
    polygon ring_with_hole = box(0, 0, 10, 10);
    ring_with_hole.rings.push_back({{3, 3}, {3, 7}, {7, 7}, {7, 3}, {3, 3}});  // clockwise hole 4 x 4
    const std::vector<labelled_polygon> fs{{7, {ring_with_hole, box(12, 12, 15, 14)}}, {8, {box(8, 8, 11, 11)}}};
    const burn_result b = burn_polygons(fs, g);
    CHECK(b.footprints[0].cells == 100 - 16 + 6);
    CHECK(b.labels(20 - 1 - 5, 5) == 0);  // inside the hole
    CHECK(b.footprints[1].cells == 9 - 4);
    CHECK(b.footprints[1].contested == 4);
}

TEST_CASE("vector/burn_polygons: footprints off the grid or too small are reported, bad input refused")
{
    const grid g{.x0 = 0, .y0 = 10, .cell = 1, .rows = 10, .cols = 10};
    const std::vector<labelled_polygon> fs{{1, {box(100, 100, 110, 110)}}, {2, {box(3.1, 3.1, 3.4, 3.4)}}, {3, {}}};
    const burn_result b = burn_polygons(fs, g);
    CHECK(b.footprints[0].outside == 1);
    CHECK(b.footprints[0].cells == 0);
    CHECK(b.footprints[1].outside == 0);
    CHECK(b.footprints[1].cells == 0);  // between centres: no cell, but it is still listed
    CHECK(b.footprints[2].outside == 1);
    CHECK_THROWS_AS(burn_polygons(std::vector<labelled_polygon>{{0, {box(1, 1, 2, 2)}}}, g), invalid_input);
    CHECK_THROWS_AS(burn_polygons(std::vector<labelled_polygon>{{4, {box(1, 1, NAN, 2)}}}, g), invalid_input);
    const burn_result empty = burn_polygons({}, grid{.x0 = 0, .y0 = 0, .cell = 1, .rows = 0, .cols = 0});
    CHECK(empty.labels.rows() == 0);
    CHECK(burn_polygons(std::vector<labelled_polygon>{{5, {box(-1, -1, 11, 11)}}}, g).footprints[0].cells == 100);
}
