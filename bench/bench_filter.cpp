// SPDX-License-Identifier: Apache-2.0
// Benchmarks of the filter kernels angular_filter and slope_aspect (morphology: bench_morphology.cpp).
// With LIDARFX_BENCH_INPUT_DIR set, the terrain comes from <dir>/terrain<n>.raw (float32, written by
// bench/peers/peer_filter_stats.py) so that lidarfx and its NumPy peers time the same cells.
#include <benchmark/benchmark.h>

#include <lidarfx/kernels/filter/angular_filter.hpp>
#include <lidarfx/kernels/filter/slope_aspect.hpp>

#include "common.hpp"
#include "reference/angular_filter.hpp"
#include "reference/slope_aspect.hpp"

#include <string>

namespace {

lidarfx::raster<float> terrain(std::ptrdiff_t n)
{
    const std::string dir = bench::input_dir();
    if (!dir.empty()) return bench::load_raw<float>(dir + "/terrain" + std::to_string(n) + ".raw", n, n);
    return bench::random_terrain(n, n, /*seed=*/42);
}

// Arguments: side n of the n x n raster, threads (0 = all cores).
void bm_angular_filter(benchmark::State& state)
{
    const auto n = state.range(0);
    const auto z = terrain(n);
    lidarfx::raster<float> out(n, n);
    const lidarfx::angular_filter_options opt{.radius_cells = 2, .run = {.threads = static_cast<int>(state.range(1))}};
    for (auto _ : state) {
        lidarfx::angular_filter(z, out, 0.5, opt);
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(state.iterations() * n * n);
}
BENCHMARK(bm_angular_filter)->ArgsProduct({{1024, 4096}, {1, 2}})->ArgNames({"n", "threads"})->UseRealTime();

// The returning form: a new raster per call (allocation and first touch included).
void bm_angular_filter_returning(benchmark::State& state)
{
    const auto n = state.range(0);
    const auto z = terrain(n);
    const lidarfx::angular_filter_options opt{.radius_cells = 2, .run = {.threads = static_cast<int>(state.range(1))}};
    for (auto _ : state) {
        const auto out = lidarfx::angular_filter(z, 0.5, opt);
        benchmark::DoNotOptimize(out.data());
    }
    state.SetItemsProcessed(state.iterations() * n * n);
}
BENCHMARK(bm_angular_filter_returning)->ArgsProduct({{4096}, {1, 2}})->ArgNames({"n", "threads"})->UseRealTime();

void bm_angular_filter_reference(benchmark::State& state)
{
    const auto n = state.range(0);
    const auto z = terrain(n);
    for (auto _ : state) {
        auto out = reference::angular_filter(z, 0.5, 2);
        benchmark::DoNotOptimize(out.data());
    }
    state.SetItemsProcessed(state.iterations() * n * n);
}
BENCHMARK(bm_angular_filter_reference)->Arg(1024)->ArgNames({"n"})->UseRealTime()->Unit(benchmark::kMillisecond);

// Arguments: side n of the n x n raster, threads (0 = all cores).
void bm_slope_aspect(benchmark::State& state)
{
    const auto n = state.range(0);
    const auto z = terrain(n);
    lidarfx::slope_aspect_result out{lidarfx::raster<float>(n, n), lidarfx::raster<float>(n, n),
                                     lidarfx::raster<std::uint8_t>(n, n)};
    const lidarfx::slope_aspect_options opt{.run = {.threads = static_cast<int>(state.range(1))}};
    for (auto _ : state) {
        lidarfx::slope_aspect(z, out.slope_deg, out.aspect_deg, out.flat, 0.5, opt);
        benchmark::DoNotOptimize(out.slope_deg.data());
        benchmark::DoNotOptimize(out.aspect_deg.data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(state.iterations() * n * n);
}
BENCHMARK(bm_slope_aspect)->ArgsProduct({{1024, 4096}, {1, 2}})->ArgNames({"n", "threads"})->UseRealTime();

// The returning form: three new rasters per call (allocation and first touch included).
void bm_slope_aspect_returning(benchmark::State& state)
{
    const auto n = state.range(0);
    const auto z = terrain(n);
    const lidarfx::slope_aspect_options opt{.run = {.threads = static_cast<int>(state.range(1))}};
    for (auto _ : state) {
        const auto out = lidarfx::slope_aspect(z, 0.5, opt);
        benchmark::DoNotOptimize(out.slope_deg.data());
    }
    state.SetItemsProcessed(state.iterations() * n * n);
}
BENCHMARK(bm_slope_aspect_returning)->ArgsProduct({{4096}, {1, 2}})->ArgNames({"n", "threads"})->UseRealTime();

void bm_slope_aspect_reference(benchmark::State& state)
{
    const auto n = state.range(0);
    const auto z = terrain(n);
    for (auto _ : state) {
        auto out = reference::slope_aspect(z, 0.5, 0.0);
        benchmark::DoNotOptimize(out.slope_deg.data());
    }
    state.SetItemsProcessed(state.iterations() * n * n);
}
BENCHMARK(bm_slope_aspect_reference)->Arg(1024)->ArgNames({"n"})->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
