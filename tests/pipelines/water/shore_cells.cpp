// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/pipelines/water/join_shore_cells.hpp>
#include <lidarfx/pipelines/water/trim_raised_edge_cells.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <vector>

using namespace lidarfx;

namespace {

/// join_shore_cells by its definition, one cell and one window at a time.
raster<std::int32_t> reference_shore(const raster<std::int32_t>& labels, const raster<std::uint32_t>& count,
                                     const raster<std::uint8_t>& excluded, const raster<std::uint8_t>& footprint,
                                     const join_shore_cells_options& o)
{
    const std::ptrdiff_t rows = labels.rows(), cols = labels.cols();
    const auto at = [&](std::ptrdiff_t r, std::ptrdiff_t c) {
        return r >= 0 && c >= 0 && r < rows && c < cols ? labels(r, c) : 0;
    };
    const auto next_to_body = [&](std::ptrdiff_t r, std::ptrdiff_t c) {
        for (int dr = -1; dr <= 1; ++dr)
            for (int dc = -1; dc <= 1; ++dc)
                if ((dr || dc) && at(r + dr, c + dc) > 0) return true;
        return false;
    };
    auto out = labels;
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            if (labels(r, c) > 0 || !footprint(r, c)) continue;
            std::map<std::int32_t, int> votes;
            int n_nb = 0;
            for (int dr = -1; dr <= 1; ++dr)
                for (int dc = -1; dc <= 1; ++dc)
                    if ((dr || dc) && at(r + dr, c + dc) > 0) ++votes[at(r + dr, c + dc)], ++n_nb;
            if (n_nb < o.min_body_neighbours) continue;
            double ws = 0, wn = 0, ls = 0, ln = 0;
            for (std::ptrdiff_t rr = r - o.window_cells; rr <= r + o.window_cells; ++rr) {
                for (std::ptrdiff_t cc = c - o.window_cells; cc <= c + o.window_cells; ++cc) {
                    if (rr < 0 || cc < 0 || rr >= rows || cc >= cols) continue;
                    if (labels(rr, cc) > 0)
                        ws += count(rr, cc), wn += 1;
                    else if (!next_to_body(rr, cc) && count(rr, cc) > 0 && !excluded(rr, cc))
                        ls += count(rr, cc), ln += 1;
                }
            }
            if (wn == 0 || ln == 0) continue;
            const double nl = ls / ln, nw = ws / wn;
            if (nl - nw >= o.min_contrast * nl && nl - count(r, c) >= o.min_water_share * (nl - nw)) {
                auto best = votes.begin();
                for (auto it = votes.begin(); it != votes.end(); ++it)
                    if (it->second > best->second) best = it;
                out(r, c) = best->first;
            }
        }
    }
    return out;
}

}  // namespace

TEST_CASE("water/join_shore_cells: an edge cell that lost most of its pulses joins; one that kept them stays land")
{
    // A lake (label 1) in the west half of a 9 x 12 raster: water returns 2 points per cell, land 10.
    raster<std::int32_t> labels(9, 12, 0);
    raster<std::uint32_t> count(9, 12, 10);
    for (std::ptrdiff_t r = 0; r < 9; ++r)
        for (std::ptrdiff_t c = 0; c < 5; ++c) labels(r, c) = 1, count(r, c) = 2;
    count(4, 5) = 4;  // water share (10 - 4) / (10 - 2) = 0.75: mostly water
    count(2, 5) = 7;  // 0.375: mostly land
    count(6, 5) = 0;  // a dropout on the edge
    const auto joined = join_shore_cells(labels, count);
    CHECK(joined == 2);
    CHECK(labels(4, 5) == 1);
    CHECK(labels(6, 5) == 1);
    CHECK(labels(2, 5) == 0);
    CHECK(labels(4, 6) == 0);  // one pass: a joined cell does not make its neighbour a shore cell
}

TEST_CASE("water/join_shore_cells: no contrast between water and land counts, no join")
{
    raster<std::int32_t> labels(7, 10, 0);
    raster<std::uint32_t> count(7, 10, 10);
    for (std::ptrdiff_t r = 0; r < 7; ++r)
        for (std::ptrdiff_t c = 0; c < 4; ++c) labels(r, c) = 1, count(r, c) = 8;  // contrast 0.2 < 0.3
    count(3, 4) = 1;
    CHECK(join_shore_cells(labels, count) == 0);
    CHECK(labels(3, 4) == 0);
    // With the contrast allowed, the same cell joins; outside the footprint it never does.
    CHECK(join_shore_cells(labels, count, {}, {}, {.min_contrast = 0.2}) == 1);
    labels(3, 4) = 0;
    raster<std::uint8_t> footprint(7, 10, 1);
    footprint(3, 4) = 0;
    CHECK(join_shore_cells(labels, count, {}, footprint, {.min_contrast = 0.2}) == 0);
}

