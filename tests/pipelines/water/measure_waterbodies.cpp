// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/pipelines/water/measure_waterbodies.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "water_test_rasters.hpp"

using namespace lidarfx;
using water_test::grid_of;
using water_test::survey;

TEST_CASE("water/measure_waterbodies: renumbers by decreasing area and describes every body")
{
    // Old labels: 1 (3 cells), 2 (merged away: no cells), 3 (5 cells), 4 (3 cells).
    auto labels = grid_of<std::int32_t>({{1, 1, 0, 3, 3, 3},  //
                                         {1, 0, 0, 3, 3, 0},
                                         {0, 0, 0, 0, 4, 4},
                                         {0, 0, 0, 0, 4, 0}});
    survey s(4, 6);
    s.min_z(0, 3) = 9.0f;
    s.min_z(0, 4) = 9.5f;
    s.min_z(1, 4) = 8.0f;
    s.drop(1, 3);               // body 3: four cells with returns at 9, 9.5, 10 and 8 m
    s.intensity(0, 5) = 30.0f;  // body 3 intensities 50, 50, 30, 50 over its cells with returns
    s.drop(0, 0);
    s.drop(0, 1);
    s.drop(1, 0);  // body 1: dropouts only
    std::vector<waterbody> bodies(4);
    for (std::int32_t k = 0; k < 4; ++k) {
        bodies[static_cast<std::size_t>(k)].seed = 10 + k;
        bodies[static_cast<std::size_t>(k)].theta_deg = 2.0 + k;
        bodies[static_cast<std::size_t>(k)].stopped_by_ks = k % 2 == 0;
    }
    measure_waterbodies(labels, bodies, s.view(), 2.0);
    CHECK(labels == grid_of<std::int32_t>({{2, 2, 0, 1, 1, 1},  //
                                           {2, 0, 0, 1, 1, 0},
                                           {0, 0, 0, 0, 3, 3},
                                           {0, 0, 0, 0, 3, 0}}));
    REQUIRE(bodies.size() == 3);
    const auto& lake = bodies[0];  // old label 3
    CHECK(lake.label == 1);
    CHECK(lake.cells == 5);
    CHECK(lake.area_m2 == 20.0);
    CHECK(lake.box.row_min == 0);
    CHECK(lake.box.col_min == 3);
    CHECK(lake.box.row_max == 1);
    CHECK(lake.box.col_max == 5);
    CHECK(lake.seed == 12);
    CHECK(lake.theta_deg == 4.0);
    CHECK(lake.stopped_by_ks);
    CHECK(lake.mean_intensity == doctest::Approx(45.0));
    CHECK(lake.water_level_m == 9.5);  // sorted {8, 9, 9.5, 10}: position 4 / 2
    CHECK(lake.dropout_fraction == doctest::Approx(0.2));
    // Equal areas keep the order of the old labels: 1 before 4.
    const auto& pond = bodies[1];
    CHECK(pond.label == 2);
    CHECK(pond.seed == 10);
    CHECK(std::isnan(pond.mean_intensity));
    CHECK(std::isnan(pond.water_level_m));
    CHECK(pond.dropout_fraction == 1.0);
    CHECK(bodies[2].label == 3);
    CHECK(bodies[2].seed == 13);
    CHECK(bodies[2].water_level_m == 10.0);
    CHECK(bodies[2].dropout_fraction == 0.0);
}

TEST_CASE("water/measure_waterbodies: without growth records the bodies get default ones")
{
    auto labels = grid_of<std::int32_t>({{0, 2, 2},  //
                                         {0, 0, 0}});
    survey s(2, 3);
    std::vector<waterbody> bodies;
    measure_waterbodies(labels, bodies, s.view(), 1.0);
    REQUIRE(bodies.size() == 1);
    CHECK(bodies[0].label == 1);
    CHECK(bodies[0].cells == 2);
    CHECK(bodies[0].seed == 0);
    CHECK(std::isnan(bodies[0].theta_deg));
    CHECK(labels(0, 1) == 1);
    // No body at all: nothing to describe.
    raster<std::int32_t> land(2, 3, 0);
    measure_waterbodies(land, bodies, s.view(), 1.0);
    CHECK(bodies.empty());
}

