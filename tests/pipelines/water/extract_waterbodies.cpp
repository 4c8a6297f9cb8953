// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/kernels/label/connected_components.hpp>
#include <lidarfx/kernels/metrics/confusion.hpp>
#include <lidarfx/kernels/points/rasterize.hpp>
#include <lidarfx/pipelines/water/extract_waterbodies.hpp>
#include <lidarfx/synth/scenes.hpp>

#include "water_test_rasters.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <utility>
#include <vector>

using namespace lidarfx;

namespace {

struct scene_run {
    synth::scene scene;
    rasterize_result rasters;
    extract_waterbodies_result result;
    confusion score;
};

scene_run run(synth::scene sc, const extract_waterbodies_options& opt = {})
{
    scene_run out{std::move(sc), {}, {}, {}};
    out.rasters = rasterize(out.scene.points.cloud(), out.scene.truth.g);
    out.result = extract_waterbodies(out.rasters, opt);
    out.score = confusion_counts(out.result.water, out.scene.truth.water_filled, out.scene.truth.g.cell);
    MESSAGE("accuracy " << 100 * out.score.accuracy() << " %, sensitivity " << 100 * out.score.sensitivity()
                        << " %, specificity " << 100 * out.score.specificity() << " %, IoU " << 100 * out.score.iou()
                        << " %, bodies " << out.result.bodies.size());
    return out;
}

}  // namespace

TEST_CASE("water/extract_waterbodies: the synthetic lake scene is mapped to the documents' accuracy and beyond")
{
    const auto r = run(synth::lake_scene());
    REQUIRE(r.result.ran);
    CHECK(r.score.accuracy() >= 0.995);
    CHECK(r.score.sensitivity() >= 0.97);
    CHECK(r.score.specificity() >= 0.995);

    // Bodies are numbered by decreasing area and their statistics match the label raster.
    std::size_t cells = 0;
    for (std::size_t i = 0; i < r.result.bodies.size(); ++i) {
        const auto& b = r.result.bodies[i];
        CHECK(b.label == static_cast<std::int32_t>(i + 1));
        if (i > 0) CHECK(b.area_m2 <= r.result.bodies[i - 1].area_m2);
        cells += b.cells;
        CHECK(b.box.row_min <= b.box.row_max);
    }
    std::size_t water_cells = 0;
    for (const auto v : r.result.water) water_cells += v;
    CHECK(cells == water_cells);

    // Islands of 200 m² and more stay land; smaller holes inside water were filled.
    const auto& t = r.scene.truth;
    const auto land_inside = connected_components(
        [&] {
            raster<std::uint8_t> m(t.g.rows, t.g.cols);
            for (std::ptrdiff_t i = 0; i < m.size(); ++i) m.data()[i] = !r.result.water.data()[i];
            return m;
        }(),
        connectivity::four);
    const double cell_area = t.g.cell * t.g.cell;
    const auto bounds = component_bounds(land_inside);
    for (std::size_t l = 1; l < land_inside.sizes.size(); ++l) {
        const auto& b = bounds[l];
        const bool touches_border =
            b.row_min == 0 || b.col_min == 0 || b.row_max == t.g.rows - 1 || b.col_max == t.g.cols - 1;
        if (!touches_border) CHECK(static_cast<double>(land_inside.sizes[l]) * cell_area >= 200.0);
    }
}

TEST_CASE("water/extract_waterbodies: the synthetic river is one body, across its bridge")
{
    const auto r = run(synth::river_scene());
    REQUIRE(r.result.ran);
    CHECK(r.score.accuracy() >= 0.995);
    CHECK(r.score.sensitivity() >= 0.97);
    CHECK(r.score.specificity() >= 0.995);
    REQUIRE_FALSE(r.result.bodies.empty());
    // The river is the largest body and holds nearly all the water found.
    std::size_t water_cells = 0;
    for (const auto v : r.result.water) water_cells += v;
    CHECK(static_cast<double>(r.result.bodies[0].cells) >= 0.95 * static_cast<double>(water_cells));
}

