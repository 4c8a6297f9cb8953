// SPDX-License-Identifier: Apache-2.0
// The waterbody method on the water family (synth/water_family.hpp): the two failure modes of issue 17 as
// fixed scenes, and a small fixed subset of the family (seeds 501-503, not reporting seeds).
#include <doctest/doctest.h>

#include <lidarfx/kernels/metrics/confusion.hpp>
#include <lidarfx/kernels/points/rasterize.hpp>
#include <lidarfx/pipelines/water/extract_waterbodies.hpp>
#include <lidarfx/synth/water_cases.hpp>
#include <lidarfx/synth/water_family.hpp>

#include <algorithm>
#include <cmath>
#include <string>

using namespace lidarfx;

namespace {

/// Found-water cells whose truth is land and that lie more than `reach` cells (Chebyshev) from any truth
/// water cell.
long false_water_beyond(const raster<std::uint8_t>& found, const raster<std::uint8_t>& truth, std::ptrdiff_t reach)
{
    long n = 0;
    for (std::ptrdiff_t r = 0; r < found.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < found.cols(); ++c) {
            if (!found.view()(r, c) || truth.view()(r, c)) continue;
            bool near = false;
            for (std::ptrdiff_t rr = std::max<std::ptrdiff_t>(0, r - reach);
                 rr <= std::min(found.rows() - 1, r + reach); ++rr)
                for (std::ptrdiff_t cc = std::max<std::ptrdiff_t>(0, c - reach);
                     cc <= std::min(found.cols() - 1, c + reach); ++cc)
                    near = near || truth.view()(rr, cc);
            n += !near;
        }
    }
    return n;
}

}  // namespace

TEST_CASE("water/family: a dropout-dominated pond in a grass field 0.7 m above it stays inside its shore")
{
    const auto pond = synth::dropout_pond_scene();
    const auto pr = rasterize(pond.points.cloud(), pond.g);
    const auto found = extract_waterbodies(pr);
    REQUIRE(found.ran);
    REQUIRE(!found.bodies.empty());
    const auto score = confusion_counts(found.water, pond.water_filled, pond.cell_m);
    MESSAGE("pond: accuracy " << 100 * score.accuracy() << " %, sensitivity " << 100 * score.sensitivity()
                              << " %, specificity " << 100 * score.specificity() << " %, level "
                              << found.bodies[0].water_level_m << " m");
    CHECK(false_water_beyond(found.water, pond.water, 2) == 0);
    CHECK(std::abs(found.bodies[0].water_level_m - 100.0) <= 0.1);
    CHECK(score.sensitivity() >= 0.95);
}

TEST_CASE("water/family: bright specular stretches of a river near nadir are water, and the river is one body")
{
    const auto river = synth::specular_river_scene();
    const auto pr = rasterize(river.points.cloud(), river.g);
    const auto found = extract_waterbodies(pr);
    REQUIRE(found.ran);
    // The stretch under the flight line (x = 200 m +- 40 m, within about 2.3 deg of nadir).
    long bright = 0, bright_found = 0;
    for (std::ptrdiff_t r = 0; r < river.g.rows; ++r) {
        for (std::ptrdiff_t c = 0; c < river.g.cols; ++c) {
            if (!river.water(r, c) || std::abs(river.g.center(r, c)[0] - 200.0) > 40) continue;
            ++bright;
            bright_found += found.water.view()(r, c);
        }
    }
    const auto score = confusion_counts(found.water, river.water_filled, river.cell_m);
    const double bright_share = static_cast<double>(bright_found) / static_cast<double>(bright);
    MESSAGE("river: accuracy " << 100 * score.accuracy() << " %, sensitivity " << 100 * score.sensitivity()
                               << " %, bright stretch found " << 100 * bright_share << " %, bodies "
                               << found.bodies.size());
    CHECK(10 * bright_found >= 9 * bright);
    CHECK(synth::river_found_as_one_body(river, found.labels.view()));
    CHECK(score.specificity() >= 0.99);
}

TEST_CASE(
    "water/family: a fixed subset of the family (seeds 501-503 per kind), mapped by flat_seed_water_method() to the "
    "thresholds measured")
{
    for (const auto kind : {synth::water_family_kind::lake, synth::water_family_kind::river}) {
        double acc = 0, sens = 0, spec = 0;
        for (unsigned seed = 501; seed <= 503; ++seed) {
            const auto s = synth::water_family({.seed = seed, .kind = kind});
            const auto pr = rasterize(s.points.cloud(), s.g);
            const auto found = extract_waterbodies(pr, flat_seed_water_method());
            const auto c = confusion_counts(found.water, s.water_filled, s.cell_m);
            acc += c.accuracy() / 3, sens += c.sensitivity() / 3, spec += c.specificity() / 3;
        }
        const bool lake = kind == synth::water_family_kind::lake;
        MESSAGE((lake ? std::string("lakes") : std::string("rivers"))
                << ": mean accuracy " << 100 * acc << " %, sensitivity " << 100 * sens << " %, specificity "
                << 100 * spec << " %");
        // Measured with flat_seed_water_method() (what `lidarfx water` runs): lakes 99.72 / 98.76 / 99.90 %,
        // rivers 99.42 / 97.16 / 99.58 % (the defaults with flat seeds alone, this test's earlier configuration:
        // lakes 99.51 / 97.00 / 99.99 %, rivers 98.46 / 97.33 / 98.55 %).
        CHECK(acc >= (lake ? 0.995 : 0.993));
        CHECK(sens >= (lake ? 0.98 : 0.965));
        CHECK(spec >= (lake ? 0.998 : 0.994));
    }
}

TEST_CASE(
    "water/family: level land of land intensity beside a pond at QL2 density is land, with flat_seed_water_method() "
    "as with the library defaults")
{
    // Level-land tuning seed 7: a pond with specular echoes and few dropouts beside a level meadow 0.5 m
    // above it (1.7 pulses/m², 2 m cells). Judged only against its ring (denser strip overlap next to it), the
    // meadow was a flat seed and became 50 000 m² of water at a level 0.5 m too high (specificity 72 %).
    // Judged against the survey's land intensity it is land.
    const auto s = synth::water_family({.seed = 7,
                                        .kind = synth::water_family_kind::lake,
                                        .min_density = 1,
                                        .max_density = 2.5,
                                        .variant = synth::water_family_variant::level_land});
    const auto pr = rasterize(s.points.cloud(), s.g);
    const auto score = [&](const extract_waterbodies_options& o) {
        return confusion_counts(extract_waterbodies(pr, o).water, s.water_filled, s.cell_m);
    };
    const auto preset = score(flat_seed_water_method());
    const auto library = score(extract_waterbodies_options{});
    auto ring_only = flat_seed_water_method();
    ring_only.flat.land_intensity_quantile = -1;
    const auto before = score(ring_only);
    MESSAGE("level meadow beside a pond: accuracy / sensitivity / specificity "
            << 100 * preset.accuracy() << " / " << 100 * preset.sensitivity() << " / " << 100 * preset.specificity()
            << " % (library defaults " << 100 * library.accuracy() << " %, ring cues only "
            << 100 * before.specificity() << " % specificity)");
    CHECK(preset.specificity() >= 0.998);
    CHECK(preset.sensitivity() >= 0.97);
    CHECK(preset.accuracy() >= library.accuracy());
    CHECK(before.specificity() < 0.9);
}
