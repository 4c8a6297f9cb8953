// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/kernels/label/connected_components.hpp>
#include <lidarfx/kernels/metrics/confusion.hpp>
#include <lidarfx/kernels/points/rasterize.hpp>
#include <lidarfx/pipelines/water/extract_waterbodies.hpp>
#include <lidarfx/pipelines/water/flat_water_seeds.hpp>
#include <lidarfx/pipelines/water/water_surface_slope.hpp>
#include <lidarfx/synth/water_cases.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "water_test_rasters.hpp"

using namespace lidarfx;

namespace {

/// A 40 × 40 survey on a plane tilted 1 cm per cell eastwards (level within the tolerance over a window)
/// with range noise: min z and max z ± 2.5 cm around it, 6 returns per cell, intensity 80.
water_test::survey flat_ground()
{
    water_test::survey s(40, 40);
    for (std::ptrdiff_t r = 0; r < 40; ++r) {
        for (std::ptrdiff_t c = 0; c < 40; ++c) {
            const float z = 10.0f + 0.01f * static_cast<float>(c), e = 0.01f * static_cast<float>((r * 7 + c * 3) % 5);
            s.min_z(r, c) = z - 0.025f + e * 0.2f;
            s.max_z(r, c) = z + 0.025f;
            s.intensity(r, c) = 80.0f;
            s.count(r, c) = 6;
        }
    }
    return s;
}

}  // namespace

TEST_CASE("flat_water_seeds: a turbid lake without dropout cells gets seeds, the meadow and the asphalt lot none")
{
    const auto lake = synth::turbid_lake_scene();
    const auto pr = rasterize(lake.points.cloud(), lake.g);
    const auto in = to_water_rasters(pr);
    // The dropout seeds find nothing: the lake loses pulses but no cell loses all of them.
    const auto dropout_seeds = water_seeds(pr.dropout, {.opening_size_cells = 3, .min_cells = 50});
    CHECK(dropout_seeds.count() == 0);
    const auto seeds = flat_water_seeds(in);
    long on_water = 0, on_land = 0;
    for (std::ptrdiff_t r = 0; r < seeds.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < seeds.cols(); ++c)
            if (seeds.view()(r, c)) (lake.water_filled(r, c) ? on_water : on_land) += 1;
    MESSAGE("turbid lake: seed cells on water " << on_water << ", on land " << on_land);
    CHECK(on_water >= 50);
    CHECK(on_land == 0);
    // The workspace form gives the same seeds, with labels of another shape or reused with garbage.
    flat_water_seeds_workspace workspace{raster<std::int32_t>(2, 3, 5)};
    for (int again = 0; again < 2; ++again) {
        CHECK(flat_water_seeds(in, {}, {}, {}, {}, workspace) == seeds);
        CHECK((workspace.labels.rows() == seeds.rows() && workspace.labels.cols() == seeds.cols()));
        std::fill(workspace.labels.begin(), workspace.labels.end(), 123);
    }

    // Cells taken by bodies grown before are cleared from the mask, and nothing else changes: taken cells
    // still count in the components, rings and slope medians. Taken: the west half (part of the lake's
    // seeds), or every cell of the seed component holding the northernmost seed cell (a component all
    // taken, which is not tested at all). With and without a surface slope.
    const auto slope = water_surface_slope(in.min_z, lake.cell_m);
    for (const bool with_slope : {false, true}) {
        const surface_slope_source source = with_slope ? surface_slope_source(slope) : surface_slope_source();
        flat_water_seeds_workspace own;
        const auto all = flat_water_seeds(in, {}, {}, source, {}, own);
        const auto parts = connected_components(all, connected_components_options{.conn = connectivity::eight});
        const auto first = std::find(all.begin(), all.end(), std::uint8_t{1}) - all.begin();
        REQUIRE(first < all.size());
        for (const bool west : {true, false}) {
            raster<std::int32_t> taken(all.rows(), all.cols(), 0);
            for (std::ptrdiff_t i = 0; i < taken.size(); ++i) {
                const bool in_it =
                    west ? i % taken.cols() < taken.cols() / 2 : parts.labels.data()[i] == parts.labels.data()[first];
                taken.data()[i] = in_it ? 7 : 0;
            }
            const auto cleared = flat_water_seeds(in, {}, {}, source, taken, own);
            long kept = 0, differ = 0;
            for (std::ptrdiff_t i = 0; i < all.size(); ++i) {
                differ += cleared.data()[i] != (taken.data()[i] > 0 ? 0 : all.data()[i]);
                kept += cleared.data()[i];
            }
            CHECK(differ == 0);
            if (west) CHECK(kept > 0);  // the east half keeps its seeds
            const auto first_size = parts.sizes[static_cast<std::size_t>(parts.labels.data()[first])];
            if (!west)
                CHECK(kept == std::count(all.begin(), all.end(), std::uint8_t{1}) - static_cast<long>(first_size));
        }
        CHECK_THROWS_AS(flat_water_seeds(in, {}, {}, source, raster<std::int32_t>(3, 3, 0), own), invalid_input);
    }

    const auto found = extract_waterbodies(pr, {.flat_seeds = true});
    REQUIRE(found.ran);
    const auto score = confusion_counts(found.water, lake.water_filled, lake.cell_m);
    MESSAGE("turbid lake: sensitivity " << 100 * score.sensitivity() << " %, specificity " << 100 * score.specificity()
                                        << " %");
    CHECK(score.sensitivity() >= 0.9);
    CHECK(score.specificity() >= 0.995);
    // The asphalt lot (x 20-80 m, y 20-60 m) stays land.
    long lot_water = 0;
    for (std::ptrdiff_t r = 0; r < lake.g.rows; ++r) {
        for (std::ptrdiff_t c = 0; c < lake.g.cols; ++c) {
            const auto [x, y] = lake.g.center(r, c);
            if (x > 20 && x < 80 && y > 20 && y < 60) lot_water += found.water.view()(r, c);
        }
    }
    CHECK(lot_water == 0);

    CHECK(extract_waterbodies(pr).bodies.empty());  // the defaults: dropout seeds only
}

