// SPDX-License-Identifier: Apache-2.0
// The hydro variant of the water family (synth/water_family.hpp): rivers at least 30 m wide whose level falls
// downstream and steps down at weirs, and lakes of at least 8,000 m².
#include <doctest/doctest.h>

#include <lidarfx/synth/water_family.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <utility>
#include <vector>

namespace {

namespace wfs = lidarfx::synth;

/// Along-river position of (x, y) in a river scene (see water_family_scene::river_angle_rad).
double hydro_along(const wfs::water_family_scene& s, double x, double y)
{
    const double h = 0.5 * s.size_m;
    return (x - h) * std::cos(s.river_angle_rad) + (y - h) * std::sin(s.river_angle_rad) + h;
}

/// Mean truth water level of the water cells whose centres lie within half a cell of along = u.
double hydro_level_at(const wfs::water_family_scene& s, double u)
{
    double sum = 0;
    long n = 0;
    for (std::ptrdiff_t r = 0; r < s.g.rows; ++r) {
        for (std::ptrdiff_t c = 0; c < s.g.cols; ++c) {
            if (!s.water(r, c)) continue;
            const auto [x, y] = s.g.center(r, c);
            if (std::abs(hydro_along(s, x, y) - u) > 0.5 * s.cell_m) continue;
            sum += s.water_z(r, c);
            ++n;
        }
    }
    REQUIRE(n > 0);
    return sum / static_cast<double>(n);
}

/// Extent of the truth water across the river at along = u: 0.25 m samples on the line across the flow, each
/// taking its cell's truth, from the first water sample to the last; NaN when the line leaves the survey within
/// 5 m of the water.
double hydro_extent_across(const wfs::water_family_scene& s, double u)
{
    constexpr double step = 0.25;
    const double h = 0.5 * s.size_m, ca = std::cos(s.river_angle_rad), sa = std::sin(s.river_angle_rad);
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    std::vector<std::pair<double, bool>> inside;  // (across, inside the survey)
    for (double v = -h; v <= 3 * h; v += step) {
        const double x = (u - h) * ca - (v - h) * sa + h, y = (u - h) * sa + (v - h) * ca + h;
        const auto cell = s.g.cell_of(x, y);
        inside.emplace_back(v, cell.has_value());
        if (cell && s.water(cell->row, cell->col)) lo = std::min(lo, v), hi = std::max(hi, v);
    }
    if (!(hi >= lo)) return std::numeric_limits<double>::quiet_NaN();
    for (const auto& [v, in] : inside)
        if (!in && v > lo - 5 && v < hi + 5) return std::numeric_limits<double>::quiet_NaN();
    return hi - lo + step;
}

/// Narrowest width of a river scene: the extent across the flow (which the slope of a meander only widens),
/// measured every metre along the river where the line across stays in the survey, averaged over 9 m (the
/// 2 m cells blur each bank by up to a cell on a single line).
double hydro_narrowest(const wfs::water_family_scene& s)
{
    std::vector<double> extent;
    for (double u = -0.2 * s.size_m; u <= 1.2 * s.size_m; u += 1) extent.push_back(hydro_extent_across(s, u));
    double narrowest = std::numeric_limits<double>::infinity();
    for (std::size_t i = 4; i + 4 < extent.size(); ++i) {
        double sum = 0;
        for (std::size_t j = i - 4; j <= i + 4; ++j) sum += extent[j];
        if (!std::isnan(sum)) narrowest = std::min(narrowest, sum / 9);
    }
    return narrowest;
}

}  // namespace

