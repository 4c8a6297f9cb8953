// SPDX-License-Identifier: Apache-2.0
// Benchmarks of the solar kernels: sun_position by SPA and by the dissertation's simple model, in positions per
// second over the hours of a year (a TMY year needs 8760 of them, so either model costs well under a millisecond).
#include <benchmark/benchmark.h>

#include <lidarfx/kernels/solar/sun_position.hpp>

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

}  // namespace

BENCHMARK_MAIN();