TEST_CASE("flat_water_seeds: flat dry ground gets none: a meadow, a dark lot on it, a raised flat roof")
{
    auto s = flat_ground();
    CHECK(flat_water_seeds(s.view()).view()(20, 20) == 0);
    // A dark asphalt lot (intensity 15) returns every pulse: dark but not sparse.
    for (std::ptrdiff_t r = 10; r < 30; ++r)
        for (std::ptrdiff_t c = 10; c < 30; ++c) s.intensity(r, c) = 15.0f;
    const auto lot = flat_water_seeds(s.view());
    long n = 0;
    for (std::ptrdiff_t i = 0; i < lot.size(); ++i) n += lot.data()[i];
    CHECK(n == 0);
    // A flat roof 4 m up with fewer returns than the ground (scan geometry): raised, so not water.
    for (std::ptrdiff_t r = 10; r < 30; ++r) {
        for (std::ptrdiff_t c = 10; c < 30; ++c) {
            s.min_z(r, c) = 14.0f + 0.01f * static_cast<float>((r + c) % 3);
            s.max_z(r, c) = s.min_z(r, c) + 0.03f;
            s.count(r, c) = 3;
        }
    }
    const auto roof = flat_water_seeds(s.view());
    n = 0;
    for (std::ptrdiff_t i = 0; i < roof.size(); ++i) n += roof.data()[i];
    CHECK(n == 0);
    // The same block at the ground's level minus 0.5 m, sparse and dark: a pond; it seeds.
    for (std::ptrdiff_t r = 10; r < 30; ++r) {
        for (std::ptrdiff_t c = 10; c < 30; ++c) {
            s.min_z(r, c) = 9.5f + 0.01f * static_cast<float>((r + c) % 3);
            s.max_z(r, c) = s.min_z(r, c) + 0.03f;
        }
    }
    const auto pond = flat_water_seeds(s.view());
    CHECK(pond.view()(20, 20) == 1);
    CHECK(pond.view()(5, 5) == 0);
}

