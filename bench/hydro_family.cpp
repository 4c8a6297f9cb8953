// SPDX-License-Identifier: Apache-2.0
// The hydro-flattening protocol of docs/hydro-flattening.md: `lidarfx hydroflatten`'s method (extract_waterbodies with
// flat_seed_water_method(), the lowest returns filled by IDW as the bare-earth DEM, hydro_flatten with the
// specification's minimum sizes) on the water family's hydro variant (synth/water_family.hpp: lakes of 55-150 m
// radius with islands, rivers 30.5-60 m wide with bridges and weirs), scored against the scenes' true water levels.
// Tuning seeds are 1-20; the table is reported once on seeds no tuning has seen.
//   hydro_family [--first N] [--count N] [--density LOW HIGH] [--verbose]
// For tuning (on the tuning seeds only), environment variables override trace_river_profile's options: HF_SHARE
// (min_return_share), HF_LEVEL_WINDOW (level_window_m), HF_RETURN_TOL (return_tolerance_m), HF_LEVEL_TOL
// (level_tolerance_m), HF_SPACING (section_spacing_m), HF_LOWEST (lowest_mode_share), HF_DECK_REACH
// (decks.reach_m), HF_UNDER_DECKS (0: without water_under_decks, to compare).
// Prints per kind: bodies flattened, the specification's checks (flatness, monotonic fall, shoreline), lake levels
// and river sections against the truth (worst, 95th percentile, share within 5 / 10 cm), deck cells flattened at the
// interpolated level (no bowl), and weirs found.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <lidarfx/kernels/interpolate/idw_fill.hpp>
#include <lidarfx/kernels/points/rasterize.hpp>
#include <lidarfx/pipelines/water/extract_waterbodies.hpp>
#include <lidarfx/pipelines/water/hydro_flatten.hpp>
#include <lidarfx/synth/water_family.hpp>

namespace {

using namespace lidarfx;

/// What one kind of scene gave, pooled over its scenes.
struct tally {
    int scenes = 0, bodies = 0, truth_bodies = 0;
    int flatness_failures = 0, uphill_steps = 0, shoreline_cells = 0;
    std::vector<double> level_errors;  ///< lakes: |level − truth|; rivers: per section
    std::size_t deck_cells = 0, deck_flattened = 0;
    double deck_worst_m = 0;
    int weirs_true = 0, weirs_found = 0;
    double worst_error_m = 0;
    unsigned worst_seed = 0;
};

double quantile(std::vector<double> v, double q)
{
    if (v.empty()) return NAN;
    std::sort(v.begin(), v.end());
    return v[static_cast<std::size_t>(std::floor(q * static_cast<double>(v.size() - 1)))];
}

double share_within(const std::vector<double>& v, double limit)
{
    if (v.empty()) return NAN;
    return static_cast<double>(std::count_if(v.begin(), v.end(), [&](double e) { return e <= limit; })) /
           static_cast<double>(v.size());
}

void score(const synth::water_family_scene& s, const hydro_flatten_result& h, unsigned seed, tally& t, bool verbose)
{
    ++t.scenes;
    t.truth_bodies += static_cast<int>(s.body_level.size());
    for (const auto& q : h.qa) {
        if (q.kind == hydro_check_kind::flatness && !q.pass) ++t.flatness_failures;
        if (q.kind == hydro_check_kind::monotonic_fall) t.uphill_steps += static_cast<int>(q.value);
        if (q.kind == hydro_check_kind::shoreline) t.shoreline_cells += static_cast<int>(q.value);
    }
    double scene_worst = 0;
    for (const auto& b : h.bodies) {
        if (!b.flattened) continue;
        ++t.bodies;
        if (b.type == hydro_body_type::lake) {
            std::vector<float> truth;
            for (std::ptrdiff_t r = 0; r < h.body.rows(); ++r)
                for (std::ptrdiff_t c = 0; c < h.body.cols(); ++c)
                    if (h.body(r, c) == b.id && std::isfinite(s.water_z(r, c))) truth.push_back(s.water_z(r, c));
            if (truth.empty()) continue;
            std::nth_element(truth.begin(), truth.begin() + static_cast<std::ptrdiff_t>(truth.size() / 2), truth.end());
            const double e = std::abs(b.level_min_m - truth[truth.size() / 2]);
            t.level_errors.push_back(e);
            scene_worst = std::max(scene_worst, e);
            continue;
        }
        const river_profile& p = b.river;
        std::vector<double> sum(p.level_m.size(), 0.0);
        std::vector<int> n(p.level_m.size(), 0);
        for (std::ptrdiff_t r = 0; r < p.section.rows(); ++r)
            for (std::ptrdiff_t c = 0; c < p.section.cols(); ++c) {
                const std::int32_t k = p.section(r, c);
                const float z = s.water_z(p.box.row_min + r, p.box.col_min + c);
                if (k < 0 || !std::isfinite(z)) continue;
                sum[static_cast<std::size_t>(k)] += z;
                ++n[static_cast<std::size_t>(k)];
            }
        for (std::size_t k = 0; k < p.level_m.size(); ++k) {
            if (n[k] < 3) continue;  // a section of fewer than 3 true water cells has no level to compare
            const double e = std::abs(p.level_m[k] - sum[k] / n[k]);
            t.level_errors.push_back(e);
            scene_worst = std::max(scene_worst, e);
        }
        t.weirs_found += static_cast<int>(p.weirs);
    }
    t.weirs_true += static_cast<int>(s.weir_along.size());
    // Decks: true water cells within a bridge's half width along the river.
    const double ca = std::cos(s.river_angle_rad), sa = std::sin(s.river_angle_rad), half = 0.5 * s.size_m;
    for (std::ptrdiff_t r = 0; r < h.body.rows() && !s.bridge_along.empty(); ++r)
        for (std::ptrdiff_t c = 0; c < h.body.cols(); ++c) {
            if (!std::isfinite(s.water_z(r, c))) continue;
            const double x = s.g.x0 + (static_cast<double>(c) + 0.5) * s.cell_m;
            const double y = s.g.y0 - (static_cast<double>(r) + 0.5) * s.cell_m;
            const double along = (x - half) * ca + (y - half) * sa + half;
            bool deck = false;
            for (const auto& br : s.bridge_along) deck = deck || std::abs(along - br[0]) <= br[1];
            if (!deck) continue;
            ++t.deck_cells;
            if (h.body(r, c) == 0) continue;
            ++t.deck_flattened;
            t.deck_worst_m =
                std::max(t.deck_worst_m, std::abs(static_cast<double>(h.water_surface(r, c)) - s.water_z(r, c)));
        }
    if (scene_worst > t.worst_error_m) {
        t.worst_error_m = scene_worst;
        t.worst_seed = seed;
    }
    if (verbose)
        std::fprintf(stderr, "seed %u density %.1f: %zu bodies, worst level error %.3f m, %zu weirs true\n", seed,
                     s.density_per_m2, h.bodies.size(), scene_worst, s.weir_along.size());
}

}  // namespace