TEST_CASE(
    "water/extract_waterbodies: a pond with returns and 40 % scattered dropouts is seeded whole with "
    "flat_seed_dropouts")
{
    // 60 x 60 cells of flat land (10 m, 4 returns, intensity 50-59) around a 30 x 30 pond at 9 m: level,
    // sparse (2 returns) and dark (20), 40 % of its cells dropouts scattered by a hash. No 3 x 3 block of
    // dropouts survives the seed opening; the pond's level cells alone are as scattered.
    water_test::survey s(60, 60);
    for (std::ptrdiff_t r = 0; r < 60; ++r)
        for (std::ptrdiff_t c = 0; c < 60; ++c) s.intensity(r, c) = 50.0f + static_cast<float>((7 * r + 3 * c) % 10);
    long pond = 0;
    for (std::ptrdiff_t r = 15; r < 45; ++r)
        for (std::ptrdiff_t c = 15; c < 45; ++c) {
            ++pond;
            const auto h = static_cast<std::uint32_t>(r * 7919 + c * 104729) * 2654435761u;
            if ((h >> 16) % 100 < 40) {
                s.drop(r, c);
                continue;
            }
            s.min_z(r, c) = s.max_z(r, c) = 9.0f;
            s.count(r, c) = 2;
            s.intensity(r, c) = 20.0f + static_cast<float>((r + c) % 3);
        }
    const auto found_in_pond = [&](const extract_waterbodies_result& w) {
        long n = 0;
        for (std::ptrdiff_t r = 15; r < 45; ++r)
            for (std::ptrdiff_t c = 15; c < 45; ++c) n += w.water.view()(r, c);
        return n;
    };
    const auto water_outside = [&](const extract_waterbodies_result& w) {
        long n = 0;
        for (std::ptrdiff_t r = 0; r < 60; ++r)
            for (std::ptrdiff_t c = 0; c < 60; ++c)
                n += w.water.view()(r, c) && (r < 15 || r >= 45 || c < 15 || c >= 45);
        return n;
    };
    auto opt = flat_seed_water_method();
    const auto with = extract_waterbodies(s.view(), 2.0, opt);
    REQUIRE(with.ran);
    CHECK(found_in_pond(with) == pond);
    CHECK(water_outside(with) == 0);
    opt.flat_seed_dropouts = false;
    const auto runs = extract_waterbodies(s.view(), 2.0, opt);  // the dropouts' straight runs seed it as well
    CHECK(found_in_pond(runs) == pond);
    CHECK(water_outside(runs) == 0);
    opt.seeds.line_length_cells = 0;
    const auto without = extract_waterbodies(s.view(), 2.0, opt);
    REQUIRE(without.ran);
    CHECK(found_in_pond(without) < pond / 2);  // the opened seed mask keeps too little of the pond
}

TEST_CASE("water/extract_waterbodies: same result for any thread count")
{
    synth::scene_options so;
    so.size_m = 300;
    const auto sc = synth::lake_scene(so);
    const auto pr = rasterize(sc.points.cloud(), sc.truth.g);
    const auto one = extract_waterbodies(pr, {.run = {.threads = 1}});
    const auto three = extract_waterbodies(pr, {.run = {.threads = 3}});
    CHECK(one.labels == three.labels);
    CHECK(one.bodies.size() == three.bodies.size());
    // Angles hold NaN (dropouts join at any θ): compared bit for bit.
    CHECK(std::memcmp(one.angle_deg.data(), three.angle_deg.data(),
                      static_cast<std::size_t>(one.angle_deg.size()) * sizeof(float)) == 0);
    // The preset reads the surface slope (computed where read, on the calling thread): the same result.
    auto preset = flat_seed_water_method();
    preset.run.threads = 1;
    const auto lazy_one = extract_waterbodies(pr, preset);
    preset.run.threads = 3;
    const auto lazy_three = extract_waterbodies(pr, preset);
    CHECK(lazy_one.labels == lazy_three.labels);
    CHECK(lazy_one.bodies.size() == lazy_three.bodies.size());
}