TEST_CASE("flat_water_seeds: a bright but very sparse pond seeds (specular echoes); weak cues together seed")
{
    // A pond 0.5 m below the meadow, as rough as the meadow (max z − min z 5 cm), with half its pulses lost
    // and its echoes brighter than the grass (specular, near nadir): not dark, not smooth, and brighter than
    // its ring, so only bright_density_ratio makes it a seed. (The ring holds the pond's own non-level edge
    // and the meadow's cells next to it, so the ratios lie between the pond's and the meadow's.)
    auto s = flat_ground();
    const auto pond = [&](std::uint32_t count, float intensity, float rough_m) {
        for (std::ptrdiff_t r = 10; r < 30; ++r) {
            for (std::ptrdiff_t c = 10; c < 30; ++c) {
                s.min_z(r, c) = 9.5f + 0.01f * static_cast<float>((r + c) % 3);
                s.max_z(r, c) = s.min_z(r, c) + rough_m;
                s.count(r, c) = count;
                s.intensity(r, c) = intensity;
            }
        }
    };
    pond(3, 120.0f, 0.05f);  // density 0.66 of the ring's, intensity 1.2 times
    CHECK(flat_water_seeds(s.view()).view()(20, 20) == 1);
    CHECK(flat_water_seeds(s.view(), {}, {.bright_density_ratio = 0}).view()(20, 20) == 0);
    pond(4, 120.0f, 0.05f);  // density 0.79: bright and only a little sparse, as a sunlit field may be
    CHECK(flat_water_seeds(s.view()).view()(20, 20) == 0);

    // Weak cues together: 8 of 10 returns (0.88 of the ring's: not sparse), intensity 0.71 of the ring's
    // (not dark), roughness 3 cm, 0.68 of the median of level cells (not smooth). Each alone is not
    // enough; their product (0.43) is within max_joint_ratio (0.6), on 324 level cells.
    for (std::ptrdiff_t i = 0; i < s.count.size(); ++i) s.count.data()[i] = 10;
    pond(8, 45.0f, 0.03f);
    CHECK(flat_water_seeds(s.view()).view()(20, 20) == 1);
    // It is also dark against the survey's land (45 <= 0.8 · 80, the meadow being land): without that test
    // only the joint path takes it.
    CHECK(flat_water_seeds(s.view(), {}, {.max_joint_ratio = 0, .max_land_intensity_ratio = 0}).view()(20, 20) == 0);
    CHECK(flat_water_seeds(s.view(), {}, {.max_joint_ratio = 0}).view()(20, 20) == 1);
    CHECK(flat_water_seeds(s.view(), {}, {.joint_min_cells = 325, .max_land_intensity_ratio = 0}).view()(20, 20) == 0);
    CHECK(flat_water_seeds(s.view()).view()(5, 5) == 0);
    // As dense as the meadow, the joint path does not take it although the product (0.48) is within
    // max_joint_ratio: like the dark and smooth paths it needs at most dark_density_ratio of the ring's
    // returns (a dark, smooth lot returns every pulse). Dark against the survey's land and 0.5 m below the
    // meadow around it, it is a seed all the same (dark and sunken: water that returns every pulse); flush
    // with the meadow, as a lot lies, it is not.
    pond(10, 45.0f, 0.03f);
    CHECK(flat_water_seeds(s.view()).view()(20, 20) == 1);
    CHECK(flat_water_seeds(s.view(), {}, {.min_raised_share = 2}).view()(20, 20) == 0);
    for (std::ptrdiff_t r = 10; r < 30; ++r)
        for (std::ptrdiff_t c = 10; c < 30; ++c) s.min_z(r, c) += 0.5f, s.max_z(r, c) += 0.5f;
    CHECK(flat_water_seeds(s.view()).view()(20, 20) == 0);
}

TEST_CASE(
    "flat_water_seeds: judged against the survey's land, a level lawn of land intensity is no seed, a dim pond is")
{
    // 60 × 60 cells of rough land (min z 10.0-10.2 m, not level), intensity 80, 8 returns per cell. A level
    // lawn (20 × 20 cells, 3 cm rough) as bright as the land, with 6 returns per cell where strip overlap
    // gives its ring 8: sparse by the ring (0.75), but land-like by the survey (its intensity is at the
    // land's 10 % quantile) and not sparse enough for that (> bright_density_ratio 0.72). A pond 0.5 m lower,
    // intensity 40, 7 returns per cell (0.875), inside a belt of dim wet ground (intensity 60): not dark
    // against that ring (0.67 > 0.6), dark against the survey's land (40 <= 0.8 · 60, the land's 10 % quantile).
    water_test::survey s(60, 60);
    for (std::ptrdiff_t r = 0; r < 60; ++r) {
        for (std::ptrdiff_t c = 0; c < 60; ++c) {
            s.min_z(r, c) = 10.0f + 0.2f * static_cast<float>((r * 7 + c * 3) % 5) / 4.0f;
            s.max_z(r, c) = s.min_z(r, c) + 0.05f;
            s.intensity(r, c) = 80.0f;
            s.count(r, c) = 8;
        }
    }
    for (std::ptrdiff_t r = 8; r < 28; ++r) {
        for (std::ptrdiff_t c = 8; c < 28; ++c) {
            s.min_z(r, c) = 10.0f + 0.01f * static_cast<float>((r + c) % 3);
            s.max_z(r, c) = s.min_z(r, c) + 0.03f;
            s.count(r, c) = 6;
        }
    }
    for (std::ptrdiff_t r = 32; r < 60; ++r)
        for (std::ptrdiff_t c = 32; c < 60; ++c) s.intensity(r, c) = 60.0f;
    for (std::ptrdiff_t r = 36; r < 56; ++r) {
        for (std::ptrdiff_t c = 36; c < 56; ++c) {
            s.min_z(r, c) = 9.5f + 0.01f * static_cast<float>((r + c) % 3);
            s.max_z(r, c) = s.min_z(r, c) + 0.03f;
            s.intensity(r, c) = 40.0f;
            s.count(r, c) = 7;
        }
    }
    const auto seeds = flat_water_seeds(s.view());
    CHECK(seeds.view()(18, 18) == 0);
    CHECK(seeds.view()(46, 46) == 1);
    // Each rule decides: without the land-like test the lawn seeds, without the survey's dark test the pond
    // does not.
    CHECK(flat_water_seeds(s.view(), {}, {.land_intensity_quantile = -1}).view()(18, 18) == 1);
    CHECK(flat_water_seeds(s.view(), {}, {.max_land_intensity_ratio = 0}).view()(46, 46) == 0);
    // The survey's land is every cell with a return outside the lowest components (the lawn and the pond):
    // its 10 % quantile is the belt's 60, its median the land's 80.
    const auto level = flat_level_cells(s.view());
    const auto comps = label_flat_seed_components(s.view(), level);
    const auto rings = measure_flat_seed_rings(s.view(), comps);
    CHECK(std::isnan(rings.land_intensity));
    CHECK(survey_land_intensity(s.view(), comps, rings) == doctest::Approx(60.0).epsilon(0.01));
    CHECK(survey_land_intensity(s.view(), comps, rings, {.land_intensity_quantile = 0.5}) ==
          doctest::Approx(80.0).epsilon(0.01));
    CHECK(std::isnan(survey_land_intensity(s.view(), comps, rings, {.land_intensity_quantile = -1})));
    CHECK_THROWS_AS(survey_land_intensity(s.view(), comps, rings, {.land_intensity_quantile = 1.5}), invalid_input);
    CHECK_THROWS_AS(survey_land_intensity(s.view(), comps, flat_seed_rings{}), invalid_input);
}

