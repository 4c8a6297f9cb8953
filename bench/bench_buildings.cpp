// SPDX-License-Identifier: Apache-2.0
// extract_buildings on a square surface model of buildings on rolling ground (1 m cells), side as argument.
#include <benchmark/benchmark.h>

#include <lidarfx/pipelines/buildings/extract_buildings.hpp>

#include <cmath>
#include <cstdint>

namespace {

/// A side x side DSM: gentle terrain with a gable building (12 x 20 m, 30 deg) every 40 m.
lidarfx::raster<float> town_dsm(std::ptrdiff_t side)
{
    lidarfx::raster<float> z(side, side);
    for (std::ptrdiff_t r = 0; r < side; ++r) {
        for (std::ptrdiff_t c = 0; c < side; ++c) {
            double v = 50.0 + 2.0 * std::sin(static_cast<double>(r) / 150.0) * std::cos(static_cast<double>(c) / 170.0);
            const std::ptrdiff_t lr = r % 40, lc = c % 40;
            if (lr >= 10 && lr < 30 && lc >= 14 && lc < 26) {
                const double to_edge = std::min(static_cast<double>(lc - 14) + 0.5, static_cast<double>(26 - lc) - 0.5);
                v += 6.0 + std::tan(30.0 * 3.14159265358979 / 180.0) * to_edge;
            }
            z(r, c) = static_cast<float>(v);
        }
    }
    return z;
}

void extraction(benchmark::State& state)
{
    const auto side = static_cast<std::ptrdiff_t>(state.range(0));
    const auto z = town_dsm(side);
    lidarfx::extract_buildings_options opt;
    opt.run.threads = static_cast<int>(state.range(1));
    const lidarfx::grid g{0.0, static_cast<double>(z.rows()), 1.0, z.rows(), z.cols()};  // 1 m cells
    std::size_t found = 0;
    for (auto _ : state) {
        const auto b = lidarfx::extract_buildings(z, g, opt);
        found = b.buildings.size();
        benchmark::DoNotOptimize(found);
    }
    state.counters["buildings"] = static_cast<double>(found);
    state.counters["Mcells/s"] =
        benchmark::Counter(static_cast<double>(side * side) * 1e-6, benchmark::Counter::kIsIterationInvariantRate);
}

}  // namespace

BENCHMARK(extraction)->Args({512, 1})->Args({2048, 1})->Args({2048, 2})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
