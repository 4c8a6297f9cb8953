// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/synth/trees.hpp>

#include <array>
#include <cmath>
#include <vector>

using namespace lidarfx::synth;
namespace las_class = lidarfx::las_class;

TEST_CASE("synth/tree: crown surface from the top at the stem down to the crown's middle at its rim")
{
    const tree t{.x = 5, .y = 5, .ground_z = 100, .crown_radius_m = 4, .crown_base_m = 6, .height_m = 16};
    CHECK(t.crown_top(5, 5) == doctest::Approx(16));
    CHECK(t.crown_top(9 - 1e-9, 5) == doctest::Approx(11).epsilon(1e-3));
    CHECK(t.crown_top(9.01, 5) < 0);
    CHECK(t.crown_top(7, 5) > t.crown_top(8, 5));
}

TEST_CASE("synth/tree_returns: multi-return pulses from the crown down to the ground")
{
    const tree t{
        .x = 0, .y = 0, .ground_z = 50, .crown_radius_m = 4, .crown_base_m = 5, .height_m = 18, .intensity = 100};
    rng r(41);
    constexpr int pulses = 20000;
    std::array<int, 5> by_count{};
    int ground_last = 0, ordered = 0, numbered = 0, first_near_top = 0, classes_ok = 0, multi = 0;
    for (int k = 0; k < pulses; ++k) {
        std::vector<std::array<double, 5>> returns;  // z, intensity, rn, nr, class
        const double top = 15.0;
        tree_returns(t, top, t.ground_z, 120.0, r, [&](double z, double i, int rn, int nr, std::uint8_t cls) {
            returns.push_back({z, i, double(rn), double(nr), double(cls)});
        });
        const auto n = returns.size();
        ++by_count[n];
        bool ok_order = true, ok_numbers = true, ok_classes = true;
        for (std::size_t j = 0; j < n; ++j) {
            ok_numbers = ok_numbers && returns[j][2] == double(j + 1) && returns[j][3] == double(n);
            if (j > 0) ok_order = ok_order && returns[j][0] <= returns[j - 1][0];
            const double h = returns[j][0] - t.ground_z;
            const auto cls = static_cast<std::uint8_t>(returns[j][4]);
            ok_classes = ok_classes && (h == 0  ? cls == las_class::ground
                                        : h > 2 ? cls == las_class::high_vegetation
                                                : cls == las_class::low_vegetation);
        }
        ordered += ok_order;
        numbered += ok_numbers;
        classes_ok += ok_classes;
        if (n > 1) {
            ++multi;
            ground_last += returns.back()[0] == t.ground_z;
            first_near_top += returns[0][0] <= t.ground_z + top && returns[0][0] >= t.ground_z + top - 0.3;
        }
    }
    CHECK(ordered == pulses);
    CHECK(numbered == pulses);
    CHECK(classes_ok == pulses);
    CHECK(first_near_top == multi);
    CHECK(by_count[0] == 0);
    // Shares: gap 10 %; then 2, 3, 4 returns 45/35/20 % of the rest; ground last 85 %. 5 sigma bounds.
    const auto near = [](int count, double p, int n) {
        return std::abs(count - p * n) < 5 * std::sqrt(p * (1 - p) * n);
    };
    CHECK(near(by_count[1], 0.1, pulses));
    CHECK(near(by_count[2], 0.9 * 0.45, pulses));
    CHECK(near(by_count[3], 0.9 * 0.35, pulses));
    CHECK(near(by_count[4], 0.9 * 0.20, pulses));
    CHECK(near(ground_last, 0.85, multi));
}

TEST_CASE("synth/scatter_trees: probability decides where trees stand; deterministic")
{
    const auto west_only = [](double x, double, double) { return x < 50 ? 1.0 : 0.0; };
    const auto flat = [](double, double) { return 7.0; };
    rng a(42), b(42);
    const auto trees = scatter_trees(a, 100, 5, tree_size{}, west_only, flat);
    const auto again = scatter_trees(b, 100, 5, tree_size{}, west_only, flat);
    REQUIRE(trees.size() == again.size());
    int west = 0;
    for (std::size_t i = 0; i < trees.size(); ++i) {
        CHECK(trees[i].x == again[i].x);
        west += trees[i].x < 50;
        CHECK(trees[i].ground_z == 7.0);
        CHECK(trees[i].crown_radius_m >= 2.0);
        CHECK(trees[i].crown_radius_m <= 5.0);
        CHECK(trees[i].height_m >= 8.0);
        CHECK(trees[i].crown_base_m >= 1.5);
        CHECK(trees[i].crown_base_m <= 0.5 * trees[i].height_m);
    }
    CHECK(west == static_cast<int>(trees.size()));
    // One proposal per 5 m lattice cell, kept everywhere x < 50: about half of 400 cells.
    CHECK(trees.size() >= 180);
    CHECK(trees.size() <= 220);
}
