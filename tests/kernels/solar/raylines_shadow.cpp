// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/kernels/solar/raylines_shadow.hpp>

#include "reference/angular_filter.hpp"  // random_raster, with_margin, inner
#include "reference/progress.hpp"
#include "reference/solar.hpp"
#include "test_values.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <sstream>
#include <string>

using namespace lidarfx;

namespace {

// The first cell where two masks differ, or "" when they are equal.
std::string first_difference(const raster<std::uint8_t>& got, const raster<std::uint8_t>& want)
{
    for (std::ptrdiff_t r = 0; r < want.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < want.cols(); ++c) {
            if (got(r, c) != want(r, c)) {
                std::ostringstream os;
                os << "cell (" << r << ", " << c << "): " << int(got(r, c)) << " vs " << int(want(r, c));
                return os.str();
            }
        }
    }
    return "";
}

// The first cell where raylines_shadow with `phases` line families differs from a search of every cell's line.
std::string differs_from_line_search(raster_view<const float> z, double cell_m, double azimuth, double elevation,
                                     int phases)
{
    return first_difference(raylines_shadow(z, cell_m, azimuth, elevation, {.line_phases = phases}),
                            reference::shadow_on_lines(z, cell_m, azimuth, elevation, 255, phases));
}

double agreement(const raster<std::uint8_t>& a, const raster<std::uint8_t>& b)
{
    std::size_t same = 0;
    for (std::ptrdiff_t r = 0; r < a.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < a.cols(); ++c) same += a(r, c) == b(r, c);
    return static_cast<double>(same) / static_cast<double>(a.rows() * a.cols());
}

}  // namespace

TEST_CASE("solar/raylines_shadow: equals a brute-force ray march for the sun along the grid axes")
{
    const unsigned seed = 20261201;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> elevation(2.0, 80.0);
    for (int trial = 0; trial < 40; ++trial) {
        const double azimuth = 90.0 * (trial % 4);
        const double e = elevation(rng);
        const auto small = reference::random_raster(rng, 17 + trial % 5, 23 - trial % 7, 0.0, 10.0, 0.05);
        const auto big = reference::with_margin(small, 2, -1000.0f);
        const auto z = reference::inner(big, 2, small.rows(), small.cols());  // strided: row_stride > cols
        INFO("seed ", seed, " trial ", trial, " azimuth ", azimuth, " elevation ", e);
        const auto want = reference::shadow_ray_march(small.view(), 1.5, azimuth, e);
        CHECK(first_difference(raylines_shadow(z, 1.5, azimuth, e), want) == "");
        CHECK(first_difference(raylines_shadow(small, 1.5, azimuth, e), want) == "");
    }
}

TEST_CASE("solar/raylines_shadow: equals a direct search over its ray lines for any azimuth")
{
    const unsigned seed = 7031;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> azimuth(-30.0, 400.0), elevation(2.0, 80.0);
    for (int trial = 0; trial < 60; ++trial) {
        const double a = trial < 8 ? 45.0 * trial : azimuth(rng), e = elevation(rng);
        const auto z = reference::random_raster(rng, 9 + trial % 13, 31 - trial % 11, 0.0, 10.0, 0.05);
        for (const int phases : {1, 2, 4, 7}) {
            INFO("seed ", seed, " trial ", trial, " azimuth ", a, " elevation ", e, " line_phases ", phases);
            CHECK(differs_from_line_search(z, 0.5, a, e, phases) == "");
        }
    }
}

TEST_CASE(
    "solar/raylines_shadow: shallow lines (swept in tiles of the transposed raster) equal the direct search on "
    "wide, tall and strided rasters")
{
    // Shallow azimuths (closer to east-west than to north-south) take the transposed sweep: 16 columns at a time,
    // blocks of 512 lines. These rasters cross several tiles and blocks, end in partial tiles, and come as views
    // with a row stride wider than their columns.
    std::mt19937 rng(1606);
    const auto wide = reference::random_raster(rng, 41, 700, 0.0, 10.0, 0.03);
    const auto tall_big = reference::with_margin(reference::random_raster(rng, 300, 37, 0.0, 10.0, 0.03), 3, 7.0f);
    const auto tall = reference::inner(tall_big, 3, 300, 37);
    for (const double a : {48.0, 80.0, 90.0, 101.0, 133.0, 228.0, 265.0, 270.0, 312.0}) {
        for (const int phases : {1, 4}) {
            INFO("azimuth ", a, " line_phases ", phases);
            CHECK(differs_from_line_search(wide, 0.7, a, 9.0, phases) == "");
            CHECK(differs_from_line_search(tall, 0.7, a, 4.0, phases) == "");
        }
    }
}

