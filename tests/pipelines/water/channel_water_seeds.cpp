// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/core/error.hpp>
#include <lidarfx/core/raster.hpp>
#include <lidarfx/kernels/metrics/confusion.hpp>
#include <lidarfx/kernels/points/rasterize.hpp>
#include <lidarfx/pipelines/water/channel_water_seeds.hpp>
#include <lidarfx/pipelines/water/extract_waterbodies.hpp>
#include <lidarfx/synth/water_family.hpp>

#include "reference/components.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>

using namespace lidarfx;

namespace {

/// A 40 x 60 survey of 2 m cells: land at 101 m (intensity 80) with a channel along the rows 18..(18 + width - 1)
/// whose water stands at 100 m (intensity 20); the banks rise to `bank` m above the water. Land intensity 80.
struct channel_scene {
    raster<float> z, intensity;
    std::ptrdiff_t first_row = 18;
    int width = 3;
    channel_scene(int water_cells, double bank) : z(40, 60, static_cast<float>(100 + bank)), intensity(40, 60, 80.0f)
    {
        width = water_cells;
        for (std::ptrdiff_t r = first_row; r < first_row + width; ++r)
            for (std::ptrdiff_t c = 0; c < z.cols(); ++c) {
                z(r, c) = 100.0f;
                intensity(r, c) = 20.0f;
            }
    }
    raster<std::uint8_t> seeds(const channel_water_seeds_options& opt = {}, raster_view<const std::int32_t> taken = {},
                               raster_view<const std::uint8_t> excluded = {}, int threads = 1) const
    {
        return channel_water_seeds(z, intensity, excluded, taken, 2.0, 80.0, opt, {.threads = threads});
    }
    bool is_channel(std::ptrdiff_t r) const { return r >= first_row && r < first_row + width; }
};

std::ptrdiff_t count_of(const raster<std::uint8_t>& m)
{
    std::ptrdiff_t n = 0;
    for (const auto v : m) n += v != 0;
    return n;
}

}  // namespace

TEST_CASE("water/channel_water_seeds: a level, dark strip between two banks is seeded, nothing else")
{
    const channel_scene scene(3, 0.5);
    // The first and last columns have no cell beyond them along the channel: they are not seeded.
    const auto seeds = scene.seeds();
    for (std::ptrdiff_t r = 0; r < seeds.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < seeds.cols(); ++c)
            CHECK(seeds(r, c) == (scene.is_channel(r) && c > 0 && c < 59 ? 1 : 0));
    // The same channel along the columns gives the transposed seeds.
    const auto across =
        channel_water_seeds(reference::transpose(scene.z), reference::transpose(scene.intensity), {}, {}, 2.0, 80.0);
    CHECK(across == reference::transpose(seeds));
}

TEST_CASE("water/channel_water_seeds: a diagonal channel is seeded")
{
    raster<float> z(50, 50, 101.0f), intensity(50, 50, 80.0f);
    for (std::ptrdiff_t r = 0; r < 50; ++r)
        for (std::ptrdiff_t c = 0; c < 50; ++c)
            if (std::abs(r - c) <= 1) {
                z(r, c) = 100.0f;
                intensity(r, c) = 20.0f;
            }
    const auto seeds = channel_water_seeds(z, intensity, {}, {}, 2.0, 80.0);
    CHECK(seeds(25, 25) == 1);
    CHECK(seeds(25, 24) == 1);
    CHECK(seeds(25, 28) == 0);
    CHECK(count_of(seeds) > 100);
}

