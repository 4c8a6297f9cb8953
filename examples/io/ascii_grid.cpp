// SPDX-License-Identifier: Apache-2.0
#include "io/ascii_grid.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
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

    /// Bytes from the text's start to the end of the last token taken.
    std::size_t position() const { return at_; }

private:
    std::string_view text_;
    std::size_t at_ = 0;
};

/// Bytes of a file's start read for its header; cells a grid may declare (2^40).
constexpr std::size_t header_bytes_max = 64 * 1024;
constexpr double max_cells = 1099511627776.0;

/// Whitespace-separated tokens of a stream, read in blocks of 1 MiB: memory of one block, whatever the file.
/// A token longer than 256 bytes is no number: `fail` is called with what is wrong.
template <class Fail>
class streamed_tokens {
public:
    streamed_tokens(std::istream& in, const Fail& fail) : in_(in), fail_(fail) {}
    std::string_view next()
    {
        for (;;) {
            while (at_ < buffer_.size() && std::isspace(static_cast<unsigned char>(buffer_[at_]))) ++at_;
            if (at_ == buffer_.size()) {
                if (!refill()) return {};
                continue;  // the new block may start with white space
            }
            std::size_t end = at_;
            while (end < buffer_.size() && !std::isspace(static_cast<unsigned char>(buffer_[end]))) ++end;
            if (end - at_ > longest_token) fail_(detail::concat("a value of more than ", longest_token, " characters"));
            if (end == buffer_.size()) {
                if (refill()) continue;  // the token may go on in the next block
                end = buffer_.size();    // the file ended with it (refill may have moved it to the start)
            }
            const std::string_view token(buffer_.data() + at_, end - at_);
            at_ = end;
            return token;
        }
    }

private:
    static constexpr std::size_t block_bytes = 1 << 20, longest_token = 256;

    /// Keeps the unread part and appends the next block; false at the end of the stream.
    bool refill()
    {
        if (done_) return false;
        buffer_.erase(0, at_);
        at_ = 0;
        const std::size_t kept = buffer_.size();
        buffer_.resize(kept + block_bytes);
        in_.read(buffer_.data() + kept, static_cast<std::streamsize>(block_bytes));
        const auto got = static_cast<std::size_t>(in_.gcount());
        buffer_.resize(kept + got);
        done_ = got < block_bytes;
        return got > 0;
    }

    std::istream& in_;
    const Fail& fail_;
    std::string buffer_;
    std::size_t at_ = 0;
    bool done_ = false;
};

