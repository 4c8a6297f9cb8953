// SPDX-License-Identifier: Apache-2.0
// libFuzzer target for the ESRI ASCII grid reader (read_ascii_grid, through a temporary file: the reader's
// public entry takes a path): any bytes must give a grid or an exception of a documented type
// (std::runtime_error, invalid_input), never a crash, a sanitizer report, another exception or an allocation
// beyond what the file's values can fill. What it accepts has the grid's shape and is written back and read
// again to the same cells (NaN, and the -9999 the writer uses for it, read as NaN). Built and run by
// scripts/fuzz.sh.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include <unistd.h>

#include <lidarfx/core/error.hpp>

#include "io/ascii_grid.hpp"

namespace {

// One file per process, removed at exit.
struct temp_files {
    std::string in, out;
    temp_files()
    {
        const auto dir = std::filesystem::temp_directory_path();
        const std::string stem = "lidarfx_ascii_fuzz_" + std::to_string(::getpid());
        in = (dir / (stem + ".asc")).string();
        out = (dir / (stem + "_out.asc")).string();
    }
    ~temp_files()
    {
        std::error_code ec;
        std::filesystem::remove(in, ec);
        std::filesystem::remove(out, ec);
    }
};

temp_files& files()
{
    static temp_files f;
    return f;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    namespace io = lidarfx::io;
    {
        std::ofstream f(files().in, std::ios::binary | std::ios::trunc);
        f.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
        if (!f) std::abort();
    }
    lidarfx::grid g;
    lidarfx::raster<float> values;
    try {
        values = io::read_ascii_grid(files().in, g);
    } catch (const std::runtime_error&) {
        return 0;
    } catch (const lidarfx::invalid_input&) {
        return 0;
    }
    if (values.rows() != g.rows || values.cols() != g.cols || !(g.cell > 0) || !std::isfinite(g.cell)) std::abort();
    try {
        io::write_ascii_grid(files().out, values, g);
    } catch (const lidarfx::invalid_input&) {
        return 0;  // a grid the writer cannot describe (e.g. a corner beyond a double)
    }
    lidarfx::grid g2;
    const auto back = io::read_ascii_grid(files().out, g2);
    if (back.rows() != values.rows() || back.cols() != values.cols()) std::abort();
    for (std::ptrdiff_t r = 0; r < values.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < values.cols(); ++c) {
            const float a = values(r, c), b = back(r, c);
            const bool same = a == b || (std::isnan(b) && (std::isnan(a) || a == static_cast<float>(io::ascii_nodata)));
            if (!same) std::abort();
        }
    }
    return 0;
}
