// SPDX-License-Identifier: Apache-2.0
// Benchmarks of the statistics kernels: ks_one_sided on LiDAR-like 16-bit intensities, on floats and doubles,
// next to the sort-and-sweep baseline (std::sort of both samples + one merge sweep) with the ratio printed.
// With LIDARFX_BENCH_INPUT_DIR set, the samples come from <dir>/ks_prev.raw and <dir>/ks_cur.raw (10^6 uint16
// each, written by bench/peers/peer_filter_stats.py) so that lidarfx and scipy test the same values.
#include <benchmark/benchmark.h>

#include <lidarfx/kernels/stats/ks_one_sided.hpp>

#include "common.hpp"
#include "reference/ks.hpp"

#include <algorithm>
#include <cstdint>
#include <ctime>
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

// 10^6 vs 10^6 floating samples: 0 = continuous (normal, current shifted by 0.02 sd), 1 = the intensities above
// (integers, many ties).
template <class T>
std::pair<std::vector<T>, std::vector<T>> floating_samples(int kind)
{
    if (kind == 1) {
        const auto p16 = intensities("ks_prev", 800, 1), c16 = intensities("ks_cur", 820, 2);
        return {std::vector<T>(p16.begin(), p16.end()), std::vector<T>(c16.begin(), c16.end())};
    }
    std::mt19937_64 rng(3);
    std::normal_distribution<double> normal(0, 1);
    std::vector<T> p(static_cast<std::size_t>(sample_size)), c(p.size());
    for (auto& v : p) v = static_cast<T>(normal(rng));
    for (auto& v : c) v = static_cast<T>(normal(rng) + 0.02);
    return {std::move(p), std::move(c)};
}

/// The baseline: copies sorted by std::sort, then one merge sweep.
template <class T>
double sort_and_sweep(const std::vector<T>& previous, const std::vector<T>& current)
{
    auto p = previous, c = current;
    std::sort(p.begin(), p.end());
    std::sort(c.begin(), c.end());
    return lidarfx::detail::ks_statistic_sorted(p, c);
}

template <class T>
void bm_ks_sort_and_sweep(benchmark::State& state)
{
    const auto [previous, current] = floating_samples<T>(static_cast<int>(state.range(0)));
    for (auto _ : state) benchmark::DoNotOptimize(sort_and_sweep(previous, current));
    state.SetItemsProcessed(state.iterations() * 2 * sample_size);
    state.SetLabel(state.range(0) == 0 ? "continuous" : "intensities");
}
BENCHMARK(bm_ks_sort_and_sweep<double>)->Arg(0)->Arg(1)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(bm_ks_sort_and_sweep<float>)->Arg(0)->Arg(1)->UseRealTime()->Unit(benchmark::kMillisecond);

/// Thread CPU time in seconds: on a shared machine it counts only this thread's work.
double thread_cpu_s()
{
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// ks_one_sided and the baseline timed in turn in each iteration, in thread CPU time (best of the iterations
/// for both): the reported time is ks_one_sided's; counters give the baseline's best time and speedup =
/// baseline / kernel. `same` is 1 when both gave the same D.
template <class T>
void bm_ks_vs_sort(benchmark::State& state)
{
    const auto [previous, current] = floating_samples<T>(static_cast<int>(state.range(0)));
    double best_kernel = 1e30, best_baseline = 1e30;
    bool same = true;
    for (auto _ : state) {
        const double t0 = thread_cpu_s();
        const double d = lidarfx::ks_one_sided(previous, current).d;
        const double t1 = thread_cpu_s();
        const double reference = sort_and_sweep(previous, current);
        const double t2 = thread_cpu_s();
        same = same && d == reference;
        const double kernel = t1 - t0;
        best_kernel = std::min(best_kernel, kernel);
        best_baseline = std::min(best_baseline, t2 - t1);
        state.SetIterationTime(kernel);
    }
    state.SetItemsProcessed(state.iterations() * 2 * sample_size);
    state.counters["baseline_ms"] = 1e3 * best_baseline;
    state.counters["kernel_ms"] = 1e3 * best_kernel;
    state.counters["speedup"] = best_baseline / best_kernel;
    state.counters["same"] = same;
    state.SetLabel(state.range(0) == 0 ? "continuous" : "intensities");
}
BENCHMARK(bm_ks_vs_sort<double>)->Arg(0)->Arg(1)->UseManualTime()->Iterations(7)->Unit(benchmark::kMillisecond);
BENCHMARK(bm_ks_vs_sort<float>)->Arg(0)->Arg(1)->UseManualTime()->Iterations(7)->Unit(benchmark::kMillisecond);

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