TEST_CASE("water/join_shore_cells: a corner touching the water is not a shore cell; the majority label wins")
{
    raster<std::int32_t> labels(8, 8, 0);
    raster<std::uint32_t> count(8, 8, 12);
    labels(0, 0) = labels(0, 1) = labels(1, 0) = labels(1, 1) = 3;  // a 2 x 2 body
    for (std::ptrdiff_t r = 0; r < 2; ++r)
        for (std::ptrdiff_t c = 0; c < 2; ++c) count(r, c) = 0;
    count(2, 2) = 0;  // touches it by a corner only (1 body neighbour)
    CHECK(join_shore_cells(labels, count) == 0);
    CHECK(join_shore_cells(labels, count, {}, {}, {.min_body_neighbours = 1}) >= 1);
    CHECK(labels(2, 2) == 3);

    raster<std::int32_t> two(5, 5, 0);
    raster<std::uint32_t> n(5, 5, 9);
    two(1, 1) = two(2, 1) = 4;
    two(1, 3) = two(2, 3) = two(3, 3) = 2;
    for (std::ptrdiff_t r = 0; r < 5; ++r)
        for (std::ptrdiff_t c = 0; c < 5; ++c)
            if (two(r, c) > 0) n(r, c) = 0;
    n(2, 2) = 0;  // between a body of 2 neighbours (label 4) and one of 3 (label 2)
    join_shore_cells(two, n);
    CHECK(two(2, 2) == 2);
}

TEST_CASE("water/join_shore_cells: matches the per-cell reference on random rasters")
{
    const unsigned seed = 20261203;
    std::mt19937 rng(seed);
    for (int trial = 0; trial < 46; ++trial) {
        // The last trials are tall: their bands of rows run on 1-3 threads.
        const bool tall = trial >= 40;
        const std::ptrdiff_t rows = tall ? 250 + static_cast<std::ptrdiff_t>(rng() % 600)
                                         : 1 + static_cast<std::ptrdiff_t>(rng() % 40),
                             cols = 1 + static_cast<std::ptrdiff_t>(rng() % (tall ? 12 : 40));
        INFO("seed " << seed << ", trial " << trial << ": " << rows << "x" << cols);
        raster<std::int32_t> labels(rows, cols, 0);
        raster<std::uint32_t> count(rows, cols);
        raster<std::uint8_t> excluded(rows, cols), footprint(rows, cols);
        // Blobs of water (sparse counts) among land (dense counts), some vegetation, a footprint with holes.
        const double share = (trial % 4) * 0.2;
        for (std::ptrdiff_t r = 0; r < rows; ++r) {
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                const bool wet =
                    std::sin(0.4 * static_cast<double>(r) + trial) + std::cos(0.3 * static_cast<double>(c)) >
                    1.0 - 2 * share;
                labels(r, c) = wet ? 1 + static_cast<std::int32_t>(c * 3 / std::max<std::ptrdiff_t>(cols, 1)) : 0;
                count(r, c) = wet ? static_cast<std::uint32_t>(rng() % 4) : static_cast<std::uint32_t>(rng() % 14);
                excluded(r, c) = rng() % 7 == 0;
                footprint(r, c) = rng() % 11 != 0;
            }
        }
        const join_shore_cells_options o{.window_cells = 1 + trial % 3,
                                         .min_water_share = 0.3 + 0.1 * (trial % 5),
                                         .min_body_neighbours = 1 + trial % 4};
        const auto want = reference_shore(labels, count, excluded, footprint, o);
        auto got = labels;
        const auto n = join_shore_cells(got, count, excluded, footprint, o, {.threads = 1 + trial % 3});
        CHECK(got == want);
        std::size_t changed = 0;
        for (std::ptrdiff_t i = 0; i < got.size(); ++i) changed += got.data()[i] != labels.data()[i];
        CHECK(n == changed);
    }
}

TEST_CASE("water/join_shore_cells: empty rasters, one cell, bad options")
{
    raster<std::int32_t> none(0, 0);
    CHECK(join_shore_cells(none, raster<std::uint32_t>(0, 0)) == 0);
    raster<std::int32_t> one(1, 1, 0);
    CHECK(join_shore_cells(one, raster<std::uint32_t>(1, 1, 0)) == 0);
    CHECK_THROWS_WITH_AS(join_shore_cells(one, raster<std::uint32_t>(1, 2, 0)), doctest::Contains("join_shore_cells"),
                         invalid_input);
    CHECK_THROWS_AS(join_shore_cells(one, raster<std::uint32_t>(1, 1, 0), {}, {}, {.min_contrast = 0}), invalid_input);
    CHECK_THROWS_AS(join_shore_cells(one, raster<std::uint32_t>(1, 1, 0), {}, {}, {.min_body_neighbours = 9}),
                    invalid_input);
    CHECK_THROWS_AS(join_shore_cells(one, raster<std::uint32_t>(1, 1, 0), {}, {}, {.window_cells = 0}), invalid_input);
}

