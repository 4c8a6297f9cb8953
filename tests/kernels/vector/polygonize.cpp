// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/kernels/vector/polygonize.hpp>

#include "reference/polygonize.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

using namespace lidarfx;

namespace {

double signed_area(const std::vector<std::array<double, 2>>& ring)
{
    double a = 0;
    for (std::size_t i = 0; i + 1 < ring.size(); ++i) a += ring[i][0] * ring[i + 1][1] - ring[i + 1][0] * ring[i][1];
    return a / 2;
}

bool same_polygons(const std::vector<label_polygons>& a, const std::vector<label_polygons>& b)
{
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        if (a[i].label != b[i].label || a[i].polygons.size() != b[i].polygons.size()) return false;
        for (std::size_t k = 0; k < a[i].polygons.size(); ++k) {
            if (a[i].polygons[k].rings != b[i].polygons[k].rings) return false;
        }
    }
    return true;
}

std::size_t count_holes(const std::vector<label_polygons>& polys)
{
    std::size_t n = 0;
    for (const auto& lp : polys)
        for (const auto& p : lp.polygons) n += p.rings.size() - 1;
    return n;
}

/// Labels 0..3 painted as random rectangles over each other, then specks: parts inside holes inside parts,
/// rings that touch at corners, holes of other labels and of background.
raster<std::int32_t> nested_labels(std::mt19937& rng, std::ptrdiff_t rows, std::ptrdiff_t cols)
{
    raster<std::int32_t> l(rows, cols, static_cast<std::int32_t>(rng() % 2));
    const int rectangles = 1 + static_cast<int>(rng() % 12);
    for (int k = 0; k < rectangles; ++k) {
        const auto r0 = static_cast<std::ptrdiff_t>(rng() % static_cast<unsigned>(rows));
        const auto c0 = static_cast<std::ptrdiff_t>(rng() % static_cast<unsigned>(cols));
        const auto r1 = std::min(rows, r0 + 1 + static_cast<std::ptrdiff_t>(rng() % 15));
        const auto c1 = std::min(cols, c0 + 1 + static_cast<std::ptrdiff_t>(rng() % 15));
        const auto v = static_cast<std::int32_t>(rng() % 4);
        for (auto r = r0; r < r1; ++r)
            for (auto c = c0; c < c1; ++c) l(r, c) = v;
    }
    const auto specks = rng() % static_cast<unsigned>(rows * cols / 4 + 1);
    for (unsigned k = 0; k < specks; ++k) {
        l(static_cast<std::ptrdiff_t>(rng() % static_cast<unsigned>(rows)),
          static_cast<std::ptrdiff_t>(rng() % static_cast<unsigned>(cols))) = static_cast<std::int32_t>(rng() % 4);
    }
    return l;
}

}  // namespace

TEST_CASE("vector/polygonize: a square with a hole, in world coordinates")
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
    CHECK(signed_area(rings[0]) == doctest::Approx(36.0));  // 3 x 3 cells of 4 m², counter-clockwise
    CHECK(signed_area(rings[1]) == doctest::Approx(-4.0));  // the hole, clockwise
    for (const auto& p : rings[0]) {
        CHECK((p[0] == 102.0 || p[0] == 108.0));
        CHECK((p[1] == 48.0 || p[1] == 42.0));
    }
}

TEST_CASE("vector/polygonize: a part inside the hole of another part keeps its own polygon")
{
    // Label 1: a 7x7 ring of cells with a 5x5 hole; in the hole a 3x3 ring of label 1 with a 1-cell hole,
    // and a second hole of the outer part in the east.
    raster<std::int32_t> l(9, 11, 0);
    for (int r = 1; r < 8; ++r)
        for (int c = 1; c < 10; ++c) l(r, c) = 1;
    for (int r = 2; r < 7; ++r)
        for (int c = 2; c < 7; ++c) l(r, c) = 0;
    for (int r = 3; r < 6; ++r)
        for (int c = 3; c < 6; ++c) l(r, c) = 1;
    l(4, 4) = 0;
    l(4, 8) = 2;
    const auto polys = polygonize(l, grid{0.0, 9.0, 1.0, 9, 11});
    REQUIRE(polys.size() == 2);
    REQUIRE(polys[0].polygons.size() == 2);
    const auto& outer = polys[0].polygons[0].rings;
    const auto& inner = polys[0].polygons[1].rings;
    REQUIRE(outer.size() == 3);  // exterior, the 5x5 hole, the east hole (label 2)
    REQUIRE(inner.size() == 2);  // exterior, the 1-cell hole
    CHECK(signed_area(outer[0]) == doctest::Approx(63.0));
    CHECK(signed_area(outer[1]) == doctest::Approx(-25.0));
    CHECK(signed_area(outer[2]) == doctest::Approx(-1.0));
    CHECK(signed_area(inner[0]) == doctest::Approx(9.0));
    CHECK(signed_area(inner[1]) == doctest::Approx(-1.0));
    CHECK(polys[1].label == 2);
    CHECK(same_polygons(polys, reference::polygonize_quadratic(l, grid{0.0, 9.0, 1.0, 9, 11})));
}

