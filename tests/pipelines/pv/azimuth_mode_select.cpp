// SPDX-License-Identifier: Apache-2.0
// The rooftop PV paper's azimuth rules (appendix step 5), one case per branch.
#include <doctest/doctest.h>

#include <lidarfx/pipelines/pv/azimuth_mode_select.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <utility>
#include <vector>

using namespace lidarfx;

namespace {

/// A 1-degree aspect histogram with planes at the given azimuths: `cells` aspects in the plane's own bin and
/// cells / 10 in each bin within +-3 degrees, so the largest `cells` gives the mode.
std::vector<std::uint32_t> aspect_histogram(std::initializer_list<std::pair<int, std::uint32_t>> planes)
{
    std::vector<std::uint32_t> h(360, 0);
    for (const auto& [azimuth, cells] : planes) {
        for (int d = -3; d <= 3; ++d)
            h[static_cast<std::size_t>(((azimuth + d) % 360 + 360) % 360)] += d == 0 ? cells : cells / 10;
    }
    return h;
}

}  // namespace

TEST_CASE("pv/azimuth_mode_select: two planes with a north mode swap by 180 degrees, a south mode stays")
{
    const auto north = azimuth_mode_select(aspect_histogram({{20, 300}, {200, 280}}));
    CHECK(north.planes == 2);
    CHECK(north.form == roof_form::two_planes);
    CHECK(north.mode_deg == 20.0);
    CHECK(north.reason == azimuth_reason::swapped);
    CHECK(north.azimuth_deg == 200.0);
    CHECK(north.suitable);

    const auto due_north = azimuth_mode_select(aspect_histogram({{0, 300}, {180, 280}}));
    CHECK(due_north.azimuth_deg == 180.0);  // 0 lies in (270, 90)

    const auto south = azimuth_mode_select(aspect_histogram({{160, 300}, {340, 280}}));
    CHECK(south.reason == azimuth_reason::kept);
    CHECK(south.azimuth_deg == 160.0);

    const auto west_mode = azimuth_mode_select(aspect_histogram({{270, 300}, {90, 280}}));  // 270 is not in (270, 90)
    CHECK(west_mode.reason == azimuth_reason::kept);
    CHECK(west_mode.azimuth_deg == 270.0);
}

TEST_CASE("pv/azimuth_mode_select: four planes with an east-side mode turn to mode + 90 when west outnumbers east")
{
    // Hip roof turned 40 degrees: planes at 130 (mode), 220, 310, 40. West half (180, 360): 220 + 310.
    const auto west_heavy = azimuth_mode_select(aspect_histogram({{130, 300}, {220, 290}, {310, 250}, {40, 200}}));
    CHECK(west_heavy.planes == 4);
    CHECK(west_heavy.form == roof_form::four_planes);
    CHECK(west_heavy.reason == azimuth_reason::turned_west);
    CHECK(west_heavy.azimuth_deg == 220.0);

    const auto east_heavy = azimuth_mode_select(aspect_histogram({{130, 300}, {220, 150}, {310, 100}, {40, 280}}));
    CHECK(east_heavy.reason == azimuth_reason::kept_east);
    CHECK(east_heavy.azimuth_deg == 130.0);

    // A mode just past the bound (default 160) faces south already and stays.
    const auto southish = azimuth_mode_select(aspect_histogram({{165, 300}, {255, 290}, {345, 250}, {75, 200}}));
    CHECK(southish.reason == azimuth_reason::kept);
    CHECK(southish.azimuth_deg == 165.0);
    // With the paper's printed bound (180) it turns.
    const auto paper = azimuth_mode_select(aspect_histogram({{165, 300}, {255, 290}, {345, 250}, {75, 200}}),
                                           {.four_plane_high_deg = 180.0});
    CHECK(paper.reason == azimuth_reason::turned_west);
    CHECK(paper.azimuth_deg == 255.0);

    // A north mode on a four-plane roof is swapped as for two planes.
    const auto north = azimuth_mode_select(aspect_histogram({{10, 300}, {100, 290}, {190, 250}, {280, 200}}));
    CHECK(north.reason == azimuth_reason::swapped);
    CHECK(north.azimuth_deg == 190.0);
}