namespace {

/// trim_raised_edge_cells by its definition.
raster<std::int32_t> reference_trim(const raster<std::int32_t>& labels, const raster<float>& min_z,
                                    const trim_raised_edge_cells_options& o)
{
    const std::ptrdiff_t rows = labels.rows(), cols = labels.cols();
    const auto edge = [&](std::ptrdiff_t r, std::ptrdiff_t c) {
        for (std::ptrdiff_t rr = r - 1; rr <= r + 1; ++rr)
            for (std::ptrdiff_t cc = c - 1; cc <= c + 1; ++cc)
                if (rr >= 0 && cc >= 0 && rr < rows && cc < cols && labels(rr, cc) <= 0) return true;
        return false;
    };
    auto out = labels;
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            if (labels(r, c) <= 0 || !edge(r, c) || !std::isfinite(min_z(r, c))) continue;
            std::vector<float> z;  // the interior cells of the same body with a finite min z
            for (std::ptrdiff_t rr = r - o.window_cells; rr <= r + o.window_cells; ++rr)
                for (std::ptrdiff_t cc = c - o.window_cells; cc <= c + o.window_cells; ++cc)
                    if (rr >= 0 && cc >= 0 && rr < rows && cc < cols && labels(rr, cc) == labels(r, c) &&
                        !edge(rr, cc) && std::isfinite(min_z(rr, cc)))
                        z.push_back(min_z(rr, cc));
            if (z.size() < o.min_level_cells) continue;
            std::sort(z.begin(), z.end());
            const double rise = static_cast<double>(min_z(r, c)) - z[z.size() / 2];
            if (rise > o.min_rise_m && rise <= o.max_rise_m) out(r, c) = 0;
        }
    }
    return out;
}

}  // namespace

TEST_CASE("water/trim_raised_edge_cells: a beach the level let in becomes land; water, decks and banks stay")
{
    // A lake (label 1) at level 10.00 in columns 0-5 of a 9 x 10 raster; column 5 is its edge.
    raster<std::int32_t> labels(9, 10, 0);
    raster<float> z(9, 10, 11.0f);
    for (std::ptrdiff_t r = 0; r < 9; ++r)
        for (std::ptrdiff_t c = 0; c < 6; ++c) labels(r, c) = 1, z(r, c) = 10.0f + 0.01f * static_cast<float>(r % 3);
    z(2, 5) = 10.12f;                                   // beach 0.11 above the local median 10.01: land
    z(4, 5) = 10.04f;                                   // within the noise: water
    z(6, 5) = 12.5f;                                    // a deck: left as it is
    z(7, 5) = std::numeric_limits<float>::quiet_NaN();  // a dropout: left
    z(3, 3) = 10.3f;                                    // raised, but interior (no land neighbour): left
    CHECK(trim_raised_edge_cells(labels, z) == 1);
    CHECK(labels(2, 5) == 0);
    CHECK(labels(4, 5) == 1);
    CHECK(labels(6, 5) == 1);
    CHECK(labels(7, 5) == 1);
    CHECK(labels(3, 3) == 1);

    // A second body 0.3 m lower right next to the lake's edge: the lake's edge cells read the lake's level.
    raster<std::int32_t> two(9, 12, 1);
    raster<float> z2(9, 12, 10.0f);
    for (std::ptrdiff_t r = 0; r < 9; ++r) {
        for (std::ptrdiff_t c = 6; c < 12; ++c) two(r, c) = 2, z2(r, c) = 9.7f;
        two(r, 5) = 0, z2(r, 5) = 11.0f;  // a land strip between them
    }
    CHECK(trim_raised_edge_cells(two, z2) == 0);  // against the lower body's level, 0.3 m would be trimmed
}

