// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include "io/ascii_grid.hpp"

#include <bit>
#include <charconv>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "io_test_util.hpp"

using namespace lidarfx;
using namespace lidarfx::io;
using io_test::runtime_error_of;

namespace {

void write_text(const std::string& path, const std::string& text)
{
    io_test::write_bytes(path, std::vector<std::uint8_t>(text.begin(), text.end()));
}

}  // namespace

TEST_CASE("io/ascii_grid: write/read round trip is bit-exact, NaN -> -9999 -> NaN, strided input")
{
    io_test::temp_dir dir;
    std::mt19937 rng(77);
    for (auto [rows, cols] : {std::pair{1, 1}, {1, 9}, {9, 1}, {7, 13}, {57, 31}}) {
        raster<float> big(rows + 3, cols + 4);
        for (auto& v : big) {
            // Any finite float bit pattern (denormals, -0, extremes) or NaN.
            float f;
            do {
                f = std::bit_cast<float>(static_cast<std::uint32_t>(rng()));
            } while (std::isinf(f));
            v = rng() % 10 == 0 ? NAN : rng() % 2 ? f : static_cast<float>(rng() % 20000) / 8.0f - 1000.0f;
        }
        const auto values = big.view().window(2, 1, rows, cols);
        const grid g{2230738.84, 252410.1, 0.25, rows, cols};
        const std::string path = dir.file("g.asc");
        write_ascii_grid(path, values, g);
        grid back_grid;
        const auto back = read_ascii_grid(path, back_grid);
        CHECK(io_test::same_cells(back, values));
        CHECK(back_grid.cols == g.cols);
        CHECK(back_grid.rows == g.rows);
        CHECK(back_grid.cell == g.cell);
        CHECK(back_grid.x0 == g.x0);
        // y0 goes through the lower-left corner: y1 = y0 - rows * cell and back, exact up to rounding.
        CHECK(back_grid.y0 == doctest::Approx(g.y0).epsilon(1e-15));
    }
}

TEST_CASE("io/read_ascii_grid: corner and centre registration, key case and order, missing NODATA_value")
{
    io_test::temp_dir dir;
    const std::string path = dir.file("h.asc");
    grid g;
    write_text(path, "ncols 3\nnrows 2\nxllcorner 100\nyllcorner 200\ncellsize 2\nNODATA_value -1\n1 2 -1\n4 5 6\n");
    auto v = read_ascii_grid(path, g);
    CHECK(g == grid{100, 204, 2, 2, 3});
    CHECK(v(0, 0) == 1);
    CHECK(std::isnan(v(0, 2)));
    CHECK(v(1, 2) == 6);

    // Centre registration (the centre of the lower-left cell), upper-case keys in another order.
    write_text(path, "NROWS 2\r\nNCOLS 3\r\nCELLSIZE 2\r\nXLLCENTER 101\r\nYLLCENTER 201\r\n1 2 3 4 5 6\r\n");
    v = read_ascii_grid(path, g);
    CHECK(g == grid{100, 204, 2, 2, 3});
    CHECK(v(1, 0) == 4);
    // Without NODATA_value nothing is NoData, not even -9999.
    write_text(path, "ncols 2\nnrows 1\nxllcorner 0\nyllcenter 0.5\ncellsize 1\n-9999 +7.5\n");
    v = read_ascii_grid(path, g);
    CHECK(g == grid{0, 1, 1, 1, 2});
    CHECK(v(0, 0) == -9999.0f);
    CHECK(v(0, 1) == 7.5f);
    // A complete header may be followed by data starting with nan.
    write_text(path, "ncols 2\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 1\nnan 3\n");
    CHECK(std::isnan(read_ascii_grid(path, g)(0, 0)));
}