// A family of ray lines and a ray from each cell's own centre pick cells up to 1 / (2 line_phases) apart across
// the ray, so they can differ along the lateral edges of shadows; the share of such cells falls as buildings
// grow. Two brute forces that differ only in how a straight ray picks cells (nearest cell per row, or every
// cell it touches) disagree with each other on about 0.45 % of these cells. With the default four families
// every trial reaches 99.5 %.
TEST_CASE("solar/raylines_shadow: agrees with a straight ray march on >= 99.5 % of a town's cells")
{
    const unsigned seed = 4242;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> azimuth(0.0, 360.0), elevation(10.0, 70.0);
    double worst = 1.0, sum = 0.0, dda_sum = 0.0, refs_sum = 0.0;
    const int trials = 24;
    for (int trial = 0; trial < trials; ++trial) {
        const double a = azimuth(rng), e = elevation(rng);
        // 1 m cells, buildings 8..30 m on a side, about a fifth of the ground covered.
        const auto z = reference::box_town(rng, 200, 220, 25, 0.3, 8, 30);
        const auto lit = raylines_shadow(z, 1.0, a, e);
        const auto sampled = reference::shadow_sampled_march(z.view(), 1.0, a, e);
        const auto dda = reference::shadow_ray_march(z.view(), 1.0, a, e);
        const double share = agreement(lit, sampled);
        INFO("seed ", seed, " trial ", trial, " azimuth ", a, " elevation ", e, " agreement ", share);
        CHECK(share >= 0.995);
        worst = std::min(worst, share);
        sum += share;
        dda_sum += agreement(lit, dda);
        refs_sum += agreement(sampled, dda);
    }
    CHECK(sum / trials >= 0.998);  // equal-sized rasters: the mean share is the share of all cells
    MESSAGE("raylines_shadow vs per-cell ray march (nearest cell per row/column), 8..30 m buildings: all cells ",
            sum / trials, ", worst trial ", worst, "; vs cell-traversal march: ", dda_sum / trials,
            "; the two marches agree with each other on ", refs_sum / trials);
}

TEST_CASE("solar/raylines_shadow: agrees with a straight ray march on >= 99 % of a town of small 3..14 m buildings")
{
    std::mt19937 rng(4243);
    std::uniform_real_distribution<double> azimuth(0.0, 360.0), elevation(10.0, 70.0);
    double sum = 0.0, worst = 1.0;
    const int trials = 12;
    for (int trial = 0; trial < trials; ++trial) {
        const double a = azimuth(rng), e = elevation(rng);
        const auto z = reference::box_town(rng, 120, 140, 40);
        const double share =
            agreement(raylines_shadow(z, 1.0, a, e), reference::shadow_sampled_march(z.view(), 1.0, a, e));
        CHECK(share >= 0.99);
        sum += share;
        worst = std::min(worst, share);
    }
    CHECK(sum / trials >= 0.995);
    MESSAGE("raylines_shadow vs per-cell ray march, 3..14 m buildings covering ~17 %: mean ", sum / trials, ", worst ",
            worst);
}

TEST_CASE("solar/raylines_shadow: a flat plane is lit everywhere, for any sun above the horizon")
{
    const raster<float> flat(30, 40, 12.5f);
    for (double a : {0.0, 33.0, 90.0, 135.0, 200.0, 270.0, 359.0}) {
        for (double e : {0.5, 10.0, 45.0, 89.0}) {
            const auto lit = raylines_shadow(flat, 1.0, a, e);
            CHECK(agreement(lit, raster<std::uint8_t>(30, 40, 1)) == 1.0);
        }
    }
}