TEST_CASE("flat_water_seeds: with a surface slope, a sloping sparse patch is no seed, a level pond is")
{
    // A sparse, dark block 0.5 m below the meadow: level (a pond), it seeds with or without the slope; tilted
    // 3 cm per 2 m cell (1.5 %, a beach: its 3 × 3 windows span 6 cm, within level_tolerance_m), it seeds
    // only without the slope cue.
    auto s = flat_ground();
    const auto block = [&](float tilt_per_cell) {
        for (std::ptrdiff_t r = 10; r < 30; ++r) {
            for (std::ptrdiff_t c = 10; c < 30; ++c) {
                s.min_z(r, c) =
                    9.5f + tilt_per_cell * static_cast<float>(c - 10) + 0.01f * static_cast<float>((r + c) % 3);
                s.max_z(r, c) = s.min_z(r, c) + 0.03f;
                s.count(r, c) = 3;
                s.intensity(r, c) = 20.0f;
            }
        }
    };
    block(0.0f);
    auto slope = water_surface_slope(s.min_z, 2.0);
    CHECK(flat_water_seeds(s.view(), {}, {}, slope).view()(20, 20) == 1);
    block(0.03f);
    slope = water_surface_slope(s.min_z, 2.0);
    CHECK(slope(20, 20) == doctest::Approx(0.015).epsilon(0.1));  // the 1 cm pattern tilts the fit a little
    CHECK(flat_water_seeds(s.view()).view()(20, 20) == 1);
    CHECK(flat_water_seeds(s.view(), {}, {}, slope).view()(20, 20) == 0);
    CHECK(flat_water_seeds(s.view(), {}, {.max_surface_slope = -1}, slope).view()(20, 20) == 1);
    CHECK(flat_water_seeds(s.view(), {}, {.max_surface_slope = 0.02}, slope).view()(20, 20) == 1);
    // A level pond with a beach joined to it (cols 30-37 rising 3 cm per cell, as sparse and dark): one
    // level component, level by its median; its beach cells are no seed cells, its pond cells are.
    block(0.0f);
    for (std::ptrdiff_t r = 10; r < 30; ++r) {
        for (std::ptrdiff_t c = 30; c < 38; ++c) {
            s.min_z(r, c) = 9.5f + 0.03f * static_cast<float>(c - 29) + 0.01f * static_cast<float>((r + c) % 3);
            s.max_z(r, c) = s.min_z(r, c) + 0.03f;
            s.count(r, c) = 3;
            s.intensity(r, c) = 20.0f;
        }
    }
    slope = water_surface_slope(s.min_z, 2.0);
    const auto without = flat_water_seeds(s.view());
    const auto with = flat_water_seeds(s.view(), {}, {}, slope);
    CHECK(without.view()(20, 20) == 1);
    CHECK(without.view()(20, 34) == 1);
    CHECK(with.view()(20, 20) == 1);
    CHECK(with.view()(20, 34) == 0);
}