TEST_CASE("water/measure_waterbodies: the statistics agree with the label raster on random bodies")
{
    std::mt19937 rng(606);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int trial = 0; trial < 30; ++trial) {
        CAPTURE(trial);
        const std::ptrdiff_t rows = 1 + rng() % 30, cols = 1 + rng() % 30;
        survey s(rows, cols);
        raster<std::int32_t> labels(rows, cols);
        for (std::ptrdiff_t r = 0; r < rows; ++r)
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                labels(r, c) = u(rng) < 0.3f ? 0 : 1 + static_cast<std::int32_t>(rng() % 6);
                s.min_z(r, c) = 5.0f + u(rng);
                s.intensity(r, c) = 100.0f * u(rng);
                if (u(rng) < 0.2f) s.drop(r, c);
            }
        const auto before = labels;
        std::vector<waterbody> bodies;
        measure_waterbodies(labels, bodies, s.view(), 0.5);
        for (std::size_t k = 0; k < bodies.size(); ++k) {
            const auto& b = bodies[k];
            CHECK(b.label == static_cast<std::int32_t>(k + 1));
            if (k > 0) CHECK(b.cells <= bodies[k - 1].cells);
            CHECK(b.area_m2 == static_cast<double>(b.cells) * 0.25);
            std::size_t cells = 0, returns = 0;
            double sum = 0;
            std::int32_t old = -1;
            for (std::ptrdiff_t r = 0; r < rows; ++r)
                for (std::ptrdiff_t c = 0; c < cols; ++c) {
                    if (labels(r, c) != b.label) continue;
                    // The renumbering is a bijection of the old labels.
                    CHECK((old < 0 || old == before(r, c)));
                    old = before(r, c);
                    ++cells;
                    CHECK((r >= b.box.row_min && r <= b.box.row_max && c >= b.box.col_min && c <= b.box.col_max));
                    if (!s.dropout(r, c)) sum += s.intensity(r, c), ++returns;
                }
            CHECK(cells == b.cells);
            if (returns > 0) CHECK(b.mean_intensity == doctest::Approx(sum / static_cast<double>(returns)));
        }
        for (std::ptrdiff_t i = 0; i < labels.size(); ++i) CHECK((labels.data()[i] == 0) == (before.data()[i] == 0));
    }
}

TEST_CASE("water/measure_waterbodies: bands of rows on several threads give one result: tight boxes, medians")
{
    // 700 rows: several bands of rows, bodies spanning them, more bodies than a block of medians.
    std::mt19937 rng(607);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const std::ptrdiff_t rows = 700, cols = 19;
    survey s(rows, cols);
    raster<std::int32_t> labels(rows, cols);
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            labels(r, c) = u(rng) < 0.25f ? 0 : 1 + static_cast<std::int32_t>((r / 29 * 2 + c / 10) % 37);
            s.min_z(r, c) = u(rng) < 0.05f ? NAN : 5.0f + u(rng);
            s.intensity(r, c) = 100.0f * u(rng);
            if (u(rng) < 0.2f) s.drop(r, c);
        }
    std::vector<std::vector<waterbody>> results;
    std::vector<raster<std::int32_t>> renumbered;
    for (const int threads : {1, 2, 3}) {
        auto l = labels;
        std::vector<waterbody> bodies;
        measure_waterbodies(l, bodies, s.view(), 1.0, {.threads = threads});
        results.push_back(bodies);
        renumbered.push_back(l);
    }
    const auto& bodies = results[0];
    REQUIRE(bodies.size() == 37);
    for (std::size_t k = 0; k < bodies.size(); ++k) {
        const auto& b = bodies[k];
        CAPTURE(k);
        cell_box box{rows, cols, -1, -1};
        std::vector<float> heights;
        for (std::ptrdiff_t r = 0; r < rows; ++r)
            for (std::ptrdiff_t c = 0; c < cols; ++c)
                if (renumbered[0](r, c) == b.label) {
                    box.extend(r, c);
                    if (!s.dropout(r, c) && std::isfinite(s.min_z(r, c))) heights.push_back(s.min_z(r, c));
                }
        CHECK(b.box.row_min == box.row_min);
        CHECK(b.box.row_max == box.row_max);
        CHECK(b.box.col_min == box.col_min);
        CHECK(b.box.col_max == box.col_max);
        REQUIRE(!heights.empty());
        std::nth_element(heights.begin(), heights.begin() + static_cast<std::ptrdiff_t>(heights.size() / 2),
                         heights.end());
        CHECK(b.water_level_m == static_cast<double>(heights[heights.size() / 2]));
        for (std::size_t t = 1; t < results.size(); ++t) {  // the same bits on 2 and 3 threads
            const auto& o = results[t][k];
            CHECK(o.cells == b.cells);
            CHECK(o.mean_intensity == b.mean_intensity);
            CHECK(o.water_level_m == b.water_level_m);
            CHECK(o.dropout_fraction == b.dropout_fraction);
        }
    }
    CHECK(renumbered[1] == renumbered[0]);
    CHECK(renumbered[2] == renumbered[0]);
}

TEST_CASE("water/measure_waterbodies: bad arguments are refused")
{
    survey s(2, 2);
    raster<std::int32_t> labels(2, 2, 0);
    std::vector<waterbody> bodies;
    CHECK_THROWS_WITH_AS(measure_waterbodies(labels, bodies, s.view(), 0.0),
                         "measure_waterbodies: cell_m must be finite and > 0 (got 0)", invalid_input);
    labels(0, 0) = -1;
    CHECK_THROWS_WITH_AS(measure_waterbodies(labels, bodies, s.view(), 1.0),
                         "measure_waterbodies: labels must be >= 0 (got -1)", invalid_input);
    raster<std::int32_t> wrong(3, 2, 0);
    CHECK_THROWS_AS(measure_waterbodies(wrong, bodies, s.view(), 1.0), invalid_input);
}
