// SPDX-License-Identifier: Apache-2.0
// vegetation_by_returns and drop_vegetation_parts: trees told from roofs by their split pulses, and
// extract_buildings with pulse counts keeping a rough old roof that the roughness rule alone drops.
#include <doctest/doctest.h>

#include <lidarfx/pipelines/buildings/extract_buildings.hpp>
#include <lidarfx/pipelines/buildings/vegetation_by_returns.hpp>

#include <cstdint>
#include <random>

using namespace lidarfx;

namespace {

/// Ground at 100 m, 80 x 80 cells of 0.5 m: a rough old roof (rows and cols [10, 40), eaves 8 m, heights that
/// jump by up to 1.2 m from cell to cell: tiles, dormers, chimneys) and a crown (rows [50, 70) x cols [20, 60),
/// 6-10 m) beside it. Every cell holds 10 points; on the roof 1 comes from a split pulse, in the crown 3.
struct returns_scene {
    raster<float> z{80, 80, 100.0f};
    raster<std::uint32_t> points{80, 80, 10u}, split{80, 80, 0u};
    grid g{0.0, 40.0, 0.5, 80, 80};

    returns_scene()
    {
        std::mt19937 rng(7);
        std::uniform_real_distribution<float> jump(0.0f, 1.2f), crown(6.0f, 10.0f);
        for (std::ptrdiff_t r = 10; r < 40; ++r) {
            for (std::ptrdiff_t c = 10; c < 40; ++c) {
                z(r, c) = 108.0f + jump(rng);
                split(r, c) = 1;
            }
        }
        for (std::ptrdiff_t r = 50; r < 70; ++r) {
            for (std::ptrdiff_t c = 20; c < 60; ++c) {
                z(r, c) = 100.0f + crown(rng);
                split(r, c) = 3;
            }
        }
    }
};

}  // namespace

TEST_CASE("vegetation_by_returns: a cell is vegetation when at least cell_share of its points are split pulses")
{
    std::mt19937 rng(3);
    std::uniform_int_distribution<std::uint32_t> count(0, 12);
    raster<std::uint32_t> points(17, 23), split(17, 23);
    for (std::ptrdiff_t r = 0; r < 17; ++r) {
        for (std::ptrdiff_t c = 0; c < 23; ++c) {
            points(r, c) = count(rng);
            split(r, c) = std::uniform_int_distribution<std::uint32_t>(0, points(r, c))(rng);
        }
    }
    for (const double share : {0.25, 0.5, 1.0}) {
        const auto mask = vegetation_by_returns({points.view(), split.view()}, {.cell_share = share});
        for (std::ptrdiff_t r = 0; r < 17; ++r) {
            for (std::ptrdiff_t c = 0; c < 23; ++c) {
                CAPTURE(points(r, c));
                CAPTURE(split(r, c));
                const bool expected = points(r, c) > 0 && split(r, c) >= share * points(r, c);
                CHECK((mask(r, c) == 1) == expected);
            }
        }
    }
    split(3, 4) = points(3, 4) + 1;
    CHECK_THROWS_AS(vegetation_by_returns({points.view(), split.view()}), invalid_input);
    CHECK_THROWS_AS(vegetation_by_returns({points.view(), points.view()}, {.cell_share = 0.0}), invalid_input);
    const raster<std::uint32_t> other(17, 22, 0u);
    CHECK_THROWS_AS(vegetation_by_returns({points.view(), other.view()}), invalid_input);
}

