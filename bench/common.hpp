// SPDX-License-Identifier: Apache-2.0
// Shared input generators for the benchmarks: deterministic, built outside the timed loops.
// Inputs can also be loaded from raw files written by the peer scripts (bench/peers/), so that lidarfx
// and its peers time the very same cells: set LIDARFX_BENCH_INPUT_DIR to the folder holding them.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>

#include <lidarfx/core/raster.hpp>

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
                                                    std::cos(0.013 * static_cast<double>(c))) + noise(rng);
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

}  // namespace bench
