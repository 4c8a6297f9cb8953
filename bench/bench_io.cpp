// SPDX-License-Identifier: Apache-2.0
// LAS reading speed: lidarfx::io::las_reader (block reads, fixed-offset decode) against a naive
// record-by-record reader, on files written by las_writer (warm in the page cache after the first pass);
// LAZ decoding speed on 1 and 2 threads, on PDAL's autzen_trim.laz (format 3) and lone-star.copc.laz
// (format 6) when LIDARFX_PDAL_DATA names PDAL's test/data folder, else on the committed fixtures.
#include <benchmark/benchmark.h>

#include <unistd.h>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <string>

#include "io/las.hpp"
#include "io/las_writer.hpp"

namespace {

/// Writes (once per run) a file of n random points in `format`; removed when the program ends.
class bench_files {
public:
    ~bench_files()
    {
        for (const auto& [key, path] : paths_) std::filesystem::remove(path);
    }
    const std::string& get(int format, std::size_t n)
    {
        auto& path = paths_[{format, n}];
        if (!path.empty()) return path;
        path = (std::filesystem::temp_directory_path() / ("lidarfx_bench_io_" + std::to_string(::getpid()) + "_" +
                                                          std::to_string(format) + "_" + std::to_string(n) + ".las"))
                   .string();
        lidarfx::io::las_writer w(path,
                                  {.version_minor = 4, .point_format = format, .offset = std::array<double, 3>{}});
        std::mt19937 rng(11);
        std::uniform_real_distribution<double> xy(0.0, 1000.0), z(0.0, 80.0);
        lidarfx::io::las_points chunk;
        for (std::size_t done = 0; done < n;) {
            const std::size_t k = std::min<std::size_t>(1 << 20, n - done);
            chunk.resize(k, lidarfx::io::las_format_has_gps_time(format));
            for (std::size_t i = 0; i < k; ++i) {
                chunk.x[i] = xy(rng);
                chunk.y[i] = xy(rng);
                chunk.z[i] = z(rng);
                chunk.intensity[i] = static_cast<std::uint16_t>(rng());
                chunk.return_number[i] = 1;
                chunk.number_of_returns[i] = 1;
            }
            w.write(chunk);
            done += k;
        }
        w.close();
        return path;
    }

private:
    std::map<std::pair<int, std::size_t>, std::string> paths_;
};

bench_files files;

void bm_las_read(benchmark::State& state)
{
    const int format = static_cast<int>(state.range(0));
    const auto n = static_cast<std::size_t>(state.range(1));
    const std::string& path = files.get(format, n);
    lidarfx::io::las_points chunk;
    for (auto _ : state) {
        lidarfx::io::las_reader r(path);
        std::size_t total = 0;
        while (const std::size_t k = r.read(chunk, 1 << 20)) total += k;
        benchmark::DoNotOptimize(chunk.x.data());
        if (total != n) state.SkipWithError("wrong point count");
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(n));
    state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(std::filesystem::file_size(path)));
}

/// Baseline: one stream read per record, fields unpacked one by one (format 0–5 layout).
void bm_las_read_naive(benchmark::State& state)
{
    const int format = static_cast<int>(state.range(0));
    const auto n = static_cast<std::size_t>(state.range(1));
    const std::string& path = files.get(format, n);
    const lidarfx::io::las_header h = lidarfx::io::las_reader(path).header();
    std::vector<double> x(n), y(n), z(n);
    std::vector<std::uint16_t> intensity(n);
    for (auto _ : state) {
        std::ifstream in(path, std::ios::binary);
        in.seekg(h.offset_to_point_data);
        char record[256];
        for (std::size_t i = 0; i < n; ++i) {
            in.read(record, h.point_record_length);
            std::int32_t q[3];
            std::memcpy(q, record, 12);
            x[i] = q[0] * h.scale[0] + h.offset[0];
            y[i] = q[1] * h.scale[1] + h.offset[1];
            z[i] = q[2] * h.scale[2] + h.offset[2];
            std::memcpy(&intensity[i], record + 12, 2);
        }
        benchmark::DoNotOptimize(x.data());
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(n));
    state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(std::filesystem::file_size(path)));
}

void bm_las_write(benchmark::State& state)
{
    const int format = static_cast<int>(state.range(0));
    const auto n = static_cast<std::size_t>(state.range(1));
    const lidarfx::io::las_points points = lidarfx::io::read_las(files.get(format, n));
    const std::string path = files.get(format, n) + ".out";
    for (auto _ : state) lidarfx::io::write_las(path, points, {.version_minor = 4, .point_format = format});
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(n));
    state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(std::filesystem::file_size(path)));
    std::filesystem::remove(path);
}

/// The LAZ file of benchmark argument `which` (0: point formats 0–3, 1: formats 6–8).
std::string laz_file(int which)
{
    const char* pdal = std::getenv("LIDARFX_PDAL_DATA");
    const std::string big = which == 0 ? "laz/autzen_trim.laz" : "copc/lone-star.copc.laz";
    if (pdal != nullptr && std::filesystem::exists(std::string(pdal) + "/" + big)) return std::string(pdal) + "/" + big;
    const auto fixtures = std::filesystem::path(__FILE__).parent_path().parent_path() / "tests" / "data";
    return (fixtures / (which == 0 ? "simple.laz" : "1.2-with-color.copc.laz")).string();
}

/// LAZ decoding into las_points (all fields), read in chunks of 2^20 points on range(1) threads.
void bm_laz_read(benchmark::State& state)
{
    const std::string path = laz_file(static_cast<int>(state.range(0)));
    const int threads = static_cast<int>(state.range(1));
    lidarfx::io::las_points chunk;
    std::uint64_t n = 0;
    for (auto _ : state) {
        lidarfx::io::las_reader r(path);
        r.set_threads(threads);
        n = 0;
        while (const std::size_t k = r.read(chunk, 1 << 20)) n += k;
        benchmark::DoNotOptimize(chunk.x.data());
    }
    state.SetLabel(std::filesystem::path(path).filename().string());
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(n));
    state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(std::filesystem::file_size(path)));
}

}  // namespace

BENCHMARK(bm_laz_read)->ArgsProduct({{0, 1}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(bm_las_read)->ArgsProduct({{0, 1, 6}, {5'000'000}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(bm_las_read_naive)->ArgsProduct({{0}, {5'000'000}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(bm_las_write)->ArgsProduct({{0, 6}, {2'000'000}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