template <class T>
bool parse(std::string_view token, T& value)
{
    if (!token.empty() && token.front() == '+') token.remove_prefix(1);  // from_chars rejects a leading '+'
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

ascii_grid_header read_ascii_grid_header(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": cannot open");
    const auto fail = [&path](const std::string& what) { throw std::runtime_error(path + ": " + what); };
    std::error_code ec;
    ascii_grid_header h;
    h.file_bytes = std::filesystem::file_size(path, ec);
    if (ec) fail("cannot read its size: " + ec.message());
    // The header's at most 8 lines fit in its first 64 KiB (longer lines hold no valid number).
    std::string head(static_cast<std::size_t>(std::min<std::uintmax_t>(h.file_bytes, header_bytes_max)), '\0');
    in.read(head.data(), static_cast<std::streamsize>(head.size()));
    head.resize(static_cast<std::size_t>(in.gcount()));

    tokens tok(head);
    std::map<std::string, double> header;
    while (!tok.peek().empty() && std::isalpha(static_cast<unsigned char>(tok.peek().front()))) {
        std::string key(tok.peek());
        for (auto& ch : key) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
        if (key != "ncols" && key != "nrows" && key != "xllcorner" && key != "yllcorner" && key != "xllcenter" &&
            key != "yllcenter" && key != "cellsize" && key != "nodata_value") {
            if (header.count("cellsize") != 0) break;  // a complete header: data may start with "nan" or "inf"
            fail("unexpected header key '" + key + "'");
        }
        tok.next();
        const auto value_text = tok.next();
        double value = 0;
        if (!parse(value_text, value)) fail("header key " + key + " has a bad value '" + std::string(value_text) + "'");
        if (!header.emplace(key, value).second) fail("header key " + key + " appears twice");
    }
    h.data_offset = tok.position();
    const auto has = [&](const char* k) { return header.count(k) != 0; };
    for (const char* k : {"ncols", "nrows", "cellsize"}) {
        if (!has(k)) fail(std::string("header has no ") + k);
    }
    if (has("xllcorner") == has("xllcenter")) fail("header needs exactly one of xllcorner and xllcenter");
    if (has("yllcorner") == has("yllcenter")) fail("header needs exactly one of yllcorner and yllcenter");
    const double ncols = header["ncols"], nrows = header["nrows"], cell = header["cellsize"];
    if (!(ncols >= 1 && nrows >= 1 && ncols == std::floor(ncols) && nrows == std::floor(nrows))) {
        fail("ncols and nrows must be positive integers");
    }
    if (!(ncols * nrows <= max_cells)) {
        fail(detail::concat("ncols ", ncols, " x nrows ", nrows, " is more than 2^40 cells"));
    }
    if (!(cell > 0 && std::isfinite(cell))) fail("cellsize must be finite and > 0");
    // Centre registration names the centre of the lower-left cell: move to its corner.
    const double xll = has("xllcorner") ? header["xllcorner"] : header["xllcenter"] - cell / 2;
    const double yll = has("yllcorner") ? header["yllcorner"] : header["yllcenter"] - cell / 2;
    if (!std::isfinite(xll) || !std::isfinite(yll)) fail("the lower-left corner must be finite");
    const auto rows = static_cast<std::ptrdiff_t>(nrows), cols = static_cast<std::ptrdiff_t>(ncols);
    h.has_nodata = has("nodata_value");
    h.nodata = h.has_nodata ? header["nodata_value"] : 0.0;
    h.g = grid{xll, yll + nrows * cell, cell, rows, cols};
    return h;
}

raster<float> read_ascii_grid(const std::string& path, grid& g, std::size_t* non_finite_cells)
{
    const ascii_grid_header h = read_ascii_grid_header(path);
    const auto fail = [&path](const std::string& what) { throw std::runtime_error(path + ": " + what); };
    // Before the grid is allocated: every value takes at least one character and all but the last a separator.
    const std::uintmax_t cells = static_cast<std::uintmax_t>(h.g.rows) * static_cast<std::uintmax_t>(h.g.cols);
    const std::uintmax_t data_bytes = h.file_bytes - h.data_offset;
    if (data_bytes < 2 * cells - 1) {
        fail(detail::concat("truncated data: expected ", cells, " values, but the ", data_bytes,
                            " bytes after the header hold at most ", (data_bytes + 1) / 2));
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) fail("cannot open");
    in.seekg(static_cast<std::streamoff>(h.data_offset));
    streamed_tokens tok(in, fail);
    const std::ptrdiff_t rows = h.g.rows, cols = h.g.cols;
    const auto nodata_float = static_cast<float>(h.nodata);
    std::size_t non_finite = 0;
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
            if (h.has_nodata && v == nodata_float && parse(t, d) && d == h.nodata) {
                v = NAN;
            } else if (!std::isfinite(v)) {
                ++non_finite;  // inf, -inf or nan in the file: no height, so no data
                v = NAN;
            }
            row[c] = v;
        }
    }
    if (!tok.next().empty()) fail(detail::concat("more values than nrows x ncols = ", rows * cols));
    if (non_finite_cells) *non_finite_cells = non_finite;
    g = h.g;
    return values;
}

std::string prj_path_of(const std::string& asc_path)
{
    return std::filesystem::path(asc_path).replace_extension(".prj").string();
}

std::string read_prj_beside(const std::string& asc_path)
{
    const std::string path = prj_path_of(asc_path);
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) return {};
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    if (!in && !in.eof()) throw std::runtime_error(path + ": cannot read the grid's CRS file");
    return text.str();
}

}  // namespace lidarfx::io