TEST_CASE("water/extract_waterbodies: its intermediate rasters are the public steps' outputs under its options")
{
    synth::scene_options so;
    so.size_m = 300;
    const auto sc = synth::river_scene(so);
    const auto pr = rasterize(sc.points.cloud(), sc.truth.g);
    const auto in = to_water_rasters(pr);
    extract_waterbodies_options o;
    o.vegetation.height_m = 3.0;
    o.vegetation.closing_size_cells = 3;
    o.angles.radius_cells = 3;
    o.seeds = {.opening_size_cells = 3, .min_cells = 50};
    o.angles.input = angular_input::idw_filled;
    o.angles.dropouts_join_any_threshold = false;
    o.flat_seeds = true;
    const auto w = extract_waterbodies(pr, o);
    REQUIRE(w.ran);
    CHECK(w.vegetation == water_vegetation(in, {.height_m = 3.0, .closing_size_cells = 3}));
    const auto angles = water_angles(
        in, pr.g.cell, {.radius_cells = 3, .input = angular_input::idw_filled, .dropouts_join_any_threshold = false});
    CHECK(std::memcmp(w.angle_deg.data(), angles.data(), static_cast<std::size_t>(angles.size()) * sizeof(float)) == 0);
    const auto seeds = water_seeds(pr.dropout, {.opening_size_cells = 3, .min_cells = 50});
    // The dropout seeds keep their labels 1..k; the seeds of flat_water_seeds (flat_seeds) follow as k + 1..
    const auto k = static_cast<std::int32_t>(seeds.count());
    for (std::ptrdiff_t i = 0; i < w.seeds.size(); ++i) {
        if (seeds.labels.data()[i] > 0)
            REQUIRE(w.seeds.data()[i] == seeds.labels.data()[i]);
        else
            REQUIRE((w.seeds.data()[i] == 0 || w.seeds.data()[i] > k));
    }
    CHECK(w.seeds_found >= seeds.count());
    o.flat_seeds = false;
    const auto dropouts_only = extract_waterbodies(pr, o);
    CHECK(dropouts_only.seeds == seeds.labels);
    CHECK(dropouts_only.seeds_found == seeds.count());
    CHECK(w.seeds_grown >= 1);
    CHECK(w.seeds_grown <= w.seeds_found);
    // The water mask is the label raster's foreground.
    for (std::ptrdiff_t i = 0; i < w.water.size(); ++i) REQUIRE((w.water.data()[i] != 0) == (w.labels.data()[i] > 0));
}

TEST_CASE("water/extract_waterbodies: huge or infinite island areas and bridge spans are exact, never overflow")
{
    synth::scene_options so;
    so.size_m = 300;
    const auto sc = synth::river_scene(so);
    const auto pr = rasterize(sc.points.cloud(), sc.truth.g);
    const double cell = pr.g.cell;
    const double whole_raster_m2 = static_cast<double>(pr.g.size()) * cell * cell;
    const double longest_run_m = static_cast<double>(pr.g.rows + pr.g.cols) * cell;
    const auto with = [&](double island_m2, double span_m) {
        extract_waterbodies_options o;
        o.islands.island_min_area_m2 = island_m2;
        o.bridges.max_span_m = span_m;
        return extract_waterbodies(pr, o).labels;
    };
    const auto reference = with(whole_raster_m2, longest_run_m);
    for (const double island : {1e20, std::numeric_limits<double>::infinity()})
        for (const double span : {1e10, std::numeric_limits<double>::infinity()})
            CHECK(with(island, span) == reference);
    CHECK_THROWS_AS(with(std::numeric_limits<double>::quiet_NaN(), 30.0), invalid_input);
    CHECK_THROWS_AS(with(200.0, std::numeric_limits<double>::quiet_NaN()), invalid_input);
}

