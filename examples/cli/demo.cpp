// SPDX-License-Identifier: Apache-2.0
// lidarfx demo: the whole chain on embedded synthetic scenes (and on the sample survey when present),
// writing rasters, pictures and tables to a folder and printing the scores against the scenes' truth.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>

#include <lidarfx/lidarfx.hpp>
#include <lidarfx/kernels/metrics/confusion.hpp>
#include <lidarfx/synth/scenes.hpp>
#include <lidarfx/pipelines/water/extract_waterbodies.hpp>

#include "cli_common.hpp"
#include "command.hpp"
#include "io/png.hpp"
#include "outputs.hpp"

namespace {

constexpr const char* usage =
    "usage: lidarfx demo [--out DIR] [--size M] [--seed N] [--threads N]\n"
    "Runs rasterize and water on the synthetic lake and river scenes (DIR/lake, DIR/river), scores the\n"
    "waterbodies against the scenes' truth (DIR/scores.csv), and runs them on the sample survey\n"
    "Haystack_Rock.las when it is found (DIR/haystack). Default DIR: lidarfx-demo.\n";

struct scored {
    std::string scene;
    lidarfx::confusion score;
    std::size_t bodies = 0;
    double seconds = 0;
};

scored run_scene(const std::string& name, const lidarfx::synth::scene& sc, const std::filesystem::path& dir,
                 int threads)
{
    std::filesystem::create_directories(dir);
    std::cout << "\n== " << name << " scene: " << sc.points.size() << " points ==\n";
    const auto t0 = std::chrono::steady_clock::now();
    lidarfx::cli::survey s;
    s.rasters = lidarfx::rasterize(sc.points.cloud(), sc.truth.g, {.threads = threads});
    s.points = sc.points.size();
    s.files = 1;
    lidarfx::extract_waterbodies_options opt;
    opt.run = {.threads = threads, .progress = lidarfx::cli::progress_bar("waterbodies")};
    const auto w = lidarfx::extract_waterbodies(s.rasters, opt);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    lidarfx::cli::print_survey(s);
    lidarfx::cli::print_diagnostics(w.diagnostics);
    lidarfx::cli::print_waterbodies(w, 5);
    lidarfx::cli::write_point_rasters(dir, s);
    lidarfx::cli::write_waterbodies(dir, s, w);
    const auto score = lidarfx::confusion_counts(w.water, sc.truth.water_filled, sc.truth.g.cell);
    // Agreement picture: true water blue, water found on land red, water missed yellow, land grey.
    lidarfx::io::rgb_image agreement;
    agreement.width = sc.truth.g.cols;
    agreement.height = sc.truth.g.rows;
    for (std::ptrdiff_t i = 0; i < w.water.size(); ++i) {
        const bool found = w.water.data()[i] != 0, truth = sc.truth.water_filled.data()[i] != 0;
        const std::array<std::uint8_t, 3> color = found && truth ? std::array<std::uint8_t, 3>{40, 110, 255}
                                                  : found        ? std::array<std::uint8_t, 3>{230, 30, 30}
                                                  : truth        ? std::array<std::uint8_t, 3>{250, 210, 0}
                                                                 : std::array<std::uint8_t, 3>{200, 200, 200};
        agreement.rgb.insert(agreement.rgb.end(), color.begin(), color.end());
    }
    lidarfx::io::write_png_rgb((dir / "agreement.png").string(), agreement);
    lidarfx::cli::say_wrote(dir / "agreement.png");
    std::cout << std::fixed << std::setprecision(2) << "score vs truth: accuracy " << 100 * score.accuracy()
              << " %, sensitivity " << 100 * score.sensitivity() << " %, specificity " << 100 * score.specificity()
              << " %, IoU " << 100 * score.iou() << " %  (" << std::setprecision(3) << seconds << " s)\n"
              << std::defaultfloat;
    return {name, score, w.bodies.size(), seconds};
}

int run_demo(const std::vector<std::string>& args)
{
    const lidarfx::cli::arguments a(args, {"out", "size", "seed", "threads"}, {"help"});
    if (const auto code = lidarfx::cli::stop_for_usage(a, usage, false)) return *code;
    const std::filesystem::path out = a.text("out", "lidarfx-demo");
    const int threads = a.integer("threads", 0);
    lidarfx::synth::scene_options so;
    so.size_m = a.number("size", so.size_m);
    so.seed = static_cast<unsigned>(a.integer("seed", static_cast<int>(so.seed)));
    std::filesystem::create_directories(out);

    std::vector<scored> results;
    results.push_back(run_scene("lake", lidarfx::synth::lake_scene(so), out / "lake", threads));
    results.push_back(run_scene("river", lidarfx::synth::river_scene(so), out / "river", threads));

    std::ofstream csv(out / "scores.csv");
    csv << "scene,waterbodies,accuracy,sensitivity,specificity,precision,iou,water_true_m2,water_found_m2,seconds\n";
    for (const auto& r : results) {
        const auto& c = r.score;
        csv << r.scene << ',' << r.bodies << ',' << c.accuracy() << ',' << c.sensitivity() << ',' << c.specificity()
            << ',' << c.precision() << ',' << c.iou() << ',' << c.area_m2(c.true_positive + c.false_negative) << ','
            << c.area_m2(c.true_positive + c.false_positive) << ',' << r.seconds << '\n';
    }
    lidarfx::cli::say_wrote(out / "scores.csv");

    const std::filesystem::path sample = std::filesystem::path(LIDARFX_DATA_DIR) / "Haystack_Rock.las";
    if (std::filesystem::exists(sample)) {
        std::cout << "\n== sample survey " << sample.string() << " ==\n";
        const auto dir = out / "haystack";
        std::filesystem::create_directories(dir);
        const auto s = lidarfx::cli::read_survey({sample.string()}, 2.0, false);
        lidarfx::cli::print_survey(s);
        lidarfx::cli::write_point_rasters(dir, s);
        const auto w = lidarfx::extract_waterbodies(s.rasters, {.run = {.threads = threads}});
        lidarfx::cli::print_diagnostics(w.diagnostics);
        std::cout << (w.ran ? "waterbody extraction ran\n"
                            : "waterbody extraction refused on these data, as it should be (no map written)\n");
    } else {
        std::cout << "\n(sample survey " << sample.string() << " not found: skipped)\n";
    }
    return 0;
}

const lidarfx::cli::registration reg{"demo", "the whole chain on embedded synthetic scenes, with scores", run_demo};

}  // namespace
