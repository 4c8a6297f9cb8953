// SPDX-License-Identifier: Apache-2.0
// The randomized roof towns: deterministic, every roof kind present, truth rasters and plane list consistent.
#include <doctest/doctest.h>

#include <lidarfx/synth/roof_towns.hpp>

#include <cmath>
#include <cstdint>
#include <map>
#include <set>

using namespace lidarfx;
using namespace lidarfx::synth;

TEST_CASE("synth/roof_towns: the same seed gives the same town, another seed another")
{
    const auto a = make_roof_town({.seed = 3, .buildings = 9});
    const auto b = make_roof_town({.seed = 3, .buildings = 9});
    const auto c = make_roof_town({.seed = 4, .buildings = 9});
    REQUIRE(a.g.rows == b.g.rows);
    bool same = true, differs = false;
    for (std::ptrdiff_t r = 0; r < a.g.rows; ++r)
        for (std::ptrdiff_t col = 0; col < a.g.cols; ++col) {
            same = same && a.dsm(r, col) == b.dsm(r, col) && a.plane_id(r, col) == b.plane_id(r, col);
            differs = differs || a.dsm(r, col) != c.dsm(r, col);
        }
    CHECK(same);
    CHECK(differs);
    CHECK(a.density_per_m2 >= 1.0);
    CHECK(a.density_per_m2 <= 8.0);
}

TEST_CASE("synth/roof_towns: truth planes match the rasters; roofs stand above the ground")
{
    const auto t = make_roof_town({.seed = 1});
    std::set<roof_town_kind> kinds;
    for (const auto& b : t.buildings) kinds.insert(b.kind);
    CHECK(kinds.size() == 5);  // 36 houses: every kind appears
    std::map<std::int32_t, std::size_t> cells;
    std::map<std::int32_t, std::int32_t> building_of;
    std::size_t roof_cells = 0, high = 0;
    for (std::ptrdiff_t r = 0; r < t.g.rows; ++r)
        for (std::ptrdiff_t c = 0; c < t.g.cols; ++c) {
            const auto p = t.plane_id(r, c);
            if (p > 0) {
                ++cells[p];
                building_of[p] = t.building_id(r, c);
                ++roof_cells;
                high += t.dsm(r, c) - t.dtm(r, c) > 2.5f;
            }
            if (p > 0) CHECK(t.building_id(r, c) > 0);
        }
    // Eaves are 3-10 m above ground; an edge cell whose samples all missed the roof keeps the ground.
    CHECK(static_cast<double>(high) >= 0.95 * static_cast<double>(roof_cells));
    for (const auto& p : t.planes) {
        CAPTURE(p.plane_id);
        CHECK(p.tilt_deg >= 0);
        CHECK(p.tilt_deg <= 55);
        CHECK(p.sloped_area_m2 == doctest::Approx(p.area_m2 / std::cos(p.tilt_deg * 3.14159265358979 / 180)));
        if (cells.count(p.plane_id) == 0) continue;  // a sliver no cell centre hit
        CHECK(building_of[p.plane_id] == p.building_id);
        // Cell-centre counts against the 0.25 m supersampled area: equal up to the cells along the outline.
        if (p.area_m2 > 30) CHECK(static_cast<double>(cells[p.plane_id]) == doctest::Approx(p.area_m2).epsilon(0.25));
    }
}
