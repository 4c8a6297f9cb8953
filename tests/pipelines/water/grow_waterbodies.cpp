// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/pipelines/water/grow_waterbodies.hpp>
#include <lidarfx/pipelines/water/water_surface_slope.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "water_test_rasters.hpp"

using namespace lidarfx;

namespace {

// 5 x 12: lake A (columns 0-4, 10 m) and lake B (columns 6-11, 10.5 m) with angles of 0, split by a steep
// bank (column 5, 12 m, 40° > θ_max) whose cell (2, 5) lies at lake A's level. One intensity everywhere, so
// no KS test rejects. Seeds: 1 and 2 in lake A, 3 in lake B, 4 on a vegetation cell of lake B.
struct two_lakes {
    water_field field;
    raster<float> min_z{5, 12, 10.0f}, max_z{5, 12, 10.0f};
    components seeds{raster<std::int32_t>(5, 12, 0), {}};

    two_lakes()
    {
        field.angle_deg = raster<float>(5, 12, 0.0f);
        field.eligible = raster<std::uint8_t>(5, 12, 1);
        field.intensity_bin = raster<std::int32_t>(5, 12, 0);
        field.bins = 1;
        for (std::ptrdiff_t r = 0; r < 5; ++r) {
            field.angle_deg(r, 5) = 40.0f;
            min_z(r, 5) = max_z(r, 5) = 12.0f;
        }
        for (std::ptrdiff_t r = 0; r < 5; ++r)
            for (std::ptrdiff_t c = 6; c < 12; ++c) min_z(r, c) = max_z(r, c) = 10.5f;
        min_z(2, 5) = 10.0f;
        max_z(2, 5) = 10.25f;
        field.eligible(4, 10) = 0;
        seeds.labels(0, 0) = seeds.labels(0, 1) = seeds.labels(1, 0) = seeds.labels(1, 1) = 1;
        seeds.labels(3, 3) = seeds.labels(4, 3) = 2;
        seeds.labels(2, 8) = 3;
        seeds.labels(4, 10) = 4;
        seeds.sizes = {60 - 8, 4, 2, 1, 1};
    }
};

// A field of rows x cols cells whose rasters the test fills, with `bins` intensity bins.
water_field field_of_shape(std::ptrdiff_t rows, std::ptrdiff_t cols, int bins)
{
    water_field field;
    field.angle_deg = raster<float>(rows, cols);
    field.eligible = raster<std::uint8_t>(rows, cols);
    field.intensity_bin = raster<std::int32_t>(rows, cols);
    field.bins = bins;
    return field;
}

}  // namespace

TEST_CASE("water/grow_waterbodies: seeds grow in order, a seed inside a body is skipped, bodies refine")
{
    two_lakes s;
    const auto g = grow_waterbodies(s.field, s.seeds, s.min_z, s.max_z);
    REQUIRE(g.bodies.size() == 2);
    CHECK(g.seeds_grown == 2);
    CHECK(g.bodies[0].label == 1);
    CHECK(g.bodies[0].seed == 1);
    CHECK(g.bodies[1].label == 2);
    CHECK(g.bodies[1].seed == 3);  // seed 2 lies in body 1; seed 4 is vegetation and grows nothing
    for (const auto& b : g.bodies) {
        CHECK(b.theta_deg == 30.0);  // steps without growth are accepted up to θ_max
        CHECK_FALSE(b.stopped_by_ks);
    }
    for (std::ptrdiff_t r = 0; r < 5; ++r)
        for (std::ptrdiff_t c = 0; c < 12; ++c) {
            CAPTURE(r);
            CAPTURE(c);
            const std::int32_t expected = c < 5 ? 1 : c > 5 ? (r == 4 && c == 10 ? 0 : 2) : (r == 2 ? 1 : 0);
            CHECK(g.labels(r, c) == expected);
            // Body cells are no longer eligible.
            CHECK(s.field.eligible(r, c) == (expected == 0 && !(r == 4 && c == 10)));
        }
}

