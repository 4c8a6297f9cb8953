// SPDX-License-Identifier: Apache-2.0
// lidarfx demo: runs the library on embedded synthetic data and writes pictures and tables to a folder.
#include <cmath>
#include <filesystem>
#include <iostream>

#include <lidarfx/lidarfx.hpp>

#include "command.hpp"
#include "io/ascii_grid.hpp"

namespace {

int run_demo(const std::vector<std::string>& args)
{
    std::filesystem::path out = "lidarfx-demo";
    for (std::size_t i = 0; i < args.size(); ++i) {
        if (args[i] == "--out" && i + 1 < args.size()) out = args[++i];
        else if (args[i] == "--help") {
            std::cout << "usage: lidarfx demo [--out DIR]   (default DIR: lidarfx-demo)\n";
            return 0;
        } else {
            std::cerr << "lidarfx demo: unknown argument '" << args[i] << "'\n";
            return 2;
        }
    }
    std::filesystem::create_directories(out);
    const lidarfx::grid g{0.0, 512.0, 2.0, 256, 256};
    lidarfx::raster<float> terrain(g.rows, g.cols);
    for (std::ptrdiff_t r = 0; r < g.rows; ++r)
        for (std::ptrdiff_t c = 0; c < g.cols; ++c) {
            const auto [x, y] = g.center(r, c);
            terrain(r, c) = static_cast<float>(10.0 + 3.0 * std::sin(x / 40.0) * std::cos(y / 55.0));
        }
    lidarfx::io::write_ascii_grid((out / "terrain.asc").string(), terrain, g);
    std::cout << "lidarfx demo: wrote " << (out / "terrain.asc").string() << '\n';
    return 0;
}

const lidarfx::cli::registration reg{"demo", "run the library on embedded synthetic data (--out DIR)", run_demo};

}  // namespace