TEST_CASE("solar/raylines_shadow: a wall's shadow is height / tan(elevation) long, within a cell")
{
    // A north-south wall 10 m tall at column 5; the sun in the west (azimuth 270) throws its shadow east.
    const double cell_m = 0.5, height_m = 10.0;
    raster<float> z(6, 200, 0.0f);
    for (std::ptrdiff_t r = 0; r < 6; ++r) z(r, 5) = static_cast<float>(height_m);
    for (double e : {10.0, 20.0, 30.0, 45.0, 60.0}) {
        const auto lit = raylines_shadow(z, cell_m, 270.0, e);
        std::ptrdiff_t c = 6;
        while (c < 200 && lit(3, c) == 0) ++c;
        const double shadow_m = double(c - 6) * cell_m;
        const double expected_m = height_m / std::tan(e * std::numbers::pi / 180.0);
        INFO("elevation ", e, " shadow ", shadow_m, " m, expected ", expected_m, " m");
        CHECK(std::fabs(shadow_m - expected_m) <= cell_m);
        CHECK(lit(3, 4) == 1);  // the sunny side
        CHECK(lit(3, 5) == 1);  // the wall top
    }
}

TEST_CASE("solar/raylines_shadow: NaN cells are marked and cast no shadow")
{
    raster<float> z(5, 12, 0.0f);
    z(2, 3) = 50.0f;  // a mast that shadows the cells east of it under a western sun
    z(2, 6) = nan_f;
    auto lit = raylines_shadow(z, 1.0, 270.0, 30.0);
    CHECK(lit(2, 6) == 255);
    CHECK(lit(2, 5) == 0);
    CHECK(lit(2, 7) == 0);  // the shadow passes over the hole
    CHECK(raylines_shadow(z, 1.0, 270.0, 30.0, {.nan_cell = 0})(2, 6) == 0);
    z(2, 3) = nan_f;  // a hole instead of the mast: everything else lit
    lit = raylines_shadow(z, 1.0, 270.0, 30.0);
    CHECK(lit(2, 3) == 255);
    CHECK(lit(2, 4) == 1);
    CHECK(lit(2, 7) == 1);
}

TEST_CASE("solar/raylines_shadow: sun at or below the horizon shadows all, at the zenith lights all")
{
    std::mt19937 rng(5);
    auto z = reference::random_raster(rng, 8, 9, 0.0, 10.0);
    z(1, 1) = nan_f;
    for (double e : {0.0, -5.0, -90.0}) {
        const auto lit = raylines_shadow(z, 1.0, 180.0, e);
        CHECK(lit(1, 1) == 255);
        CHECK(lit(4, 4) == 0);
        CHECK(agreement(lit, raster<std::uint8_t>(8, 9, 0)) == doctest::Approx(71.0 / 72.0));
    }
    const auto noon = raylines_shadow(z, 1.0, 180.0, 90.0);
    CHECK(agreement(noon, raster<std::uint8_t>(8, 9, 1)) == doctest::Approx(71.0 / 72.0));
}

TEST_CASE("solar/raylines_shadow: shadow only grows as the sun sinks")
{
    std::mt19937 rng(99);
    const auto z = reference::box_town(rng, 60, 70, 15);
    for (double a : {10.0, 100.0, 222.0, 300.0}) {
        const auto high = raylines_shadow(z, 1.0, a, 50.0), low = raylines_shadow(z, 1.0, a, 20.0);
        bool monotone = true;
        for (std::ptrdiff_t r = 0; r < z.rows(); ++r)
            for (std::ptrdiff_t c = 0; c < z.cols(); ++c) monotone = monotone && (low(r, c) <= high(r, c));
        CHECK(monotone);
    }
}

TEST_CASE("solar/raylines_shadow: the same result for any thread count; progress and cancellation")
{
    std::mt19937 rng(31337);
    const auto z = reference::box_town(rng, 700, 650, 300);
    for (double a : {0.0, 37.0, 90.0, 163.0, 250.0, 333.0}) {
        const auto one = raylines_shadow(z, 1.0, a, 25.0);
        for (int threads : {2, 3, 0}) {
            CHECK(first_difference(raylines_shadow(z, 1.0, a, 25.0, {.run = {.threads = threads}}), one) == "");
        }
    }
    reference::progress_log log;
    raylines_shadow(z, 1.0, 70.0, 25.0, {.run = {.threads = 2, .progress = log.callback()}});
    CHECK(log.monotone_to_one());  // with a helper thread the caller may report once
    CHECK_THROWS_AS(raylines_shadow(z, 1.0, 70.0, 25.0, {.run = {.progress = reference::cancel_at_once()}}), cancelled);
}