int main(int argc, char** argv)
{
    unsigned first = 1, count = 20;
    double low = 2, high = 8;
    bool verbose = false;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--first") && i + 1 < argc) {
            first = static_cast<unsigned>(std::atoi(argv[++i]));
        } else if (!std::strcmp(argv[i], "--count") && i + 1 < argc) {
            count = static_cast<unsigned>(std::atoi(argv[++i]));
        } else if (!std::strcmp(argv[i], "--density") && i + 2 < argc) {
            low = std::atof(argv[++i]);
            high = std::atof(argv[++i]);
        } else if (!std::strcmp(argv[i], "--verbose")) {
            verbose = true;
        } else {
            std::fprintf(stderr, "usage: hydro_family [--first N] [--count N] [--density LOW HIGH] [--verbose]\n");
            return 2;
        }
    }
    hydro_flatten_options method;
    const auto knob = [](const char* name, double& value) {
        if (const char* v = std::getenv(name)) value = std::atof(v);
    };
    knob("HF_SHARE", method.river.min_return_share);
    knob("HF_LEVEL_WINDOW", method.river.level_window_m);
    knob("HF_RETURN_TOL", method.river.return_tolerance_m);
    knob("HF_LEVEL_TOL", method.river.level_tolerance_m);
    knob("HF_SPACING", method.river.section_spacing_m);
    knob("HF_LOWEST", method.river.lowest_mode_share);
    knob("HF_DECK_REACH", method.decks.reach_m);
    if (const char* v = std::getenv("HF_UNDER_DECKS")) method.under_decks = std::atoi(v) != 0;
    if (const char* v = std::getenv("HF_TO_BANKS")) method.to_banks = std::atoi(v) != 0;
    knob("HF_BANK_QUANTILE", method.banks.bank_quantile);
    std::printf("hydro family, seeds %u-%u, %.1f-%.1f pulses/m2, flat_seed_water_method(), hydro_flatten defaults\n",
                first, first + count - 1, low, high);
    std::printf(
        "| kind | scenes | bodies flattened / true | flatness fails | uphill steps | shoreline cells | level "
        "error worst / p95 (m) | within 5 cm / 10 cm | deck cells flattened, worst (m) | weirs found / true | "
        "worst scene |\n|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const auto kind : {synth::water_family_kind::lake, synth::water_family_kind::river}) {
        tally t;
        for (unsigned seed = first; seed < first + count; ++seed) {
            const auto s = synth::water_family({.seed = seed,
                                                .kind = kind,
                                                .min_density = low,
                                                .max_density = high,
                                                .variant = synth::water_family_variant::hydro});
            const auto pr = rasterize(s.points.cloud(), s.g);
            const auto w = extract_waterbodies(pr, flat_seed_water_method());
            const raster<float> dem = idw_fill(pr.min_z, s.cell_m).filled;
            const auto h = hydro_flatten(dem, w.labels, pr.min_z, pr.max_z, s.cell_m, method);
            score(s, h, seed, t, verbose);
        }
        const bool lake = kind == synth::water_family_kind::lake;
        std::printf(
            "| %s | %d | %d / %d | %d | %d | %d | %.3f / %.3f | %.1f %% / %.1f %% | %zu of %zu, %.3f | %d / %d | "
            "%u (%.3f m) |\n",
            lake ? "lakes" : "rivers", t.scenes, t.bodies, t.truth_bodies, t.flatness_failures, t.uphill_steps,
            t.shoreline_cells, quantile(t.level_errors, 1.0), quantile(t.level_errors, 0.95),
            100 * share_within(t.level_errors, 0.05), 100 * share_within(t.level_errors, 0.10), t.deck_flattened,
            t.deck_cells, t.deck_worst_m, t.weirs_found, t.weirs_true, t.worst_seed, t.worst_error_m);
        std::fflush(stdout);
    }
    return 0;
}