TEST_CASE("flat_water_seeds: options out of range and rasters of different shapes are refused")
{
    const auto s = flat_ground();
    CHECK_THROWS_AS(flat_water_seeds(s.view(), {}, {.level_radius_cells = 0}), invalid_input);
    CHECK_THROWS_AS(flat_water_seeds(s.view(), {}, {.max_density_ratio = 0}), invalid_input);
    CHECK_THROWS_AS(flat_water_seeds(s.view(), {}, {.max_lower_share = 2}), invalid_input);
    CHECK_THROWS_AS(flat_water_seeds(s.view(), {}, {.bright_density_ratio = 1.5}), invalid_input);
    CHECK_THROWS_AS(flat_water_seeds(s.view(), {}, {.max_joint_ratio = -1}), invalid_input);
    const raster<std::uint8_t> wrong(3, 3, 0);
    CHECK_THROWS_AS(flat_water_seeds(s.view(), wrong), invalid_input);
    // Without a count raster there is no density to compare: no seed.
    auto v = s.view();
    v.count = {};
    CHECK(flat_water_seeds(v).size() == s.min_z.size());
}

TEST_CASE("extract_waterbodies: a flat-seeded lake whose level lies on a multiple of two level gates stays whole")
{
    // The flat seed mask is cut where min z crosses a band of 2 level gates (0.3 m), so that a seed along a
    // falling river holds one level. The bands are centred on each seed part's own mean: a lake whose level
    // sits exactly on 0.3 m · k, its returns ±2-3 cm on both sides of it, is not shredded into pieces that
    // the seed opening and min_seed_cells then drop (water family lake 586: 79 % sensitivity before).
    const auto lake = synth::turbid_lake_scene();
    auto pr = rasterize(lake.points.cloud(), lake.g);
    std::vector<float> level;
    for (std::ptrdiff_t r = 0; r < pr.g.rows; ++r)
        for (std::ptrdiff_t c = 0; c < pr.g.cols; ++c)
            if (lake.water_filled(r, c) && std::isfinite(pr.min_z(r, c))) level.push_back(pr.min_z(r, c));
    REQUIRE(level.size() > 100);
    std::nth_element(level.begin(), level.begin() + static_cast<std::ptrdiff_t>(level.size() / 2), level.end());
    const double median = level[level.size() / 2];
    const extract_waterbodies_options o{.flat_seeds = true};
    const double band = 2 * o.grow.level_gate_m;
    for (const double target : {std::round(median / band) * band, std::round(median / band) * band + band / 2}) {
        const auto shift = static_cast<float>(target - median);
        auto moved = pr;
        for (auto& z : moved.min_z) z += shift;
        for (auto& z : moved.max_z) z += shift;
        const auto found = extract_waterbodies(moved, o);
        REQUIRE(found.ran);
        const auto score = confusion_counts(found.water, lake.water_filled, lake.cell_m);
        MESSAGE("lake level at " << target << " m (band " << band << " m): sensitivity " << 100 * score.sensitivity()
                                 << " %");
        CHECK(score.sensitivity() >= 0.9);
        CHECK(score.specificity() >= 0.995);
    }
}

