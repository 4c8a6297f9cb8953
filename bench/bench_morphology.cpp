// SPDX-License-Identifier: Apache-2.0
// Binary morphology: morph_open / morph_close on n x n masks, square sizes 5 and 25, 1 thread and all; the
// returning form of morph_open; squared_distance_transform on 1 and 2 threads.
// Input: <LIDARFX_BENCH_INPUT_DIR>/mask4096.raw (written by bench/peers/peer_morphology_label.py) when set,
// else a uniform random mask. The "ones" counter (cells set in the output) lets the peer script check
// that OpenCV computed the same result.
#include <benchmark/benchmark.h>

#include <lidarfx/kernels/filter/distance_transform.hpp>
#include <lidarfx/kernels/filter/morphology.hpp>

#include "common.hpp"
#include "reference/morphology.hpp"

#include <algorithm>
#include <cstdint>
#include <numeric>

namespace {

constexpr std::ptrdiff_t full_side = 4096;

/// The shared 4096 x 4096 mask (loaded or generated once), or its top-left n x n corner.
lidarfx::raster<std::uint8_t> input_mask(std::ptrdiff_t n)
{
    static const lidarfx::raster<std::uint8_t> full = [] {
        const auto dir = bench::input_dir();
        return dir.empty() ? bench::random_mask(full_side, full_side, 7)
                           : bench::load_raw<std::uint8_t>(dir + "/mask4096.raw", full_side, full_side);
    }();
    return lidarfx::raster<std::uint8_t>(full.view().window(0, 0, n, n));
}

double ones(const lidarfx::raster<std::uint8_t>& m)
{
    return static_cast<double>(std::count_if(m.begin(), m.end(), [](std::uint8_t v) { return v != 0; }));
}

template <bool Open>
void bm_morph(benchmark::State& state)
{
    const auto n = state.range(0);
    const auto in = input_mask(n);
    lidarfx::raster<std::uint8_t> out(n, n);
    const lidarfx::morphology_options opt{.size_cells = static_cast<int>(state.range(1)),
                                          .run = {.threads = static_cast<int>(state.range(2))}};
    for (auto _ : state) {
        if constexpr (Open)
            lidarfx::morph_open(in, out, opt);
        else
            lidarfx::morph_close(in, out, opt);
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(state.iterations() * n * n);
    state.counters["ones"] = ones(out);
}

void bm_morph_open(benchmark::State& state)
{
    bm_morph<true>(state);
}
void bm_morph_close(benchmark::State& state)
{
    bm_morph<false>(state);
}

/// The returning form (a new raster per call: its allocation and first touch are part of the time), to
/// compare with bm_morph_open's into form (issue 16: within 1.2x).
void bm_morph_open_returning(benchmark::State& state)
{
    const auto n = state.range(0);
    const auto in = input_mask(n);
    const lidarfx::morphology_options opt{.size_cells = static_cast<int>(state.range(1)),
                                          .run = {.threads = static_cast<int>(state.range(2))}};
    double set = 0;
    for (auto _ : state) {
        const auto out = lidarfx::morph_open(in, opt);
        benchmark::DoNotOptimize(out.data());
        set = static_cast<double>(out(n / 2, n / 2));
    }
    state.SetItemsProcessed(state.iterations() * n * n);
    state.counters["centre"] = set;
}

/// squared_distance_transform of the mask (features = its ones), returning form; threads as given.
void bm_squared_distance_transform(benchmark::State& state)
{
    const auto n = state.range(0);
    // A sparse feature set (1 cell in 1000), so that distances are long and the row pass does real work.
    const auto features = bench::random_mask(n, n, 11, 0.001);
    const lidarfx::distance_transform_options opt{.run = {.threads = static_cast<int>(state.range(1))}};
    for (auto _ : state) {
        const auto d = lidarfx::squared_distance_transform(features, opt);
        benchmark::DoNotOptimize(d.data());
    }
    state.SetItemsProcessed(state.iterations() * n * n);
}

/// Baseline: the brute-force window min/max of the tests (cost grows with size squared).
void bm_morph_open_naive(benchmark::State& state)
{
    const auto n = state.range(0);
    const auto size = static_cast<int>(state.range(1));
    const auto in = input_mask(n);
    lidarfx::raster<std::uint8_t> out;
    for (auto _ : state) {
        out = reference::open(in, size, size);
        benchmark::DoNotOptimize(out.data());
    }
    state.SetItemsProcessed(state.iterations() * n * n);
    state.counters["ones"] = ones(out);
}

}  // namespace

// Arguments: side n, square size, threads (0 = all cores).
BENCHMARK(bm_morph_open)->ArgsProduct({{1024, 4096}, {5, 25}, {1, 0}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(bm_morph_close)->ArgsProduct({{1024, 4096}, {5, 25}, {1, 0}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(bm_morph_open_returning)->ArgsProduct({{4096}, {5}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(bm_morph_open)->ArgsProduct({{4096}, {5}, {2}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(bm_squared_distance_transform)->ArgsProduct({{4096}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(bm_morph_open_naive)->Args({1024, 5})->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
