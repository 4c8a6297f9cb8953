// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/synth/scenes.hpp>

#include "synth/scene_stats.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

using namespace synth_test;

namespace {

constexpr auto make_river = [] { return river_scene(); };  // built once (see once())
const scene& river()
{
    return once(make_river).s;
}
const cell_points& river_cells()
{
    return once(make_river).cells;
}

}  // namespace

TEST_CASE("synth/river_scene: one river crossing the scene from west to east, 15-40 m wide")
{
    const auto& t = river().truth;
    const auto parts = components8(t.water);
    REQUIRE(parts.sizes.size() == 2);  // a single waterbody, continuous under the bridge
    // It touches the west and the east edges.
    bool west = false, east = false;
    for (std::ptrdiff_t r = 0; r < t.g.rows; ++r) {
        west = west || t.water(r, 0);
        east = east || t.water(r, t.g.cols - 1);
    }
    CHECK(west);
    CHECK(east);
    // Width across the channel: vertical extent in each column times cos(angle of the channel), the
    // angle from the centres of neighbouring columns. 2 m cells: +-2 cells of quantisation.
    std::vector<double> centre(static_cast<std::size_t>(t.g.cols)), extent(static_cast<std::size_t>(t.g.cols));
    for (std::ptrdiff_t c = 0; c < t.g.cols; ++c) {
        double sum = 0;
        std::size_t n = 0;
        for (std::ptrdiff_t r = 0; r < t.g.rows; ++r) {
            if (t.water(r, c)) sum += static_cast<double>(r), ++n;
        }
        REQUIRE(n > 0);
        centre[static_cast<std::size_t>(c)] = sum / static_cast<double>(n);
        extent[static_cast<std::size_t>(c)] = static_cast<double>(n) * t.g.cell;
    }
    double narrowest = 1e9, widest = 0;
    for (std::size_t c = 2; c + 2 < centre.size(); ++c) {
        const double slope = (centre[c + 2] - centre[c - 2]) / 4.0;
        const double width = extent[c] / std::sqrt(1 + slope * slope);
        narrowest = std::min(narrowest, width);
        widest = std::max(widest, width);
    }
    CHECK(narrowest >= 15.0 - 4.0);
    CHECK(widest <= 40.0 + 4.0);
    CHECK(widest - narrowest > 8.0);
}

TEST_CASE("synth/river_scene: the water level falls downstream, 1-2 m over the scene")
{
    const auto& t = river().truth;
    // Least-squares line z = a + b x through the water cells.
    double sx = 0, sz = 0, sxx = 0, sxz = 0, n = 0;
    float lowest = 1e9f, highest = -1e9f;
    for (std::ptrdiff_t r = 0; r < t.g.rows; ++r) {
        for (std::ptrdiff_t c = 0; c < t.g.cols; ++c) {
            if (!t.water(r, c)) continue;
            const double x = t.g.center(r, c)[0], z = t.water_z(r, c);
            sx += x, sz += z, sxx += x * x, sxz += x * z, n += 1;
            lowest = std::min(lowest, t.water_z(r, c));
            highest = std::max(highest, t.water_z(r, c));
        }
    }
    const double b = (n * sxz - sx * sz) / (n * sxx - sx * sx);
    CHECK(b * 640 == doctest::Approx(-1.5).epsilon(0.01));
    CHECK(highest - lowest > 1.0f);
    CHECK(highest - lowest < 2.0f);
}

TEST_CASE("synth/river_scene: the bridge deck stands 5-8 m above the water, and hides it")
{
    const auto& s = river();
    const auto& t = s.truth;
    const auto& cells = river_cells();
    std::size_t deck_points = 0, over_water = 0, too_low = 0, hidden_returns = 0, deck_water_cells = 0;
    for (std::ptrdiff_t r = 0; r < t.g.rows; ++r) {
        for (std::ptrdiff_t c = 0; c < t.g.cols; ++c) {
            for (const auto i : cells.at(r, c)) {
                if (s.points.classification[i] != las_class::bridge_deck) continue;
                ++deck_points;
                if (!t.water(r, c)) continue;
                ++over_water;
                const double above = s.points.z[i] - t.water_z(r, c);
                too_low += above < 5.0 || above > 8.0;
            }
            // Under the deck, the truth is water; only deck returns come back from there.
            if (t.surface(r, c) == las_class::bridge_deck && t.water(r, c)) ++deck_water_cells;
            if (block_all(t.g.rows, t.g.cols, r, c,
                          [&](auto rr, auto cc) { return t.surface(rr, cc) == las_class::bridge_deck; })) {
                for (const auto i : cells.at(r, c))
                    hidden_returns += s.points.classification[i] != las_class::bridge_deck;
            }
        }
    }
    CHECK(deck_points > 300);
    CHECK(over_water > 100);
    CHECK(too_low == 0);
    CHECK(hidden_returns == 0);
    CHECK(deck_water_cells > 10);
}

