// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/synth/scenes.hpp>

#include "synth/scene_stats.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <vector>

using namespace synth_test;

namespace {

constexpr auto make_lake = [] { return lake_scene(); };  // built once (see once())
const scene& lake()
{
    return once(make_lake).s;
}
const cell_points& lake_cells()
{
    return once(make_lake).cells;
}

/// Land cells at least `margin` cells from any water cell (Chebyshev distance).
raster<std::uint8_t> land_away_from_water(const scene_truth& t, int margin)
{
    raster<std::uint8_t> out(t.g.rows, t.g.cols, 1);
    for (std::ptrdiff_t r = 0; r < t.g.rows; ++r) {
        for (std::ptrdiff_t c = 0; c < t.g.cols; ++c) {
            if (!t.water(r, c)) continue;
            for (std::ptrdiff_t dr = -margin; dr <= margin; ++dr) {
                for (std::ptrdiff_t dc = -margin; dc <= margin; ++dc) {
                    if (t.g.contains(r + dr, c + dc)) out(r + dr, c + dc) = 0;
                }
            }
        }
    }
    return out;
}

}  // namespace

TEST_CASE("synth/lake_scene: default scene size, grid and point budget")
{
    const auto& s = lake();
    CHECK(s.truth.g == grid{0.0, 640.0, 2.0, 320, 320});
    // 640 m x 640 m x 2 pulses/m^2 = 819200 pulses; water dropouts remove some, trees add returns.
    CHECK(s.points.size() > 700000);
    CHECK(s.points.size() < 1000000);
    const auto& p = s.points;
    CHECK(p.y.size() == p.size());
    CHECK(p.intensity.size() == p.size());
    CHECK(p.classification.size() == p.size());
    CHECK(*std::min_element(p.x.begin(), p.x.end()) >= 0.0);
    CHECK(*std::max_element(p.x.begin(), p.x.end()) <= 640.0);
    CHECK(*std::min_element(p.y.begin(), p.y.end()) >= 0.0);
    CHECK(*std::max_element(p.y.begin(), p.y.end()) <= 640.0);
    const auto cloud = p.cloud();
    CHECK(cloud.size() == p.size());
    CHECK(cloud.z(12345) == p.z[12345]);
    CHECK(cloud.intensity(777) == p.intensity[777]);
}

TEST_CASE("synth/lake_scene: a large lake and a pond, each flat, below banks that rise from the shore")
{
    const auto& t = lake().truth;
    std::map<float, std::size_t> cells_by_level;
    std::size_t inconsistent = 0;
    for (std::ptrdiff_t r = 0; r < t.g.rows; ++r) {
        for (std::ptrdiff_t c = 0; c < t.g.cols; ++c) {
            inconsistent += (t.water(r, c) == 1) != !std::isnan(t.water_z(r, c));
            if (t.water(r, c)) {
                ++cells_by_level[t.water_z(r, c)];
                inconsistent += t.ground_z(r, c) != t.water_z(r, c) || t.surface(r, c) != las_class::water;
            }
        }
    }
    CHECK(inconsistent == 0);
    REQUIRE(cells_by_level.size() == 2);  // two flat water surfaces
    std::vector<std::size_t> sizes;
    for (const auto& [level, n] : cells_by_level) sizes.push_back(n);
    std::sort(sizes.begin(), sizes.end());
    CHECK(sizes[1] > 10000);  // the lake: > 4 ha of 2 m cells
    CHECK(sizes[0] > 750);    // the pond: > 0.3 ha
    CHECK(sizes[0] * 4 < sizes[1]);
    // Every land cell next to water stands above that water by the bank's 0.3 m (truth has no noise).
    int low_banks = 0, bank_cells = 0;
    for (std::ptrdiff_t r = 1; r + 1 < t.g.rows; ++r) {
        for (std::ptrdiff_t c = 1; c + 1 < t.g.cols; ++c) {
            if (t.water(r, c)) continue;
            for (const auto [dr, dc] : {std::array<int, 2>{0, 1}, {0, -1}, {1, 0}, {-1, 0}}) {
                if (!t.water(r + dr, c + dc)) continue;
                ++bank_cells;
                low_banks += t.ground_z(r, c) < t.water_z(r + dr, c + dc) + 0.25f;
            }
        }
    }
    CHECK(bank_cells > 300);
    CHECK(low_banks == 0);
}

