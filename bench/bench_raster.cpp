// SPDX-License-Identifier: Apache-2.0
// Benchmarks of the point-to-raster algorithms: rasterize (10^7 points, 2 m cells) and idw_fill (2048^2
// cells, 30 % holes in blobs). With LIDARFX_BENCH_INPUT_DIR set, the inputs are the raw files written by
// bench/peers/peer_raster.py (points_{x,y,z}.raw float64, points_intensity.raw uint16,
// points_returns.raw uint8, idw_z.raw float32), so lidarfx and NumPy/SciPy time the same data.
#include <benchmark/benchmark.h>

#include <lidarfx/kernels/interpolate/idw_fill.hpp>
#include <lidarfx/kernels/points/rasterize.hpp>

#include "common.hpp"
#include "reference/idw.hpp"
#include "reference/rasterize.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <random>
#include <string>
#include <vector>

namespace {

constexpr std::ptrdiff_t points_n = 10'000'000;
constexpr double cell_m = 2.0;
constexpr std::ptrdiff_t idw_n = 2048;

/// A survey in acquisition order: flight strips along y, zigzag scan lines across each strip.
struct survey {
    std::vector<double> x, y, z;
    std::vector<std::uint16_t> intensity;
    std::vector<std::uint8_t> returns;
    lidarfx::soa_cloud<> cloud() const { return {x, y, z, intensity, {}, returns}; }
};

survey generate_survey(std::ptrdiff_t n)
{
    // 4 strips of 500 m (+5 % side overlap) over 2000 m x 2000 m, scan lines 0.5 m apart.
    constexpr int strips = 4;
    constexpr double width = 500.0, length = 2000.0, spacing = 0.5, x_origin = 500000.0, y_origin = 4200000.0;
    const auto lines = static_cast<std::ptrdiff_t>(length / spacing) * strips;
    const std::ptrdiff_t per_line = n / lines + 1;
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> jitter(-0.2, 0.2), unit(0.0, 1.0);
    survey s;
    for (auto* v : {&s.x, &s.y, &s.z}) v->reserve(static_cast<std::size_t>(n));
    for (std::ptrdiff_t k = 0; static_cast<std::ptrdiff_t>(s.x.size()) < n; ++k) {
        const auto strip = static_cast<double>((k / (lines / strips)) % strips);
        const double y = y_origin + spacing * static_cast<double>(k % (lines / strips));
        for (std::ptrdiff_t j = 0; j < per_line && static_cast<std::ptrdiff_t>(s.x.size()) < n; ++j) {
            const double t = (static_cast<double>(j) + 0.5) / static_cast<double>(per_line);
            const double across = (k % 2 ? 1.0 - t : t) * width * 1.1 - 0.05 * width;
            const double x = x_origin + strip * width + across + jitter(rng);
            const double ground = 100.0 + 10.0 * std::sin(x * 0.003) * std::cos(y * 0.002);
            const bool tree = unit(rng) < 0.2;
            s.x.push_back(x);
            s.y.push_back(y + jitter(rng));
            s.z.push_back(ground + (tree ? 15.0 * unit(rng) : 0.05 * jitter(rng)));
            s.intensity.push_back(static_cast<std::uint16_t>(unit(rng) * 4000.0));
            s.returns.push_back(static_cast<std::uint8_t>(tree ? 2 : 1));
        }
    }
    return s;
}

template <class T>
std::vector<T> load_vector(const std::string& dir, const std::string& name, std::ptrdiff_t n)
{
    const auto r = bench::load_raw<T>(dir + "/points_" + name + ".raw", 1, n);
    return {r.data(), r.data() + n};
}

const survey& points()
{
    static const survey s = [] {
        const std::string dir = bench::input_dir();
        if (dir.empty()) return generate_survey(points_n);
        return survey{load_vector<double>(dir, "x", points_n), load_vector<double>(dir, "y", points_n),
                      load_vector<double>(dir, "z", points_n), load_vector<std::uint16_t>(dir, "intensity", points_n),
                      load_vector<std::uint8_t>(dir, "returns", points_n)};
    }();
    return s;
}

/// The same points in random order (worst case for cache locality).
const survey& shuffled_points()
{
    static const survey s = [] {
        const survey& p = points();
        std::vector<std::size_t> order(p.x.size());
        std::iota(order.begin(), order.end(), std::size_t{0});
        std::shuffle(order.begin(), order.end(), std::mt19937(7));
        survey out;
        for (std::size_t i : order) {
            out.x.push_back(p.x[i]);
            out.y.push_back(p.y[i]);
            out.z.push_back(p.z[i]);
            out.intensity.push_back(p.intensity[i]);
            out.returns.push_back(p.returns[i]);
        }
        return out;
    }();
    return s;
}

lidarfx::grid survey_grid(const survey& s)
{
    return lidarfx::snapped_grid(lidarfx::bounds_of(s.cloud()), cell_m);
}

/// Elevation with 30 % NaN cells in round blobs of radius 2..40 cells (dropout patches, lakes).
lidarfx::raster<float> holes_raster(std::ptrdiff_t n, unsigned seed, double share = 0.3)
{
    auto z = bench::random_terrain(n, n, seed);
    std::mt19937 rng(seed);
    std::uniform_int_distribution<std::ptrdiff_t> at(0, n - 1);
    std::uniform_real_distribution<double> radius(2.0, 40.0);
    std::ptrdiff_t holes = 0;
    while (static_cast<double>(holes) < share * static_cast<double>(n * n)) {
        const auto r0 = at(rng), c0 = at(rng);
        const double rad = radius(rng);
        const auto k = static_cast<std::ptrdiff_t>(rad);
        for (auto r = std::max<std::ptrdiff_t>(0, r0 - k); r <= std::min(n - 1, r0 + k); ++r) {
            for (auto c = std::max<std::ptrdiff_t>(0, c0 - k); c <= std::min(n - 1, c0 + k); ++c) {
                const auto dr = static_cast<double>(r - r0), dc = static_cast<double>(c - c0);
                if (dr * dr + dc * dc <= rad * rad && !std::isnan(z(r, c))) {
                    z(r, c) = std::numeric_limits<float>::quiet_NaN();
                    ++holes;
                }
            }
        }
    }
    return z;
}

const lidarfx::raster<float>& idw_input()
{
    static const lidarfx::raster<float> z = [] {
        const std::string dir = bench::input_dir();
        if (dir.empty()) return holes_raster(idw_n, 11);
        return bench::load_raw<float>(dir + "/idw_z.raw", idw_n, idw_n);
    }();
    return z;
}

void bm_rasterize(benchmark::State& state, const survey& s)
{
    const auto cloud = s.cloud();
    const auto g = survey_grid(s);
    const int threads = static_cast<int>(state.range(0));
    for (auto _ : state) {
        auto out = lidarfx::rasterize(cloud, g, {.run = {.threads = threads}});
        benchmark::DoNotOptimize(out.count.data());
    }
    state.counters["cells"] = static_cast<double>(g.size());
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(s.x.size()));
}

