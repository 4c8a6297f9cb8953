// SPDX-License-Identifier: Apache-2.0
// facade_lit: every sub-patch's lit state equals a brute-force ray test, on boxes and random box towns.
#include <doctest/doctest.h>

#include <lidarfx/pipelines/buildings/facade_lit.hpp>
#include <lidarfx/pipelines/buildings/facade_patches.hpp>

#include <cmath>
#include <random>

#include "../../reference/facades.hpp"
#include "../../reference/progress.hpp"

using namespace lidarfx;

namespace {

/// Lit states by the brute force `ref` (a reference:: function of a point) for every sub-patch.
template <class Ref>
std::vector<std::uint8_t> brute(const raster<float>& z, double cell_m, const std::vector<facade_patch>& subs, double az,
                                double el, Ref&& ref)
{
    std::vector<std::uint8_t> out;
    for (const facade_patch& p : subs) {
        out.push_back(ref(z.view(), cell_m, p.front_row, p.front_col, p.height_m, p.facing_azimuth_deg, az, el));
    }
    return out;
}

}  // namespace

TEST_CASE("buildings/facade_lit: an isolated box -- the walls facing the sun are lit, the others are not")
{
    const auto s = reference::one_box(40, 40, 15, 15, 8, 10, 10.0f, 25.0f);
    const auto subs = facade_patches(s.dsm, s.ids, 1.0);
    // Sun in the south-east, 30 degrees up: south and east walls lit, north and west walls dark.
    const auto lit = facade_lit(s.dsm, subs, 1.0, 135.0, 30.0);
    for (std::size_t i = 0; i < subs.size(); ++i) {
        const double a = subs[i].facing_azimuth_deg;
        CHECK(lit[i] == (a == 90.0 || a == 180.0 ? 1 : 0));
    }
    // Below the horizon and at the zenith nothing is lit.
    for (const double e : {-5.0, 0.0, 90.0}) {
        for (const std::uint8_t v : facade_lit(s.dsm, subs, 1.0, 135.0, e)) CHECK(v == 0);
    }
}

TEST_CASE("buildings/facade_lit: a taller building in front shades the lower levels of a wall, not the upper ones")
{
    // A 15 m box (rows 10..15); south of it, rows 22..23, a 30 m wide, 8 m tall slab.
    auto s = reference::one_box(40, 40, 10, 15, 6, 10, 0.0f, 15.0f);
    for (std::ptrdiff_t r = 22; r < 24; ++r)
        for (std::ptrdiff_t c = 5; c < 35; ++c) {
            s.dsm(r, c) = 8.0f;
            s.ids(r, c) = 2;
        }
    const auto subs = facade_patches(s.dsm, s.ids, 1.0);
    // Sun due south 45 degrees up: from the front cells (row 16) the slab's near edge (row 22, 8 m tall) is 6 m
    // away, so points below 8 - 6 = 2 m are shaded.
    const auto lit = facade_lit(s.dsm, subs, 1.0, 180.0, 45.0);
    std::size_t shaded = 0, checked = 0;
    for (std::size_t i = 0; i < subs.size(); ++i) {
        if (subs[i].building_id != 1 || subs[i].facing_azimuth_deg != 180.0) continue;
        ++checked;
        const bool want = subs[i].height_m >= 8.0 - 6.0;
        CHECK(lit[i] == (want ? 1 : 0));
        shaded += lit[i] == 0;
    }
    CHECK(checked == 10u * 8);
    CHECK(shaded == 10u * 1);  // level 0 (centre 0.9375 m) of each of the 10 south walls
}

