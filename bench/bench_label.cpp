// SPDX-License-Identifier: Apache-2.0
// Connected components (eight-connectivity, labels and sizes) of a 4096 x 4096 mask, 1 thread and all.
// Input: <LIDARFX_BENCH_INPUT_DIR>/mask4096.raw (written by bench/peers/peer_morphology_label.py) when set,
// else a uniform random mask. The "components" counter lets the peer script check the count against
// OpenCV's.
#include <benchmark/benchmark.h>

#include <lidarfx/kernels/label/connected_components.hpp>

#include "common.hpp"
#include "reference/components.hpp"

#include <cstdint>

namespace {

lidarfx::raster<std::uint8_t> input_mask(std::ptrdiff_t n)
{
    const auto dir = bench::input_dir();
    return dir.empty() ? bench::random_mask(n, n, 7) : bench::load_raw<std::uint8_t>(dir + "/mask4096.raw", n, n);
}

void bm_connected_components(benchmark::State& state)
{
    const auto n = state.range(0);
    const auto in = input_mask(n);
    const lidarfx::connected_components_options opt{.conn = lidarfx::connectivity::eight,
                                                    .run = {.threads = static_cast<int>(state.range(1))}};
    std::size_t count = 0;
    for (auto _ : state) {
        const auto comps = lidarfx::connected_components(in, opt);
        count = comps.count();
        benchmark::DoNotOptimize(comps.labels.data());
    }
    state.SetItemsProcessed(state.iterations() * n * n);
    state.counters["components"] = static_cast<double>(count);
}

/// Into form: labels written into a raster allocated once, outside the timed loop.
void bm_connected_components_into(benchmark::State& state)
{
    const auto n = state.range(0);
    const auto in = input_mask(n);
    const lidarfx::connected_components_options opt{.conn = lidarfx::connectivity::eight,
                                                    .run = {.threads = static_cast<int>(state.range(1))}};
    lidarfx::raster<std::int32_t> labels(n, n);
    std::size_t count = 0;
    for (auto _ : state) {
        count = lidarfx::connected_components(in, labels, opt).size() - 1;
        benchmark::DoNotOptimize(labels.data());
    }
    state.SetItemsProcessed(state.iterations() * n * n);
    state.counters["components"] = static_cast<double>(count);
}

/// Baseline: the tests' breadth-first flood fill.
void bm_connected_components_naive(benchmark::State& state)
{
    const auto n = state.range(0);
    const auto in = input_mask(n);
    std::size_t count = 0;
    for (auto _ : state) {
        const auto comps = reference::flood_label(in, lidarfx::connectivity::eight);
        count = comps.count();
        benchmark::DoNotOptimize(comps.labels.data());
    }
    state.SetItemsProcessed(state.iterations() * n * n);
    state.counters["components"] = static_cast<double>(count);
}

}  // namespace

// Arguments: side n, threads (0 = all cores).
BENCHMARK(bm_connected_components)->ArgsProduct({{4096}, {1, 0}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(bm_connected_components_into)->ArgsProduct({{4096}, {1, 0}})->Unit(benchmark::kMillisecond)->UseRealTime();
// Exactly 2 threads (issue 16's scaling target), whatever the machine's core count.
BENCHMARK(bm_connected_components)->ArgsProduct({{4096}, {2}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(bm_connected_components_into)->ArgsProduct({{4096}, {2}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(bm_connected_components_naive)->Args({4096})->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