TEST_CASE("drop_vegetation_parts: parts the laser did not see and parts of split pulses are dropped")
{
    // Four parts of 100 cells, 10 points per cell elsewhere: part 1 holds 15 % split pulses (a roof), part 2
    // 25 % (a crown), part 3 no point at all (a surface interpolated over a canal), part 4 one point per cell
    // (below a quarter of the mean: unseen).
    raster<std::int32_t> ids(10, 50, 0);
    raster<std::uint32_t> points(10, 50, 10u), split(10, 50, 0u);
    for (std::ptrdiff_t r = 0; r < 10; ++r) {
        for (std::ptrdiff_t c = 0; c < 40; ++c) {
            const auto part = static_cast<std::int32_t>(c / 10 + 1);
            ids(r, c) = part;
            points(r, c) = part == 3 ? 0u : part == 4 ? 1u : 10u;
            split(r, c) = part == 1 ? (r < 5 ? 2u : 1u) : part == 2 ? (r < 5 ? 3u : 2u) : 0u;
        }
    }
    // The mean over the cells with points: (300 x 10 + 100 x 1) / 400 = 7.75 points per cell.
    const auto [kept, dropped] = drop_vegetation_parts(ids, 4, {points.view(), split.view()});
    CHECK(kept == 1);
    CHECK(dropped == 3);
    CHECK(ids(0, 0) == 1);
    CHECK(ids(0, 15) == 0);
    CHECK(ids(0, 25) == 0);
    CHECK(ids(0, 35) == 0);

    // With no density asked for, part 4 counts as seen; part 3, without a point, never does.
    raster<std::int32_t> again(10, 50, 0);
    for (std::ptrdiff_t r = 0; r < 10; ++r)
        for (std::ptrdiff_t c = 20; c < 40; ++c) again(r, c) = static_cast<std::int32_t>(c / 10 - 1);
    const auto lenient = drop_vegetation_parts(again, 2, {points.view(), split.view()}, {.min_seen_density = 0.0});
    CHECK(lenient[0] == 1);
    CHECK(again(0, 35) == 1);
    CHECK(again(0, 25) == 0);
    CHECK_THROWS_AS(drop_vegetation_parts(again, 2, {points.view(), split.view()}, {.min_seen_density = 1.5}),
                    invalid_input);
}

TEST_CASE("extract_buildings with pulse counts keeps a rough old roof and drops the crown beside it")
{
    const returns_scene s;
    const auto by_returns = extract_buildings(s.z, s.g, {}, pulse_returns{s.points.view(), s.split.view()});
    REQUIRE(by_returns.buildings.size() == 1);
    CHECK(by_returns.building_id(25, 25) == 1);
    CHECK(by_returns.building_id(60, 40) == 0);
    CHECK(by_returns.buildings[0].roof_area_horizontal_m2 > 0.9 * 15.0 * 15.0);
    CHECK(by_returns.rejected_rough == 1);

    // Without the counts, the roughness rule drops the rough roof with the crown.
    CHECK(extract_buildings(s.z, s.g).building_id(25, 25) == 0);
    // A survey without any split pulse says nothing of trees: the roughness rule decides, as without counts.
    const raster<std::uint32_t> no_split(80, 80, 0u);
    CHECK(extract_buildings(s.z, s.g, {}, pulse_returns{s.points.view(), no_split.view()}).building_id ==
          extract_buildings(s.z, s.g).building_id);
    // The cell rule alone (any split pulse marks vegetation) loses the roof: every roof cell holds one.
    raster<std::uint8_t> any_split(80, 80, 0);
    for (std::ptrdiff_t r = 0; r < 80; ++r)
        for (std::ptrdiff_t c = 0; c < 80; ++c) any_split(r, c) = s.split(r, c) > 0;
    CHECK(extract_buildings(s.z, s.g, {}, any_split.view()).building_id(25, 25) == 0);

    // Same result for any thread count.
    extract_buildings_options many;
    many.run.threads = 3;
    const auto threaded = extract_buildings(s.z, s.g, {}, pulse_returns{s.points.view(), s.split.view()}, many);
    CHECK(threaded.building_id == by_returns.building_id);
    CHECK_THROWS_AS(extract_buildings(s.z, s.g, {}, pulse_returns{s.points.view(), s.points.view()},
                                      extract_buildings_options{.returns = {.part_share = 1.5}}),
                    invalid_input);
}