TEST_CASE("buildings/facade_lit: equals a straight ray march for the sun along the grid axes")
{
    std::mt19937 rng(5);
    for (int town = 0; town < 4; ++town) {
        const auto s = reference::box_town_ids(rng, 48, 56, 14);
        const auto subs = facade_patches(s.dsm, s.ids, 1.5);
        REQUIRE(subs.size() > 100);
        for (const double az : {0.0, 90.0, 180.0, 270.0}) {
            for (const double el : {8.0, 27.0, 61.0}) {
                CHECK(facade_lit(s.dsm, subs, 1.5, az, el) ==
                      brute(s.dsm, 1.5, subs, az, el, reference::facade_lit_ray_march));
            }
        }
    }
}

TEST_CASE("buildings/facade_lit: equals a direct search over its ray lines for random sun positions and towns")
{
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> azimuth(0.0, 360.0), elevation(1.0, 89.0);
    std::size_t lit_total = 0, total = 0;
    for (int town = 0; town < 6; ++town) {
        const auto s = reference::box_town_ids(rng, 50, 45, 16);
        const auto subs = facade_patches(s.dsm, s.ids, 1.0);
        for (int sun = 0; sun < 8; ++sun) {
            const double az = azimuth(rng), el = elevation(rng);
            const auto got = facade_lit(s.dsm, subs, 1.0, az, el);
            CHECK(got == brute(s.dsm, 1.0, subs, az, el, reference::facade_lit_on_line));
            for (const auto v : got) lit_total += v;
            total += got.size();
        }
    }
    // Both states occur (the test can fail).
    CHECK(lit_total > total / 10);
    CHECK(lit_total < total * 9 / 10);
}

TEST_CASE("buildings/facade_lit: agrees with a straight ray march from the front cell for >= 97 % of sub-patches")
{
    std::mt19937 rng(23);
    std::uniform_real_distribution<double> azimuth(0.0, 360.0), elevation(5.0, 80.0);
    std::size_t same = 0, total = 0;
    for (int town = 0; town < 4; ++town) {
        const auto s = reference::box_town_ids(rng, 60, 60, 18);
        const auto subs = facade_patches(s.dsm, s.ids, 1.0);
        for (int sun = 0; sun < 6; ++sun) {
            const double az = azimuth(rng), el = elevation(rng);
            const auto got = facade_lit(s.dsm, subs, 1.0, az, el);
            const auto dda = brute(s.dsm, 1.0, subs, az, el, reference::facade_lit_ray_march);
            for (std::size_t i = 0; i < got.size(); ++i) same += got[i] == dda[i];
            total += got.size();
        }
    }
    const double share = static_cast<double>(same) / static_cast<double>(total);
    MESSAGE("facade_lit agrees with a straight (DDA) ray march on ", 100.0 * share, " % of ", total,
            " sub-patch states");
    CHECK(share >= 0.97);
}

TEST_CASE("buildings/facade_lit: the same result for any thread count; bad input is refused")
{
    std::mt19937 rng(3);
    const auto s = reference::box_town_ids(rng, 300, 280, 120);
    const auto subs = facade_patches(s.dsm, s.ids, 1.0);
    const auto one = facade_lit(s.dsm, subs, 1.0, 123.0, 17.0, {.run = {.threads = 1}});
    CHECK(facade_lit(s.dsm, subs, 1.0, 123.0, 17.0, {.run = {.threads = 2}}) == one);
    CHECK(facade_lit(s.dsm, subs, 1.0, 123.0, 17.0, {.run = {.threads = 3}}) == one);
    CHECK_THROWS_AS(facade_lit(s.dsm, subs, 0.0, 123.0, 17.0), invalid_input);
    CHECK_THROWS_AS(facade_lit(s.dsm, subs, 1.0, std::nan(""), 17.0), invalid_input);
    CHECK_THROWS_AS(facade_lit(s.dsm, subs, 1.0, 123.0, 91.0), invalid_input);
    CHECK_THROWS_AS(facade_lit(s.dsm, subs, 1.0, 123.0, 17.0, {.run = {.threads = -1}}), invalid_input);
    const raster<float> small(10, 10, 0.0f);
    CHECK_THROWS_AS(facade_lit(small, subs, 1.0, 123.0, 17.0), invalid_input);
}