TEST_CASE(
    "water/grow_waterbodies: a seed partly inside a body grows from its free cells when they are at least "
    "min_free_seed_share of it")
{
    // Seed 2 now also covers 3 cells of lake B: 3 of its 5 cells lie outside body 1 (60 %).
    const auto straddling = [](two_lakes& s) {
        s.seeds.labels(3, 7) = s.seeds.labels(3, 8) = s.seeds.labels(4, 7) = 2;
        s.seeds.sizes = {60 - 11, 4, 5, 1, 1};
    };
    two_lakes s;
    straddling(s);
    const auto g = grow_waterbodies(s.field, s.seeds, s.min_z, s.max_z);
    REQUIRE(g.bodies.size() == 2);
    CHECK(g.bodies[1].seed == 2);  // lake B grows from seed 2's free cells; seed 3 then lies in it
    CHECK(g.labels(0, 11) == 2);
    CHECK(g.labels(3, 3) == 1);  // its cells in lake A stay lake A's
    two_lakes t;
    straddling(t);
    const auto h = grow_waterbodies(t.field, t.seeds, t.min_z, t.max_z, {}, {}, {.min_free_seed_share = 1.0});
    REQUIRE(h.bodies.size() == 2);
    CHECK(h.bodies[1].seed == 3);  // a cell in a body skips the seed: lake B grows from seed 3
    two_lakes u;
    straddling(u);
    const auto k = grow_waterbodies(u.field, u.seeds, u.min_z, u.max_z, {}, {}, {.min_free_seed_share = 0.75});
    REQUIRE(k.bodies.size() == 2);
    CHECK(k.bodies[1].seed == 3);  // 60 % free < 75 %: skipped
    two_lakes v;
    CHECK_THROWS_WITH_AS(grow_waterbodies(v.field, v.seeds, v.min_z, v.max_z, {}, {}, {.min_free_seed_share = 0.0}),
                         "grow_waterbodies: min_free_seed_share must be in (0, 1] (got 0)", invalid_input);
}

TEST_CASE("water/grow_waterbodies: the refinement options reach the bodies")
{
    two_lakes s;
    const auto g = grow_waterbodies(s.field, s.seeds, s.min_z, s.max_z, {}, {.depth_cells = 0});
    CHECK(g.labels(2, 5) == 0);
    two_lakes t;
    const auto h = grow_waterbodies(t.field, t.seeds, t.min_z, t.max_z, {}, {.max_rise_m = 0.125});
    CHECK(h.labels(2, 5) == 0);  // its highest return rises 0.25 m above the water
    two_lakes u;
    const auto k = grow_waterbodies(u.field, u.seeds, u.min_z, u.max_z, {.theta_max_deg = 45.0});
    CHECK(k.bodies.size() == 1);  // 40° banks join at θ 45°: one body over both lakes
    CHECK(k.labels(0, 11) == 1);
}

TEST_CASE("water/grow_waterbodies: no seed, no body")
{
    two_lakes s;
    const components none{raster<std::int32_t>(5, 12, 0), {60}};
    const auto g = grow_waterbodies(s.field, none, s.min_z, s.max_z);
    CHECK(g.bodies.empty());
    CHECK(g.labels == raster<std::int32_t>(5, 12, 0));
}

TEST_CASE("water/grow_waterbodies: progress is monotone and ends at 1; returning false cancels")
{
    water_test::check_progress_and_cancel(
        [&](const execution& run) {
            two_lakes s;
            return grow_waterbodies(s.field, s.seeds, s.min_z, s.max_z, {}, {}, {}, run);
        },
        "grow_waterbodies");
}

