// SPDX-License-Identifier: Apache-2.0
// Shared input generators for the benchmarks: deterministic, built outside the timed loops.
// Inputs can also be loaded from raw files written by the peer scripts (bench/peers/), so that lidarfx
// and its peers time the very same cells: set LIDARFX_BENCH_INPUT_DIR to the folder holding them.
// Every program that includes this header prints, in Google Benchmark's context, the CPU model, its vector
// extensions, the extensions the build targets and the build flags (see build_context below).
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>

#include <benchmark/benchmark.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <lidarfx/core/raster.hpp>

#ifndef LIDARFX_BENCH_FLAGS
#define LIDARFX_BENCH_FLAGS "unknown (not set by bench/CMakeLists.txt)"
#endif

namespace bench {

/// Smooth random terrain (sum of a few sines) plus noise, metres.
inline lidarfx::raster<float> random_terrain(std::ptrdiff_t rows, std::ptrdiff_t cols, unsigned seed)
{
    std::mt19937 rng(seed);
    std::normal_distribution<float> noise(0.0f, 0.05f);
    lidarfx::raster<float> z(rows, cols);
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c)
            z(r, c) = static_cast<float>(20.0 + 5.0 * std::sin(0.01 * static_cast<double>(r)) *
                                                    std::cos(0.013 * static_cast<double>(c))) +
                      noise(rng);
    return z;
}

/// Random 0/1 mask with the given share of ones.
inline lidarfx::raster<std::uint8_t> random_mask(std::ptrdiff_t rows, std::ptrdiff_t cols, unsigned seed,
                                                 double ones = 0.5)
{
    std::mt19937 rng(seed);
    std::bernoulli_distribution b(ones);
    lidarfx::raster<std::uint8_t> m(rows, cols);
    for (auto& v : m) v = b(rng) ? 1 : 0;
    return m;
}

/// Folder of shared raw inputs, or empty when LIDARFX_BENCH_INPUT_DIR is unset.
inline std::string input_dir()
{
    const char* dir = std::getenv("LIDARFX_BENCH_INPUT_DIR");
    return dir ? std::string(dir) : std::string();
}

/// Loads rows*cols raw native-endian T values from `path` into a raster (peer scripts write them with
/// numpy's ndarray.tofile). @throws std::runtime_error if the file is missing or has the wrong size.
template <class T>
lidarfx::raster<T> load_raw(const std::string& path, std::ptrdiff_t rows, std::ptrdiff_t cols)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": cannot open");
    lidarfx::raster<T> out(rows, cols);
    in.read(reinterpret_cast<char*>(out.data()), static_cast<std::streamsize>(sizeof(T) * out.size()));
    if (in.gcount() != static_cast<std::streamsize>(sizeof(T) * out.size()))
        throw std::runtime_error(path + ": too short");
    return out;
}

/// The value of the first /proc/cpuinfo line starting with `key` (e.g. "model name"), or "" off Linux.
inline std::string cpuinfo_field(const std::string& key)
{
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind(key, 0) == 0) {
            const auto colon = line.find(':');
            return colon == std::string::npos ? std::string() : line.substr(colon + 2);
        }
    }
    return {};
}

/// The vector extensions among the CPU's flags (/proc/cpuinfo), in a fixed order: what the machine offers.
inline std::string cpu_vector_extensions()
{
    std::istringstream flags(" " + cpuinfo_field("flags") + " ");
    const std::string all = flags.str();
    std::string out;
    for (const char* f : {"sse2", "sse4_2", "avx", "avx2", "fma", "bmi2", "avx512f", "avx512dq", "avx512cd", "avx512bw",
                          "avx512vl", "avx512_vnni", "avx512_bf16", "avx512_vbmi2", "asimd", "sve"}) {
        if (all.find(" " + std::string(f) + " ") != std::string::npos) out += (out.empty() ? "" : " ") + std::string(f);
    }
    return out;
}

/// The vector extensions this build may use (the compiler's predefined macros): what the code targets.
inline std::string build_vector_extensions()
{
    std::string out = "sse2";
#ifdef __SSE4_2__
    out += " sse4_2";
#endif
#ifdef __AVX__
    out += " avx";
#endif
#ifdef __AVX2__
    out += " avx2";
#endif
#ifdef __FMA__
    out += " fma";
#endif
#ifdef __AVX512F__
    out += " avx512f";
#endif
#ifdef __AVX512BW__
    out += " avx512bw";
#endif
#ifdef __AVX512VL__
    out += " avx512vl";
#endif
#if defined(__aarch64__)
    out = "asimd";
#endif
    return out;
}

/// Adds cpu_model, cpu_vector_extensions, build_vector_extensions, compiler and build_flags to Google
/// Benchmark's context (printed before the results and stored in --benchmark_format=json output).
inline bool add_build_context()
{
    benchmark::AddCustomContext("cpu_model", cpuinfo_field("model name"));
    benchmark::AddCustomContext("cpu_vector_extensions", cpu_vector_extensions());
    benchmark::AddCustomContext("hardware_threads", std::to_string(std::thread::hardware_concurrency()));
    benchmark::AddCustomContext("build_vector_extensions", build_vector_extensions());
#ifdef __VERSION__
    benchmark::AddCustomContext("compiler", __VERSION__);
#endif
    benchmark::AddCustomContext("build_flags", LIDARFX_BENCH_FLAGS);
    // LIDARFX_BENCH_KEEP_FREED_MEMORY=1: the allocator settings of the lidarfx program (examples/cli,
    // keep_freed_memory), under which freed rasters are reused instead of coming back as fresh pages.
    const char* keep = std::getenv("LIDARFX_BENCH_KEEP_FREED_MEMORY");
    bool kept = false;
#if defined(__GLIBC__)
    if (keep && std::string(keep) == "1") {
        mallopt(M_MMAP_THRESHOLD, 512 << 20);
        mallopt(M_TRIM_THRESHOLD, 1 << 30);
        kept = true;
    }
#endif
    benchmark::AddCustomContext("allocator",
                                kept ? "freed blocks < 512 MiB kept (as the lidarfx program)" : "glibc defaults");
    return true;
}

/// Runs add_build_context once per program, before BENCHMARK_MAIN's main() starts.
inline const bool build_context_added = add_build_context();

}  // namespace bench
