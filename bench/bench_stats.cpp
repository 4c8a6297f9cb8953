// SPDX-License-Identifier: Apache-2.0
// Benchmarks of the statistics kernels: ks_one_sided on LiDAR-like 16-bit intensities and on floats.
// With LIDARFX_BENCH_INPUT_DIR set, the samples come from <dir>/ks_prev.raw and <dir>/ks_cur.raw (10^6 uint16
// each, written by bench/peers/peer_filter_stats.py) so that lidarfx and scipy test the same values.
#include <benchmark/benchmark.h>

#include <lidarfx/kernels/stats/ks_one_sided.hpp>

#include "reference/ks.hpp"
#include "common.hpp"

#include <algorithm>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace {

constexpr std::ptrdiff_t sample_size = 1'000'000;

// Intensity-like samples: exponential brightness, the current one slightly brighter.
std::vector<std::uint16_t> intensities(const char* name, double mean, unsigned seed)
{
    const std::string dir = bench::input_dir();
    if (!dir.empty()) {
        const auto r = bench::load_raw<std::uint16_t>(dir + "/" + name + ".raw", 1, sample_size);
        return {r.begin(), r.end()};
    }
    std::mt19937 rng(seed);
    std::exponential_distribution<double> brightness(1 / mean);
    std::vector<std::uint16_t> out(static_cast<std::size_t>(sample_size));
    for (auto& v : out) v = static_cast<std::uint16_t>(std::min(65535.0, brightness(rng)));
    return out;
}

void bm_ks_uint16(benchmark::State& state)
{
    const auto previous = intensities("ks_prev", 800, 1), current = intensities("ks_cur", 820, 2);
    for (auto _ : state) benchmark::DoNotOptimize(lidarfx::ks_one_sided(previous, current));
    state.SetItemsProcessed(state.iterations() * 2 * sample_size);
}
BENCHMARK(bm_ks_uint16)->UseRealTime()->Unit(benchmark::kMillisecond);

// The same values as float: the sort-and-merge path.
void bm_ks_float(benchmark::State& state)
{
    const auto p16 = intensities("ks_prev", 800, 1), c16 = intensities("ks_cur", 820, 2);
    const std::vector<float> previous(p16.begin(), p16.end()), current(c16.begin(), c16.end());
    for (auto _ : state) benchmark::DoNotOptimize(lidarfx::ks_one_sided(previous, current));
    state.SetItemsProcessed(state.iterations() * 2 * sample_size);
}
BENCHMARK(bm_ks_float)->UseRealTime()->Unit(benchmark::kMillisecond);

// One region-growing test: both histograms are kept up to date by the caller, the test is O(bins).
void bm_ks_histogram_test(benchmark::State& state)
{
    lidarfx::ks_histogram previous, current;
    previous.add(intensities("ks_prev", 800, 1));
    current.add(intensities("ks_cur", 820, 2));
    for (auto _ : state) benchmark::DoNotOptimize(lidarfx::ks_one_sided(previous, current));
    state.SetItemsProcessed(state.iterations() * 2 * sample_size);
}
BENCHMARK(bm_ks_histogram_test)->UseRealTime()->Unit(benchmark::kMicrosecond);

// The direct supremum is O((n + m)^2): 2 x 2000 values only.
void bm_ks_reference(benchmark::State& state)
{
    const auto p16 = intensities("ks_prev", 800, 1), c16 = intensities("ks_cur", 820, 2);
    const std::vector<std::uint16_t> previous(p16.begin(), p16.begin() + 2000),
        current(c16.begin(), c16.begin() + 2000);
    for (auto _ : state) benchmark::DoNotOptimize(reference::ks_statistic(previous, current));
    state.SetItemsProcessed(state.iterations() * 4000);
}
BENCHMARK(bm_ks_reference)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
