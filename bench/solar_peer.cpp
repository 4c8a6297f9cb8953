// SPDX-License-Identifier: Apache-2.0
// lidarfx's side of bench/peers/grass_solar.sh: writes the box town of bench/bench_shadow.cpp as raw float32,
// and runs raylines_shadow or horizon_map on such a file, timing the kernel alone (best of REPEAT runs; the
// file's reading and writing are not timed, as GRASS's import and export are not) and writing its output raw.
//
// Usage:
//   solar_peer town N OUT.f32                                      N x N town, 1 m cells, row 0 north
//   solar_peer shadow IN.f32 N AZ_DEG EL_DEG THREADS REPEAT OUT.u8  1 = lit, 0 = shadow
//   solar_peer horizon IN.f32 N AZ_DEG THREADS REPEAT OUT.f32       horizon angle in degrees
// Azimuths clockwise from north. Prints "seconds S" (the best kernel time) and "cells_per_s R".
#include <lidarfx/kernels/solar/horizon_map.hpp>
#include <lidarfx/kernels/solar/raylines_shadow.hpp>

#include "reference/solar.hpp"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

namespace {

lidarfx::raster<float> read_f32(const std::string& path, std::ptrdiff_t n)
{
    lidarfx::raster<float> z(n, n);
    std::ifstream in(path, std::ios::binary);
    in.read(reinterpret_cast<char*>(z.data()), static_cast<std::streamsize>(n * n * sizeof(float)));
    if (!in)
        throw std::runtime_error(path + ": cannot read " + std::to_string(n) + " x " + std::to_string(n) +
                                 " float32 cells (give the side N the file was written with)");
    return z;
}

template <class T>
void write_raw(const std::string& path, const lidarfx::raster<T>& r)
{
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(r.data()), static_cast<std::streamsize>(r.rows() * r.cols() * sizeof(T)));
    if (!out) throw std::runtime_error(path + ": cannot write (check the directory exists and is writable)");
}

// Best wall time in seconds of `run` over `repeat` calls.
template <class F>
double best_seconds(int repeat, F&& run)
{
    double best = std::numeric_limits<double>::infinity();
    for (int i = 0; i < std::max(1, repeat); ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        run();
        best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    return best;
}

void report(double seconds, std::ptrdiff_t n)
{
    std::printf("seconds %.6f\ncells_per_s %.0f\n", seconds, static_cast<double>(n * n) / seconds);
}

}  // namespace

int main(int argc, char** argv)
try {
    const std::string mode = argc > 1 ? argv[1] : "";
    if (mode == "town" && argc == 4) {
        const std::ptrdiff_t n = std::stol(argv[2]);
        std::mt19937 rng(20261201);  // the town of bench/bench_shadow.cpp
        write_raw(argv[3], reference::box_town(rng, n, n, static_cast<int>(n * n / 2000), 0.3, 8, 30));
        return 0;
    }
    if (mode == "shadow" && argc == 9) {
        const std::ptrdiff_t n = std::stol(argv[3]);
        const auto z = read_f32(argv[2], n);
        lidarfx::raster<std::uint8_t> lit(n, n);
        const lidarfx::raylines_shadow_options opt{.run = {.threads = std::stoi(argv[6])}};
        const double s = best_seconds(std::stoi(argv[7]), [&] {
            lidarfx::raylines_shadow(z, lit, 1.0, std::stod(argv[4]), std::stod(argv[5]), opt);
        });
        write_raw(argv[8], lit);
        report(s, n);
        return 0;
    }
    if (mode == "horizon" && argc == 8) {
        const std::ptrdiff_t n = std::stol(argv[3]);
        const auto z = read_f32(argv[2], n);
        lidarfx::raster<float> h(n, n);
        const lidarfx::horizon_map_options opt{.run = {.threads = std::stoi(argv[5])}};
        const double s =
            best_seconds(std::stoi(argv[6]), [&] { lidarfx::horizon_map(z, h, 1.0, std::stod(argv[4]), opt); });
        write_raw(argv[7], h);
        report(s, n);
        return 0;
    }
    std::cerr << "usage: solar_peer town N OUT.f32 | shadow IN.f32 N AZ EL THREADS REPEAT OUT.u8 |"
                 " horizon IN.f32 N AZ THREADS REPEAT OUT.f32\n";
    return 2;
} catch (const std::exception& e) {
    std::cerr << "solar_peer: " << e.what() << "\n";
    return 1;
}
