// SPDX-License-Identifier: Apache-2.0
// The steps of flat_water_seeds: flat_level_cells, label_flat_seed_components, measure_flat_seed_rings,
// select_flat_seeds and write_flat_seed_mask, each against a plain reference, and their composition.
#include <doctest/doctest.h>

#include <lidarfx/pipelines/water/flat_level_cells.hpp>
#include <lidarfx/pipelines/water/flat_seed_components.hpp>
#include <lidarfx/pipelines/water/flat_seed_rings.hpp>
#include <lidarfx/pipelines/water/flat_water_seeds.hpp>
#include <lidarfx/pipelines/water/select_flat_seeds.hpp>
#include <lidarfx/pipelines/water/water_surface_slope.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "water_test_rasters.hpp"

using namespace lidarfx;

namespace {

/// A random survey of plateaus (level patches at a few heights, noise below the tolerance on some), with
/// dropouts, rough cells, and varying counts and intensities: many components, rings and shared rings.
water_test::survey random_survey(std::mt19937& rng, std::ptrdiff_t rows, std::ptrdiff_t cols)
{
    water_test::survey s(rows, cols);
    std::uniform_int_distribution<int> level(0, 3), count(1, 8);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const std::ptrdiff_t block = 3 + static_cast<std::ptrdiff_t>(rng() % 5);
    std::vector<int> heights(static_cast<std::size_t>((rows / block + 1) * (cols / block + 1)));
    for (auto& h : heights) h = level(rng);
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const int h = heights[static_cast<std::size_t>((r / block) * (cols / block + 1) + c / block)];
            const float z = 10.0f + 0.5f * static_cast<float>(h) + 0.03f * u(rng);
            s.min_z(r, c) = z;
            s.max_z(r, c) = z + (u(rng) < 0.1f ? 0.5f : 0.1f * u(rng));
            s.intensity(r, c) = 20.0f + 60.0f * u(rng);
            s.count(r, c) = static_cast<std::uint32_t>(count(rng));
            if (u(rng) < 0.05f) s.drop(r, c);
        }
    }
    return s;
}

/// flat_level_cells by its definition, with thresholds exact in float.
raster<std::uint8_t> brute_level(const water_rasters& in, const flat_water_seeds_options& opt)
{
    const std::ptrdiff_t rows = in.min_z.rows(), cols = in.min_z.cols(), k = opt.level_radius_cells;
    raster<std::uint8_t> out(rows, cols, 0);
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const float z0 = in.min_z(r, c);
            if (in.dropout(r, c) != 0 || !std::isfinite(z0)) continue;
            if (!(in.max_z(r, c) - z0 <= static_cast<float>(opt.max_roughness_m))) continue;
            float lo = std::numeric_limits<float>::infinity(), hi = -lo;
            for (std::ptrdiff_t rr = std::max<std::ptrdiff_t>(0, r - k); rr <= std::min(rows - 1, r + k); ++rr)
                for (std::ptrdiff_t cc = std::max<std::ptrdiff_t>(0, c - k); cc <= std::min(cols - 1, c + k); ++cc)
                    if (std::isfinite(in.min_z(rr, cc))) {
                        lo = std::min(lo, in.min_z(rr, cc));
                        hi = std::max(hi, in.min_z(rr, cc));
                    }
            out(r, c) = hi - lo <= static_cast<float>(opt.level_tolerance_m);
        }
    }
    return out;
}

/// measure_flat_seed_rings by its definition: every cell with a return in no level component, against every
/// component with a cell within ring_cells of it.
flat_seed_rings brute_rings(const water_rasters& in, const flat_seed_components& comps,
                            const flat_water_seeds_options& opt)
{
    const std::ptrdiff_t rows = in.min_z.rows(), cols = in.min_z.cols(), q = opt.ring_cells;
    const std::size_t n = comps.count();
    flat_seed_rings out{std::vector<double>(n + 1, 0), std::vector<double>(n + 1, 0), std::vector<double>(n + 1, 0),
                        std::vector<double>(n + 1, 0), std::vector<double>(n + 1, 0)};
    const auto& labels = comps.labels;
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            if (labels(r, c) != 0 || in.dropout(r, c) != 0 || !std::isfinite(in.min_z(r, c))) continue;
            std::vector<float> lowest(n + 1, std::numeric_limits<float>::infinity());
            for (std::ptrdiff_t rr = std::max<std::ptrdiff_t>(0, r - q); rr <= std::min(rows - 1, r + q); ++rr)
                for (std::ptrdiff_t cc = std::max<std::ptrdiff_t>(0, c - q); cc <= std::min(cols - 1, c + q); ++cc)
                    if (labels(rr, cc) > 0) {
                        auto& low = lowest[static_cast<std::size_t>(labels(rr, cc))];
                        low = std::min(low, in.min_z(rr, cc));
                    }
            for (std::size_t l = 1; l <= n; ++l) {
                if (comps.free_cells[l] == 0 || std::isinf(lowest[l])) continue;
                out.count_sum[l] += in.count(r, c);
                out.cells[l] += 1;
                out.intensity_sum[l] += in.mean_intensity(r, c);
                out.lower[l] += in.min_z(r, c) < lowest[l] - opt.level_tolerance_m;
                out.raised[l] += in.min_z(r, c) > lowest[l] + opt.level_tolerance_m;
            }
        }
    }
    return out;
}

}  // namespace

