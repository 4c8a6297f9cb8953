// SPDX-License-Identifier: Apache-2.0
// Benchmarks of the buildings pipeline's energy part: a year of hourly clear-sky records on a synthetic town of
// 1,000 box buildings (1024 x 1024 cells of 1 m): facade_lit for one sun position, facade_sky_view (72 sweeps) and
// surface_energy for the whole year (roof patches and facade sub-patches).
#include <benchmark/benchmark.h>

#include <lidarfx/kernels/solar/clear_sky.hpp>
#include <lidarfx/pipelines/buildings/facade_lit.hpp>
#include <lidarfx/pipelines/buildings/facade_patches.hpp>
#include <lidarfx/pipelines/buildings/facade_sky_view.hpp>
#include <lidarfx/pipelines/buildings/surface_energy.hpp>

#include <cstddef>
#include <cstdint>
#include <random>

namespace {

struct town {
    lidarfx::raster<float> dsm;
    lidarfx::raster<std::int32_t> ids;
};

/// 1,000 box buildings, one per 32 x 32 m lot of a 32 x 32 lot grid (the last 24 lots stay empty), each 8..22 m a
/// side and 6..30 m tall, on flat ground at 100 m with 0.2 m of noise.
const town& thousand_buildings()
{
    static const town t = [] {
        const std::ptrdiff_t n = 1024, lot = 32;
        town s{lidarfx::raster<float>(n, n), lidarfx::raster<std::int32_t>(n, n, 0)};
        std::mt19937 rng(2026);
        std::uniform_real_distribution<double> noise(0.0, 0.2), height(6.0, 30.0);
        std::uniform_int_distribution<std::ptrdiff_t> side(8, 22);
        for (std::ptrdiff_t r = 0; r < n; ++r)
            for (std::ptrdiff_t c = 0; c < n; ++c) s.dsm(r, c) = static_cast<float>(100.0 + noise(rng));
        for (std::int32_t b = 0; b < 1000; ++b) {
            const std::ptrdiff_t r0 = (b / 32) * lot + 2, c0 = (b % 32) * lot + 2, h = side(rng), w = side(rng);
            const auto top = static_cast<float>(100.0 + height(rng));
            for (std::ptrdiff_t r = r0; r < r0 + h; ++r)
                for (std::ptrdiff_t c = c0; c < c0 + w; ++c) {
                    s.dsm(r, c) = top;
                    s.ids(r, c) = b + 1;
                }
        }
        return s;
    }();
    return t;
}

void bm_facade_lit(benchmark::State& state)
{
    const town& t = thousand_buildings();
    const auto subs = lidarfx::facade_patches(t.dsm, t.ids, 1.0);
    const int threads = static_cast<int>(state.range(0));
    for (auto _ : state) {
        benchmark::DoNotOptimize(lidarfx::facade_lit(t.dsm, subs, 1.0, 150.0, 35.0, {.run = {.threads = threads}}));
    }
    state.counters["sub_patches"] = static_cast<double>(subs.size());
}
BENCHMARK(bm_facade_lit)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

void bm_facade_sky_view(benchmark::State& state)
{
    const town& t = thousand_buildings();
    const auto subs = lidarfx::facade_patches(t.dsm, t.ids, 1.0);
    const int threads = static_cast<int>(state.range(0));
    for (auto _ : state) {
        benchmark::DoNotOptimize(lidarfx::facade_sky_view(t.dsm, subs, 1.0, {.run = {.threads = threads}}));
    }
}
BENCHMARK(bm_facade_sky_view)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->Iterations(1);

void bm_surface_energy_year(benchmark::State& state)
{
    const town& t = thousand_buildings();
    const auto records = lidarfx::clear_sky_records(2023, 40.0, -75.2);
    const int threads = static_cast<int>(state.range(0));
    std::size_t roofs = 0, facades = 0, daylight = 0;
    for (auto _ : state) {
        const auto res =
            lidarfx::surface_energy(t.dsm, t.ids, 1.0, {40.0, -75.2, -5.0}, records, {.run = {.threads = threads}});
        roofs = res.roofs.size();
        facades = res.facades.size();
        daylight = res.sun_up_records;
        benchmark::DoNotOptimize(res.facade_energy.data());
    }
    state.counters["roof_patches"] = static_cast<double>(roofs);
    state.counters["sub_patches"] = static_cast<double>(facades);
    state.counters["daylight_hours"] = static_cast<double>(daylight);
}
BENCHMARK(bm_surface_energy_year)->Arg(1)->Arg(2)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
