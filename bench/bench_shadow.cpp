// SPDX-License-Identifier: Apache-2.0
// Benchmarks of the shadow, horizon and sky view kernels (kernels/solar/raylines_shadow.hpp, horizon_map.hpp,
// sky_view_factor.hpp) on a box
// town: 1 m cells, buildings 8..30 m on a side and 3..25 m tall over noisy ground. Azimuths 180 (rays along
// columns), 135 (diagonal) and 250 (mostly along rows) cover both sweep shapes.
#include <benchmark/benchmark.h>

#include <lidarfx/kernels/solar/horizon_map.hpp>
#include <lidarfx/kernels/solar/raylines_shadow.hpp>
#include <lidarfx/kernels/solar/sky_view_factor.hpp>

#include "reference/solar.hpp"

#include <cstdint>
#include <map>
#include <random>

namespace {

const lidarfx::raster<float>& town(std::ptrdiff_t n)
{
    static std::map<std::ptrdiff_t, lidarfx::raster<float>> cache;  // benchmark program: built once per size
    auto it = cache.find(n);
    if (it == cache.end()) {
        std::mt19937 rng(20261201);
        it = cache.emplace(n, reference::box_town(rng, n, n, static_cast<int>(n * n / 2000), 0.3, 8, 30)).first;
    }
    return it->second;
}

// Arguments: side n, sun azimuth in degrees, threads (0 = all cores), line families (line_phases; 4 is the
// default, 1 the dissertation's single family). Sun elevation 30 degrees. Along the axes (180) and diagonals
// (135) one family is exact and the only one swept.
void bm_raylines_shadow(benchmark::State& state)
{
    const auto n = state.range(0);
    const auto& z = town(n);
    lidarfx::raster<std::uint8_t> lit(n, n);
    const lidarfx::raylines_shadow_options opt{.line_phases = static_cast<int>(state.range(3)),
                                               .run = {.threads = static_cast<int>(state.range(2))}};
    for (auto _ : state) {
        lidarfx::raylines_shadow(z, lit, 1.0, static_cast<double>(state.range(1)), 30.0, opt);
        benchmark::DoNotOptimize(lit.data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(state.iterations() * n * n);
}
BENCHMARK(bm_raylines_shadow)
    ->ArgsProduct({{4096}, {180, 135, 250, 200}, {1, 0}, {4, 1}})
    ->ArgNames({"n", "azimuth", "threads", "phases"})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// Baseline: a straight ray march from every cell (tests/reference/solar.hpp), O(cells * shadow length).
void bm_raylines_shadow_reference(benchmark::State& state)
{
    const auto n = state.range(0);
    const auto& z = town(n);
    for (auto _ : state) {
        auto lit = reference::shadow_sampled_march(z.view(), 1.0, static_cast<double>(state.range(1)), 30.0);
        benchmark::DoNotOptimize(lit.data());
    }
    state.SetItemsProcessed(state.iterations() * n * n);
}
BENCHMARK(bm_raylines_shadow_reference)
    ->ArgsProduct({{512}, {135}})
    ->ArgNames({"n", "azimuth"})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// Arguments: side n, azimuth in degrees, threads (0 = all cores). One horizon map per iteration.
void bm_horizon_map(benchmark::State& state)
{
    const auto n = state.range(0);
    const auto& z = town(n);
    lidarfx::raster<float> h(n, n);
    const lidarfx::horizon_map_options opt{.run = {.threads = static_cast<int>(state.range(2))}};
    for (auto _ : state) {
        lidarfx::horizon_map(z, h, 1.0, static_cast<double>(state.range(1)), opt);
        benchmark::DoNotOptimize(h.data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(state.iterations() * n * n);
}
BENCHMARK(bm_horizon_map)
    ->ArgsProduct({{2048}, {180, 135, 250}, {1, 0}})
    ->ArgNames({"n", "azimuth", "threads"})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// Baseline: the direct maximum-angle search over each cell's ray line, O(cells * line length).
void bm_horizon_map_reference(benchmark::State& state)
{
    const auto n = state.range(0);
    const auto& z = town(n);
    for (auto _ : state) {
        auto h = reference::horizon_on_lines(z.view(), 1.0, static_cast<double>(state.range(1)));
        benchmark::DoNotOptimize(h.data());
    }
    state.SetItemsProcessed(state.iterations() * n * n);
}
BENCHMARK(bm_horizon_map_reference)
    ->ArgsProduct({{256}, {135}})
    ->ArgNames({"n", "azimuth"})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// Arguments: side n, method (0 source share, 1 cosine-weighted), threads (0 = all cores). 72 azimuths.
void bm_sky_view_factor(benchmark::State& state)
{
    const auto n = state.range(0);
    const auto& z = town(n);
    lidarfx::raster<float> svf(n, n);
    const lidarfx::sky_view_factor_options opt{.method = state.range(1) == 0
                                                             ? lidarfx::sky_view_factor_method::source_share
                                                             : lidarfx::sky_view_factor_method::cosine_weighted,
                                               .run = {.threads = static_cast<int>(state.range(2))}};
    for (auto _ : state) {
        lidarfx::sky_view_factor(z, svf, 1.0, opt);
        benchmark::DoNotOptimize(svf.data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(state.iterations() * n * n);
}
BENCHMARK(bm_sky_view_factor)
    ->ArgsProduct({{2048}, {0, 1}, {1, 0}})
    ->ArgNames({"n", "method", "threads"})
    ->Iterations(1)
    ->UseRealTime()
    ->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
