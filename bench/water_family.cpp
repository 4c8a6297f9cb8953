// SPDX-License-Identifier: Apache-2.0
// The water-family protocol of docs/waterbodies.md: extract_waterbodies on randomized lake and river surveys
// (synth/water_family.hpp), scored by area against truth water_filled. Parameters are chosen on the tuning
// seeds (1-20, `--tuning`); the table is reported on the disjoint reporting seeds (1001-1050 per kind).
// Prints, per configuration and kind: mean, 5th percentile ("worst 5 %") and worst scene of accuracy,
// sensitivity, specificity and IoU, and the share of rivers with bridges found as one body.
//   water_family [--tuning] [--first N] [--count N] [--ablation] [--scenes]
// For tuning (on the tuning seeds only), environment variables override the defaults' row: WF_GATE,
// WF_DRIFT, WF_EXEMPT, WF_ANYANGLE (grow.level_*), WF_FIRST (0/1, grow.test_first_step), WF_Q (seed level quantile),
// WF_SEEDMIN, WF_OPEN, WF_LINE (seeds), WF_FLAT (0/1)
// and WF_FLAT_{TOL,RAD,ROUGH,MIN,RING,DENS,DARKDENS,DARK,SMOOTH,LOWER,BRIGHT,JOINT,JOINTMIN} (flat_water_seeds
// options), WF_RISE (grow.level_rise_m), WF_TOUCH (0/1, bridges.join_touching), WF_SLOPE
// (grow.level_follow_max_slope), WF_SLOPE_{RAD,MIN,BAND} (water_surface_slope options), WF_BSEED (rounds of
// seeds beyond bridges), WF_BSEED_{MIN,BEYOND,BEHIND,TOL,CLEAR,AWAY,SLOPE} (their options), WF_FLAT_SLOPE
// (flat.max_surface_slope), WF_FLAT_DROPOUTS (0/1, flat_seed_dropouts), WF_FREE_SHARE (growing.min_free_seed_share),
// WF_TRIM (0/1, trim_edges), WF_TRIM_{MIN,MAX,WIN} (trim_raised_edge_cells options), WF_SHORE (0/1, shore_cells),
// WF_SHORE_{WIN,CONTRAST,SHARE,NB} (join_shore_cells options), WF_CHANNEL (0/1, channel_seeds),
// WF_CH_{TOL,ALONG,RISE,WIDTH,DARK,MIN,CLEAR,LOWER} (channel_water_seeds options), WF_PRESET=1 (start from
// flat_seed_water_method() instead of the defaults); WATER_FAMILY_VERBOSE=1 prints every scene's scores to stderr.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <lidarfx/kernels/metrics/confusion.hpp>
#include <lidarfx/kernels/points/rasterize.hpp>
#include <lidarfx/pipelines/water/extract_waterbodies.hpp>
#include <lidarfx/synth/water_family.hpp>

