// SPDX-License-Identifier: Apache-2.0
// lidarfx demo: the whole chain on embedded synthetic scenes (and on the sample survey when present),
// writing rasters, pictures and tables to a folder and printing the scores against the scenes' truth.
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <iostream>

#include <lidarfx/kernels/metrics/confusion.hpp>
#include <lidarfx/lidarfx.hpp>
#include <lidarfx/pipelines/water/extract_waterbodies.hpp>
#include <lidarfx/synth/roof_metrics.hpp>
#include <lidarfx/synth/roof_towns.hpp>
#include <lidarfx/synth/scenes.hpp>

#include "cli_common.hpp"
#include "command.hpp"
#include "io/figure.hpp"
#include "io/png.hpp"
#include "io/tables.hpp"
#include "outputs.hpp"
#include "roof_outputs.hpp"

namespace {

constexpr const char* usage =
    "usage: lidarfx demo [--out DIR] [--size M] [--seed N] [--threads N] [--las FILE]\n"
    "Runs rasterize and water on the embedded synthetic lake and river scenes (DIR/lake, DIR/river) and\n"
    "scores the waterbodies against the scenes' truth (DIR/scores.csv). Runs rooftop PV suitability in planes\n"
    "and paper mode on a synthetic roof town (make_roof_town, seed 4, 36 buildings; DIR/roofs_planes,\n"
    "DIR/roofs_paper) and scores the roof planes against its truth (DIR/roof_scores.csv). --las FILE adds a\n"
    "real survey (DIR/<file name>): its rasters, and its waterbodies or the reasons the data cannot support them.\n"
    "--size and --seed set the lake and river scenes (the roof town is fixed).\n"
    "Default DIR: lidarfx-demo; --threads 0 = all cores (default).\n";

struct scored {
    std::string scene;
    lidarfx::confusion score;
    std::size_t bodies = 0;
    double seconds = 0;
};

scored run_scene(const std::string& name, const lidarfx::synth::scene& sc, const std::filesystem::path& dir,
                 int threads)
{
    lidarfx::io::output_folder folder(dir);
    std::cout << "\n== " << name << " scene: " << sc.points.size() << " points ==\n";
    const auto t0 = std::chrono::steady_clock::now();
    lidarfx::cli::survey s;
    s.rasters = lidarfx::rasterize(sc.points.cloud(), sc.truth.g, {.run = {.threads = threads}});
    lidarfx::scan_coverage scans(sc.truth.g);  // the scene's pulses come in scan order, with their times
    scans.add(sc.points.x, sc.points.y, sc.points.gps_time);
    s.scan_covered = scans.take();
    s.points = sc.points.size();
    s.files = 1;
    auto opt = lidarfx::flat_seed_water_method();  // what `lidarfx water` runs
    opt.run = {.threads = threads, .progress = lidarfx::cli::progress_bar("waterbodies")};
    const auto found = lidarfx::cli::find_waterbodies(s, opt);
    const auto& w = found.result;
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    lidarfx::cli::print_survey(s);
    lidarfx::cli::print_diagnostics(w.diagnostics);
    lidarfx::cli::print_waterbodies(w, 5);
    lidarfx::cli::write_point_rasters(folder, s);
    lidarfx::cli::write_waterbodies(folder, s, w, found.footprint);
    const auto score = lidarfx::confusion_counts(w.water, sc.truth.water_filled, sc.truth.g.cell);
    // Agreement picture: true water blue, water found on land red, water missed yellow, land grey; cells
    // outside the flown footprint are no data.
    constexpr std::array<std::uint8_t, 3> true_water{40, 110, 255}, false_water{230, 30, 30}, missed{250, 210, 0},
        land{200, 200, 200};
    lidarfx::io::rgb_image agreement;
    agreement.width = sc.truth.g.cols;
    agreement.height = sc.truth.g.rows;
    lidarfx::raster<std::uint8_t> unflown(sc.truth.g.rows, sc.truth.g.cols, 0);
    for (std::ptrdiff_t i = 0; i < w.water.size(); ++i) {
        const bool detected = w.water.data()[i] != 0, truth = sc.truth.water_filled.data()[i] != 0;
        const auto color = detected && truth ? true_water : detected ? false_water : truth ? missed : land;
        agreement.rgb.insert(agreement.rgb.end(), color.begin(), color.end());
        unflown.data()[i] = found.footprint.data()[i] == 0;
    }
    const auto figure = lidarfx::io::make_figure(
        agreement, unflown,
        {.title = "agreement.png: waterbodies found vs the " + name + " scene's truth",
         .cell_size = sc.truth.g.cell,
         .unit = "m",
         .key = {{true_water, "true water"}, {false_water, "false water"}, {missed, "missed water"}, {land, "land"}},
         .no_data_name = "no data (unflown)"});
    folder.write("agreement.png", [&](const std::string& path) { lidarfx::io::write_png_rgb(path, figure.image); });
    lidarfx::cli::commit_and_report(folder, "lidarfx demo (" + name + " scene)");
    std::cout << std::fixed << std::setprecision(2) << "score vs truth: accuracy " << 100 * score.accuracy()
              << " %, sensitivity " << 100 * score.sensitivity() << " %, specificity " << 100 * score.specificity()
              << " %, IoU " << 100 * score.iou() << " %  (" << std::setprecision(3) << seconds << " s)\n"
              << std::defaultfloat;
    return {name, score, w.bodies.size(), seconds};
}

// The demo's roof town: fixed, the first of the reporting seeds of docs/pv.md, small enough to take seconds.
constexpr std::uint64_t roof_town_seed = 4;

struct roof_scored {
    lidarfx::roof_mode mode = lidarfx::roof_mode::planes;
    lidarfx::synth::roof_scores score;
    std::size_t buildings = 0, patches = 0, suitable = 0;
    double seconds = 0;
};

const char* mode_name(lidarfx::roof_mode m)
{
    return m == lidarfx::roof_mode::paper ? "paper" : "planes";
}

// roof_suitability in `mode` on `town`, scored against its truth, with its roof outputs in `dir`.
roof_scored run_roof_town(const lidarfx::synth::roof_town& town, lidarfx::roof_mode mode,
                          const std::filesystem::path& dir, int threads)
{
    lidarfx::io::output_folder folder(dir);
    lidarfx::roof_suitability_options opt;
    opt.mode = mode;
    opt.run = {.threads = threads};
    const auto t0 = std::chrono::steady_clock::now();
    const auto r = lidarfx::roof_suitability(town.dsm, town.dtm, town.building_id, town.g, opt);
    roof_scored out{mode,
                    {},
                    town.buildings.size(),
                    r.patches.size(),
                    0,
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()};
    lidarfx::synth::score_roofs(town, r, opt, out.score);
    for (const auto& p : r.patches) out.suitable += p.suitable;
    // The town's grid is in metres and has no CRS.
    lidarfx::cli::write_roof_patches(folder, r, {town.dsm, town.g.cell, town.g, 1.0, 0});
    lidarfx::cli::commit_and_report(folder, std::string("lidarfx demo (roof town, ") + mode_name(mode) + " mode)");
    const auto& s = out.score;
    std::cout << std::fixed << std::setprecision(1) << mode_name(mode) << " mode: " << out.patches << " patches, "
              << out.suitable << " suitable; true planes " << s.true_planes << ", found " << 100 * s.found_share()
              << " %, tilt within 5 deg " << 100 * s.tilt5() << " %, within 10 deg " << 100 * s.tilt10()
              << " %, azimuth within 15 deg " << 100 * s.azimuth15() << " %, suitability recall " << 100 * s.recall()
              << " % precision " << 100 * s.precision() << " %, sloped-area RMSE " << 100 * s.area_rmse() << " %  ("
              << std::setprecision(3) << out.seconds << " s)\n"
              << std::defaultfloat;
    return out;
}

// roof_scores.csv: one row per mode, shares in percent (no run time: the file is the same on every run).
void write_roof_scores(lidarfx::io::output_folder& top, const std::vector<roof_scored>& results)
{
    namespace io = lidarfx::io;
    std::vector<std::vector<io::table_value>> rows;
    for (const auto& r : results) {
        const auto& s = r.score;
        rows.push_back({mode_name(r.mode), r.buildings, s.true_planes, r.patches, r.suitable, 100 * s.found_share(),
                        100 * s.tilt5(), 100 * s.tilt10(), 100 * s.azimuth15(), 100 * s.recall(), 100 * s.precision(),
                        100 * s.area_rmse()});
    }
    top.write("roof_scores.csv", [&](const std::string& path) {
        io::write_csv(
            path,
            {io::text_column("mode"), io::text_column("buildings"), io::text_column("true_planes"),
             io::text_column("patches"), io::text_column("suitable_patches"), io::percent_column("planes_found_pct"),
             io::percent_column("tilt_within_5_deg_pct"), io::percent_column("tilt_within_10_deg_pct"),
             io::percent_column("azimuth_within_15_deg_pct"), io::percent_column("suitability_recall_pct"),
             io::percent_column("suitability_precision_pct"), io::percent_column("sloped_area_rmse_pct")},
            rows);
    });
}

// scores.csv: one row per scene, the confusion scores in percent, the run time last.
void write_water_scores(lidarfx::io::output_folder& top, const std::vector<scored>& results)
{
    namespace io = lidarfx::io;
    std::vector<std::vector<io::table_value>> rows;
    for (const auto& r : results) {
        const auto& c = r.score;
        rows.push_back({r.scene, r.bodies, 100 * c.accuracy(), 100 * c.sensitivity(), 100 * c.specificity(),
                        100 * c.precision(), 100 * c.iou(), c.area_m2(c.true_positive + c.false_negative),
                        c.area_m2(c.true_positive + c.false_positive), r.seconds});
    }
    top.write("scores.csv", [&](const std::string& path) {
        io::write_csv(
            path,
            {io::text_column("scene"), io::text_column("waterbodies"), io::percent_column("accuracy_pct"),
             io::percent_column("sensitivity_pct"), io::percent_column("specificity_pct"),
             io::percent_column("precision_pct"), io::percent_column("iou_pct"), io::area_column("water_true_m2"),
             io::area_column("water_found_m2"), io::seconds_column("run_time_s")},
            rows);
    });
}

int run_demo(const std::vector<std::string>& args)
{
    const lidarfx::cli::arguments a(args, {"out", "size", "seed", "threads", "las"}, {"help"});
    if (const auto code = lidarfx::cli::stop_for_usage(a, usage, false)) return *code;
    const std::filesystem::path out = a.text("out", "lidarfx-demo");
    const int threads = a.integer("threads", 0);
    lidarfx::synth::scene_options so;
    so.size_m = a.number("size", so.size_m);
    so.seed = static_cast<unsigned>(a.integer("seed", static_cast<int>(so.seed)));
    lidarfx::io::output_folder top(out);

    std::vector<scored> results;
    results.push_back(run_scene("lake", lidarfx::synth::lake_scene(so), out / "lake", threads));
    results.push_back(run_scene("river", lidarfx::synth::river_scene(so), out / "river", threads));

    write_water_scores(top, results);

    lidarfx::synth::roof_town_options to;
    to.seed = roof_town_seed;
    const auto town = lidarfx::synth::make_roof_town(to);
    std::cout << "\n== roof town (seed " << to.seed << "): " << town.buildings.size() << " buildings, "
              << town.planes.size() << " roof planes, " << std::setprecision(3) << town.density_per_m2 << " points/m2, "
              << town.g.cols << " x " << town.g.rows << " cells of " << town.g.cell << " m ==\n"
              << std::defaultfloat;
    std::vector<roof_scored> roofs;
    for (const auto mode : {lidarfx::roof_mode::planes, lidarfx::roof_mode::paper})
        roofs.push_back(run_roof_town(town, mode, out / (std::string("roofs_") + mode_name(mode)), threads));
    write_roof_scores(top, roofs);
    lidarfx::cli::commit_and_report(top, lidarfx::cli::command_line("demo", args));

    if (a.has("las")) {
        const std::filesystem::path survey_file = a.text("las", "");
        std::cout << "\n== survey " << survey_file.string() << " ==\n";
        lidarfx::io::output_folder dir(out / survey_file.stem(), {survey_file});
        lidarfx::cli::survey_options options;
        options.threads = threads;
        options.show_progress = false;
        options.bytes_per_cell = 128;
        const auto s = lidarfx::cli::read_survey({survey_file.string()}, options);
        lidarfx::cli::print_survey(s);
        lidarfx::cli::write_point_rasters(dir, s);
        const auto found = lidarfx::cli::find_waterbodies(s, {.run = {.threads = threads}});
        const auto& w = found.result;
        lidarfx::cli::print_diagnostics(w.diagnostics);
        if (w.ran) {
            lidarfx::cli::print_waterbodies(w, 5);
            lidarfx::cli::write_waterbodies(dir, s, w, found.footprint);
        } else {
            std::cout << "waterbody extraction refused on these data (no map written)\n";
        }
        lidarfx::cli::commit_and_report(dir, lidarfx::cli::command_line("demo", args));
    }
    return 0;
}

const lidarfx::cli::registration reg{"demo", "the whole chain on embedded synthetic scenes, with scores", run_demo};

}  // namespace