TEST_CASE("water/trim_raised_edge_cells: matches the per-cell reference on random rasters; bad input")
{
    const unsigned seed = 20261204;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> noise(-0.1f, 0.4f);
    for (int trial = 0; trial < 46; ++trial) {
        // The last trials are tall: their bands of rows run on 1-3 threads.
        const bool tall = trial >= 40;
        const std::ptrdiff_t rows = tall ? 250 + static_cast<std::ptrdiff_t>(rng() % 600)
                                         : 1 + static_cast<std::ptrdiff_t>(rng() % 30),
                             cols = 1 + static_cast<std::ptrdiff_t>(rng() % (tall ? 12 : 30));
        INFO("seed " << seed << ", trial " << trial << ": " << rows << "x" << cols);
        raster<std::int32_t> labels(rows, cols, 0);
        raster<float> z(rows, cols);
        for (std::ptrdiff_t r = 0; r < rows; ++r) {
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                labels(r, c) =
                    std::sin(0.5 * static_cast<double>(r) + trial) + std::cos(0.35 * static_cast<double>(c)) > 0.2
                        ? 1 + static_cast<std::int32_t>(r % 2)
                        : 0;
                const auto pick = rng() % 40;
                z(r, c) = pick < 4    ? std::numeric_limits<float>::quiet_NaN()
                          : pick == 4 ? std::numeric_limits<float>::infinity()
                          : pick == 5 ? -std::numeric_limits<float>::infinity()
                                      : 5.0f + noise(rng);
            }
        }
        const trim_raised_edge_cells_options o{.window_cells = 1 + trial % 3,
                                               .min_rise_m = 0.02 * (trial % 4),
                                               .max_rise_m = 0.3,
                                               .min_level_cells = 1 + static_cast<std::size_t>(trial % 3)};
        const auto want = reference_trim(labels, z, o);
        auto got = labels;
        const auto n = trim_raised_edge_cells(got, z, o, {.threads = 1 + trial % 3});
        CHECK(got == want);
        std::size_t changed = 0;
        for (std::ptrdiff_t i = 0; i < got.size(); ++i) changed += got.data()[i] != labels.data()[i];
        CHECK(n == changed);
    }
    raster<std::int32_t> one(1, 1, 1);
    CHECK(trim_raised_edge_cells(one, raster<float>(1, 1, 3.0f)) == 0);
    raster<std::int32_t> none(0, 0);
    CHECK(trim_raised_edge_cells(none, raster<float>(0, 0)) == 0);
    CHECK_THROWS_AS(trim_raised_edge_cells(one, raster<float>(2, 1, 0.0f)), invalid_input);
    CHECK_THROWS_AS(trim_raised_edge_cells(one, raster<float>(1, 1, 0.0f), {.min_rise_m = 0.5, .max_rise_m = 0.5}),
                    invalid_input);
}

TEST_CASE(
    "water/shore steps: windows of more than 64 cells or past the raster, repeated heights and ±0, match the "
    "references")
{
    // The class rows are kept for the rows in reach (all of them when the window is taller than the raster);
    // the level of up to 64 heights is found by counts, of more by nth_element; -0 and +0 are one height.
    const unsigned seed = 20261205;
    std::mt19937 rng(seed);
    for (int trial = 0; trial < 30; ++trial) {
        const std::ptrdiff_t rows = 1 + static_cast<std::ptrdiff_t>(rng() % 25),
                             cols = 1 + static_cast<std::ptrdiff_t>(rng() % 25);
        const int window = std::vector<int>{4, 5, 7, 12, 40}[static_cast<std::size_t>(trial % 5)];
        INFO("seed " << seed << ", trial " << trial << ": " << rows << "x" << cols << ", window " << window);
        raster<std::int32_t> labels(rows, cols, 0);
        raster<float> z(rows, cols);
        raster<std::uint32_t> count(rows, cols);
        raster<std::uint8_t> excluded(rows, cols), footprint(rows, cols, 1);
        for (std::ptrdiff_t r = 0; r < rows; ++r) {
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                const bool wet =
                    std::sin(0.3 * static_cast<double>(r) + trial) + std::cos(0.25 * static_cast<double>(c)) > 0;
                labels(r, c) = wet ? 1 + static_cast<std::int32_t>(rng() % 8 == 0) : 0;
                const auto step = static_cast<int>(rng() % 5) - 1;  // heights -0.05 .. 0.15 in steps of 0.05, ±0
                z(r, c) = step == 0 ? (rng() % 2 ? 0.0f : -0.0f) : 0.05f * static_cast<float>(step);
                count(r, c) = wet ? static_cast<std::uint32_t>(rng() % 3) : static_cast<std::uint32_t>(rng() % 12);
                excluded(r, c) = rng() % 9 == 0;
            }
        }
        const trim_raised_edge_cells_options t{
            .window_cells = window, .min_rise_m = trial % 2 ? 0.0 : 0.04, .max_rise_m = 0.3, .min_level_cells = 1};
        auto got = labels;
        trim_raised_edge_cells(got, z, t);
        CHECK(got == reference_trim(labels, z, t));
        const join_shore_cells_options j{
            .window_cells = window, .min_contrast = 0.2, .min_water_share = 0.4, .min_body_neighbours = 1 + trial % 3};
        got = labels;
        join_shore_cells(got, count, excluded, footprint, j);
        CHECK(got == reference_shore(labels, count, excluded, footprint, j));
    }
}