TEST_CASE("water/channel_water_seeds: the banks, the width and the level decide")
{
    SUBCASE("a bank just below bank_rise_m is no bank; at it, one")
    {
        const channel_water_seeds_options opt{.bank_rise_m = 0.125};  // exact in float above 100 m
        CHECK(count_of(channel_scene(3, 0.125 - 1.0 / 128).seeds(opt)) == 0);
        CHECK(count_of(channel_scene(3, 0.125).seeds(opt)) == 3 * 58);
    }
    SUBCASE("a strip wider than max_width_m is a level field: 9 cells of 2 m is 18 m, 10 cells too wide")
    {
        CHECK(count_of(channel_scene(9, 0.5).seeds()) == 9 * 58);
        CHECK(count_of(channel_scene(10, 0.5).seeds()) == 0);
        CHECK(count_of(channel_scene(10, 0.5).seeds({.max_width_m = 20})) == 10 * 58);
    }
    SUBCASE("a strip on a terrace above lower water is not the lowest: only the water is seeded")
    {
        channel_scene scene(6, 0.5);
        for (std::ptrdiff_t c = 0; c < 60; ++c) scene.z(18, c) = scene.z(19, c) = 99.8f;  // the river, 0.2 m lower
        const auto seeds = scene.seeds();
        for (std::ptrdiff_t c = 1; c < 59; ++c) {
            CHECK(seeds(18, c) == 1);
            CHECK(seeds(19, c) == 1);
            for (std::ptrdiff_t r = 20; r < 24; ++r) CHECK(seeds(r, c) == 0);
        }
    }
    SUBCASE("a level strip above lower ground around it (a flat roof between higher roof parts) is not seeded")
    {
        channel_scene roof(3, 8.0);  // the strip at 100 m between parts at 108 m
        for (std::ptrdiff_t r = 0; r < 40; ++r)
            for (std::ptrdiff_t c = 0; c < 60; ++c)
                if (r < 12 || r > 26) roof.z(r, c) = 97.0f;  // the ground, 4 rows beyond each higher part
        CHECK(count_of(roof.seeds()) == 0);
        CHECK(count_of(roof.seeds({.max_lower_share = 0.3})) == 3 * 58);
    }
    SUBCASE("a trough falling more than the tolerance per cell is not level along any axis")
    {
        channel_scene scene(3, 2.0);
        for (std::ptrdiff_t r = 0; r < 40; ++r)
            for (std::ptrdiff_t c = 0; c < 60; ++c) scene.z(r, c) += 0.06f * static_cast<float>(c);
        CHECK(count_of(scene.seeds()) == 0);
        // 3 cells along; the channel falling away within max_width_m is up to 7 % of the surroundings.
        const channel_water_seeds_options steep{.level_tolerance_m = 0.19, .bank_rise_m = 0.25, .max_lower_share = 0.1};
        CHECK(count_of(scene.seeds(steep)) == 3 * 58);
    }
    SUBCASE("dropouts: passed across the strip, not seeds themselves; along, one measured cell each way suffices")
    {
        channel_scene scene(3, 0.5);
        for (std::ptrdiff_t c = 0; c < 60; c += 2) scene.z(19, c) = NAN;  // every other cell of the middle row
        scene.z(18, 30) = scene.z(18, 31) = scene.z(18, 32) = NAN;
        const auto seeds = scene.seeds();
        CHECK(seeds(19, 2) == 0);   // no return
        CHECK(seeds(19, 3) == 1);   // one measured cell each way, 1 cell away
        CHECK(seeds(18, 28) == 1);  // 29 measured on one way
        CHECK(seeds(18, 29) == 0);  // 30, 31 and 32 empty: nothing measured within 3 cells on that way
        CHECK(seeds(18, 33) == 0);  // likewise
        CHECK(seeds(18, 34) == 1);  // 33 measured
        CHECK(seeds(20, 30) == 1);  // across, the empty cells of row 19 are part of the strip
    }
}

TEST_CASE("water/channel_water_seeds: land-bright cells, vegetation, bodies nearby and small groups are left out")
{
    const channel_scene scene(3, 0.5);
    SUBCASE("intensity above max_intensity_ratio times the land's")
    {
        channel_scene bright(3, 0.5);
        for (std::ptrdiff_t c = 0; c < 60; ++c)
            for (std::ptrdiff_t r = 18; r < 21; ++r) bright.intensity(r, c) = 48.5f;  // above 0.6 · 80 = 48
        CHECK(count_of(bright.seeds()) == 0);
        CHECK(count_of(bright.seeds({.max_intensity_ratio = 0.61})) == 3 * 58);
        CHECK(count_of(channel_water_seeds(scene.z, scene.intensity, {}, {}, 2.0, NAN)) == 0);  // no land measured
    }
    SUBCASE("excluded cells")
    {
        raster<std::uint8_t> vegetation(40, 60, 0);
        for (std::ptrdiff_t r = 18; r < 21; ++r) vegetation(r, 10) = 1;
        const auto seeds = scene.seeds({}, {}, vegetation);
        CHECK(seeds(19, 10) == 0);
        CHECK(seeds(19, 11) == 1);
    }
    SUBCASE("a body within clear_cells (the shore of water already found)")
    {
        raster<std::int32_t> taken(40, 60, 0);
        taken(10, 30) = 2;  // 8 rows above the channel's first row
        CHECK(count_of(scene.seeds({}, taken)) == 3 * 58);
        const auto seeds = scene.seeds({.clear_cells = 8}, taken);
        CHECK(seeds(18, 30) == 0);
        CHECK(seeds(18, 38) == 0);
        CHECK(seeds(18, 39) == 1);
        CHECK(seeds(19, 30) == 1);  // 9 rows away
    }
    SUBCASE("groups smaller than min_cells")
    {
        channel_scene short_channel(3, 0.5);
        for (std::ptrdiff_t r = 18; r < 21; ++r)
            for (std::ptrdiff_t c = 6; c < 60; ++c) short_channel.z(r, c) = 100.5f;  // 6 columns of water remain
        // Columns 1-4 are channel cells (column 0 has nothing beyond it, column 5 a bank along the row): 12.
        CHECK(count_of(short_channel.seeds({.along_cells = 1, .min_cells = 13})) == 0);
        CHECK(count_of(short_channel.seeds({.along_cells = 1, .min_cells = 12})) == 12);
    }
}

