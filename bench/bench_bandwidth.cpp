// SPDX-License-Identifier: Apache-2.0
// Memory bandwidth on 4096 x 4096 float rasters, STREAM-style (McCalpin): copy a = b and triad a = b + s * c,
// on 1 and 2 threads through lidarfx::parallel_for_rows (64-row blocks, as the kernels use). A kernel whose
// 2-thread speed-up falls short of 1.7x is bandwidth-bound when its bytes per second approach these figures.
// Bytes counted as STREAM does: copy 8 per cell (one read, one write), triad 12 (two reads, one write).
#include <benchmark/benchmark.h>

#include <lidarfx/core/parallel.hpp>
#include <lidarfx/core/raster.hpp>

#include "common.hpp"

#include <algorithm>

namespace {

constexpr std::ptrdiff_t side = 4096;

// Arguments: threads.
void bm_stream_copy(benchmark::State& state)
{
    lidarfx::raster<float> a(side, side, 0.0f), b(side, side, 1.0f);
    const int threads = static_cast<int>(state.range(0));
    for (auto _ : state) {
        lidarfx::parallel_for_rows(side, 64, threads, [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
            std::copy(b.row(r0), b.row(r0) + (r1 - r0) * side, a.row(r0));
        });
        benchmark::DoNotOptimize(a.data());
        benchmark::ClobberMemory();
    }
    state.SetBytesProcessed(state.iterations() * side * side * 8);
}
BENCHMARK(bm_stream_copy)->ArgName("threads")->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// Arguments: threads.
void bm_stream_triad(benchmark::State& state)
{
    lidarfx::raster<float> a(side, side, 0.0f), b(side, side, 1.0f), c(side, side, 2.0f);
    const int threads = static_cast<int>(state.range(0));
    const float s = 3.0f;
    for (auto _ : state) {
        lidarfx::parallel_for_rows(side, 64, threads, [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
            const float* pb = b.row(r0);
            const float* pc = c.row(r0);
            float* pa = a.row(r0);
            for (std::ptrdiff_t i = 0; i < (r1 - r0) * side; ++i) pa[i] = pb[i] + s * pc[i];
        });
        benchmark::DoNotOptimize(a.data());
        benchmark::ClobberMemory();
    }
    state.SetBytesProcessed(state.iterations() * side * side * 12);
}
BENCHMARK(bm_stream_triad)->ArgName("threads")->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// First touch: a fresh raster of 4096 x 4096 floats written in full (page faults and the kernel's zeroing of
// new pages included): the floor under any returning form's extra cost over its into form.
void bm_first_touch(benchmark::State& state)
{
    const int threads = static_cast<int>(state.range(0));
    for (auto _ : state) {
        lidarfx::raster<float> a(side, side, lidarfx::uninitialized);
        lidarfx::parallel_for_rows(side, 64, threads, [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
            std::fill(a.row(r0), a.row(r0) + (r1 - r0) * side, 1.0f);
        });
        benchmark::DoNotOptimize(a.data());
        benchmark::ClobberMemory();
    }
    state.SetBytesProcessed(state.iterations() * side * side * 4);
}
BENCHMARK(bm_first_touch)->ArgName("threads")->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