TEST_CASE("pv/azimuth_mode_select: three planes abandon a turn or swap towards a missing side")
{
    // Planes at 120 (mode), 300, 30: no plane near 120 + 90 = 210, west (300) outnumbers east (120 + 30)? no:
    // make west heavy so the turn is tried, then abandoned.
    const auto missing = azimuth_mode_select(aspect_histogram({{120, 300}, {300, 290}, {30, 150}}));
    CHECK(missing.planes == 3);
    CHECK(missing.form == roof_form::three_planes);
    CHECK(missing.reason == azimuth_reason::kept_east);  // east (120 + 30) = 450 > west 290
    const auto missing_west_heavy = azimuth_mode_select(aspect_histogram({{120, 300}, {300, 295}, {250, 200}}));
    CHECK(missing_west_heavy.planes == 3);
    // 120 + 90 = 210: the nearest aspects are at 250 - 3 = 247, more than 10 degrees away.
    CHECK(missing_west_heavy.reason == azimuth_reason::swap_abandoned);
    CHECK(missing_west_heavy.azimuth_deg == 120.0);

    const auto present = azimuth_mode_select(aspect_histogram({{120, 300}, {210, 295}, {300, 200}}));
    CHECK(present.reason == azimuth_reason::turned_west);
    CHECK(present.azimuth_deg == 210.0);

    // A north mode whose opposite side is missing keeps the mode (the east-south-west filter drops it later).
    const auto north = azimuth_mode_select(aspect_histogram({{350, 300}, {80, 200}, {260, 200}}));
    CHECK(north.reason == azimuth_reason::swap_abandoned);
    CHECK(north.azimuth_deg == 350.0);
}

TEST_CASE("pv/azimuth_mode_select: a shed, a complex roof, an empty building, ties")
{
    const auto shed_north = azimuth_mode_select(aspect_histogram({{5, 400}}));
    CHECK(shed_north.form == roof_form::one_plane);
    CHECK(shed_north.reason == azimuth_reason::swap_abandoned);
    CHECK(shed_north.azimuth_deg == 5.0);
    const auto shed_south = azimuth_mode_select(aspect_histogram({{175, 400}}));
    CHECK(shed_south.reason == azimuth_reason::kept);

    const auto complex =
        azimuth_mode_select(aspect_histogram({{0, 200}, {72, 200}, {144, 210}, {216, 200}, {288, 200}}));
    CHECK(complex.planes == 5);
    CHECK(complex.form == roof_form::complex);
    CHECK(complex.reason == azimuth_reason::too_many_planes);
    CHECK_FALSE(complex.suitable);
    CHECK(std::isnan(complex.azimuth_deg));

    const auto empty = azimuth_mode_select(std::vector<std::uint32_t>(360, 0));
    CHECK(empty.reason == azimuth_reason::no_cells);
    CHECK_FALSE(empty.suitable);
    CHECK(std::isnan(empty.mode_deg));

    std::vector<std::uint32_t> tie(360, 0);
    tie[100] = 50;
    tie[280] = 50;
    CHECK(azimuth_mode_select(tie).mode_deg == 100.0);  // the smaller azimuth wins a tie

    // Small clutter (a chimney's few aspects) is not a plane.
    auto cluttered = aspect_histogram({{20, 300}, {200, 280}});
    cluttered[110] = 8;
    CHECK(azimuth_mode_select(cluttered).planes == 2);

    CHECK_THROWS_AS(azimuth_mode_select(std::vector<std::uint32_t>(359, 1)), invalid_input);
    CHECK_THROWS_AS(azimuth_mode_select(aspect_histogram({{20, 300}}), {.min_plane_share = 0}), invalid_input);
}