TEST_CASE("flat_water_seeds' row helpers: next_positive and ring_row against plain loops")
{
    // Plain references: the first positive value from c on, and the ring test cell by cell.
    const auto first_positive = [](const auto& row, std::ptrdiff_t c) {
        const auto n = static_cast<std::ptrdiff_t>(row.size());
        while (c < n && !(row[static_cast<std::size_t>(c)] > 0)) ++c;
        return c;
    };
    std::uint32_t state = 12345;  // LCG: deterministic, no <random> distribution differences
    const auto next = [&] { return (state = state * 1664525u + 1013904223u) >> 8; };
    for (const std::ptrdiff_t n : {0, 1, 2, 15, 16, 17, 31, 32, 33, 100, 257}) {
        for (int trial = 0; trial < 20; ++trial) {
            // Sparse positives (1 in 40), runs of -1 and 0, or none at all (trial 0), or all positive (trial 1).
            std::vector<std::int32_t> labels(static_cast<std::size_t>(n));
            std::vector<std::uint8_t> bytes(labels.size());
            for (std::size_t i = 0; i < labels.size(); ++i) {
                const std::uint32_t x = next() % 40;
                labels[i] = trial == 0   ? -static_cast<std::int32_t>(x % 2)
                            : trial == 1 ? 1 + static_cast<std::int32_t>(x)
                            : x == 0     ? static_cast<std::int32_t>(next() % 1000 + 1)
                            : x < 10     ? -1
                                         : 0;
                bytes[i] = static_cast<std::uint8_t>(trial == 1 || x == 0 ? 1 + next() % 255 : 0);
            }
            if (trial == 2 && n > 0) labels.back() = std::numeric_limits<std::int32_t>::max();  // at the border
            for (std::ptrdiff_t c = 0; c <= n; ++c) {
                REQUIRE(detail::next_positive(labels.data(), c, n) == first_positive(labels, c));
                REQUIRE(detail::next_positive(bytes.data(), c, n) == first_positive(bytes, c));
            }
            // ring_row: every combination of its five inputs, NaN and infinite heights among them.
            std::vector<std::int32_t> highest(labels.size());
            std::vector<std::uint8_t> drop(labels.size()), inside(labels.size()), out(labels.size(), 7);
            std::vector<float> z(labels.size());
            constexpr float inf = std::numeric_limits<float>::infinity();
            const float heights[] = {1.5f, std::numeric_limits<float>::quiet_NaN(), inf, -inf, -0.0f};
            for (std::size_t i = 0; i < labels.size(); ++i) {
                highest[i] = next() % 3 == 0 ? 0 : static_cast<std::int32_t>(next() % 50 + 1);
                drop[i] = static_cast<std::uint8_t>(next() % 4 == 0);
                inside[i] = static_cast<std::uint8_t>(next() % 5 == 0 ? 0 : next() % 255 + 1);
                z[i] = heights[next() % 5];
            }
            detail::ring_row(labels.data(), highest.data(), drop.data(), z.data(), inside.data(), out.data(), n);
            for (std::size_t i = 0; i < labels.size(); ++i) {
                const bool ring = labels[i] == 0 && highest[i] != 0 && !drop[i] && std::isfinite(z[i]) && inside[i];
                REQUIRE(out[i] == (ring ? 1 : 0));
            }
        }
    }
}

TEST_CASE("flat_water_seeds: more large components than 16-bit labels hold give the same seeds as fewer")
{
    // Single level cells every third row and column (each its own component, min_cells 1) among rough cells
    // with returns: those with 2 returns against the ring's 4 are sparse seeds, those with 4 are not. 768²
    // holds 65536 components (the ring's labels in 32 bits), 300² 10000 (in 16 bits); ring_cells 1 reaches
    // one component, 2 several.
    for (const std::ptrdiff_t side : {300, 768}) {
        water_test::survey s(side, side);
        for (std::ptrdiff_t r = 0; r < side; ++r) {
            for (std::ptrdiff_t c = 0; c < side; ++c) {
                const bool level = r % 3 == 0 && c % 3 == 0;
                s.max_z(r, c) = level ? 10.0f : 11.0f;
                s.count(r, c) = level && (r * 7 + c * 13) % 5 < 2 ? 2 : 4;
            }
        }
        for (const int ring : {1, 2}) {
            for (const int threads : {1, 2}) {
                const auto seeds =
                    flat_water_seeds(s.view(), {}, {.min_cells = 1, .ring_cells = ring}, {}, {}, {.threads = threads});
                long wrong = 0, seeded = 0;
                for (std::ptrdiff_t r = 0; r < side; ++r) {
                    for (std::ptrdiff_t c = 0; c < side; ++c) {
                        const bool expected = r % 3 == 0 && c % 3 == 0 && s.count(r, c) == 2;
                        wrong += (seeds.view()(r, c) != 0) != expected;
                        seeded += seeds.view()(r, c) != 0;
                    }
                }
                CAPTURE(side);
                CAPTURE(ring);
                CHECK(seeded > 0);
                CHECK(wrong == 0);
            }
        }
    }
}

