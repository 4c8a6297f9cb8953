// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/synth/scenes.hpp>

#include "synth/scene_stats.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

using namespace synth_test;

namespace {

using scene_fn = std::function<scene(const scene_options&)>;

struct named_scene {
    const char* name;
    scene_fn make;
};

const named_scene all_scenes[] = {{"lake_scene", [](const scene_options& o) { return lake_scene(o); }},
                                  {"river_scene", [](const scene_options& o) { return river_scene(o); }},
                                  {"town_scene", [](const scene_options& o) { return town_scene(o); }}};

}  // namespace

TEST_CASE("synth/scenes: the same seed gives the same scene, another seed another one")
{
    for (const auto& item : all_scenes) {
        const auto& name = item.name;
        const auto& make = item.make;
        CAPTURE(name);
        const scene a = make({.seed = 7, .size_m = 200});
        const scene b = make({.seed = 7, .size_m = 200});
        const scene c = make({.seed = 8, .size_m = 200});
        CHECK(a.points == b.points);
        CHECK(same_truth(a.truth, b.truth));
        CHECK_FALSE(a.points == c.points);
        CHECK_FALSE(same_bits(a.truth.ground_z, c.truth.ground_z));
    }
}

TEST_CASE("synth/scenes: size and density options are honoured")
{
    for (const auto& item : all_scenes) {
        const auto& name = item.name;
        const auto& make = item.make;
        CAPTURE(name);
        for (const auto& [size, density] : {std::array<double, 2>{150, 4.0}, {300, 0.5}, {101, 2.0}}) {
            const scene s = make({.seed = 3, .size_m = size, .density_per_m2 = density});
            const auto& p = s.points;
            CHECK(*std::max_element(p.x.begin(), p.x.end()) <= size);
            CHECK(*std::max_element(p.y.begin(), p.y.end()) <= size);
            CHECK(*std::min_element(p.x.begin(), p.x.end()) >= 0);
            CHECK(*std::min_element(p.y.begin(), p.y.end()) >= 0);
            // Truth grid: 2 m cells from x = 0, north edge at the size rounded up to whole cells.
            const auto n = static_cast<std::ptrdiff_t>(std::ceil(size / 2.0));
            CHECK(s.truth.g == grid{0.0, 2.0 * static_cast<double>(n), 2.0, n, n});
            // First returns over non-water cells that have any return (single dropouts skipped).
            const auto cells = group_by_cell(p, s.truth.g);
            std::size_t first = 0, area_cells = 0;
            for (std::ptrdiff_t r = 0; r < n; ++r) {
                for (std::ptrdiff_t c = 0; c < n; ++c) {
                    const auto [x, y] = s.truth.g.center(r, c);
                    if (s.truth.water(r, c) || cells.count(r, c) == 0 || x > size - 1 || y > size - 1) continue;
                    if (block_all(n, n, r, c, [&](auto rr, auto cc) { return s.truth.water(rr, cc) == 0; })) {
                        ++area_cells;
                        for (const auto i : cells.at(r, c)) first += p.return_number[i] == 1;
                    }
                }
            }
            const double measured = static_cast<double>(first) / (4.0 * static_cast<double>(area_cells));
            // Pulse counts are whole lines and pulses; with jitter, 3 % covers small scenes at 0.5 / m^2.
            CHECK(measured == doctest::Approx(density).epsilon(0.03));
        }
    }
}

TEST_CASE("synth/scenes: the truth cell option sets the truth grid, not the points")
{
    const scene coarse = lake_scene({.seed = 2, .size_m = 160, .truth_cell_m = 4.0});
    const scene fine = lake_scene({.seed = 2, .size_m = 160, .truth_cell_m = 0.5});
    const scene odd = lake_scene({.seed = 2, .size_m = 160, .truth_cell_m = 3.0});
    CHECK(coarse.points == fine.points);
    CHECK(coarse.points == odd.points);
    CHECK(coarse.truth.g == grid{0.0, 160.0, 4.0, 40, 40});
    CHECK(fine.truth.g == grid{0.0, 160.0, 0.5, 320, 320});
    CHECK(odd.truth.g == grid{0.0, 162.0, 3.0, 54, 54});  // aligned to multiples of 3 m, covering 160 m
    // The same world sampled at other centres: the water share agrees.
    const auto share = [](const scene_truth& t) {
        double w = 0;
        for (const auto v : t.water) w += v;
        return w / static_cast<double>(t.water.size());
    };
    CHECK(share(coarse.truth) == doctest::Approx(share(fine.truth)).epsilon(0.1));
}

TEST_CASE("synth/scenes: bad options are refused with the option named")
{
    for (const auto& item : all_scenes) {
        const auto& name = item.name;
        const auto& make = item.make;
        const std::string fn = name;
        CHECK_THROWS_WITH_AS(make({.size_m = 0}), (fn + ": size_m must be finite and > 0 (got 0)").c_str(),
                             invalid_input);
        CHECK_THROWS_WITH_AS(make({.size_m = -5}), (fn + ": size_m must be finite and > 0 (got -5)").c_str(),
                             invalid_input);
        CHECK_THROWS_WITH_AS(make({.density_per_m2 = 0}),
                             (fn + ": density_per_m2 must be finite and > 0 (got 0)").c_str(), invalid_input);
        CHECK_THROWS_WITH_AS(make({.truth_cell_m = -1}),
                             (fn + ": truth_cell_m must be finite and > 0 (got -1)").c_str(), invalid_input);
        CHECK_THROWS_AS(make({.size_m = NAN}), invalid_input);
        CHECK_THROWS_AS(make({.density_per_m2 = INFINITY}), invalid_input);
        CHECK_THROWS_WITH_AS(make({.size_m = 1e5, .density_per_m2 = 1}),
                             (fn + ": size_m^2 * density_per_m2 must be <= 1e9 pulses (got 10000000000)").c_str(),
                             invalid_input);
        CHECK_THROWS_AS(make({.size_m = 1000, .truth_cell_m = 0.01}), invalid_input);
    }
}
