// SPDX-License-Identifier: Apache-2.0
// Rooftop PV: roof_suitability in planes and paper mode on randomized roof towns (synth/roof_towns.hpp) at
// 1 m cells, up to 10,000 buildings on 4100 x 4100 cells.
#include <benchmark/benchmark.h>

#include <map>

#include <lidarfx/pipelines/pv/roof_suitability.hpp>
#include <lidarfx/synth/roof_towns.hpp>

namespace {

/// A town of `buildings` houses, 41 m apart (10,000 houses: 4100 x 4100 cells), built once per size.
const lidarfx::synth::roof_town& town(int buildings)
{
    static std::map<int, lidarfx::synth::roof_town> cache;
    auto it = cache.find(buildings);
    if (it == cache.end()) {
        lidarfx::synth::roof_town_options o;
        o.seed = 11;
        o.buildings = buildings;
        o.spacing_m = 41;
        it = cache.emplace(buildings, lidarfx::synth::make_roof_town(o)).first;
    }
    return it->second;
}

void bm_roof_suitability(benchmark::State& state, lidarfx::roof_mode mode)
{
    const auto& t = town(static_cast<int>(state.range(0)));
    lidarfx::roof_suitability_options o;
    o.mode = mode;
    o.run.threads = static_cast<int>(state.range(1));
    std::size_t patches = 0;
    for (auto _ : state) {
        const auto r = lidarfx::roof_suitability(t.dsm, t.dtm, t.building_id, t.g, o);
        patches = r.patches.size();
        benchmark::DoNotOptimize(r.patch_id.view().row(0));
    }
    state.SetItemsProcessed(state.iterations() * t.g.rows * t.g.cols);
    state.counters["cells"] = static_cast<double>(t.g.rows * t.g.cols);
    state.counters["buildings"] = static_cast<double>(t.buildings.size());
    state.counters["patches"] = static_cast<double>(patches);
}

}  // namespace

BENCHMARK_CAPTURE(bm_roof_suitability, planes, lidarfx::roof_mode::planes)
    ->ArgsProduct({{400, 10000}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(bm_roof_suitability, paper, lidarfx::roof_mode::paper)
    ->ArgsProduct({{10000}, {1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

BENCHMARK_MAIN();