TEST_CASE("synth/water_family: hydro rivers fall in steps at their weirs")
{
    int weirs = 0;
    for (unsigned seed = 1; seed <= 5; ++seed) {
        CAPTURE(seed);
        const auto s = wfs::water_family({.seed = seed,
                                          .kind = wfs::water_family_kind::river,
                                          .min_density = 2,
                                          .max_density = 2,
                                          .variant = wfs::water_family_variant::hydro});
        REQUIRE(s.weir_along.size() <= 2);
        CHECK(s.bridges <= 2);
        weirs += static_cast<int>(s.weir_along.size());
        // The level falls monotonically downstream (toward increasing along) over every water cell.
        std::vector<std::pair<double, float>> cells;
        for (std::ptrdiff_t r = 0; r < s.g.rows; ++r)
            for (std::ptrdiff_t c = 0; c < s.g.cols; ++c)
                if (s.water(r, c)) {
                    const auto [x, y] = s.g.center(r, c);
                    cells.emplace_back(hydro_along(s, x, y), s.water_z(r, c));
                }
        REQUIRE(!cells.empty());
        std::sort(cells.begin(), cells.end());
        long rises = 0;
        for (std::size_t i = 1; i < cells.size(); ++i) rises += cells[i].second > cells[i - 1].second;
        CHECK(rises == 0);
        CHECK(s.body_level.size() == 1);
        CHECK(hydro_level_at(s, 0.5 * s.size_m) == doctest::Approx(s.body_level[0]).epsilon(1e-4));
        // At each weir the level drops by its drop: the fall across the weir (5 m either side) less the fall
        // of the 10 m above it.
        for (std::size_t k = 0; k < s.weir_along.size(); ++k) {
            const double u = s.weir_along[k][0], drop = s.weir_along[k][1];
            CAPTURE(u);
            CHECK(drop >= 0.3);
            CHECK(drop <= 1.5);
            if (k > 0) CHECK(u - s.weir_along[k - 1][0] >= 60);
            for (const auto& b : s.bridge_along) CHECK(std::abs(u - b[0]) >= b[1] + 25);
            const double above = hydro_level_at(s, u - 5), below = hydro_level_at(s, u + 5);
            const double linear = hydro_level_at(s, u - 15) - above;
            CHECK(std::abs(above - below - linear - drop) <= 0.01);
            // The weir's crossing lies at least 80 m inside the survey.
            for (std::ptrdiff_t r = 0; r < s.g.rows; ++r)
                for (std::ptrdiff_t c = 0; c < s.g.cols; ++c) {
                    const auto [x, y] = s.g.center(r, c);
                    if (!s.water(r, c) || std::abs(hydro_along(s, x, y) - u) > 0.5 * s.cell_m) continue;
                    CHECK(std::min(x, y) >= 80 - s.cell_m);
                    CHECK(std::max(x, y) <= s.size_m - 80 + s.cell_m);
                }
        }
        // At least 30 m wide (the specification's minimum nominal width is 30.5 m).
        const double narrowest = hydro_narrowest(s);
        MESSAGE("seed " << seed << ": " << s.weir_along.size() << " weirs, " << s.bridges << " bridges, narrowest "
                        << narrowest << " m");
        CHECK(narrowest >= 30);
        CHECK(narrowest <= 60);
    }
    CHECK(weirs >= 3);
}

TEST_CASE("synth/water_family: hydro lakes hold at least 8,000 m² of water each; other variants have no weirs")
{
    int islands = 0;
    for (unsigned seed = 1; seed <= 3; ++seed) {
        CAPTURE(seed);
        const auto s = wfs::water_family({.seed = seed,
                                          .kind = wfs::water_family_kind::lake,
                                          .min_density = 2,
                                          .max_density = 2,
                                          .variant = wfs::water_family_variant::hydro});
        std::map<std::int32_t, long> cells;
        for (std::ptrdiff_t r = 0; r < s.g.rows; ++r)
            for (std::ptrdiff_t c = 0; c < s.g.cols; ++c)
                if (s.body_id(r, c) > 0) ++cells[s.body_id(r, c)];
        REQUIRE(cells.size() == s.body_level.size());
        for (const auto& [body, n] : cells) CHECK(static_cast<double>(n) * s.cell_m * s.cell_m >= 8000);
        CHECK(s.weir_along.empty());
        islands += s.islands;
    }
    CHECK(islands > 0);
    for (const auto variant : {wfs::water_family_variant::classic, wfs::water_family_variant::level_land,
                               wfs::water_family_variant::narrow_river}) {
        for (unsigned seed = 1; seed <= 2; ++seed) {
            const auto s = wfs::water_family({.seed = seed,
                                              .kind = wfs::water_family_kind::river,
                                              .min_density = 0.5,
                                              .max_density = 0.5,
                                              .variant = variant});
            CHECK(s.weir_along.empty());
        }
    }
}