TEST_CASE("io/read_ascii_grid: malformed files are rejected with the file name and the reason")
{
    io_test::temp_dir dir;
    const std::string path = dir.file("bad.asc");
    grid g;
    const auto error = [&](const std::string& text) {
        write_text(path, text);
        return runtime_error_of([&] { (void)read_ascii_grid(path, g); });
    };
    const std::string head = "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n";
    CHECK(error(head + "1 2 3\n") == path + ": truncated data: expected 4 values, found 3");
    CHECK(error(head + "1 2 3 4 5\n") == path + ": more values than nrows x ncols = 4");
    CHECK(error(head + "1 2 x 4\n") == path + ": bad value 'x' at row 1, column 0");
    CHECK(error("ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\n1 2 3 4\n") == path + ": header has no cellsize");
    CHECK(error("ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncolour 3\n") == path + ": unexpected header key 'colour'");
    CHECK(error("ncols 2\nncols 2\n") == path + ": header key ncols appears twice");
    CHECK(error("ncols two\n") == path + ": header key ncols has a bad value 'two'");
    CHECK(error("ncols 2\nnrows 2\nyllcorner 0\ncellsize 1\n1 2 3 4\n") ==
          path + ": header needs exactly one of xllcorner and xllcenter");
    CHECK(error("ncols 2\nnrows 0\nxllcorner 0\nyllcorner 0\ncellsize 1\n") ==
          path + ": ncols and nrows must be positive integers");
    CHECK(error("ncols 2\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize -1\n1 2\n") ==
          path + ": cellsize must be finite and > 0");
    CHECK(runtime_error_of([&] { (void)read_ascii_grid(dir.file("none.asc"), g); }) ==
          dir.file("none.asc") + ": cannot open");
}

TEST_CASE("io/write_ascii_grid: checks the shape and the grid")
{
    io_test::temp_dir dir;
    const raster<float> v(2, 3, 1.0f);
    CHECK_THROWS_WITH_AS(write_ascii_grid(dir.file("a.asc"), v, {0, 0, 1, 3, 2}),
                         "write_ascii_grid: raster shape must equal the grid's", invalid_input);
    CHECK_THROWS_WITH_AS(write_ascii_grid(dir.file("a.asc"), v, {0, 0, -1, 2, 3}),
                         "write_ascii_grid: grid.cell must be finite and > 0 (got -1)", invalid_input);
    CHECK_THROWS_WITH_AS(write_ascii_grid(dir.file("a.asc"), raster<float>(0, 0), {0, 0, 1, 0, 0}),
                         "write_ascii_grid: raster must not be empty", invalid_input);
    CHECK(runtime_error_of([&] {
              write_ascii_grid(dir.file("no/a.asc"), v, {0, 0, 1, 2, 3});
          }) == dir.file("no/a.asc") + ": cannot open for writing");
}

TEST_CASE("io/write_ascii_grid: every value is written as std::to_chars writes it (whole numbers, -0, 1e5, NaN)")
{
    // The writer has fast paths for whole numbers and NaN; their text must be the shortest round trip that
    // to_chars gives, across the places where fixed and scientific forms trade places.
    std::vector<float> values{0.0f,      -0.0f,     1.0f,     -1.0f,       7.0f,      99999.0f, -99999.0f,
                              100000.0f, 123456.0f, 1e6f,     20000.0f,    0.5f,      -2.25f,   1e-7f,
                              3.4e38f,   NAN,       65535.0f, 16777216.0f, -100000.0f};
    std::mt19937 rng(5);
    for (int i = 0; i < 200; ++i) values.push_back(static_cast<float>(static_cast<int>(rng() % 400001) - 200000));
    raster<float> r(1, static_cast<std::ptrdiff_t>(values.size()));
    for (std::size_t i = 0; i < values.size(); ++i) r(0, static_cast<std::ptrdiff_t>(i)) = values[i];
    io_test::temp_dir dir;
    const auto path = dir.file("values.asc");
    write_ascii_grid(path, r, grid{0.0, 1.0, 1.0, 1, r.cols()});
    const auto bytes = io_test::read_bytes(path);
    const std::string text(bytes.begin(), bytes.end());
    std::string expected;
    for (std::size_t i = 0; i < values.size(); ++i) {
        char buf[64];
        const float v = std::isnan(values[i]) ? -9999.0f : values[i];
        const auto end = std::isnan(values[i]) ? std::to_chars(buf, buf + sizeof buf, -9999.0)
                                               : std::to_chars(buf, buf + sizeof buf, v);
        if (i) expected += ' ';
        expected.append(buf, end.ptr);
    }
    const auto last_line = text.substr(text.rfind('\n', text.size() - 2) + 1);
    CHECK(last_line == expected + "\n");
}