TEST_CASE("water/grow_waterbodies: bad arguments are refused")
{
    two_lakes s;
    const components small{raster<std::int32_t>(4, 12, 0), {48}};
    CHECK_THROWS_WITH_AS(
        grow_waterbodies(s.field, small, s.min_z, s.max_z),
        "grow_waterbodies: field.eligible and seeds.labels must have the same shape (got 5x12 and 4x12)",
        invalid_input);
    const raster<float> short_max_z(4, 12, 1.0f);
    CHECK_THROWS_WITH_AS(grow_waterbodies(s.field, s.seeds, s.min_z, short_max_z),
                         "grow_waterbodies: field.eligible and max_z must have the same shape (got 5x12 and 4x12)",
                         invalid_input);
    CHECK_THROWS_WITH_AS(grow_waterbodies(s.field, s.seeds, s.min_z, s.max_z, {}, {.tolerance_m = -1}),
                         "grow_waterbodies: tolerance_m must be >= 0 (got -1)", invalid_input);
}

TEST_CASE("water/grow_waterbodies: equals the public steps composed, on random fields")
{
    // The reference: per seed in label order, its free cells (row order) grown by grow_waterbody, refined by
    // join_level_cells, then labelled and taken out of the eligible cells.
    std::mt19937 rng(17);
    for (int trial = 0; trial < 30; ++trial) {
        CAPTURE(trial);
        const std::ptrdiff_t rows = 1 + static_cast<std::ptrdiff_t>(rng() % 40),
                             cols = 1 + static_cast<std::ptrdiff_t>(rng() % 40);
        std::uniform_real_distribution<float> unit(0, 1);
        water_field field = field_of_shape(rows, cols, 8);
        raster<float> min_z(rows, cols), max_z(rows, cols);
        components seeds{raster<std::int32_t>(rows, cols, 0), {0}};
        const int n_seeds = 1 + static_cast<int>(rng() % 5);
        seeds.sizes.assign(static_cast<std::size_t>(n_seeds + 1), 0);
        for (std::ptrdiff_t i = 0; i < rows * cols; ++i) {
            field.angle_deg.data()[i] = unit(rng) < 0.2f ? NAN : 12.0f * unit(rng);
            field.eligible.data()[i] = unit(rng) < 0.9f;
            const bool dropout = unit(rng) < 0.3f;
            field.intensity_bin.data()[i] = dropout ? -1 : static_cast<std::int32_t>(rng() % 8);
            min_z.data()[i] = dropout ? NAN : 10.0f + 0.3f * unit(rng);
            max_z.data()[i] = min_z.data()[i] + 0.6f * unit(rng);
            if (unit(rng) < 0.05f) {
                const auto label = 1 + static_cast<std::int32_t>(rng() % static_cast<unsigned>(n_seeds));
                seeds.labels.data()[i] = label;
                ++seeds.sizes[static_cast<std::size_t>(label)];
            }
        }
        field.min_z = min_z;
        const grow_waterbody_options grow{.min_ks_samples = 5};
        const join_level_cells_options level{.tolerance_m = 0.1, .max_rise_m = 0.4, .depth_cells = 2};
        const grow_waterbodies_options opt{};

        water_field reference_field = field;
        field.min_z = min_z;
        raster<std::int32_t> labels(rows, cols, 0);
        std::vector<double> thetas;
        grow_waterbody_workspace workspace;
        for (std::int32_t s = 1; s <= n_seeds; ++s) {
            std::vector<std::ptrdiff_t> cells, free;
            for (std::ptrdiff_t i = 0; i < rows * cols; ++i)
                if (seeds.labels.data()[i] == s) cells.push_back(i);
            for (const auto i : cells)
                if (labels.data()[i] <= 0) free.push_back(i);
            if (free.empty() ||
                (free.size() < cells.size() &&
                 static_cast<double>(free.size()) < opt.min_free_seed_share * static_cast<double>(cells.size())))
                continue;
            auto region = grow_waterbody(reference_field, free, grow, workspace);
            if (region.cells.empty()) continue;
            join_level_cells(region.cells, min_z, max_z, reference_field.eligible, level);
            thetas.push_back(region.theta_deg);
            for (const auto i : region.cells) {
                labels.data()[i] = static_cast<std::int32_t>(thetas.size());
                reference_field.eligible.data()[i] = 0;
            }
        }
        for (auto& l : labels) l = std::max(l, 0);

        for (const int threads : {1, 2, 3}) {
            CAPTURE(threads);
            water_field grown_field = field;
            const auto grown =
                grow_waterbodies(grown_field, seeds, min_z, max_z, grow, level, opt, {.threads = threads});
            CHECK(grown.labels == labels);
            CHECK(grown_field.eligible == reference_field.eligible);
            REQUIRE(grown.bodies.size() == thetas.size());
            for (std::size_t k = 0; k < thetas.size(); ++k) CHECK(grown.bodies[k].theta_deg == thetas[k]);
        }
    }
}