TEST_CASE("flat_water_seeds' slope test: drop_sloping against a plain median per component")
{
    // The plain form: each kept component's slopes (NaN as 0) in a vector of its own, in row order, and its median.
    const auto plain = [](const raster<std::int32_t>& labels, const raster<float>& slope, std::size_t count,
                          double max_slope, std::vector<std::uint8_t> keep) {
        std::vector<std::vector<float>> slopes(count + 1);
        for (std::ptrdiff_t r = 0; r < labels.rows(); ++r) {
            for (std::ptrdiff_t c = 0; c < labels.cols(); ++c) {
                const std::int32_t l = labels(r, c);
                if (l > 0) slopes[static_cast<std::size_t>(l)].push_back(std::isnan(slope(r, c)) ? 0.0f : slope(r, c));
            }
        }
        for (std::size_t l = 1; l <= count; ++l)
            if (keep[l] && !slopes[l].empty() && detail::median(slopes[l]) > max_slope) keep[l] = 0;
        return keep;
    };
    std::uint32_t state = 4242;  // LCG: deterministic
    const auto next = [&] { return (state = state * 1664525u + 1013904223u) >> 8; };
    constexpr float nan = std::numeric_limits<float>::quiet_NaN();
    const std::pair<std::ptrdiff_t, std::ptrdiff_t> shapes[] = {{0, 0}, {1, 1}, {1, 200}, {200, 1}, {3, 65}, {90, 140}};
    for (const auto& item : shapes) {
        const auto& rows = std::get<0>(item);
        const auto& cols = std::get<1>(item);
        for (int trial = 0; trial < 10; ++trial) {
            // Runs of labels 1..count (several runs per row, labels repeating across rows), -1 (small
            // components) and 0; slopes around the threshold, NaN among them; every size counted.
            const std::size_t count = 1 + next() % 12;
            raster<std::int32_t> labels(rows, cols, 0);
            raster<float> slope(rows, cols, 0.0f);
            std::vector<std::size_t> sizes(count + 1, 0);
            for (std::ptrdiff_t r = 0; r < rows; ++r) {
                for (std::ptrdiff_t c = 0; c < cols;) {
                    const std::uint32_t kind = next() % 4;
                    const auto l = kind == 0 ? 0 : kind == 1 ? -1 : static_cast<std::int32_t>(1 + next() % count);
                    for (std::ptrdiff_t e = std::min(cols, c + 1 + static_cast<std::ptrdiff_t>(next() % 90)); c < e;
                         ++c) {
                        labels(r, c) = trial == 0 ? 0 : l;
                        if (labels(r, c) > 0) ++sizes[static_cast<std::size_t>(labels(r, c))];
                        const std::uint32_t x = next() % 20;
                        slope(r, c) = x == 0 ? nan : 0.001f * static_cast<float>(x) * (trial % 3 == 1 ? 1.0f : 0.8f);
                    }
                }
            }
            std::vector<std::uint8_t> keep(count + 1, 0);
            for (std::size_t l = 1; l <= count; ++l) keep[l] = static_cast<std::uint8_t>(trial == 2 || next() % 3 != 0);
            for (const double max_slope : {0.008, 0.0, 1.0}) {
                auto got = keep;
                detail::drop_sloping(labels, slope, sizes, max_slope, got);
                CAPTURE(rows);
                CAPTURE(cols);
                CAPTURE(trial);
                REQUIRE(got == plain(labels, slope, count, max_slope, keep));
            }
        }
    }
}

TEST_CASE("flat_water_seeds' level window (radii 1 and 2) against the window read cell by cell")
{
    // The level test of every cell from its clipped (2k + 1)² window of finite min z, by plain loops.
    std::uint32_t state = 777;
    const auto next = [&] { return (state = state * 1664525u + 1013904223u) >> 8; };
    constexpr float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    const float heights[] = {10.0f, 10.04f, 10.1f, 10.11f, 9.95f, 0.0f, -0.0f, nan, inf, -inf, 3e38f, -3e38f};
    const float max_rough = 0.2f, tolerance = 0.1f;
    for (const auto& [rows, cols] : std::vector<std::pair<std::ptrdiff_t, std::ptrdiff_t>>{
             {1, 1}, {1, 7}, {7, 1}, {2, 2}, {3, 5}, {5, 3}, {17, 33}, {64, 70}}) {
        for (int k = 1; k <= 2; ++k) {
            for (int trial = 0; trial < 6; ++trial) {
                raster<float> z0(rows, cols), z1(rows, cols);
                raster<std::uint8_t> drop(rows, cols), inside(rows, cols), ex(rows, cols);
                for (std::ptrdiff_t r = 0; r < rows; ++r) {
                    for (std::ptrdiff_t c = 0; c < cols; ++c) {
                        // Mostly level heights (trial 0: all finite), some no-data and extreme ones.
                        const auto pick = next() % (trial == 0 ? 5 : std::size(heights));
                        z0(r, c) = heights[pick] + (trial == 1 ? 0.001f * static_cast<float>(next() % 50) : 0.0f);
                        z1(r, c) = z0(r, c) + 0.1f * static_cast<float>(next() % 3);
                        drop(r, c) = static_cast<std::uint8_t>(next() % 9 == 0);
                        inside(r, c) = static_cast<std::uint8_t>(next() % 11 == 0 ? 0 : 1 + next() % 200);
                        ex(r, c) = static_cast<std::uint8_t>(next() % 7 == 0 ? 1 + next() % 200 : 0);
                    }
                }
                const std::vector<float> nan_row(static_cast<std::size_t>(cols), nan);
                std::vector<float> low(static_cast<std::size_t>(cols + 2 * k)), high(low.size());
                std::vector<std::uint8_t> out(static_cast<std::size_t>(cols));
                for (std::ptrdiff_t r = 0; r < rows; ++r) {
                    const float* window[5];
                    for (std::ptrdiff_t d = -k; d <= k; ++d)
                        window[d + k] = r + d >= 0 && r + d < rows ? z0.view().row(r + d) : nan_row.data();
                    (k == 1 ? detail::level_window_row<1>
                            : detail::level_window_row<2>)(window, low.data(), high.data(), z0.view().row(r),
                                                           z1.view().row(r), drop.view().row(r), inside.view().row(r),
                                                           ex.view().row(r), out.data(), cols, max_rough, tolerance);
                    for (std::ptrdiff_t c = 0; c < cols; ++c) {
                        float lo = inf, hi = -inf;
                        for (std::ptrdiff_t rr = std::max<std::ptrdiff_t>(0, r - k); rr <= std::min(rows - 1, r + k);
                             ++rr)
                            for (std::ptrdiff_t cc = std::max<std::ptrdiff_t>(0, c - k);
                                 cc <= std::min(cols - 1, c + k); ++cc)
                                if (std::isfinite(z0(rr, cc))) {
                                    lo = std::min(lo, z0(rr, cc));
                                    hi = std::max(hi, z0(rr, cc));
                                }
                        const bool level = !drop(r, c) && std::isfinite(z0(r, c)) && inside(r, c) && !ex(r, c) &&
                                           z1(r, c) - z0(r, c) <= max_rough && hi - lo <= tolerance;
                        REQUIRE(out[static_cast<std::size_t>(c)] == (level ? 1 : 0));
                    }
                }
            }
        }
    }
}

