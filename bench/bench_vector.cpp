// SPDX-License-Identifier: Apache-2.0
// polygonize on a 2048 x 2048 label raster of four bands, each riddled with holes: every hole is a ring of
// background cells around a one-cell island of the band's label, so a label has as many exterior rings
// as holes. The hole assignment is a single sweep (time grows with the raster and the boundary length);
// the reference tests each hole against every exterior ring of its label (time grows with holes²).
#include <benchmark/benchmark.h>

#include <lidarfx/kernels/vector/polygonize.hpp>

#include "reference/polygonize.hpp"

#include <cmath>
#include <cstdint>
#include <random>

namespace {

/// n x n labels in four vertical bands (1..4) with about `holes` holes on a jittered lattice.
lidarfx::raster<std::int32_t> holed_bands(std::ptrdiff_t n, std::ptrdiff_t holes, unsigned seed)
{
    lidarfx::raster<std::int32_t> l(n, n);
    for (std::ptrdiff_t r = 0; r < n; ++r)
        for (std::ptrdiff_t c = 0; c < n; ++c) l(r, c) = static_cast<std::int32_t>(1 + 4 * c / n);
    if (holes <= 0) return l;
    const auto per_side = static_cast<std::ptrdiff_t>(std::ceil(std::sqrt(static_cast<double>(holes))));
    const std::ptrdiff_t spacing = n / per_side;  // >= 5: a 3x3 hole, jitter 0..spacing-5, a band of land
    std::mt19937 rng(seed);
    for (std::ptrdiff_t i = 0; i < per_side; ++i) {
        for (std::ptrdiff_t j = 0; j < per_side && i * per_side + j < holes; ++j) {
            const auto r0 = i * spacing + 1 + static_cast<std::ptrdiff_t>(rng() % static_cast<unsigned>(spacing - 4));
            const auto c0 = j * spacing + 1 + static_cast<std::ptrdiff_t>(rng() % static_cast<unsigned>(spacing - 4));
            const auto island = l(r0 + 1, c0 + 1);
            for (std::ptrdiff_t r = r0; r < r0 + 3; ++r)
                for (std::ptrdiff_t c = c0; c < c0 + 3; ++c) l(r, c) = 0;
            l(r0 + 1, c0 + 1) = island;
        }
    }
    return l;
}

std::size_t count_holes(const std::vector<lidarfx::label_polygons>& polys)
{
    std::size_t n = 0;
    for (const auto& lp : polys)
        for (const auto& p : lp.polygons) n += p.rings.size() - 1;
    return n;
}

/// Times `outline` (polygonize or the quadratic baseline) on a holed n x n raster.
template <class Outline>
void time_outlines(benchmark::State& state, Outline outline)
{
    const auto n = state.range(0);
    const auto labels = holed_bands(n, state.range(1), 7);
    const lidarfx::grid g{0.0, static_cast<double>(n), 1.0, n, n};
    std::size_t holes = 0;
    for (auto _ : state) {
        const auto polys = outline(labels.view(), g);
        holes = count_holes(polys);
        benchmark::DoNotOptimize(polys.data());
    }
    state.SetItemsProcessed(state.iterations() * n * n);
    state.counters["holes"] = static_cast<double>(holes);
}

void bm_polygonize(benchmark::State& state)
{
    time_outlines(state, [](const auto& labels, const lidarfx::grid& g) { return lidarfx::polygonize(labels, g); });
}

/// Baseline: the first implementation (even-odd test of each hole against the exteriors of its label).
void bm_polygonize_quadratic(benchmark::State& state)
{
    time_outlines(
        state, [](const auto& labels, const lidarfx::grid& g) { return reference::polygonize_quadratic(labels, g); });
}

}  // namespace

// Arguments: side n, number of holes.
BENCHMARK(bm_polygonize)->ArgsProduct({{2048}, {0, 1000, 10000, 30000, 100000}})->Unit(benchmark::kMillisecond);
BENCHMARK(bm_polygonize_quadratic)->ArgsProduct({{2048}, {1000, 3000, 10000, 30000}})->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
