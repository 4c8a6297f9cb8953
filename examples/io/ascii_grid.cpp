// SPDX-License-Identifier: Apache-2.0
#include "io/ascii_grid.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include <lidarfx/core/error.hpp>

namespace lidarfx::io {

namespace {

template <class T>
void append_number(std::string& out, T v)
{
    char buf[64];
    out.append(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
}

/// A cell value as std::to_chars writes it (shortest round trip), faster for the common cases: whole numbers
/// of magnitude below 1e5 (counts, masks, labels), for which the shortest form is the integer itself, and
/// NaN, written as the precomputed no-data token.
void append_cell(std::string& out, float v, const std::string& nodata)
{
    if (std::isnan(v)) {
        out += nodata;
    } else if (v == std::trunc(v) && std::abs(v) < 1e5f && !(v == 0 && std::signbit(v))) {
        char buf[16];
        out.append(buf, std::to_chars(buf, buf + sizeof buf, static_cast<int>(v)).ptr);
    } else {
        append_number(out, v);
    }
}

/// Splits text into whitespace-separated tokens, one at a time.
class tokens {
public:
    explicit tokens(std::string_view text) : text_(text) {}
    std::string_view next()
    {
        while (at_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[at_]))) ++at_;
        const std::size_t start = at_;
        while (at_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[at_]))) ++at_;
        return text_.substr(start, at_ - start);
    }
    std::string_view peek()
    {
        const std::size_t saved = at_;
        const auto t = next();
        at_ = saved;
        return t;
    }

private:
    std::string_view text_;
    std::size_t at_ = 0;
};

template <class T>
bool parse(std::string_view token, T& value)
{
    if (!token.empty() && token.front() == '+') token.remove_prefix(1);   // from_chars rejects a leading '+'
    const auto res = std::from_chars(token.data(), token.data() + token.size(), value);
    return res.ec == std::errc() && res.ptr == token.data() + token.size();
}

}  // namespace

void write_ascii_grid(const std::string& path, raster_view<const float> values, const grid& g)
{
    g.validate("write_ascii_grid");
    detail::require(values.rows() == g.rows && values.cols() == g.cols, "write_ascii_grid",
                    "raster shape must equal the grid's");
    detail::require(!values.empty(), "write_ascii_grid", "raster must not be empty");
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error(path + ": cannot open for writing");
    std::string text = "ncols " + std::to_string(g.cols) + "\nnrows " + std::to_string(g.rows) + "\nxllcorner ";
    append_number(text, g.x0);
    text += "\nyllcorner ";
    append_number(text, g.y1());
    text += "\ncellsize ";
    append_number(text, g.cell);
    text += "\nNODATA_value ";
    append_number(text, ascii_nodata);
    text += '\n';
    std::string nodata;
    append_number(nodata, ascii_nodata);
    for (std::ptrdiff_t r = 0; r < values.rows(); ++r) {
        const float* row = values.row(r);
        for (std::ptrdiff_t c = 0; c < values.cols(); ++c) {
            if (c) text += ' ';
            append_cell(text, row[c], nodata);
        }
        text += '\n';
        out.write(text.data(), static_cast<std::streamsize>(text.size()));
        text.clear();
    }
    out.close();
    if (!out) throw std::runtime_error(path + ": write failed");
}

raster<float> read_ascii_grid(const std::string& path, grid& g)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": cannot open");
    std::ostringstream buffer;
    buffer << in.rdbuf();
    const std::string text = buffer.str();
    const auto fail = [&path](const std::string& what) { throw std::runtime_error(path + ": " + what); };

    tokens tok(text);
    std::map<std::string, double> header;
    while (!tok.peek().empty() && std::isalpha(static_cast<unsigned char>(tok.peek().front()))) {
        std::string key(tok.peek());
        for (auto& ch : key) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
        if (key != "ncols" && key != "nrows" && key != "xllcorner" && key != "yllcorner" && key != "xllcenter" &&
            key != "yllcenter" && key != "cellsize" && key != "nodata_value") {
            if (header.count("cellsize") != 0) break;   // a complete header: data may start with "nan" or "inf"
            fail("unexpected header key '" + key + "'");
        }
        tok.next();
        const auto value_text = tok.next();
        double value = 0;
        if (!parse(value_text, value)) fail("header key " + key + " has a bad value '" + std::string(value_text) + "'");
        if (!header.emplace(key, value).second) fail("header key " + key + " appears twice");
    }
    const auto has = [&](const char* k) { return header.count(k) != 0; };
    for (const char* k : {"ncols", "nrows", "cellsize"}) {
        if (!has(k)) fail(std::string("header has no ") + k);
    }
    if (has("xllcorner") == has("xllcenter")) fail("header needs exactly one of xllcorner and xllcenter");
    if (has("yllcorner") == has("yllcenter")) fail("header needs exactly one of yllcorner and yllcenter");
    const double ncols = header["ncols"], nrows = header["nrows"], cell = header["cellsize"];
    if (!(ncols >= 1 && nrows >= 1 && ncols == std::floor(ncols) && nrows == std::floor(nrows) &&
          ncols * nrows <= 1e12)) {
        fail("ncols and nrows must be positive integers");
    }
    if (!(cell > 0 && std::isfinite(cell))) fail("cellsize must be finite and > 0");
    // Centre registration names the centre of the lower-left cell: move to its corner.
    const double xll = has("xllcorner") ? header["xllcorner"] : header["xllcenter"] - cell / 2;
    const double yll = has("yllcorner") ? header["yllcorner"] : header["yllcenter"] - cell / 2;
    if (!std::isfinite(xll) || !std::isfinite(yll)) fail("the lower-left corner must be finite");
    const auto rows = static_cast<std::ptrdiff_t>(nrows), cols = static_cast<std::ptrdiff_t>(ncols);
    const bool has_nodata = has("nodata_value");
    const double nodata = has_nodata ? header["nodata_value"] : 0.0;
    const auto nodata_float = static_cast<float>(nodata);

    raster<float> values(rows, cols);
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        float* row = values.row(r);
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const auto t = tok.next();
            if (t.empty()) {
                fail(detail::concat("truncated data: expected ", rows * cols, " values, found ", r * cols + c));
            }
            float v = 0;
            // Parsing straight to float avoids double rounding; NoData is compared at double precision.
            if (!parse(t, v)) fail(detail::concat("bad value '", t, "' at row ", r, ", column ", c));
            double d = 0;
            if (has_nodata && v == nodata_float && parse(t, d) && d == nodata) v = NAN;
            row[c] = v;
        }
    }
    if (!tok.next().empty()) fail(detail::concat("more values than nrows x ncols = ", rows * cols));
    g = grid{xll, yll + nrows * cell, cell, rows, cols};
    return values;
}

}  // namespace lidarfx::io