TEST_CASE(
    "water/grow_waterbodies: floods grown ahead on other threads give the bodies of the turns one after another, "
    "bit for bit, however many threads")
{
    // Many seeds on one field: lakes at three levels with banks between them, seeds inside and across them (so later
    // seeds fall in earlier bodies, partly or wholly, and floods ahead are often overtaken), a lazy surface slope
    // read by every thread, and a second round of seeds grown into the same result.
    std::mt19937 rng(4242);
    std::uniform_real_distribution<float> unit(0, 1);
    for (int trial = 0; trial < 15; ++trial) {
        CAPTURE(trial);
        // The last trials are larger fields, with more seeds: floods ahead reach far from their seeds.
        const std::ptrdiff_t grow_by = trial < 12 ? 1 : 4;
        const std::ptrdiff_t rows = grow_by * (30 + static_cast<std::ptrdiff_t>(rng() % 50)),
                             cols = grow_by * (30 + static_cast<std::ptrdiff_t>(rng() % 70));
        water_field field = field_of_shape(rows, cols, 8);
        raster<float> min_z(rows, cols), max_z(rows, cols);
        for (std::ptrdiff_t r = 0; r < rows; ++r) {
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                const bool bank = (c % 23 == 11) || (r % 17 == 8 && unit(rng) < 0.8f);
                const float level = 10.0f + 0.4f * static_cast<float>((c / 23 + r / 17) % 3);
                const bool dropout = !bank && unit(rng) < 0.25f;
                field.angle_deg(r, c) = bank ? 35.0f : (unit(rng) < 0.15f ? NAN : 6.0f * unit(rng));
                field.eligible(r, c) = unit(rng) < 0.93f;
                field.intensity_bin(r, c) = dropout ? -1 : static_cast<std::int32_t>(rng() % (bank ? 8 : 4));
                min_z(r, c) = dropout ? NAN : (bank ? level + 1.5f : level + 0.08f * unit(rng));
                max_z(r, c) = min_z(r, c) + 0.3f * unit(rng);
            }
        }
        const auto random_seeds = [&](int count) {
            components seeds{raster<std::int32_t>(rows, cols, 0),
                             std::vector<std::size_t>(static_cast<std::size_t>(count + 1), 0)};
            for (int s = 1; s <= count; ++s) {
                const std::ptrdiff_t r0 = static_cast<std::ptrdiff_t>(rng() % static_cast<unsigned>(rows - 3)),
                                     c0 = static_cast<std::ptrdiff_t>(rng() % static_cast<unsigned>(cols - 3));
                const std::ptrdiff_t h = 1 + static_cast<std::ptrdiff_t>(rng() % 3),
                                     w = 1 + static_cast<std::ptrdiff_t>(rng() % 3);
                for (std::ptrdiff_t r = r0; r < r0 + h; ++r)
                    for (std::ptrdiff_t c = c0; c < c0 + w; ++c) seeds.labels(r, c) = s;  // later seeds overwrite
            }
            for (const auto l : seeds.labels) ++seeds.sizes[static_cast<std::size_t>(l)];
            return seeds;
        };
        const components first =
                             random_seeds(static_cast<int>(grow_by * grow_by) * (10 + static_cast<int>(rng() % 40))),
                         second = random_seeds(8);
        const grow_waterbody_options grow{.min_ks_samples = 8, .level_gate_m = 0.2, .level_follow_max_slope = 0.01};
        const join_level_cells_options level{.tolerance_m = 0.1, .max_rise_m = 0.4, .depth_cells = 2};
        const grow_waterbodies_options opt{.min_free_seed_share = 0.5};
        const auto grow_all = [&](int threads, water_field& f) {
            lazy_water_surface_slope slope(min_z, 1.0);
            f.min_z = min_z;
            f.surface_slope = slope;
            auto g = grow_waterbodies(f, first, min_z, max_z, grow, level, opt, {.threads = threads});
            grow_waterbodies(f, second, min_z, max_z, g, grow, level, opt, static_cast<std::int32_t>(first.count()),
                             {.threads = threads});
            f.surface_slope = {};
            return g;
        };
        water_field one_field = field;
        const auto one = grow_all(1, one_field);
        CHECK(one.bodies.size() > 3);
        for (const int threads : {2, 3, 8}) {
            CAPTURE(threads);
            water_field many_field = field;
            const auto many = grow_all(threads, many_field);
            CHECK(many.labels == one.labels);
            CHECK(many_field.eligible == one_field.eligible);
            CHECK(many.seeds_grown == one.seeds_grown);
            REQUIRE(many.bodies.size() == one.bodies.size());
            for (std::size_t k = 0; k < one.bodies.size(); ++k) {
                CHECK(many.bodies[k].label == one.bodies[k].label);
                CHECK(many.bodies[k].seed == one.bodies[k].seed);
                CHECK(many.bodies[k].theta_deg == one.bodies[k].theta_deg);
                CHECK(many.bodies[k].stopped_by_ks == one.bodies[k].stopped_by_ks);
            }
        }
    }
}

