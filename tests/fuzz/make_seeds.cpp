// SPDX-License-Identifier: Apache-2.0
// Writes the seed corpus of the LAS fuzz target: small writer outputs for every point format and version,
// two files for the grid path (points on the corners and edges of decimal bounds; header bounds near 2^48
// around one point, as a crafted file has them), and the head of a real file (header, VLRs, a few points,
// counts patched) when one is given.
// Usage: make_seeds <out_dir> [real.las]
#include <array>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <string>

#include "io/las.hpp"
#include "io/las_writer.hpp"

namespace {

void save(const std::filesystem::path& path, const std::vector<std::uint8_t>& bytes)
{
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

}  // namespace

int main(int argc, char** argv)
{
    if (argc < 2) {
        std::cerr << "usage: make_seeds <out_dir> [real.las]\n";
        return 2;
    }
    const std::filesystem::path out = argv[1];
    std::filesystem::create_directories(out);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(0.0, 100.0);
    for (int format = 0; format <= 10; ++format) {
        const int first = format >= 6 ? 4 : format >= 4 ? 3 : format >= 2 ? 2 : 0;
        for (int version : {first, 4}) {
            lidarfx::io::las_points p;
            p.resize(4, lidarfx::io::las_format_has_gps_time(format));
            for (std::size_t i = 0; i < 4; ++i) {
                p.x[i] = 500000 + u(rng);
                p.y[i] = 5000000 + u(rng);
                p.z[i] = u(rng);
                p.intensity[i] = static_cast<std::uint16_t>(rng());
                p.return_number[i] = static_cast<std::uint8_t>(1 + i % 3);
                p.number_of_returns[i] = 3;
                p.classification[i] = static_cast<std::uint8_t>(2 + i);
                p.scan_angle_deg[i] = static_cast<float>(i) - 2.0f;
            }
            const lidarfx::io::las_write_options opt{.version_minor = version,
                                                     .point_format = format,
                                                     .extra_bytes = format % 3,
                                                     .epsg_projected = 32610,
                                                     .epsg_vertical = 5703,
                                                     .wkt = version == 4 ? "PROJCS[\"WGS 84 / UTM 10N\"]" : ""};
            save(out / ("writer_f" + std::to_string(format) + "_v1" + std::to_string(version) + ".las"),
                 lidarfx::io::encode_las(p, opt));
        }
    }
    {
        // Bounds 1000..1010 x 2000..2010 with points on every corner and edge: for most cell sizes the far
        // edges fall on or a hair off the lattice.
        lidarfx::io::las_points p;
        p.resize(12, false);
        const double xs[] = {1000, 1010, 1000, 1010, 1003.37, 1010, 1000, 1005.5, 1007.01, 1010, 1001, 1009.99};
        const double ys[] = {2000, 2010, 2010, 2000, 2000, 2004.41, 2007.7, 2010, 2005, 2009.99, 2000.01, 2002};
        for (std::size_t i = 0; i < 12; ++i) {
            p.x[i] = xs[i];
            p.y[i] = ys[i];
            p.z[i] = 10.0 + static_cast<double>(i);
            p.intensity[i] = static_cast<std::uint16_t>(100 * i);
            p.return_number[i] = 1;
            p.number_of_returns[i] = static_cast<std::uint8_t>(1 + i % 2);
        }
        save(out / "grid_edges.las", lidarfx::io::encode_las(p, {.version_minor = 2,
                                                                 .point_format = 0,
                                                                 .scale = {0.01, 0.01, 0.01},
                                                                 .offset = std::array<double, 3>{0, 0, 0}}));
        // One point; the header claims bounds from 0 to 2^48 (a grid that cannot exist at any usual cell).
        lidarfx::io::las_points one;
        one.resize(1, true);
        one.x[0] = 12.5;
        one.y[0] = 7.25;
        one.return_number[0] = one.number_of_returns[0] = 1;
        std::vector<std::uint8_t> bytes = lidarfx::io::encode_las(one, {.version_minor = 4, .point_format = 6});
        const double far = 281474976710656.0, zero = 0.0;
        for (int k = 0; k < 2; ++k) {
            std::memcpy(bytes.data() + 179 + 16 * k, &far, 8);   // max x, max y
            std::memcpy(bytes.data() + 187 + 16 * k, &zero, 8);  // min x, min y
        }
        save(out / "grid_huge_bounds.las", bytes);
    }
    if (argc > 2) {
        std::ifstream in(argv[2], std::ios::binary);
        std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        if (bytes.size() < 227) {
            std::cerr << "make_seeds: " << argv[2] << ": not a LAS file, skipped\n";
            return 0;
        }
        // Keep the header, the VLRs and 16 points; patch the counts so the head is a valid file.
        std::uint32_t offset = 0;
        std::uint16_t length = 0;
        std::memcpy(&offset, bytes.data() + 96, 4);
        std::memcpy(&length, bytes.data() + 105, 2);
        const std::uint32_t keep = 16;
        if (offset + std::size_t{keep} * length <= bytes.size()) {
            bytes.resize(offset + std::size_t{keep} * length);
            std::memcpy(bytes.data() + 107, &keep, 4);
            std::memcpy(bytes.data() + 111, &keep, 4);
            std::memset(bytes.data() + 115, 0, 16);
        }
        save(out / "real_head.las", bytes);
    }
    return 0;
}