TEST_CASE("vector/polygonize: areas equal cell counts on random labels; corner contacts stay simple")
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
        for (int k = 1; k < 3; ++k)
            CHECK(area[static_cast<std::size_t>(k)] == doctest::Approx(cells[static_cast<std::size_t>(k)] * 2.25));
    }
    CHECK_THROWS_AS(polygonize(raster<std::int32_t>(2, 2), grid{0, 0, 1, 3, 2}), invalid_input);
}

TEST_CASE("vector/polygonize: same rings in the same order as the quadratic hole assignment")
{
    const unsigned seed = 20240611;
    std::mt19937 rng(seed);
    std::size_t holes = 0;
    for (int trial = 0; trial < 300; ++trial) {
        CAPTURE(seed);
        CAPTURE(trial);
        const std::ptrdiff_t rows = 1 + rng() % 40, cols = 1 + rng() % 40;
        raster<std::int32_t> l(rows, cols);
        if (trial % 3 == 0) {
            // Noise: many small parts, holes and corner contacts.
            for (auto& v : l) v = static_cast<std::int32_t>(rng() % (2 + trial % 4));
        } else {
            l = nested_labels(rng, rows, cols);
        }
        const grid g{-10.0, 20.0, 0.5, rows, cols};
        const auto fast = polygonize(l, g);
        CHECK(same_polygons(fast, reference::polygonize_quadratic(l, g)));
        holes += count_holes(fast);
    }
    CHECK(holes > 1000);  // the cases exercise the hole assignment
}

TEST_CASE("vector/polygonize: a strided window gives what its contiguous copy gives")
{
    std::mt19937 rng(5);
    for (int trial = 0; trial < 20; ++trial) {
        const auto big = nested_labels(rng, 40, 37);
        const auto in = big.view().window(3, 2, 30, 31);  // row_stride 37 != cols 31
        raster<std::int32_t> copy(30, 31);
        for (std::ptrdiff_t r = 0; r < 30; ++r)
            for (std::ptrdiff_t c = 0; c < 31; ++c) copy(r, c) = in(r, c);
        const grid g{0.0, 0.0, 1.0, 30, 31};
        CHECK(same_polygons(polygonize(in, g), polygonize(copy, g)));
    }
}

TEST_CASE("vector/polygonize: progress is monotone and ends at 1; returning false cancels")
{
    std::mt19937 rng(3);
    const auto l = nested_labels(rng, 600, 300);  // more than one progress step in each phase
    const grid g{0.0, 0.0, 1.0, 600, 300};
    std::vector<double> seen;
    const auto polys = polygonize(l, g, {.run = {.progress = [&](double f) {
                                             seen.push_back(f);
                                             return true;
                                         }}});
    REQUIRE(seen.size() >= 3);
    CHECK(std::is_sorted(seen.begin(), seen.end()));
    CHECK(seen.front() > 0.0);
    CHECK(seen.back() == 1.0);
    CHECK(same_polygons(polys, polygonize(l, g)));
    // Cancelled at the first report, and at the last one.
    CHECK_THROWS_WITH_AS(polygonize(l, g, {.run = {.progress = [](double) { return false; }}}), "polygonize: cancelled",
                         cancelled);
    CHECK_THROWS_AS(polygonize(l, g, {.run = {.progress = [](double f) { return f < 1.0; }}}), cancelled);
    // Threads are accepted and ignored; a negative count is an error.
    CHECK(same_polygons(polygonize(l, g, {.run = {.threads = 0}}), polys));
    CHECK_THROWS_WITH_AS(polygonize(l, g, {.run = {.threads = -1}}), "polygonize: run.threads must be >= 0 (got -1)",
                         invalid_input);
}