TEST_CASE("water/grow_waterbodies: a cell that only a flood grown ahead reaches cannot make the threads throw")
{
    // 1 x 8: seed 1's body takes cells 0-3 (cell 3 through join_level_cells at depth 2, past the steep cell 2), and
    // cell 3 holds an intensity bin out of range. The sequential run never queues it: by seed 2's turn it is no
    // longer eligible. A flood grown ahead for seed 2 sees it eligible and throws on it; that flood is grown again
    // at its turn instead of its error standing.
    for (const int threads : {1, 2}) {
        CAPTURE(threads);
        water_field field = field_of_shape(1, 8, 1);
        for (auto& a : field.angle_deg) a = 0.0f;
        for (auto& e : field.eligible) e = 1;
        for (auto& b : field.intensity_bin) b = 0;
        raster<float> min_z(1, 8, 10.0f), max_z(1, 8, 10.0f);
        field.angle_deg(0, 2) = 40.0f;
        field.intensity_bin(0, 3) = 1 << 24;
        for (std::ptrdiff_t c = 4; c < 8; ++c) min_z(0, c) = max_z(0, c) = 11.0f;
        field.eligible(0, 6) = field.eligible(0, 7) = 0;
        components seeds{raster<std::int32_t>(1, 8, 0), {6, 1, 1}};
        seeds.labels(0, 0) = 1;
        seeds.labels(0, 5) = 2;
        const auto g = grow_waterbodies(field, seeds, min_z, max_z, {}, {}, {}, {.threads = threads});
        REQUIRE(g.bodies.size() == 2);
        const std::int32_t want[8] = {1, 1, 1, 1, 2, 2, 0, 0};
        for (std::ptrdiff_t c = 0; c < 8; ++c) CHECK(g.labels(0, c) == want[c]);
    }
}