TEST_CASE("water/channel_water_seeds: any thread count gives the same seeds; refusals")
{
    const unsigned seed = 91;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> height(99.9f, 100.4f), light(5.0f, 90.0f), share(0.0f, 1.0f);
    raster<float> z(123, 77), intensity(123, 77);
    for (std::ptrdiff_t i = 0; i < z.rows() * z.cols(); ++i) {
        z.data()[i] = share(rng) < 0.1f ? NAN : height(rng);
        intensity.data()[i] = light(rng);
    }
    const channel_water_seeds_options opt{.level_tolerance_m = 0.2, .bank_rise_m = 0.25, .min_cells = 1};
    const auto one = channel_water_seeds(z, intensity, {}, {}, 2.0, 80.0, opt, {.threads = 1});
    INFO("seed " << seed);
    CHECK(count_of(one) > 0);
    for (const int threads : {2, 3, 8})
        CHECK(channel_water_seeds(z, intensity, {}, {}, 2.0, 80.0, opt, {.threads = threads}) == one);

    CHECK_THROWS_AS(channel_water_seeds(z, raster<float>(3, 3), {}, {}, 2.0, 80.0), invalid_input);
    CHECK_THROWS_AS(channel_water_seeds(z, intensity, {}, {}, 0.0, 80.0), invalid_input);
    CHECK_THROWS_AS(channel_water_seeds(z, intensity, {}, {}, 2.0, 80.0, {.bank_rise_m = 0.05}), invalid_input);
    CHECK_THROWS_AS(channel_water_seeds(z, intensity, {}, {}, 2.0, 80.0, {.along_cells = 0}), invalid_input);
    CHECK_THROWS_AS(channel_water_seeds(z, intensity, {}, {}, 2.0, 80.0, {.min_cells = 0}), invalid_input);
    CHECK_THROWS_AS(channel_water_seeds(z, intensity, {}, {}, 2.0, 80.0, {.clear_cells = -1}), invalid_input);
    CHECK_THROWS_AS(channel_water_seeds(z, intensity, {}, {}, 2.0, 80.0, {.max_intensity_ratio = 0}), invalid_input);
}

TEST_CASE("water/channel_water_seeds: lidarfx water's method finds a narrow river it misses without channel seeds")
{
    // Narrow-river tuning seed 4 on 3 m cells: a river 5-15 m wide that neither dropouts nor flat seeds start.
    synth::water_family_options o;
    o.seed = 4;
    o.kind = synth::water_family_kind::river;
    o.variant = synth::water_family_variant::narrow_river;
    o.min_density = 1;
    o.max_density = 8;
    o.cell_m = 3;
    const auto scene = synth::water_family(o);
    const auto rasters = rasterize(scene.points.cloud(), scene.g);
    const auto with = flat_seed_water_method();  // channel seeds on
    auto without = with;
    without.channel_seeds = false;
    const auto with_channels =
        confusion_counts(extract_waterbodies(rasters, with).water, scene.water_filled, scene.cell_m);
    const auto flat_only =
        confusion_counts(extract_waterbodies(rasters, without).water, scene.water_filled, scene.cell_m);
    CHECK(with_channels.sensitivity() > 0.9);
    CHECK(flat_only.sensitivity() < 0.05);
    CHECK(with_channels.specificity() > 0.99);
}

TEST_CASE("water/channel_water_seeds: a channel seed's flood that spreads over bright land is taken back")
{
    // Classic river seed 12019: a dark trough in a field of land intensity seeds a flood that, left alone, takes
    // about 20,000 m² of the field (specificity 93 %); its body is brighter than the channel cells may be.
    synth::water_family_options o;
    o.seed = 12019;
    o.kind = synth::water_family_kind::river;
    const auto scene = synth::water_family(o);
    const auto rasters = rasterize(scene.points.cloud(), scene.g);
    const auto result = extract_waterbodies(rasters, flat_seed_water_method());
    const auto scores = confusion_counts(result.water, scene.water_filled, scene.cell_m);
    CHECK(scores.specificity() > 0.99);
    CHECK(scores.sensitivity() > 0.95);
    for (const auto& body : result.bodies) CHECK(body.mean_intensity < 60);
}