void bm_rasterize_scan_order(benchmark::State& state)
{
    bm_rasterize(state, points());
}
void bm_rasterize_shuffled(benchmark::State& state)
{
    bm_rasterize(state, shuffled_points());
}

/// A sparse survey: 1,000 points spread over 5 km x 5 km, 1 m cells (25 M cells). The accumulator holds
/// only the tiles the points fall in; the time is mostly writing the six 25 M-cell rasters of the result.
void bm_rasterize_sparse(benchmark::State& state)
{
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(0.0, 5000.0);
    std::vector<double> x, y, z;
    for (int i = 0; i < 1000; ++i) {
        x.push_back(400000.0 + u(rng));
        y.push_back(5000000.0 + u(rng));
        z.push_back(100.0 + u(rng) / 50.0);
    }
    const lidarfx::soa_cloud<> cloud(x, y, z);
    const auto g = lidarfx::snapped_grid(lidarfx::bounds_of(cloud), 1.0);
    for (auto _ : state) {
        auto out = lidarfx::rasterize(cloud, g);
        benchmark::DoNotOptimize(out.count.data());
    }
    state.counters["cells"] = static_cast<double>(g.size());
}

void bm_rasterize_reference(benchmark::State& state)
{
    const auto cloud = points().cloud();
    const auto g = survey_grid(points());
    for (auto _ : state) {
        auto out = reference::rasterize(cloud, g);
        benchmark::DoNotOptimize(out.count.data());
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(cloud.size()));
}

void bm_bounds_of(benchmark::State& state)
{
    const auto cloud = points().cloud();
    for (auto _ : state) benchmark::DoNotOptimize(lidarfx::bounds_of(cloud));
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(cloud.size()));
}

void bm_idw_fill(benchmark::State& state)
{
    const auto& z = idw_input();
    const auto n = z.rows();
    lidarfx::raster<float> out(n, n);
    const lidarfx::idw_fill_options opt{.k = static_cast<int>(state.range(1)),
                                        .run = {.threads = static_cast<int>(state.range(2))}};
    for (auto _ : state) {
        lidarfx::idw_fill(z, out, cell_m, opt);
        benchmark::DoNotOptimize(out.data());
    }
    state.SetItemsProcessed(state.iterations() * n * n);
}

void bm_idw_fill_reference(benchmark::State& state)
{
    const auto n = state.range(0);
    const auto z = holes_raster(n, 11);
    for (auto _ : state) {
        auto out = reference::idw_fill(z.view(), cell_m, {.k = 8});
        benchmark::DoNotOptimize(out.data());
    }
    state.SetItemsProcessed(state.iterations() * n * n);
}

}  // namespace

BENCHMARK(bm_rasterize_scan_order)->ArgName("threads")->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(bm_rasterize_shuffled)->ArgName("threads")->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(bm_rasterize_sparse)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(bm_rasterize_reference)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(bm_bounds_of)->Unit(benchmark::kMillisecond);
BENCHMARK(bm_idw_fill)
    ->ArgNames({"n", "k", "threads"})
    ->ArgsProduct({{idw_n}, {8}, {1, 0}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(bm_idw_fill)
    ->ArgNames({"n", "k", "threads"})
    ->Args({idw_n, 1, 1})
    ->Args({idw_n, 32, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(bm_idw_fill_reference)->Arg(128)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