namespace {

using namespace lidarfx;

struct configuration {
    std::string name;
    std::function<void(extract_waterbodies_options&)> set;
};

/// A scene kept for scoring: its rasters and truth (not its points).
struct prepared {
    unsigned seed;
    synth::water_family_scene truth;  // points dropped
    rasterize_result rasters;
};

struct score {
    unsigned seed;
    double acc, sens, spec, iou;
    bool has_bridges, one_body;
};

std::vector<score> run(const std::vector<prepared>& scenes, const extract_waterbodies_options& o)
{
    std::vector<score> out;
    for (const auto& p : scenes) {
        const auto w = extract_waterbodies(p.rasters, o);
        const auto c = confusion_counts(w.water, p.truth.water_filled, p.truth.cell_m);
        score s{p.seed, c.accuracy(), c.sensitivity(), c.specificity(), c.iou(), p.truth.bridges > 0, false};
        if (p.truth.kind == synth::water_family_kind::river && s.has_bridges)
            s.one_body = synth::river_found_as_one_body(p.truth, w.labels.view());
        if (std::getenv("WATER_FAMILY_VERBOSE"))
            std::fprintf(stderr,
                         "    %s seed %u ran %d seeds %zu grown %zu bodies %zu dropout %.3f acc %.2f sens %.2f "
                         "spec %.2f one %d\n",
                         p.truth.kind == synth::water_family_kind::lake ? "lake" : "river", p.seed, w.ran,
                         w.seeds_found, w.seeds_grown, w.bodies.size(), w.diagnostics.dropout_fraction, 100 * s.acc,
                         100 * s.sens, 100 * s.spec, s.has_bridges ? int(s.one_body) : -1);
        if (std::getenv("WATER_FAMILY_BODIES")) {
            for (const auto& b : w.bodies)
                std::fprintf(stderr,
                             "      body %d: %.0f m2, level %.2f, intensity %.1f, dropouts %.3f, theta %.0f, ks %d, "
                             "seed rank %d\n",
                             b.label, b.area_m2, b.water_level_m, b.mean_intensity, b.dropout_fraction, b.theta_deg,
                             int(b.stopped_by_ks), int(b.seed));
            for (double level : p.truth.body_level) std::fprintf(stderr, "      true level %.2f\n", level);
        }
        out.push_back(s);
    }
    return out;
}

/// Mean, 5th percentile (the ⌈n/20⌉-th lowest) and minimum of one metric.
std::array<double, 3> summary(const std::vector<score>& v, double score::*m)
{
    std::vector<double> x;
    for (const auto& s : v) x.push_back(s.*m);
    std::sort(x.begin(), x.end());
    double mean = 0;
    for (double a : x) mean += a / static_cast<double>(x.size());
    const std::size_t k = (x.size() + 19) / 20 - 1;
    return {100 * mean, 100 * x[k], 100 * x.front()};
}

unsigned worst_seed(const std::vector<score>& v)
{
    return std::min_element(v.begin(), v.end(), [](const score& a, const score& b) { return a.acc < b.acc; })->seed;
}

}  // namespace