TEST_CASE("synth/lake_scene: islands over 200 m^2 are land in both masks, smaller ones are filled")
{
    const auto& t = lake().truth;
    int large = 0, small = 0;
    for (const auto& [x, y, radius, area] : t.islands) {
        CHECK(area == doctest::Approx(std::numbers::pi * radius * radius));
        const auto centre = t.g.cell_of(x, y);
        REQUIRE(centre);
        CHECK(t.water(centre->row, centre->col) == 0);
        CHECK(t.surface(centre->row, centre->col) != las_class::water);
        // Land cells of the island (centres within the radius) versus its area.
        std::size_t land = 0, filled = 0;
        for (std::ptrdiff_t r = 0; r < t.g.rows; ++r) {
            for (std::ptrdiff_t c = 0; c < t.g.cols; ++c) {
                const auto [cx, cy] = t.g.center(r, c);
                if (std::hypot(cx - x, cy - y) >= radius) continue;
                land += t.water(r, c) == 0;
                filled += t.water_filled(r, c);
            }
        }
        const double cell_area = t.g.cell * t.g.cell;
        // Counting 2 m cell centres in a disc of >= 3.6 m radius: within 30 % (+ one cell) of the area.
        CHECK(std::abs(static_cast<double>(land) * cell_area - area) <= 0.3 * area + cell_area);
        // The island is surrounded by water: the ring just outside it is water.
        for (int k = 0; k < 16; ++k) {
            const double a = k * 0.39269908169872414;
            const auto out = t.g.cell_of(x + (radius + 3) * std::cos(a), y + (radius + 3) * std::sin(a));
            REQUIRE(out);
            CHECK(t.water(out->row, out->col) == 1);
        }
        if (area > island_fill_area_m2) {
            ++large;
            CHECK(filled == 0);
        } else {
            ++small;
            CHECK(filled == land);
            CHECK(area >= 40);
            CHECK(area <= 100);
        }
        // Islands return points, and none of them is a water return.
        std::size_t island_points = 0, water_points = 0;
        const auto& cells = lake_cells();
        for (std::ptrdiff_t r = 0; r < t.g.rows; ++r) {
            for (std::ptrdiff_t c = 0; c < t.g.cols; ++c) {
                const auto [cx, cy] = t.g.center(r, c);
                if (std::hypot(cx - x, cy - y) > radius - 1.5) continue;  // whole cell on the island
                for (const auto i : cells.at(r, c)) {
                    ++island_points;
                    water_points += lake().points.classification[i] == las_class::water;
                }
            }
        }
        CHECK(island_points > 0);
        CHECK(water_points == 0);
    }
    CHECK(large >= 2);
    CHECK(small >= 3);
    // water_filled = water plus the small islands, nothing else.
    std::size_t extra = 0, lost = 0;
    for (std::ptrdiff_t r = 0; r < t.g.rows; ++r) {
        for (std::ptrdiff_t c = 0; c < t.g.cols; ++c) {
            lost += t.water_filled(r, c) < t.water(r, c);
            extra += t.water_filled(r, c) > t.water(r, c);
        }
    }
    CHECK(lost == 0);
    CHECK(extra > 0);
}

TEST_CASE("synth/lake_scene: water cells hold only weak returns and a few glints, or none")
{
    const auto& s = lake();
    const auto& t = s.truth;
    const auto& cells = lake_cells();
    std::size_t returns = 0, weak = 0, glints = 0, off_class = 0, off_level = 0;
    for (std::ptrdiff_t r = 0; r < t.g.rows; ++r) {
        for (std::ptrdiff_t c = 0; c < t.g.cols; ++c) {
            // Interior water: the 3x3 block is water, so no island or bank point can fall in the cell.
            if (!block_all(t.g.rows, t.g.cols, r, c, [&](auto rr, auto cc) { return t.water(rr, cc) == 1; })) continue;
            for (const auto i : cells.at(r, c)) {
                ++returns;
                const auto v = s.points.intensity[i];
                weak += v >= 2 && v <= 20;
                glints += v >= 200 && v <= 400;
                off_class += s.points.classification[i] != las_class::water || s.points.number_of_returns[i] != 1;
                off_level += std::abs(s.points.z[i] - t.water_z(r, c)) > 0.05 + 1e-6;  // +-5 cm noise
            }
        }
    }
    CHECK(returns > 20000);
    CHECK(weak + glints == returns);
    CHECK(off_class == 0);
    CHECK(off_level == 0);
    const double glint_share = static_cast<double>(glints) / static_cast<double>(returns);
    CHECK(glint_share > 0.005);
    CHECK(glint_share < 0.05);
}