TEST_CASE("solar/raylines_shadow: bad input is refused with invalid_input")
{
    const raster<float> z(4, 4, 1.0f);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_AS(raylines_shadow(z, 0.0, 180.0, 30.0), invalid_input);
    CHECK_THROWS_AS(raylines_shadow(z, -1.0, 180.0, 30.0), invalid_input);
    CHECK_THROWS_AS(raylines_shadow(z, nan, 180.0, 30.0), invalid_input);
    CHECK_THROWS_AS(raylines_shadow(z, 1.0, nan, 30.0), invalid_input);
    CHECK_THROWS_AS(raylines_shadow(z, 1.0, 180.0, nan), invalid_input);
    CHECK_THROWS_AS(raylines_shadow(z, 1.0, 180.0, 91.0), invalid_input);
    CHECK_THROWS_AS(raylines_shadow(z, 1.0, std::numeric_limits<double>::infinity(), 30.0), invalid_input);
    CHECK_THROWS_AS(raylines_shadow(z, 1.0, 180.0, 30.0, {.run = {.threads = -1}}), invalid_input);
    raster<std::uint8_t> wrong(4, 5);
    CHECK_THROWS_AS(raylines_shadow(z, wrong, 1.0, 180.0, 30.0), invalid_input);
    try {
        raylines_shadow(z, 0.0, 180.0, 30.0);
    } catch (const invalid_input& e) {
        CHECK(std::string(e.what()) == "raylines_shadow: cell_m must be finite and > 0 (got 0)");
    }
}

TEST_CASE("solar/raylines_shadow: the design spelling compiles; empty and 1x1 rasters")
{
    const raster<float> dem(3, 3, 5.0f);
    const raster_view<const float> dsm = dem.view();
    const raster<std::uint8_t> lit = raylines_shadow(dsm, 1.0, 180.0, 30.0);
    CHECK(lit(1, 1) == 1);
    CHECK(raylines_shadow(raster<float>(0, 0), 1.0, 45.0, 30.0).rows() == 0);
    CHECK(raylines_shadow(raster<float>(1, 1, 3.0f), 1.0, 45.0, 30.0)(0, 0) == 1);
}

TEST_CASE(
    "solar/raylines_shadow: steep lines (the owner family and up to three others in one pass, the rest one by one) "
    "equal the direct search across blocks of lines, for 1 to 6 families")
{
    // Blocks of 512 lines split these rasters; at a block's edge a row may hold cells of some families' lines
    // and not of the owner family's, and those cells must still raise the other families' maxima.
    std::mt19937 rng(2412);
    const auto wide = reference::random_raster(rng, 37, 1100, 0.0, 12.0, 0.03);
    const auto big = reference::with_margin(reference::random_raster(rng, 29, 530, 0.0, 12.0, 0.03), 2, -5.0f);
    const auto strided = reference::inner(big, 2, 29, 530);
    for (const double a : {0.0, 14.0, 31.0, 44.0, 137.0, 180.0, 203.0, 226.0, 316.0, 349.0}) {
        for (const int phases : {1, 2, 3, 4, 5, 6}) {
            INFO("azimuth ", a, " line_phases ", phases);
            CHECK(differs_from_line_search(wide, 0.8, a, 7.0, phases) == "");
            CHECK(differs_from_line_search(strided, 0.8, a, 3.0, phases) == "");
        }
    }
}

TEST_CASE("solar/raylines_shadow: a tall east edge shadows every family's lines where blocks of lines meet it")
{
    // Lines enter from the east edge; where a block of 512 lines starts at that edge, a row's edge cell may lie on
    // the block's first line of one family and on the previous block's last line of the owner family. Its key
    // must still reach the first family's line. Widths around 512 put a block boundary on the edge.
    // The edge cells' heights differ, so that each casts a shadow of its own.
    const std::ptrdiff_t rows = 60;
    std::mt19937 rng(512);
    std::uniform_real_distribution<float> height(0.0f, 40.0f);
    for (std::ptrdiff_t cols = 470; cols <= 530; cols += 3) {
        lidarfx::raster<float> z(rows, cols, 0.0f);
        for (std::ptrdiff_t r = 0; r < rows; ++r) z(r, cols - 1) = height(rng);
        for (const double a : {20.0, 30.0, 150.0, 160.0}) {
            for (const int phases : {2, 3, 4, 5}) {
                INFO("columns ", cols, " azimuth ", a, " line_phases ", phases);
                CHECK(differs_from_line_search(z, 1.0, a, 10.0, phases) == "");
            }
        }
    }
}
