// SPDX-License-Identifier: Apache-2.0
// Writes a synthetic survey for the tiled-run tests and benchmark: the lake scene (lakes with islands) and
// the river scene (a meandering river under a bridge) side by side, W = 2 x SIZE metres east-west by SIZE
// north-south, cut into square LAS files of FILE metres (names file_<row>_<col>.las, row 0 in the north),
// each file's points in scan order with GPS times (point format 1, EPSG:32633, origin 500000 E 4000000 N).
// Lakes and the river cross file borders and, for most tile edges, tile borders and corners.
// Usage: make_water_survey OUT_DIR [--size SIZE=600] [--density PULSES_PER_M2=2] [--file FILE=200] [--seed N=1]
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <lidarfx/synth/scenes.hpp>

#include "io/las_writer.hpp"

namespace {

constexpr double east0 = 500000.0, north0 = 4000000.0;

int usage()
{
    std::cerr << "usage: make_water_survey OUT_DIR [--size SIZE=600] [--density PULSES_PER_M2=2] [--file FILE=200] "
                 "[--seed N=1]\n";
    return 2;
}

}  // namespace

int main(int argc, char** argv)
{
    // An option where the folder should be (--help, a mistyped flag) is refused, never taken as a folder name.
    if (argc < 2 || argv[1][0] == '-') return usage();
    const std::filesystem::path out = argv[1];
    double size = 600, density = 2, file = 200;
    unsigned seed = 1;
    for (int i = 2; i + 1 < argc; i += 2) {
        const std::string name = argv[i];
        const double v = std::atof(argv[i + 1]);
        if (name == "--size")
            size = v;
        else if (name == "--density")
            density = v;
        else if (name == "--file")
            file = v;
        else if (name == "--seed")
            seed = static_cast<unsigned>(v);
        else
            return usage();
    }
    if (!(size > 0) || !(density > 0) || !(file > 0)) return usage();
    std::filesystem::create_directories(out);
    const auto files_x = static_cast<int>(std::ceil(2 * size / file)),
               files_y = static_cast<int>(std::ceil(size / file));
    std::map<int, std::unique_ptr<lidarfx::io::las_writer>> writers;
    const lidarfx::io::las_write_options wo{
        .point_format = 1, .offset = std::array<double, 3>{east0, north0, 0.0}, .epsg_projected = 32633};
    for (int r = 0; r < files_y; ++r) {
        for (int c = 0; c < files_x; ++c) {
            const auto path = out / ("file_" + std::to_string(r) + "_" + std::to_string(c) + ".las");
            writers[r * files_x + c] = std::make_unique<lidarfx::io::las_writer>(path.string(), wo);
        }
    }
    std::uint64_t total = 0;
    for (int part = 0; part < 2; ++part) {
        const lidarfx::synth::scene_options so{.seed = seed, .size_m = size, .density_per_m2 = density};
        const auto scene = part == 0 ? lidarfx::synth::lake_scene(so) : lidarfx::synth::river_scene(so);
        const auto& p = scene.points;
        const double x_shift = east0 + part * size;
        std::map<int, lidarfx::io::las_points> buckets;
        const double time_shift = part * 1.0e5;  // the second scene flown later
        for (std::size_t i = 0; i < p.size(); ++i) {
            const double x = p.x[i] + x_shift, y = p.y[i] + north0;
            const int c = std::min(files_x - 1, static_cast<int>((x - east0) / file));
            const int r = std::min(files_y - 1, static_cast<int>((north0 + size - y) / file));
            auto& b = buckets[r * files_x + c];
            b.x.push_back(x);
            b.y.push_back(y);
            b.z.push_back(p.z[i]);
            b.intensity.push_back(p.intensity[i]);
            b.return_number.push_back(p.return_number[i]);
            b.number_of_returns.push_back(p.number_of_returns[i]);
            b.classification.push_back(p.classification[i]);
            b.gps_time.push_back(p.gps_time[i] + time_shift);
        }
        for (auto& [k, b] : buckets) {
            writers.at(k)->write(b);
            total += b.size();
        }
    }
    for (auto& [k, w] : writers) w->close();
    std::cout << "make_water_survey: " << total << " points in " << writers.size() << " files of " << file << " m in "
              << out.string() << '\n';
    return 0;
}
