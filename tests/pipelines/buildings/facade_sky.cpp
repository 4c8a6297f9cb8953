// SPDX-License-Identifier: Apache-2.0
// facade_horizon and facade_sky_view: an open wall sees half the sky (cosine-weighted) and the 1,081-source share
// of a brute-force count; horizons equal a direct search; a neighbour lowers the view of the lower levels.
#include <doctest/doctest.h>

#include <lidarfx/pipelines/buildings/facade_patches.hpp>
#include <lidarfx/pipelines/buildings/facade_sky_view.hpp>

#include <cmath>
#include <random>

#include "../../reference/facades.hpp"
#include "../../reference/progress.hpp"

using namespace lidarfx;

TEST_CASE("buildings/facade_sky_view: an unobstructed wall -- cosine-weighted 0.5, sources = the brute-force count")
{
    const auto s = reference::one_box(30, 30, 12, 11, 6, 8, 10.0f, 22.0f);
    const auto subs = facade_patches(s.dsm, s.ids, 1.0);
    const auto cosine = facade_sky_view(s.dsm, subs, 1.0, {.method = sky_view_factor_method::cosine_weighted});
    const auto share = facade_sky_view(s.dsm, subs, 1.0);
    REQUIRE(subs.size() == 8u * 28);
    for (std::size_t i = 0; i < subs.size(); ++i) {
        const facade_patch& p = subs[i];
        CHECK(cosine[i] == doctest::Approx(0.5).epsilon(1e-12));
        const int count = reference::facade_visible_sources(s.dsm.view(), 1.0, p.front_row, p.front_col, p.height_m,
                                                            p.facing_azimuth_deg);
        CHECK(count == 35 * 15);  // 35 azimuths strictly in front of the wall, 15 elevations each; no zenith
        CHECK(share[i] == doctest::Approx(count / 1081.0).epsilon(1e-12));
    }
}

TEST_CASE("buildings/facade_horizon: equals a direct search over its ray lines, for any azimuth, on random towns")
{
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> azimuth(0.0, 360.0);
    double largest = 0.0;
    for (int town = 0; town < 5; ++town) {
        const auto s = reference::box_town_ids(rng, 46, 52, 15);
        const auto subs = facade_patches(s.dsm, s.ids, 1.0);
        for (int k = 0; k < 10; ++k) {
            const double az = k < 4 ? 90.0 * k : azimuth(rng);
            const auto got = facade_horizon(s.dsm, subs, 1.0, az);
            for (std::size_t i = 0; i < subs.size(); ++i) {
                const facade_patch& p = subs[i];
                const double want =
                    reference::facade_horizon_on_line(s.dsm.view(), 1.0, p.front_row, p.front_col, p.height_m, az);
                CHECK(got[i] == doctest::Approx(want).epsilon(1e-12));
                largest = std::max(largest, want);
            }
        }
    }
    CHECK(largest > 1.0);  // some horizons above 45 degrees: the towns do obstruct
}

TEST_CASE("buildings/facade_sky_view: the source share equals the brute-force count of visible sources on towns")
{
    std::mt19937 rng(29);
    const auto s = reference::box_town_ids(rng, 40, 40, 12);
    const auto subs = facade_patches(s.dsm, s.ids, 1.0);
    const auto share = facade_sky_view(s.dsm, subs, 1.0, {.directions = 24});
    std::size_t differ = 0, obstructed = 0;
    for (std::size_t i = 0; i < subs.size(); ++i) {
        const facade_patch& p = subs[i];
        const int count = reference::facade_visible_sources(s.dsm.view(), 1.0, p.front_row, p.front_col, p.height_m,
                                                            p.facing_azimuth_deg, 24);
        differ += std::lround(share[i] * (15 * 24 + 1)) != count;
        obstructed += count < 11 * 15;
    }
    CHECK(differ == 0);
    CHECK(obstructed > subs.size() / 10);
}

TEST_CASE("buildings/facade_sky_view: a facing building lowers the view of the lower levels most; open walls stay 0.5")
{
    // Two boxes 6 m apart, each 20 m tall: the facing walls (A's south, B's north) see less sky near the ground.
    auto s = reference::one_box(50, 40, 10, 10, 8, 20, 0.0f, 20.0f);
    for (std::ptrdiff_t r = 24; r < 32; ++r)
        for (std::ptrdiff_t c = 10; c < 30; ++c) {
            s.dsm(r, c) = 20.0f;
            s.ids(r, c) = 2;
        }
    const auto subs = facade_patches(s.dsm, s.ids, 1.0);
    const auto svf = facade_sky_view(s.dsm, subs, 1.0, {.method = sky_view_factor_method::cosine_weighted});
    for (std::size_t i = 0; i < subs.size(); ++i) {
        const facade_patch& p = subs[i];
        CHECK(svf[i] <= 0.5 + 1e-12);
        const bool facing_other = (p.building_id == 1 && p.facing_azimuth_deg == 180.0) ||
                                  (p.building_id == 2 && p.facing_azimuth_deg == 0.0);
        if (p.facing_azimuth_deg == 90.0 || p.facing_azimuth_deg == 270.0) continue;  // half open
        if (!facing_other) {
            CHECK(svf[i] == doctest::Approx(0.5).epsilon(1e-12));
        } else if (p.col == 20 && p.level > 0) {
            CHECK(svf[i] > svf[i - 1]);  // higher up, more sky
            CHECK(svf[i] < 0.5);
        }
    }
}

TEST_CASE("buildings/facade_sky_view: the same result for any thread count; progress, cancellation, refusals")
{
    std::mt19937 rng(41);
    const auto s = reference::box_town_ids(rng, 200, 220, 60);
    const auto subs = facade_patches(s.dsm, s.ids, 1.0);
    const auto one = facade_sky_view(s.dsm, subs, 1.0, {.directions = 16, .run = {.threads = 1}});
    CHECK(facade_sky_view(s.dsm, subs, 1.0, {.directions = 16, .run = {.threads = 2}}) == one);
    CHECK(facade_sky_view(s.dsm, subs, 1.0, {.directions = 16, .run = {.threads = 3}}) == one);
    reference::progress_log log;
    facade_sky_view(s.dsm, subs, 1.0, {.directions = 8, .run = {.progress = log.callback()}});
    CHECK(log.monotone_to_one());
    CHECK_THROWS_AS(
        facade_sky_view(s.dsm, subs, 1.0, {.directions = 8, .run = {.progress = [](double) { return false; }}}),
        cancelled);
    CHECK_THROWS_AS(facade_sky_view(s.dsm, subs, 0.0), invalid_input);
    CHECK_THROWS_AS(facade_sky_view(s.dsm, subs, 1.0, {.directions = 3}), invalid_input);
    CHECK_THROWS_AS(facade_horizon(s.dsm, subs, 1.0, std::nan("")), invalid_input);
    const raster<float> small(10, 10, 0.0f);
    CHECK_THROWS_AS(facade_sky_view(small, subs, 1.0), invalid_input);
}