TEST_CASE("water/channel_water_seeds: a gently rising shore is passed, the raster's edge is no bank, odd inputs")
{
    SUBCASE("a row 0.08 m above the water (above the tolerance, below a bank) is passed, not seeded")
    {
        channel_scene scene(3, 0.5);
        for (std::ptrdiff_t c = 0; c < 60; ++c) scene.z(20, c) = 100.08f;
        const auto seeds = scene.seeds();
        CHECK(seeds(18, 30) == 1);
        CHECK(seeds(19, 30) == 1);
        CHECK(seeds(20, 30) == 0);  // the water beside it lies more than the tolerance below it
    }
    SUBCASE("water reaching the raster's edge across has no bank on that side")
    {
        channel_scene scene(3, 0.5);
        for (std::ptrdiff_t r = 18; r < 40; ++r)
            for (std::ptrdiff_t c = 0; c < 60; ++c) scene.z(r, c) = 100.0f;
        CHECK(count_of(scene.seeds({.max_width_m = 1000})) == 0);
    }
    SUBCASE("NaN intensity is no seed; widths beyond the raster count as the raster")
    {
        channel_scene scene(3, 0.5);
        scene.intensity(19, 30) = NAN;
        CHECK(scene.seeds()(19, 30) == 0);
        CHECK(scene.seeds()(19, 31) == 1);
        CHECK(scene.seeds({.max_width_m = 1e12}) == scene.seeds({.max_width_m = 400}));
        CHECK(scene.seeds({.along_cells = 1 << 30}) == scene.seeds({.along_cells = 100}));
    }
    SUBCASE("refusals")
    {
        const channel_scene scene(3, 0.5);
        for (const channel_water_seeds_options& opt :
             {channel_water_seeds_options{.level_tolerance_m = -0.01}, channel_water_seeds_options{.max_width_m = 0},
              channel_water_seeds_options{.max_lower_share = 1.5},
              channel_water_seeds_options{.max_lower_share = -0.1}})
            CHECK_THROWS_AS(scene.seeds(opt), invalid_input);
        CHECK_THROWS_AS(scene.seeds({}, raster<std::int32_t>(3, 3, 0)), invalid_input);
        CHECK_THROWS_AS(scene.seeds({}, {}, raster<std::uint8_t>(3, 3, 0)), invalid_input);
    }
}

TEST_CASE("water/extract_waterbodies: bright bodies grown from channel seeds are taken back, the rest renumbered")
{
    // Bodies 1-4 in columns 0-1, 2-3, 4-5, 6-7 of a 4 x 10 raster; bodies 2-4 are the new ones (first = 1).
    // Body 3 is bright (90 > 48), body 4 has no measured cell (all dropouts): it stays.
    water_rasters in;
    raster<float> z(4, 10, 100.0f), light(4, 10, 20.0f), high(4, 10, 100.5f);
    raster<std::uint8_t> dropout(4, 10, 0);
    grow_waterbodies_result grown{raster<std::int32_t>(4, 10, 0), {}, 4};
    for (std::ptrdiff_t r = 0; r < 4; ++r)
        for (std::ptrdiff_t c = 0; c < 8; ++c) grown.labels(r, c) = static_cast<std::int32_t>(c / 2 + 1);
    for (std::ptrdiff_t r = 0; r < 4; ++r) {
        light(r, 0) = light(r, 1) = 90.0f;  // body 1 is bright too, but not a new body
        light(r, 4) = light(r, 5) = 90.0f;
        dropout(r, 6) = dropout(r, 7) = 1;
        light(r, 6) = light(r, 7) = NAN;
    }
    for (int k = 0; k < 4; ++k) {
        waterbody body;
        body.label = k + 1;
        body.seed = 10 * (k + 1);
        grown.bodies.push_back(body);
    }
    in.min_z = z;
    in.max_z = high;
    in.mean_intensity = light;
    in.dropout = dropout;
    raster<std::uint8_t> eligible(4, 10, 0);
    detail::drop_bright_bodies(grown, 1, in, 48.0, eligible);
    REQUIRE(grown.bodies.size() == 3);
    CHECK(grown.seeds_grown == 3);
    for (std::size_t k = 0; k < 3; ++k) CHECK(grown.bodies[k].label == static_cast<std::int32_t>(k + 1));
    CHECK(grown.bodies[0].seed == 10);
    CHECK(grown.bodies[1].seed == 20);
    CHECK(grown.bodies[2].seed == 40);
    for (std::ptrdiff_t r = 0; r < 4; ++r) {
        CHECK(grown.labels(r, 0) == 1);
        CHECK(grown.labels(r, 2) == 2);
        CHECK(grown.labels(r, 4) == 0);
        CHECK(eligible(r, 4) == 1);
        CHECK(eligible(r, 2) == 0);
        CHECK(grown.labels(r, 7) == 3);
        CHECK(grown.labels(r, 9) == 0);
    }
}