TEST_CASE("survey_land_intensity: the quantile's bin against a sort of the land cells, the same for any thread count")
{
    // Random rolling ground with level patches (some of them lowest components), random intensities over six
    // decades, negative and NaN intensities and dropouts: the answer is the middle of the 16-bit bin of the
    // ceil(q n)-th smallest land intensity (negative as 0), whatever the thread count.
    std::mt19937 rng(20261207);
    std::uniform_real_distribution<double> u(0, 1);
    water_test::survey s(173, 61);
    for (std::ptrdiff_t r = 0; r < 173; ++r) {
        for (std::ptrdiff_t c = 0; c < 61; ++c) {
            const bool patch = (r / 20) % 2 == 0 && (c / 15) % 2 == 0;
            const auto z = static_cast<float>(patch ? 9.0 + 0.005 * u(rng) : 10.0 + 2.0 * u(rng));
            s.min_z(r, c) = z, s.max_z(r, c) = z + 0.02f;
            s.intensity(r, c) = static_cast<float>(std::pow(10.0, 6.0 * u(rng) - 2.0));
            if (u(rng) < 0.03) s.intensity(r, c) = -5.0f;
            if (u(rng) < 0.02) s.intensity(r, c) = std::nanf("");
            if (u(rng) < 0.05) s.drop(r, c);
        }
    }
    const auto level = flat_level_cells(s.view());
    const auto comps = label_flat_seed_components(s.view(), level);
    const auto rings = measure_flat_seed_rings(s.view(), comps);
    REQUIRE(comps.count() > 0);
    for (const double q : {0.1, 0.5, 0.93}) {
        const flat_water_seeds_options opt{.land_intensity_quantile = q};
        std::vector<float> land;
        for (std::ptrdiff_t r = 0; r < 173; ++r)
            for (std::ptrdiff_t c = 0; c < 61; ++c) {
                const auto l = static_cast<std::size_t>(comps.labels(r, c));
                const bool lowest_component =
                    l > 0 && rings.cells[l] > 0 && rings.lower[l] <= opt.max_lower_share * rings.cells[l];
                if (lowest_component || s.dropout(r, c) || !std::isfinite(s.min_z(r, c)) ||
                    !std::isfinite(s.intensity(r, c)))
                    continue;
                land.push_back(std::max(s.intensity(r, c), 0.0f));
            }
        REQUIRE(land.size() > 5000);
        std::sort(land.begin(), land.end());
        const auto k = static_cast<std::size_t>(std::ceil(q * static_cast<double>(land.size()))) - 1;
        const auto expected = std::bit_cast<float>((std::bit_cast<std::uint32_t>(land[k]) & 0xFFFF0000u) | 0x8000u);
        for (const int threads : {1, 2, 3, 8}) {
            CAPTURE(threads);
            CHECK(survey_land_intensity(s.view(), comps, rings, opt, {.threads = threads}) == expected);
        }
    }
}