int main(int argc, char** argv)
{
    unsigned first = 1001, count = 50;
    bool ablation = false, list_scenes = false;
    synth::water_family_options family;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--tuning"))
            first = 1, count = 20;
        else if (!std::strcmp(argv[i], "--first") && i + 1 < argc)
            first = static_cast<unsigned>(std::atoi(argv[++i]));
        else if (!std::strcmp(argv[i], "--count") && i + 1 < argc)
            count = static_cast<unsigned>(std::atoi(argv[++i]));
        else if (!std::strcmp(argv[i], "--ablation"))
            ablation = true;
        else if (!std::strcmp(argv[i], "--scenes"))
            list_scenes = true;
        else if (!std::strcmp(argv[i], "--variant") && i + 1 < argc) {
            const std::string v = argv[++i];
            family.variant = v == "level-land"     ? synth::water_family_variant::level_land
                             : v == "narrow-river" ? synth::water_family_variant::narrow_river
                             : v == "hydro"        ? synth::water_family_variant::hydro
                                                   : synth::water_family_variant::classic;
            if (v != "level-land" && v != "narrow-river" && v != "hydro" && v != "classic") {
                std::fprintf(stderr, "water_family: unknown variant %s\n", v.c_str());
                return 2;
            }
        } else if (!std::strcmp(argv[i], "--density") && i + 2 < argc) {
            family.min_density = std::atof(argv[++i]);
            family.max_density = std::atof(argv[++i]);
        } else if (!std::strcmp(argv[i], "--cell") && i + 1 < argc)
            family.cell_m = std::atof(argv[++i]);
        else {
            std::fprintf(stderr,
                         "usage: water_family [--tuning] [--first N] [--count N] [--ablation] [--scenes] "
                         "[--variant classic|level-land|narrow-river|hydro] [--density MIN MAX] [--cell M]\n");
            return 2;
        }
    }
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<prepared> lakes, rivers;
    for (unsigned seed = first; seed < first + count; ++seed) {
        for (const auto kind : {synth::water_family_kind::lake, synth::water_family_kind::river}) {
            auto options = family;
            options.seed = seed, options.kind = kind;
            auto s = synth::water_family(options);
            auto pr = rasterize(s.points.cloud(), s.g);
            s.points = {};
            (kind == synth::water_family_kind::lake ? lakes : rivers).push_back({seed, std::move(s), std::move(pr)});
        }
    }
    const double gen_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("seeds %u-%u per kind; scenes generated and rasterized in %.1f s\n\n", first, first + count - 1, gen_s);
    if (list_scenes) {
        std::printf(
            "| kind | seed | size m | pts/m² | cell m | H m | angle ° | overlap | drop nadir | glint | turbid | "
            "bridges | islands |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
        for (const auto* v : {&lakes, &rivers})
            for (const auto& p : *v) {
                const auto& s = p.truth;
                std::printf("| %s | %u | %.0f | %.2f | %.1f | %.0f | %.1f | %.2f | %.2f | %.2f | %d | %d | %d |\n",
                            s.kind == synth::water_family_kind::lake ? "lake" : "river", p.seed, s.size_m,
                            s.density_per_m2, s.cell_m, s.scan.flying_height_m, s.scan.max_scan_angle_deg,
                            s.scan.overlap, s.returns.drop_nadir, s.returns.glint, s.returns.turbid ? 1 : 0, s.bridges,
                            s.islands);
            }
        std::printf("\n");
    }

    std::vector<configuration> configs{
        {"previous method (before the family)", [](extract_waterbodies_options& o) { o = previous_water_method(); }},
        {"lidarfx defaults",
         [](extract_waterbodies_options& o) {
             if (const char* v = std::getenv("WF_PRESET"); v && std::atoi(v) != 0) o = flat_seed_water_method();
             if (const char* v = std::getenv("WF_FLAT_DROPOUTS")) o.flat_seed_dropouts = std::atoi(v) != 0;
             if (const char* v = std::getenv("WF_CHANNEL")) o.channel_seeds = std::atoi(v) != 0;
             if (const char* v = std::getenv("WF_CH_TOL")) o.channel.level_tolerance_m = std::atof(v);
             if (const char* v = std::getenv("WF_CH_ALONG")) o.channel.along_cells = std::atoi(v);
             if (const char* v = std::getenv("WF_CH_RISE")) o.channel.bank_rise_m = std::atof(v);
             if (const char* v = std::getenv("WF_CH_WIDTH")) o.channel.max_width_m = std::atof(v);
             if (const char* v = std::getenv("WF_CH_DARK")) o.channel.max_intensity_ratio = std::atof(v);
             if (const char* v = std::getenv("WF_CH_MIN")) o.channel.min_cells = static_cast<std::size_t>(std::atoi(v));
             if (const char* v = std::getenv("WF_CH_CLEAR")) o.channel.clear_cells = std::atoi(v);
             if (const char* v = std::getenv("WF_CH_LOWER")) o.channel.max_lower_share = std::atof(v);
             if (const char* v = std::getenv("WF_FREE_SHARE")) o.growing.min_free_seed_share = std::atof(v);
             if (const char* v = std::getenv("WF_GATE")) o.grow.level_gate_m = std::atof(v);
             if (const char* v = std::getenv("WF_DRIFT")) o.grow.level_drift_m = std::atof(v);
             if (const char* v = std::getenv("WF_EXEMPT")) o.grow.level_ks_exempt_m = std::atof(v);
             if (const char* v = std::getenv("WF_Q")) o.grow.seed_level.quantile = std::atof(v);
             if (const char* v = std::getenv("WF_SEEDMIN")) o.seeds.min_cells = static_cast<std::size_t>(std::atoi(v));
             if (const char* v = std::getenv("WF_OPEN")) o.seeds.opening_size_cells = std::atoi(v);
             if (const char* v = std::getenv("WF_LINE")) o.seeds.line_length_cells = std::atoi(v);
             if (const char* v = std::getenv("WF_ANYANGLE")) o.grow.level_any_angle_m = std::atof(v);
             if (const char* v = std::getenv("WF_FLAT")) o.flat_seeds = std::atoi(v) != 0;
             if (const char* v = std::getenv("WF_FLAT_TOL")) o.flat.level_tolerance_m = std::atof(v);
             if (const char* v = std::getenv("WF_FLAT_RAD")) o.flat.level_radius_cells = std::atoi(v);
             if (const char* v = std::getenv("WF_FLAT_ROUGH")) o.flat.max_roughness_m = std::atof(v);
             if (const char* v = std::getenv("WF_FLAT_MIN")) o.flat.min_cells = static_cast<std::size_t>(std::atoi(v));
             if (const char* v = std::getenv("WF_FLAT_RING")) o.flat.ring_cells = std::atoi(v);
             if (const char* v = std::getenv("WF_FLAT_DENS")) o.flat.max_density_ratio = std::atof(v);
             if (const char* v = std::getenv("WF_FLAT_DARKDENS")) o.flat.dark_density_ratio = std::atof(v);
             if (const char* v = std::getenv("WF_FLAT_DARK")) o.flat.max_intensity_ratio = std::atof(v);
             if (const char* v = std::getenv("WF_FLAT_SMOOTH")) o.flat.max_roughness_ratio = std::atof(v);
             if (const char* v = std::getenv("WF_FLAT_LOWER")) o.flat.max_lower_share = std::atof(v);
             if (const char* v = std::getenv("WF_FLAT_BRIGHT")) o.flat.bright_density_ratio = std::atof(v);
             if (const char* v = std::getenv("WF_FLAT_JOINT")) o.flat.max_joint_ratio = std::atof(v);
             if (const char* v = std::getenv("WF_FLAT_JOINTMIN"))
                 o.flat.joint_min_cells = static_cast<std::size_t>(std::atoi(v));
             if (const char* v = std::getenv("WF_FLAT_LANDQ")) o.flat.land_intensity_quantile = std::atof(v);
             if (const char* v = std::getenv("WF_FLAT_LANDDARK")) o.flat.max_land_intensity_ratio = std::atof(v);
             if (const char* v = std::getenv("WF_RISE")) o.grow.level_rise_m = std::atof(v);
             if (const char* v = std::getenv("WF_FIRST")) o.grow.test_first_step = std::atoi(v) != 0;
             if (const char* v = std::getenv("WF_SLOPE")) o.grow.level_follow_max_slope = std::atof(v);
             if (const char* v = std::getenv("WF_SLOPE_BAND")) o.surface_slope.band_m = std::atof(v);
             if (const char* v = std::getenv("WF_FLAT_SLOPE")) o.flat.max_surface_slope = std::atof(v);
             if (const char* v = std::getenv("WF_SLOPE_RAD")) o.surface_slope.radius_cells = std::atoi(v);
             if (const char* v = std::getenv("WF_SLOPE_MIN"))
                 o.surface_slope.min_cells = static_cast<std::size_t>(std::atoi(v));
             if (const char* v = std::getenv("WF_TOUCH")) o.bridges.join_touching = std::atoi(v) != 0;
             if (const char* v = std::getenv("WF_BSEED")) o.bridge_seed_rounds = std::atoi(v);
             if (const char* v = std::getenv("WF_BSEED_MIN"))
                 o.bridge_seed_min_cells = static_cast<std::size_t>(std::atoi(v));
             if (const char* v = std::getenv("WF_BSEED_BEYOND")) o.bridge_seeds.beyond_cells = std::atoi(v);
             if (const char* v = std::getenv("WF_BSEED_BEHIND")) o.bridge_seeds.behind_cells = std::atoi(v);
             if (const char* v = std::getenv("WF_BSEED_TOL")) o.bridge_seeds.level_tolerance_m = std::atof(v);
             if (const char* v = std::getenv("WF_BSEED_CLEAR")) o.bridge_seeds.min_clearance_m = std::atof(v);
             if (const char* v = std::getenv("WF_BSEED_AWAY")) o.bridge_seeds.clear_cells = std::atoi(v);
             if (const char* v = std::getenv("WF_BSEED_SLOPE")) o.bridge_seeds.max_surface_slope = std::atof(v);
             if (const char* v = std::getenv("WF_SHORE")) o.shore_cells = std::atoi(v) != 0;
             if (const char* v = std::getenv("WF_TRIM")) o.trim_edges = std::atoi(v) != 0;
             if (const char* v = std::getenv("WF_TRIM_MIN")) o.trim.min_rise_m = std::atof(v);
             if (const char* v = std::getenv("WF_TRIM_MAX")) o.trim.max_rise_m = std::atof(v);
             if (const char* v = std::getenv("WF_TRIM_WIN")) o.trim.window_cells = std::atoi(v);
             if (const char* v = std::getenv("WF_SHORE_WIN")) o.shore.window_cells = std::atoi(v);
             if (const char* v = std::getenv("WF_SHORE_CONTRAST")) o.shore.min_contrast = std::atof(v);
             if (const char* v = std::getenv("WF_SHORE_SHARE")) o.shore.min_water_share = std::atof(v);
             if (const char* v = std::getenv("WF_SHORE_NB")) o.shore.min_body_neighbours = std::atoi(v);
         }},
    };
    if (!std::getenv("WF_PRESET"))
        configs.push_back({"flat_seed_water_method() (`lidarfx water`)",
                           [](extract_waterbodies_options& o) { o = flat_seed_water_method(); }});
    if (ablation) {
        const auto preset = [](std::function<void(extract_waterbodies_options&)> change) {
            return [change](extract_waterbodies_options& o) {
                o = flat_seed_water_method();
                change(o);
            };
        };
        configs.push_back(
            {"flat_seed_water_method() without the dropouts next to flat seeds (flat_seed_dropouts = false)",
             preset([](extract_waterbodies_options& o) { o.flat_seed_dropouts = false; })});
        configs.push_back(
            {"flat_seed_water_method() skipping every seed with a cell in a body (min_free_seed_share = 1)",
             preset([](extract_waterbodies_options& o) { o.growing.min_free_seed_share = 1; })});
        configs.push_back({"flat_seed_water_method() with the default level drift (grow.level_drift_m = 0.005)",
                           preset([](extract_waterbodies_options& o) { o.grow.level_drift_m = 0.005; })});
        configs.push_back({"flat_seed_water_method() with bridge seeds of >= 8 cells (bridge_seed_min_cells = 8)",
                           preset([](extract_waterbodies_options& o) { o.bridge_seed_min_cells = 8; })});
        configs.push_back({"flat_seed_water_method() without edge trimming (trim_edges = false)",
                           preset([](extract_waterbodies_options& o) { o.trim_edges = false; })});
        configs.push_back({"flat_seed_water_method() without shore cells (shore_cells = false)",
                           preset([](extract_waterbodies_options& o) { o.shore_cells = false; })});
        configs.push_back({"flat_seed_water_method() without the first-step test",
                           preset([](extract_waterbodies_options& o) { o.grow.test_first_step = false; })});
        configs.push_back({"flat_seed_water_method() without seeds beyond bridges",
                           preset([](extract_waterbodies_options& o) { o.bridge_seed_rounds = 0; })});
        configs.push_back({"flat_seed_water_method() without the level-surface cue (grow.level_follow_max_slope = -1)",
                           preset([](extract_waterbodies_options& o) { o.grow.level_follow_max_slope = -1; })});

        configs.push_back({"without the level gate", [](extract_waterbodies_options& o) { o.grow.level_gate_m = 0; }});
        configs.push_back({"without level cells exempt from KS",
                           [](extract_waterbodies_options& o) { o.grow.level_ks_exempt_m = -1; }});
        configs.push_back(
            {"with flat seeds (flat_seeds = true)", [](extract_waterbodies_options& o) { o.flat_seeds = true; }});
        configs.push_back({"with flat seeds, without their bright and joint paths", [](extract_waterbodies_options& o) {
                               o.flat_seeds = true;
                               o.flat.bright_density_ratio = 0;
                               o.flat.max_joint_ratio = 0;
                           }});
        configs.push_back({"with flat seeds, touching bodies not merged", [](extract_waterbodies_options& o) {
                               o.flat_seeds = true;
                               o.bridges.join_touching = false;
                           }});
        configs.push_back({"with flat seeds and a level that never rises (grow.level_rise_m = 0)",
                           [](extract_waterbodies_options& o) {
                               o.flat_seeds = true;
                               o.grow.level_rise_m = 0;
                           }});
        configs.push_back(
            {"with flat seeds and a level that follows min z only on a level surface "
             "(grow.level_follow_max_slope = 0.008)",
             [](extract_waterbodies_options& o) {
                 o.flat_seeds = true;
                 o.grow.level_follow_max_slope = 0.008;
             }});
        configs.push_back({"without edge trimming (trim_edges = false)",
                           [](extract_waterbodies_options& o) { o.trim_edges = false; }});
        configs.push_back({"without shore cells (shore_cells = false)",
                           [](extract_waterbodies_options& o) { o.shore_cells = false; }});
        configs.push_back({"without the first-step test (grow.test_first_step = false)",
                           [](extract_waterbodies_options& o) { o.grow.test_first_step = false; }});
        configs.push_back({"without seeds beyond bridges (bridge_seed_rounds = 0)",
                           [](extract_waterbodies_options& o) { o.bridge_seed_rounds = 0; }});
        configs.push_back(
            {"without bridges (no joins across decks, no seeds beyond them)", [](extract_waterbodies_options& o) {
                 o.join_bridges = false;
                 o.bridge_seed_rounds = 0;
             }});
        configs.push_back({"without level refinement", [](extract_waterbodies_options& o) {
                               o.level.tolerance_m = 0;
                               o.bridges.water_tolerance_m = 0;  // the tolerance both steps shared
                           }});
    }
    std::printf(
        "| configuration | kind | acc mean / 5%% / worst | sens mean / 5%% / worst | spec mean / 5%% / worst | "
        "IoU mean / 5%% / worst | worst seed | bridges one body |\n|---|---|---|---|---|---|---|---|\n");
    for (const auto& cfg : configs) {
        extract_waterbodies_options o;
        o.run.threads = 1;
        cfg.set(o);
        o.run.threads = 1;
        for (const auto* v : {&lakes, &rivers}) {
            const auto t = std::chrono::steady_clock::now();
            const auto scores = run(*v, o);
            const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
            std::printf("| %s | %s |", cfg.name.c_str(), v == &lakes ? "lake" : "river");
            for (auto m : {&score::acc, &score::sens, &score::spec, &score::iou}) {
                const auto s = summary(scores, m);
                std::printf(" %.2f / %.2f / %.2f |", s[0], s[1], s[2]);
            }
            std::printf(" %u |", worst_seed(scores));
            if (v == &rivers) {
                int with = 0, one = 0;
                for (const auto& s : scores) with += s.has_bridges, one += s.has_bridges && s.one_body;
                std::printf(" %d / %d (%.0f %%) |", one, with, with ? 100.0 * one / with : 0.0);
            } else {
                std::printf(" — |");
            }
            std::printf("\n");
            std::fflush(stdout);
            std::fprintf(stderr, "  (%s %s: %.2f s)\n", cfg.name.c_str(), v == &lakes ? "lake" : "river", secs);
            if (std::getenv("WATER_FAMILY_VERBOSE")) {
                for (const auto& s : scores)
                    std::fprintf(stderr, "    seed %u acc %.2f sens %.2f spec %.2f one %d\n", s.seed, 100 * s.acc,
                                 100 * s.sens, 100 * s.spec, s.one_body);
            }
        }
    }
    return 0;
}
