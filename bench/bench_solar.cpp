// SPDX-License-Identifier: Apache-2.0
// Benchmarks of the solar kernels and pipeline: sun_position by SPA and by the dissertation's simple model, in
// positions per second over the hours of a year (a TMY year needs 8760 of them, so either model costs well under
// a millisecond); and irradiance_maps over a whole year of hourly clear-sky records on a box town.
#include <benchmark/benchmark.h>

#include <lidarfx/kernels/solar/clear_sky.hpp>
#include <lidarfx/kernels/solar/sun_position.hpp>
#include <lidarfx/pipelines/solar/irradiance_maps.hpp>

#include <random>

#include "reference/solar.hpp"

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace {

namespace chr = std::chrono;

// Every hour of 2023 at its half hour (the middle of an hourly record).
std::vector<chr::sys_seconds> hours_of_a_year()
{
    std::vector<chr::sys_seconds> times;
    const chr::sys_seconds start = chr::sys_days{chr::year{2023} / chr::January / 1} + chr::minutes{30};
    for (int h = 0; h < 8760; ++h) times.push_back(start + chr::hours{h});
    return times;
}

void bm_sun_position(benchmark::State& state, lidarfx::sun_model model)
{
    const auto times = hours_of_a_year();
    const lidarfx::sun_position_options opt{.model = model, .elevation_m = 200.0};
    for (auto _ : state) {
        for (const auto t : times) benchmark::DoNotOptimize(lidarfx::sun_position(t, 48.2, 16.4, opt));
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(times.size()));
}
BENCHMARK_CAPTURE(bm_sun_position, spa, lidarfx::sun_model::spa)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(bm_sun_position, simple, lidarfx::sun_model::simple)->Unit(benchmark::kMillisecond);

// A year of hourly records (8760, about 4400 with the sun up, as a TMY3 year) on an n x n box town at 1 m
// cells, one building per 1,750 m^2 (600 on 1024^2), SVF included. Arguments: n, threads (0 = all cores), shadow
// line families (4 = default, 1 = the dissertation's single family).
void bm_irradiance_year(benchmark::State& state)
{
    const auto n = state.range(0);
    std::mt19937 rng(20261202);
    const auto z = reference::box_town(rng, n, n, static_cast<int>(n * n / 1750), 0.3, 8, 30);
    const auto records = lidarfx::clear_sky_records(2023, 36.1, -79.9);
    lidarfx::irradiance_maps_options opt{.run = {.threads = static_cast<int>(state.range(1))}};
    opt.shadow_line_phases = static_cast<int>(state.range(2));
    for (auto _ : state) {
        auto maps = lidarfx::irradiance_maps(z, 1.0, {36.1, -79.9}, records, {}, {}, opt);
        benchmark::DoNotOptimize(maps.annual_kwh_m2.data());
        state.counters["sun_up_records"] = static_cast<double>(maps.sun_up_records);
    }
    state.SetItemsProcessed(state.iterations() * n * n);
}
BENCHMARK(bm_irradiance_year)
    ->ArgsProduct({{1024}, {1, 0}, {4, 1}})
    ->ArgNames({"n", "threads", "phases"})
    ->Iterations(1)
    ->UseRealTime()
    ->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