TEST_CASE("synth/river_scene: a road on embankments leads to both ends of the bridge")
{
    const auto& s = river();
    const auto& t = s.truth;
    const auto& p = s.points;
    double deck_z = 0;
    for (std::size_t i = 0; i < p.size(); ++i)
        if (p.classification[i] == las_class::bridge_deck) deck_z = std::max(deck_z, p.z[i] - 0.05);
    const auto& cells = river_cells();
    std::size_t road_on_border = 0, ramp_points = 0, ramp_low = 0;
    raster<std::uint8_t> road_at_deck(t.g.rows, t.g.cols);
    for (std::ptrdiff_t r = 0; r < t.g.rows; ++r) {
        for (std::ptrdiff_t c = 0; c < t.g.cols; ++c) {
            if (t.surface(r, c) != las_class::road_surface) continue;
            if (r == 0 || r == t.g.rows - 1) ++road_on_border;
            bool next_to_deck = false;
            for (std::ptrdiff_t dr = -1; dr <= 1; ++dr)
                for (std::ptrdiff_t dc = -1; dc <= 1; ++dc)
                    next_to_deck = next_to_deck || (t.g.contains(r + dr, c + dc) &&
                                                    t.surface(r + dr, c + dc) == las_class::bridge_deck);
            if (!next_to_deck) continue;
            road_at_deck(r, c) = 1;
            for (const auto i : cells.at(r, c)) {
                if (p.classification[i] != las_class::road_surface) continue;
                ++ramp_points;
                // The ramps climb at 6 %: within a few metres of the deck they are within 0.5 m of it.
                ramp_low += std::abs(p.z[i] - deck_z) > 0.5;
            }
        }
    }
    CHECK(road_on_border >= 4);                          // the road leaves the scene north and south
    CHECK(components8(road_at_deck).sizes.size() == 3);  // and reaches the deck at both ends
    CHECK(ramp_points > 10);
    CHECK(ramp_low == 0);
}

TEST_CASE("synth/river_scene: banks carry trees, water dropouts come in patches")
{
    const auto& t = river().truth;
    const auto& cells = river_cells();
    // Distance to the river in cells, by a two-pass chamfer-free check on a band.
    std::size_t near_trees = 0, near_cells = 0, far_trees = 0, far_cells = 0;
    raster<std::uint8_t> empty_water(t.g.rows, t.g.cols);
    std::size_t water = 0, water_empty = 0;
    for (std::ptrdiff_t r = 0; r < t.g.rows; ++r) {
        for (std::ptrdiff_t c = 0; c < t.g.cols; ++c) {
            if (t.water(r, c)) {
                const bool under_deck = t.surface(r, c) == las_class::bridge_deck;
                if (!under_deck) ++water, water_empty += cells.count(r, c) == 0;
                empty_water(r, c) = !under_deck && cells.count(r, c) == 0;
                continue;
            }
            std::ptrdiff_t nearest = 1000;
            for (std::ptrdiff_t dr = -40; dr <= 40; ++dr) {
                if (!t.g.contains(r + dr, c) || !t.water(r + dr, c)) continue;
                nearest = std::min(nearest, std::abs(dr));
            }
            const bool tree = t.surface(r, c) == las_class::high_vegetation;
            if (nearest >= 2 && nearest <= 10) ++near_cells, near_trees += tree;  // 4-20 m from the water
            if (nearest > 40) ++far_cells, far_trees += tree;
        }
    }
    const double near_share = static_cast<double>(near_trees) / static_cast<double>(near_cells);
    const double far_share = static_cast<double>(far_trees) / static_cast<double>(far_cells);
    CHECK(near_share > 2 * far_share);
    const double empty_share = static_cast<double>(water_empty) / static_cast<double>(water);
    CHECK(empty_share > 0.35);
    CHECK(empty_share < 0.55);
    const auto parts = components8(empty_water);
    CHECK(largest(parts) >= 100);
}