TEST_CASE("synth/lake_scene: glints come near nadir")
{
    // The default pattern flies two 320 m strips (the 536 m swath does not cover 640 m), centred on
    // x = 160 and x = 480; returns within 35 m of a centre are within 2 degrees of nadir.
    const auto& p = lake().points;
    std::size_t near = 0, near_glints = 0, far = 0, far_glints = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (p.classification[i] != las_class::water) continue;
        const double off = std::min(std::abs(p.x[i] - 160), std::abs(p.x[i] - 480));
        const bool glint = p.intensity[i] >= 200;
        if (off < 35) ++near, near_glints += glint;
        if (off > 100) ++far, far_glints += glint;
    }
    REQUIRE(near > 1000);
    REQUIRE(far > 1000);
    const double near_share = static_cast<double>(near_glints) / static_cast<double>(near);
    const double far_share = static_cast<double>(far_glints) / static_cast<double>(far);
    CHECK(near_share > 5 * far_share);
}

TEST_CASE("synth/lake_scene: water dropouts come in large patches plus single cells; land dropouts are isolated")
{
    const auto& t = lake().truth;
    const auto& cells = lake_cells();
    raster<std::uint8_t> empty_water(t.g.rows, t.g.cols), empty_land(t.g.rows, t.g.cols);
    const auto open_land = land_away_from_water(t, 2);
    std::size_t water = 0, water_empty = 0, land = 0, land_empty = 0;
    for (std::ptrdiff_t r = 0; r < t.g.rows; ++r) {
        for (std::ptrdiff_t c = 0; c < t.g.cols; ++c) {
            const bool empty = cells.count(r, c) == 0;
            if (block_all(t.g.rows, t.g.cols, r, c, [&](auto rr, auto cc) { return t.water(rr, cc) == 1; })) {
                ++water;
                water_empty += empty;
            }
            if (t.water(r, c)) empty_water(r, c) = empty;
            if (open_land(r, c)) {
                ++land;
                land_empty += empty;
                empty_land(r, c) = empty;
            }
        }
    }
    // Documented: 40 % of each waterbody in patches, 10 % of the rest single cells, scan-angle losses
    // empty a few more: about 46 %.
    const double water_share = static_cast<double>(water_empty) / static_cast<double>(water);
    CHECK(water_share > 0.40);
    CHECK(water_share < 0.52);
    // Documented: 1.5 % of land cells.
    const double land_share = static_cast<double>(land_empty) / static_cast<double>(land);
    CHECK(land_share > 0.010);
    CHECK(land_share < 0.020);

    const auto water_parts = components8(empty_water);
    std::size_t in_big = 0, total = 0;
    for (std::size_t k = 1; k < water_parts.sizes.size(); ++k) {
        total += water_parts.sizes[k];
        if (water_parts.sizes[k] >= 100) in_big += water_parts.sizes[k];
    }
    CHECK(static_cast<double>(in_big) > 0.75 * static_cast<double>(total));
    // Each waterbody (told apart by its level) holds a patch of >= 100 cells: a seed for the method.
    std::map<float, std::size_t> biggest_patch;
    for (std::ptrdiff_t r = 0; r < t.g.rows; ++r)
        for (std::ptrdiff_t c = 0; c < t.g.cols; ++c)
            if (const auto label = water_parts.labels(r, c)) {
                auto& best = biggest_patch[t.water_z(r, c)];
                best = std::max(best, water_parts.sizes[static_cast<std::size_t>(label)]);
            }
    REQUIRE(biggest_patch.size() == 2);
    for (const auto& [level, size] : biggest_patch) CHECK(size >= 100);

    const auto land_parts = components8(empty_land);
    std::size_t isolated = 0;
    for (std::size_t k = 1; k < land_parts.sizes.size(); ++k) isolated += land_parts.sizes[k] == 1;
    // Independent 1.5 % cells: a cell has no empty 8-neighbour with probability 0.985^8 = 0.89.
    CHECK(static_cast<double>(isolated) > 0.8 * static_cast<double>(land_empty));
    CHECK(largest(land_parts) < 25);  // never a 5x5 block: a 5x5 opening removes all land dropouts
}