TEST_CASE("water/extract_waterbodies: bad input is refused with clear messages")
{
    raster<float> z(4, 4, 1.0f), z2(4, 5, 1.0f);
    raster<std::uint8_t> d(4, 4);
    CHECK_THROWS_WITH_AS(extract_waterbodies(water_rasters{z, z2, z, d}, 2.0),
                         "extract_waterbodies: min_z and max_z must have the same shape (got 4x4 and 4x5)",
                         invalid_input);
    CHECK_THROWS_WITH_AS(extract_waterbodies(water_rasters{z, z, z, d}, 0.0),
                         "extract_waterbodies: cell_m must be finite and > 0 (got 0)", invalid_input);
    extract_waterbodies_options o;
    o.grow.ks.alpha = 1.0;
    CHECK_THROWS_WITH_AS(extract_waterbodies(water_rasters{z, z, z, d}, 2.0, o),
                         "extract_waterbodies: ks.alpha must be in (0, 1) (got 1)", invalid_input);
    o = {};
    o.grow.theta_start_deg = 10;
    o.grow.theta_max_deg = 5;
    CHECK_THROWS_WITH_AS(extract_waterbodies(water_rasters{z, z, z, d}, 2.0, o),
                         "extract_waterbodies: theta_max_deg must be >= theta_start_deg and <= 90 (got 5)",
                         invalid_input);
    o = {};
    o.seeds.opening_size_cells = 4;
    CHECK_THROWS_WITH_AS(extract_waterbodies(water_rasters{z, z, z, d}, 2.0, o),
                         "extract_waterbodies: opening_size_cells must be odd and >= 1 (got 4)", invalid_input);
    o = {};
    o.run.threads = -1;
    CHECK_THROWS_WITH_AS(extract_waterbodies(water_rasters{z, z, z, d}, 2.0, o),
                         "extract_waterbodies: run.threads must be >= 0 (got -1)", invalid_input);
}

TEST_CASE("water/extract_waterbodies: progress is monotone and ends at 1; returning false cancels")
{
    synth::scene_options so;
    so.size_m = 300;
    const auto sc = synth::lake_scene(so);
    const auto pr = rasterize(sc.points.cloud(), sc.truth.g);
    std::vector<double> seen;
    extract_waterbodies_options o;
    o.run.progress = [&](double f) {
        seen.push_back(f);
        return true;
    };
    const auto w = extract_waterbodies(pr, o);
    REQUIRE(seen.size() >= 2);
    CHECK(seen.front() == 0.0);
    CHECK(seen.back() == 1.0);
    CHECK(std::is_sorted(seen.begin(), seen.end()));
    CHECK_FALSE(w.bodies.empty());

    o.run.progress = [](double f) { return f < 0.5; };
    CHECK_THROWS_WITH_AS(extract_waterbodies(pr, o), "extract_waterbodies: cancelled", cancelled);
}

TEST_CASE("water/extract_waterbodies: the edge steps' options are checked up front, in extract_waterbodies' name")
{
    water_test::survey s(20, 20);
    auto o = flat_seed_water_method();
    o.trim.max_rise_m = o.trim.min_rise_m;
    CHECK_THROWS_WITH_AS(extract_waterbodies(s.view(), 2.0, o), doctest::Contains("extract_waterbodies"),
                         invalid_input);
    o = flat_seed_water_method();
    o.shore.min_water_share = 0;
    CHECK_THROWS_WITH_AS(extract_waterbodies(s.view(), 2.0, o), doctest::Contains("extract_waterbodies"),
                         invalid_input);
    o.shore_cells = false;  // an unused step's options are not read
    CHECK_NOTHROW(extract_waterbodies(s.view(), 2.0, o));
    CHECK(!previous_water_method().trim_edges);
    CHECK(!previous_water_method().shore_cells);
}
