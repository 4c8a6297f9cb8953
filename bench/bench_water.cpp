// SPDX-License-Identifier: Apache-2.0
// Waterbody extraction: the whole pipeline from rasters to labels on a 4096 x 4096 scene, and from a LAS
// file to labels (read, rasterize, extract).
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <map>

#include <lidarfx/kernels/points/rasterize.hpp>
#include <lidarfx/synth/scenes.hpp>
#include <lidarfx/pipelines/water/extract_waterbodies.hpp>

#include "io/las.hpp"
#include "io/las_writer.hpp"

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
const lidarfx::point_rasters& rasters_4096()
{
    static const lidarfx::point_rasters big = [] {
        const auto& sc = lake(2048);
        const auto tile = lidarfx::rasterize(sc.points.cloud(), sc.truth.g, {.threads = 0});
        const std::ptrdiff_t n = tile.g.rows, m = tile.g.cols;
        lidarfx::point_rasters out;
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

void bm_extract_waterbodies_4096(benchmark::State& state)
{
    const auto& pr = rasters_4096();
    const lidarfx::extract_waterbodies_options opt{.run = {.threads = static_cast<int>(state.range(0))}};
    std::size_t bodies = 0;
    for (auto _ : state) {
        const auto w = lidarfx::extract_waterbodies(pr, opt);
        bodies = w.bodies.size();
        benchmark::DoNotOptimize(w.labels.data());
    }
    state.SetItemsProcessed(state.iterations() * pr.g.size());
    state.counters["bodies"] = static_cast<double>(bodies);
}
BENCHMARK(bm_extract_waterbodies_4096)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

/// A LAS file of the 2048 m lake scene (8.4 million points), written once.
const std::string& lake_las()
{
    static const std::string path = [] {
        const auto p = (std::filesystem::temp_directory_path() / "lidarfx_bench_lake2048.las").string();
        const auto& sc = lake(2048);
        lidarfx::io::las_points pts;
        pts.x = sc.points.x;
        pts.y = sc.points.y;
        pts.z = sc.points.z;
        pts.intensity = sc.points.intensity;
        pts.return_number = sc.points.return_number;
        pts.number_of_returns = sc.points.number_of_returns;
        pts.classification = sc.points.classification;
        pts.classification_flags.assign(pts.size(), 0);
        pts.scan_angle_deg.assign(pts.size(), 0.0f);
        lidarfx::io::write_las(p, pts, {.point_format = 0});
        return p;
    }();
    return path;
}

void bm_las_to_waterbodies(benchmark::State& state)
{
    const auto& path = lake_las();
    const auto& sc = lake(2048);
    const int threads = static_cast<int>(state.range(0));
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
        const auto w = lidarfx::extract_waterbodies(acc.finish(), {.run = {.threads = threads}});
        benchmark::DoNotOptimize(w.labels.data());
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(points));
}
BENCHMARK(bm_las_to_waterbodies)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