TEST_CASE("io/read_ascii_grid: values straddling the 1 MiB read blocks come back bit for bit")
{
    io_test::temp_dir dir;
    std::mt19937 rng(2026);
    // 640 x 700 cells of up to 15 characters: about 4 MB of text, so tokens cross three block edges somewhere.
    raster<float> values(640, 700);
    for (auto& v : values) {
        float f;
        do {
            f = std::bit_cast<float>(static_cast<std::uint32_t>(rng()));
        } while (!std::isfinite(f));
        v = rng() % 7 == 0 ? NAN : f;
    }
    const grid g{500000, 4000640, 1.0, values.rows(), values.cols()};
    const std::string path = dir.file("big.asc");
    write_ascii_grid(path, values, g);
    grid back_grid;
    std::size_t non_finite = 99;
    const auto back = read_ascii_grid(path, back_grid, &non_finite);
    CHECK(io_test::same_cells(back, values));
    CHECK(non_finite == 0);  // NaN cells were written as NODATA_value, which is no data, not a non-finite height
}

TEST_CASE("io/read_ascii_grid: inf, -inf and nan heights are no data, counted")
{
    io_test::temp_dir dir;
    const std::string path = dir.file("inf.asc");
    write_text(path,
               "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\nNODATA_value -9999\n"
               "inf 1 -9999\n-inf nan 2\n");
    grid g;
    std::size_t non_finite = 0;
    const auto v = read_ascii_grid(path, g, &non_finite);
    CHECK(non_finite == 3);
    CHECK(std::isnan(v(0, 0)));
    CHECK(v(0, 1) == 1.0f);
    CHECK(std::isnan(v(0, 2)));  // NODATA_value: no data, not counted
    CHECK(std::isnan(v(1, 0)));
    CHECK(std::isnan(v(1, 1)));
    CHECK(v(1, 2) == 2.0f);
}

TEST_CASE("io/read_ascii_grid: a header promising more cells than its file holds fails before the grid exists")
{
    io_test::temp_dir dir;
    const std::string path = dir.file("huge.asc");
    grid g;
    // 20000 x 20000 cells (1.6 GB of floats) declared in a 100-byte file: the header reads, the grid is refused.
    write_text(path, "ncols 20000\nnrows 20000\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n");
    const ascii_grid_header h = read_ascii_grid_header(path);
    CHECK(h.g.rows == 20000);
    CHECK(h.g.cols == 20000);
    CHECK(h.file_bytes == 65);
    CHECK(h.data_offset == 58);
    CHECK(runtime_error_of([&] { (void)read_ascii_grid(path, g); }) ==
          path + ": truncated data: expected 400000000 values, but the 7 bytes after the header hold at most 4");
    write_text(path, "ncols 2147483648\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n");
    CHECK(runtime_error_of([&] { (void)read_ascii_grid(path, g); }) ==
          path + ": truncated data: expected 2147483648 values, but the 7 bytes after the header hold at most 4");
    write_text(path, "ncols 2000000\nnrows 2000000\nxllcorner 0\nyllcorner 0\ncellsize 1\n1\n");
    CHECK(runtime_error_of([&] { (void)read_ascii_grid_header(path); }) ==
          path + ": ncols 2000000 x nrows 2000000 is more than 2^40 cells");
    // A value of 300 characters is no number (and is not held whole, whatever its length).
    write_text(path, "ncols 2\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 " + std::string(300, '7') + "\n");
    CHECK(runtime_error_of([&] { (void)read_ascii_grid(path, g); }) == path + ": a value of more than 256 characters");
}

TEST_CASE("io/read_ascii_grid: a file whose last value ends exactly at a 1 MiB block, without a newline")
{
    io_test::temp_dir dir;
    const std::string path = dir.file("edge.asc");
    // The data after "cellsize 1" is "\n1 1 ... 1": 1 + (2 x 2^19 - 1) = 2^20 bytes, the last value the block's end.
    const std::ptrdiff_t cols = 1 << 19;
    std::string text = "ncols " + std::to_string(cols) + "\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 1\n";
    for (std::ptrdiff_t c = 0; c < cols; ++c) text += c + 1 < cols ? "1 " : "2";
    write_text(path, text);
    grid g;
    const auto v = read_ascii_grid(path, g);
    REQUIRE(v.cols() == cols);
    CHECK(v(0, 0) == 1.0f);
    CHECK(v(0, cols - 1) == 2.0f);
}
