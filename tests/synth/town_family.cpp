// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/synth/town_family.hpp>

#include <set>

using namespace lidarfx;
using namespace lidarfx::synth;

TEST_CASE("town_family: deterministic, varied, with truth for every building and roof face")
{
    town_family_options o;
    o.size_m = 120;
    const auto a = town_family(o), b = town_family(o);
    CHECK(a.town.points.x == b.town.points.x);
    CHECK(a.town.points.z == b.town.points.z);
    CHECK(a.density_per_m2 >= 1.0);
    CHECK(a.density_per_m2 <= 8.0);
    const auto& t = a.town.truth;
    REQUIRE(t.footprints.size() >= 4);
    std::set<std::int32_t> ids;
    for (const auto v : t.building_id) ids.insert(v);
    CHECK(ids.size() == t.footprints.size() + 1);  // every building has cells, plus 0
    std::set<double> tilts;
    for (const auto& p : t.roof_planes) {
        CHECK(p.tilt_deg <= 55.0);
        if (p.tilt_deg > 0) CHECK(p.tilt_deg >= 5.0);
        tilts.insert(p.tilt_deg);
    }
    CHECK(tilts.size() >= 3);
    o.seed = 2;
    const auto c = town_family(o);
    CHECK(c.density_per_m2 != a.density_per_m2);
    CHECK(c.town.points.x != a.town.points.x);
}