TEST_CASE("flat_level_cells: matches its definition for small and large windows, any thread count")
{
    const unsigned seed = 1204;
    std::mt19937 rng(seed);
    for (int trial = 0; trial < 30; ++trial) {
        std::uniform_int_distribution<int> dim(1, 45);
        const auto s = random_survey(rng, dim(rng), dim(rng));
        const flat_water_seeds_options opt{
            .level_radius_cells = 1 + trial % 4, .level_tolerance_m = 0.25, .max_roughness_m = 0.125};
        INFO("seed " << seed << " trial " << trial << " radius " << opt.level_radius_cells);
        CHECK(flat_level_cells(s.view(), {}, opt, {.threads = trial % 3}) == brute_level(s.view(), opt));
    }
}

TEST_CASE("flat_level_cells: excluded and outside-footprint cells are never level; shapes are checked")
{
    auto s = water_test::survey(6, 7);
    raster<std::uint8_t> excluded(6, 7, 0), footprint(6, 7, 1);
    excluded(2, 3) = 1;
    footprint(4, 4) = 0;
    auto in = s.view();
    in.footprint = footprint;
    const auto level = flat_level_cells(in, excluded);
    CHECK(level(2, 3) == 0);
    CHECK(level(4, 4) == 0);
    CHECK(std::count(level.begin(), level.end(), std::uint8_t{1}) == 6 * 7 - 2);
    raster<std::uint8_t> wrong(3, 3, 0);
    CHECK_THROWS_AS(flat_level_cells(in, wrong), invalid_input);
    CHECK_THROWS_AS(flat_level_cells(in, {}, {}, wrong), invalid_input);
}

TEST_CASE("label_flat_seed_components and measure_flat_seed_rings: match their definitions on random surveys")
{
    const unsigned seed = 361;
    std::mt19937 rng(seed);
    for (int trial = 0; trial < 30; ++trial) {
        std::uniform_int_distribution<int> dim(2, 50);
        const auto s = random_survey(rng, dim(rng), dim(rng));
        const flat_water_seeds_options opt{.level_tolerance_m = 0.25,
                                           .max_roughness_m = 0.125,
                                           .min_cells = 1 + static_cast<std::size_t>(trial % 6),
                                           .ring_cells = 1 + trial % 5};
        const execution run{.threads = trial % 3};
        INFO("seed " << seed << " trial " << trial);
        const auto level = flat_level_cells(s.view(), {}, opt, run);
        const auto comps = label_flat_seed_components(s.view(), level, {}, opt, {}, run);
        // Labels: the components of >= min_cells cells numbered in raster-scan order, -1 the smaller ones.
        const auto all = connected_components(level, connectivity::eight);
        std::vector<std::int32_t> expected(all.sizes.size(), 0);
        std::int32_t next = 0;
        for (std::size_t l = 1; l < all.sizes.size(); ++l) expected[l] = all.sizes[l] >= opt.min_cells ? ++next : -1;
        bool labels_ok = comps.count() == static_cast<std::size_t>(next);
        for (std::ptrdiff_t i = 0; i < level.size(); ++i)
            labels_ok = labels_ok && comps.labels.data()[i] == expected[static_cast<std::size_t>(all.labels.data()[i])];
        CHECK(labels_ok);
        const auto rings = measure_flat_seed_rings(s.view(), comps, opt, run);
        const auto brute = brute_rings(s.view(), comps, opt);
        CHECK(rings.cells == brute.cells);
        CHECK(rings.count_sum == brute.count_sum);
        CHECK(rings.lower == brute.lower);
        CHECK(rings.raised == brute.raised);
        // Intensities summed in another order: equal to rounding (a few ulp of sums of < 2500 values).
        for (std::size_t l = 1; l <= comps.count(); ++l)
            CHECK(rings.intensity_sum[l] == doctest::Approx(brute.intensity_sum[l]).epsilon(1e-12));
    }
}

TEST_CASE("flat_water_seeds: the composition of its steps, with a surface slope and taken cells")
{
    const unsigned seed = 77;
    std::mt19937 rng(seed);
    for (int trial = 0; trial < 20; ++trial) {
        std::uniform_int_distribution<int> dim(8, 60);
        const auto s = random_survey(rng, dim(rng), dim(rng));
        const auto in = s.view();
        const flat_water_seeds_options opt{.level_tolerance_m = 0.25,
                                           .max_roughness_m = 0.125,
                                           .min_cells = 4,
                                           .ring_cells = 2,
                                           .max_density_ratio = 1.0,
                                           .dark_density_ratio = 1.0};
        const auto slope = water_surface_slope(in.min_z, 1.0);
        raster<std::int32_t> taken(in.min_z.rows(), in.min_z.cols(), 0);
        for (std::ptrdiff_t i = 0; i < taken.size(); ++i) taken.data()[i] = (rng() % 4 == 0) ? 3 : 0;
        INFO("seed " << seed << " trial " << trial);
        auto mask = flat_level_cells(in, {}, opt);
        const auto comps = label_flat_seed_components(in, mask, taken, opt);
        auto rings = measure_flat_seed_rings(in, comps, opt);
        rings.land_intensity = survey_land_intensity(in, comps, rings, opt);
        const auto keep = select_flat_seeds(comps, rings, opt, slope);
        write_flat_seed_mask(comps, keep, mask, taken, slope, opt);
        CHECK(mask == flat_water_seeds(in, {}, opt, slope, taken));
        CHECK_THROWS_AS(write_flat_seed_mask(comps, {}, mask), invalid_input);
    }
}
