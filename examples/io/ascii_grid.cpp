// SPDX-License-Identifier: Apache-2.0
#include "io/ascii_grid.hpp"

#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace lidarfx::io {

void write_ascii_grid(const std::string& path, raster_view<const float> values, const grid& g)
{
    detail::require(values.rows() == g.rows && values.cols() == g.cols, "write_ascii_grid",
                    "raster shape must equal the grid's");
    std::ofstream out(path);
    if (!out) throw std::runtime_error(path + ": cannot open for writing");
    out.precision(12);
    out << "ncols " << g.cols << "\nnrows " << g.rows << "\nxllcorner " << g.x0 << "\nyllcorner " << g.y1()
        << "\ncellsize " << g.cell << "\nNODATA_value " << ascii_nodata << '\n';
    out.precision(7);
    for (std::ptrdiff_t r = 0; r < values.rows(); ++r) {
        const float* row = values.row(r);
        for (std::ptrdiff_t c = 0; c < values.cols(); ++c) {
            if (c) out << ' ';
            if (std::isnan(row[c])) out << ascii_nodata; else out << row[c];
        }
        out << '\n';
    }
    if (!out) throw std::runtime_error(path + ": write failed");
}

raster<float> read_ascii_grid(const std::string& path, grid& g)
{
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot open");
    double xll = 0, yll = 0, cell = 0, nodata = ascii_nodata;
    long long ncols = -1, nrows = -1;
    bool centre = false;
    std::string key;
    while (in >> std::ws && std::isalpha(in.peek()) && in >> key) {
        for (auto& ch : key) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
        if (key == "ncols") in >> ncols;
        else if (key == "nrows") in >> nrows;
        else if (key == "xllcorner") in >> xll;
        else if (key == "yllcorner") in >> yll;
        else if (key == "xllcenter") { in >> xll; centre = true; }
        else if (key == "yllcenter") { in >> yll; centre = true; }
        else if (key == "cellsize") in >> cell;
        else if (key == "nodata_value") in >> nodata;
        else throw std::runtime_error(path + ": unexpected header key '" + key + "'");
    }
    if (ncols < 0 || nrows < 0 || !(cell > 0)) throw std::runtime_error(path + ": incomplete or invalid header");
    if (centre) { xll -= cell / 2; yll -= cell / 2; }
    g = grid{xll, yll + static_cast<double>(nrows) * cell, cell, nrows, ncols};
    raster<float> values(nrows, ncols);
    for (long long r = 0; r < nrows; ++r) {
        for (long long c = 0; c < ncols; ++c) {
            double v;
            if (!(in >> v)) throw std::runtime_error(path + ": truncated data at row " + std::to_string(r));
            values(r, c) = v == nodata ? NAN : static_cast<float>(v);
        }
    }
    return values;
}

}  // namespace lidarfx::io