TEST_CASE("synth/lake_scene: pulse density on open land is the option's")
{
    const auto& s = lake();
    const auto& t = s.truth;
    const auto& cells = lake_cells();
    const auto open_land = land_away_from_water(t, 2);
    std::size_t first = 0, area_cells = 0;
    for (std::ptrdiff_t r = 0; r < t.g.rows; ++r) {
        for (std::ptrdiff_t c = 0; c < t.g.cols; ++c) {
            if (!open_land(r, c) || cells.count(r, c) == 0) continue;  // skip single-cell dropouts
            ++area_cells;
            for (const auto i : cells.at(r, c)) first += s.points.return_number[i] == 1;
        }
    }
    const double density = static_cast<double>(first) / (static_cast<double>(area_cells) * t.g.cell * t.g.cell);
    CHECK(density == doctest::Approx(2.0).epsilon(0.02));
}

TEST_CASE("synth/lake_scene: trees give multi-return pulses from canopy to ground; land intensities")
{
    const auto& p = lake().points;
    const auto& t = lake().truth;
    std::map<int, std::size_t> by_returns;
    std::size_t pulses_ok = 0, pulses = 0;
    for (std::size_t i = 0; i < p.size();) {
        const int n = p.number_of_returns[i];
        ++by_returns[n];
        ++pulses;
        bool ok = i + static_cast<std::size_t>(n) <= p.size();
        for (int k = 0; ok && k < n; ++k) {
            const auto j = i + static_cast<std::size_t>(k);
            ok = p.return_number[j] == k + 1 && p.number_of_returns[j] == n && p.x[j] == p.x[i] &&
                 (k == 0 || p.z[j] <= p.z[j - 1] + 0.1);  // +-5 cm noise on each return
        }
        pulses_ok += ok;
        i += static_cast<std::size_t>(std::max(1, n));
    }
    CHECK(pulses_ok == pulses);
    CHECK(by_returns.size() == 4);  // 1..4 returns
    CHECK(by_returns[2] > 10000);
    CHECK(by_returns[4] > 1000);
    // Tree cells: the height spread within a cell exceeds 2 m in most of them (the vegetation mask).
    const auto& cells = lake_cells();
    std::size_t tree_cells = 0, tall = 0;
    for (std::ptrdiff_t r = 0; r < t.g.rows; ++r) {
        for (std::ptrdiff_t c = 0; c < t.g.cols; ++c) {
            if (t.surface(r, c) != las_class::high_vegetation || cells.count(r, c) == 0) continue;
            ++tree_cells;
            double lo = 1e9, hi = -1e9;
            for (const auto i : cells.at(r, c)) lo = std::min(lo, p.z[i]), hi = std::max(hi, p.z[i]);
            tall += hi - lo > 2.0;
        }
    }
    CHECK(tree_cells > 5000);
    CHECK(static_cast<double>(tall) > 0.8 * static_cast<double>(tree_cells));
    // Single-return ground and road intensities: grass/soil 60-180, asphalt 40-80.
    std::size_t ground = 0, ground_ok = 0, road = 0, road_ok = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (p.number_of_returns[i] != 1) continue;
        if (p.classification[i] == las_class::ground)
            ++ground, ground_ok += p.intensity[i] >= 59 && p.intensity[i] <= 181;
        if (p.classification[i] == las_class::road_surface)
            ++road, road_ok += p.intensity[i] >= 40 && p.intensity[i] <= 83;
    }
    CHECK(road > 3000);
    CHECK(ground_ok == ground);
    CHECK(road_ok == road);
}

TEST_CASE("synth/lake_scene: ground returns lie on the truth ground")
{
    const auto& p = lake().points;
    const auto& t = lake().truth;
    const auto& cells = lake_cells();
    std::vector<double> off;
    for (std::ptrdiff_t r = 1; r + 1 < t.g.rows; ++r) {
        for (std::ptrdiff_t c = 1; c + 1 < t.g.cols; ++c) {
            if (t.water(r, c)) continue;
            // Local slope from the truth bounds how far a point in the cell may sit from the centre value.
            const double slope = std::max(std::abs(t.ground_z(r, c + 1) - t.ground_z(r, c - 1)),
                                          std::abs(t.ground_z(r + 1, c) - t.ground_z(r - 1, c))) /
                                 (2 * t.g.cell);
            for (const auto i : cells.at(r, c)) {
                if (p.classification[i] != las_class::ground) continue;
                off.push_back(std::abs(p.z[i] - t.ground_z(r, c)) - slope * t.g.cell);
            }
        }
    }
    REQUIRE(off.size() > 100000);
    std::sort(off.begin(), off.end());
    CHECK(off[off.size() / 2] < 0.05);         // median within the noise
    CHECK(off[off.size() * 99 / 100] < 0.35);  // micro-relief curvature and bank bends
}
