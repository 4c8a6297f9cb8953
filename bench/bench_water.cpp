// SPDX-License-Identifier: Apache-2.0
// Waterbody extraction: the whole pipeline from rasters to labels on a 4096 x 4096 scene, its steps one by
// one on the same scene (the island step next to its whole-raster reference), and from a LAS file to labels
// (read, rasterize, extract).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <vector>

#include <lidarfx/kernels/points/rasterize.hpp>
#include <lidarfx/pipelines/water/extract_waterbodies.hpp>
#include <lidarfx/synth/scenes.hpp>

#include "common.hpp"
#include "io/las.hpp"
#include "io/las_writer.hpp"
#include "reference/islands.hpp"

namespace {

/// A synthetic lake scene of side `size_m` at 2 points/m², rasterized on its 2 m truth grid.
const lidarfx::synth::scene& lake(double size_m)
{
    static std::map<double, lidarfx::synth::scene> cache;
    auto it = cache.find(size_m);
    if (it == cache.end()) {
        lidarfx::synth::scene_options o;
        o.size_m = size_m;
        it = cache.emplace(size_m, lidarfx::synth::lake_scene(o)).first;
    }
    return it->second;
}

/// 4096 x 4096 rasters: 4 x 4 copies of the rasters of a 2048 m lake scene (1024 x 1024 cells).
const lidarfx::rasterize_result& rasters_4096()
{
    static const lidarfx::rasterize_result big = [] {
        const auto& sc = lake(2048);
        const auto tile = lidarfx::rasterize(sc.points.cloud(), sc.truth.g, {.run = {.threads = 0}});
        const std::ptrdiff_t n = tile.g.rows, m = tile.g.cols;
        lidarfx::rasterize_result out;
        out.g = lidarfx::grid{0, 4.0 * static_cast<double>(n) * tile.g.cell, tile.g.cell, 4 * n, 4 * m};
        out.min_z = lidarfx::raster<float>(4 * n, 4 * m);
        out.max_z = out.mean_intensity = out.min_z;
        out.count = lidarfx::raster<std::uint32_t>(4 * n, 4 * m);
        out.dropout = out.multiple_returns = lidarfx::raster<std::uint8_t>(4 * n, 4 * m);
        for (std::ptrdiff_t r = 0; r < 4 * n; ++r)
            for (std::ptrdiff_t c = 0; c < 4 * m; ++c) {
                out.min_z(r, c) = tile.min_z(r % n, c % m);
                out.max_z(r, c) = tile.max_z(r % n, c % m);
                out.mean_intensity(r, c) = tile.mean_intensity(r % n, c % m);
                out.count(r, c) = tile.count(r % n, c % m);
                out.dropout(r, c) = tile.dropout(r % n, c % m);
                out.multiple_returns(r, c) = tile.multiple_returns(r % n, c % m);
            }
        return out;
    }();
    return big;
}

/// Args: threads (0 = all), flat seeds (1 = on, 0 = dropout seeds only, the default; 2 = on, with the level
/// following min z only on a level surface: flat_seed_water_method(), what `lidarfx water` runs).
void bm_extract_waterbodies_4096(benchmark::State& state)
{
    const auto& pr = rasters_4096();
    lidarfx::extract_waterbodies_options opt;
    opt.flat_seeds = state.range(1) != 0;
    if (state.range(1) == 2) opt = lidarfx::flat_seed_water_method();
    opt.run.threads = static_cast<int>(state.range(0));
    std::size_t bodies = 0;
    // One untimed call first: a process's first 1-2 GB of fresh pages cost this VM several times more than
    // later ones (docs/performance.md, "Returning forms and first touch"), which would weigh on the mean of
    // the few timed calls. The steady state is what a tool that maps several tiles sees.
    benchmark::DoNotOptimize(lidarfx::extract_waterbodies(pr, opt).labels.data());
    for (auto _ : state) {
        const auto w = lidarfx::extract_waterbodies(pr, opt);
        bodies = w.bodies.size();
        benchmark::DoNotOptimize(w.labels.data());
    }
    state.SetItemsProcessed(state.iterations() * pr.g.size());
    state.counters["bodies"] = static_cast<double>(bodies);
}
BENCHMARK(bm_extract_waterbodies_4096)
    ->ArgNames({"threads", "flat"})
    ->Args({1, 1})
    ->Args({2, 1})
    ->Args({1, 2})
    ->Args({2, 2})
    ->Args({1, 0})
    ->Args({2, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

/// Labels of the 4096 x 4096 scene as they reach a step: after growing (no bridges, no islands) or after
/// bridging (no islands).
const lidarfx::raster<std::int32_t>& labels_4096(bool bridged)
{
    static std::map<bool, lidarfx::raster<std::int32_t>> cache;
    auto it = cache.find(bridged);
    if (it == cache.end()) {
        lidarfx::extract_waterbodies_options o{.islands = {.island_min_area_m2 = 0}, .run = {.threads = 0}};
        if (!bridged) o.join_bridges = false;
        it = cache.emplace(bridged, lidarfx::extract_waterbodies(rasters_4096(), o).labels).first;
    }
    return it->second;
}

void bm_water_step_4096(benchmark::State& state)
{
    const auto& pr = rasters_4096();
    const auto in = lidarfx::to_water_rasters(pr);
    const double cell = pr.g.cell;
    const int threads = static_cast<int>(state.range(1));
    const lidarfx::execution run{.threads = threads};
    for (auto _ : state) {
        switch (state.range(0)) {
            case 0:
                benchmark::DoNotOptimize(lidarfx::assess_water_inputs(in, cell).dropout_fraction);
                break;
            case 1:
                benchmark::DoNotOptimize(lidarfx::water_vegetation(in, {}, run).data());
                break;
            case 2:
                benchmark::DoNotOptimize(lidarfx::water_angles(in, cell, {}, run).data());
                break;
            case 3:
                benchmark::DoNotOptimize(lidarfx::water_seeds(pr.dropout, {}, run).labels.data());
                break;
            case 4:
                benchmark::DoNotOptimize(lidarfx::intensity_bins(pr.mean_intensity, pr.dropout).bin.data());
                break;
            case 5: {
                state.PauseTiming();
                auto labels = labels_4096(false);
                state.ResumeTiming();
                lidarfx::join_across_bridges(labels, pr.min_z, lidarfx::water_levels(labels, pr.min_z), cell);
                benchmark::DoNotOptimize(labels.data());
                break;
            }
            case 6: {
                state.PauseTiming();
                auto labels = labels_4096(true);
                state.ResumeTiming();
                benchmark::DoNotOptimize(lidarfx::fill_small_islands(labels, cell, {}, run));
                break;
            }
            case 7: {
                state.PauseTiming();
                auto labels = labels_4096(true);
                state.ResumeTiming();
                reference::fill_small_islands(labels, static_cast<std::size_t>(std::ceil(200.0 / (cell * cell))));
                benchmark::DoNotOptimize(labels.data());
                break;
            }
            case 8: {
                state.PauseTiming();
                auto labels = labels_4096(true);
                std::vector<lidarfx::waterbody> bodies;
                state.ResumeTiming();
                lidarfx::measure_waterbodies(labels, bodies, in, cell);
                benchmark::DoNotOptimize(bodies.data());
                break;
            }
            case 9: {  // with the vegetation mask excluded, as extract_waterbodies calls it
                static const auto vegetation = lidarfx::water_vegetation(in, {}, {.threads = 0});
                benchmark::DoNotOptimize(lidarfx::flat_water_seeds(in, vegetation, {}, {}, {}, run).data());
                break;
            }
            case 10:
                benchmark::DoNotOptimize(lidarfx::water_surface_slope(in.min_z, cell, {}, run).data());
                break;
        }
    }
    static const char* const names[] = {
        "assess_water_inputs", "water_vegetation",    "water_angles",       "water_seeds",
        "intensity_bins",      "join_across_bridges", "fill_small_islands", "reference::fill_small_islands",
        "measure_waterbodies", "flat_water_seeds",    "water_surface_slope"};
    state.SetLabel(names[state.range(0)]);
    state.SetItemsProcessed(state.iterations() * pr.g.size());
}
BENCHMARK(bm_water_step_4096)
    ->ArgsProduct({{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10}, {1}})
    ->ArgsProduct({{1, 2, 3, 6, 9, 10}, {0}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

/// A LAS file of the 2048 m lake scene (8.4 million points), written once.
const std::string& lake_las()
{
    static const std::string path = [] {
        const auto p = (std::filesystem::temp_directory_path() / "lidarfx_bench_lake2048.las").string();
        const auto& sc = lake(2048);
        const auto pts = lidarfx::io::las_points_from(sc.points);
        lidarfx::io::write_las(p, pts, {.point_format = 0});
        return p;
    }();
    return path;
}

/// Args: threads (0 = all), flat seeds (0 = dropout seeds only, the library's default; 1 = flat seeds with
/// the level-surface cue, flat_seed_water_method(), what `lidarfx water` runs by default).
void bm_las_to_waterbodies(benchmark::State& state)
{
    const auto& path = lake_las();
    const auto& sc = lake(2048);
    const int threads = static_cast<int>(state.range(0));
    auto opt = state.range(1) != 0 ? lidarfx::flat_seed_water_method() : lidarfx::extract_waterbodies_options{};
    opt.run.threads = threads;
    std::size_t points = 0;
    for (auto _ : state) {
        lidarfx::io::las_reader reader(path);
        lidarfx::raster_accumulator acc(sc.truth.g);
        lidarfx::io::las_points chunk;
        points = 0;
        while (const std::size_t n = reader.read(chunk, std::size_t{1} << 20)) {
            acc.add(chunk.cloud());
            points += n;
        }
        const auto w = lidarfx::extract_waterbodies(acc.finish(), opt);
        benchmark::DoNotOptimize(w.labels.data());
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(points));
}
BENCHMARK(bm_las_to_waterbodies)
    ->ArgNames({"threads", "flat"})
    ->ArgsProduct({{1, 0}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
