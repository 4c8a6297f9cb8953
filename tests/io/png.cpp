// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include "io/png.hpp"

#include <lidarfx/core/raster.hpp>

#include <random>

#ifdef LIDARFX_HAVE_ZLIB
#include <zlib.h>
#endif
#include <string_view>

#include "io_test_util.hpp"

using namespace lidarfx;
using namespace lidarfx::io;

namespace {

/// Bit-by-bit CRC-32 (no table), the plain definition the table-driven one must match.
std::uint32_t crc32_bitwise(const std::uint8_t* p, std::size_t n)
{
    std::uint32_t c = 0xFFFFFFFFu;
    for (std::size_t i = 0; i < n; ++i) {
        c ^= p[i];
        for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    }
    return ~c;
}

/// Adler-32 with a modulo after every byte.
std::uint32_t adler32_plain(const std::vector<std::uint8_t>& v)
{
    std::uint32_t a = 1, b = 0;
    for (auto x : v) {
        a = (a + x) % 65521;
        b = (b + a) % 65521;
    }
    return b << 16 | a;
}

std::uint32_t be32(const std::uint8_t* p)
{
    return std::uint32_t{p[0]} << 24 | std::uint32_t{p[1]} << 16 | std::uint32_t{p[2]} << 8 | p[3];
}

/// What a PNG decoder sees in a file (zlib inflates compressed data); every structural check is a CHECK.
struct decoded_png {
    std::uint32_t width = 0, height = 0;
    int colour_type = -1;
    std::vector<std::uint8_t> pixels;  // rows without filter bytes
};

decoded_png decode_png(const std::vector<std::uint8_t>& f)
{
    decoded_png out;
    const std::uint8_t signature[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
    REQUIRE(f.size() >= 8);
    CHECK(std::equal(signature, signature + 8, f.begin()));
    std::vector<std::string> order;
    std::vector<std::uint8_t> z;
    for (std::size_t at = 8; at < f.size();) {
        REQUIRE(at + 12 <= f.size());
        const std::uint32_t length = be32(&f[at]);
        REQUIRE(at + 12 + length <= f.size());
        const std::string type(reinterpret_cast<const char*>(&f[at + 4]), 4);
        CHECK(be32(&f[at + 8 + length]) == crc32_bitwise(&f[at + 4], 4 + length));
        const std::uint8_t* data = &f[at + 8];
        if (type == "IHDR") {
            REQUIRE(length == 13);
            out.width = be32(data);
            out.height = be32(data + 4);
            CHECK(data[8] == 8);  // bit depth
            out.colour_type = data[9];
            CHECK(data[10] == 0);  // deflate
            CHECK(data[11] == 0);  // adaptive filtering
            CHECK(data[12] == 0);  // no interlace
        } else if (type == "IDAT") {
            z.insert(z.end(), data, data + length);
        }
        if (order.empty() || order.back() != type) order.push_back(type);
        at += 12 + length;
    }
    CHECK(order == std::vector<std::string>{"IHDR", "IDAT", "IEND"});
    // zlib: header, then stored blocks (read here) or compressed ones (inflated by zlib), Adler-32.
    REQUIRE(z.size() >= 6);
    CHECK((z[0] & 0x0F) == 8);
    CHECK((z[0] * 256 + z[1]) % 31 == 0);
    CHECK((z[1] & 0x20) == 0);  // no preset dictionary
    const std::size_t channels = out.colour_type == 2 ? 3 : 1;
    const std::size_t line = 1 + out.width * channels;
    std::vector<std::uint8_t> raw;
    if (!deflate_available()) {
        std::size_t at = 2;
        for (bool final = false; !final;) {
            REQUIRE(at + 5 <= z.size());
            final = (z[at] & 1) != 0;
            CHECK(((z[at] >> 1) & 3) == 0);  // stored
            const std::uint32_t len = z[at + 1] | z[at + 2] << 8;
            const std::uint32_t nlen = z[at + 3] | z[at + 4] << 8;
            CHECK(len == (~nlen & 0xFFFFu));
            REQUIRE(at + 5 + len <= z.size());
            raw.insert(raw.end(), z.begin() + static_cast<std::ptrdiff_t>(at + 5),
                       z.begin() + static_cast<std::ptrdiff_t>(at + 5 + len));
            at += 5 + len;
        }
        REQUIRE(at + 4 == z.size());
        CHECK(be32(&z[at]) == adler32_plain(raw));
    } else {
#ifdef LIDARFX_HAVE_ZLIB
        uLongf size = static_cast<uLongf>(line * out.height);
        raw.resize(size);
        REQUIRE(uncompress(raw.data(), &size, z.data(), static_cast<uLong>(z.size())) == Z_OK);
        raw.resize(size);
        CHECK(be32(&z[z.size() - 4]) == adler32_plain(raw));
#endif
    }
    // Scanlines: a filter byte (0 none, 1 Sub, 2 Up) and width * channels samples, unfiltered here.
    REQUIRE(raw.size() == line * out.height);
    std::vector<std::uint8_t> previous(line - 1, 0);
    for (std::size_t r = 0; r < out.height; ++r) {
        const std::uint8_t type = raw[r * line];
        CHECK(type <= 2);
        std::vector<std::uint8_t> row(raw.begin() + static_cast<std::ptrdiff_t>(r * line + 1),
                                      raw.begin() + static_cast<std::ptrdiff_t>((r + 1) * line));
        for (std::size_t i = 0; i < row.size(); ++i) {
            if (type == 1 && i >= channels) row[i] = static_cast<std::uint8_t>(row[i] + row[i - channels]);
            if (type == 2) row[i] = static_cast<std::uint8_t>(row[i] + previous[i]);
        }
        out.pixels.insert(out.pixels.end(), row.begin(), row.end());
        previous = row;
    }
    return out;
}

std::vector<std::uint8_t> bytes_of(std::string_view s)
{
    return {s.begin(), s.end()};
}

}  // namespace

TEST_CASE("io/crc32, io/adler32: published check values and agreement with plain definitions")
{
    CHECK(crc32(bytes_of("123456789")) == 0xCBF43926u);  // the CRC-32 check value
    CHECK(crc32(bytes_of("")) == 0u);
    CHECK(adler32(bytes_of("Wikipedia")) == 0x11E60398u);
    CHECK(adler32(bytes_of("")) == 1u);
    std::mt19937 rng(1);
    for (std::size_t n : {1u, 7u, 5551u, 5552u, 5553u, 100000u}) {
        std::vector<std::uint8_t> v(n);
        for (auto& x : v)
            x = static_cast<std::uint8_t>(rng() | (n == 100000 ? 0xF0 : 0));  // large bytes stress overflow
        CHECK(crc32(v) == crc32_bitwise(v.data(), v.size()));
        CHECK(adler32(v) == adler32_plain(v));
        // Continuing over two parts equals one pass.
        const std::span<const std::uint8_t> all(v);
        const std::size_t half = n / 2;
        CHECK(crc32(all.subspan(half), crc32(all.first(half))) == crc32(v));
        CHECK(adler32(all.subspan(half), adler32(all.first(half))) == adler32(v));
    }
}

TEST_CASE("io/write_png_gray: the file decodes back to the pixels (strided views, odd sizes, many blocks)")
{
    io_test::temp_dir dir;
    std::mt19937 rng(8);
    for (const auto& item : {std::pair{1, 1}, {1, 9}, {9, 1}, {7, 13}, {257, 131}, {300, 700}}) {
        const auto& rows = std::get<0>(item);
        const auto& cols = std::get<1>(item);
        CAPTURE(rows);
        CAPTURE(cols);
        raster<std::uint8_t> big(rows + 2, cols + 5);
        for (auto& v : big) v = static_cast<std::uint8_t>(rng());
        const auto view = big.view().window(1, 3, rows, cols);  // row_stride > cols
        const std::string path = dir.file("gray.png");
        write_png_gray(path, view);
        const auto png = decode_png(io_test::read_bytes(path));
        CHECK(png.width == static_cast<std::uint32_t>(cols));
        CHECK(png.height == static_cast<std::uint32_t>(rows));
        CHECK(png.colour_type == 0);
        std::vector<std::uint8_t> expected;
        for (std::ptrdiff_t r = 0; r < rows; ++r) expected.insert(expected.end(), view.row(r), view.row(r) + cols);
        CHECK(png.pixels == expected);
    }
}

TEST_CASE("io/write_png_rgb: the file decodes back to the pixels; sizes are checked")
{
    io_test::temp_dir dir;
    std::mt19937 rng(9);
    const std::ptrdiff_t w = 123, h = 77;
    std::vector<std::uint8_t> rgb(static_cast<std::size_t>(w * h * 3));
    for (auto& v : rgb) v = static_cast<std::uint8_t>(rng());
    const std::string path = dir.file("rgb.png");
    write_png_rgb(path, w, h, rgb);
    const auto png = decode_png(io_test::read_bytes(path));
    CHECK(png.width == 123);
    CHECK(png.height == 77);
    CHECK(png.colour_type == 2);
    CHECK(png.pixels == rgb);
    write_png_rgb(path, rgb_image{w, h, rgb});
    CHECK(decode_png(io_test::read_bytes(path)).pixels == rgb);

    CHECK_THROWS_WITH_AS(write_png_rgb(path, w, h + 1, rgb),
                         "write_png_rgb: rgb.size() must be width * height * 3 (got 28413)", invalid_input);
    CHECK_THROWS_WITH_AS(write_png_rgb(path, 0, 0, {}), "encode_png: width must be in 1..2^31-1 (got 0)",
                         invalid_input);
    CHECK_THROWS_WITH_AS(write_png_gray(path, raster<std::uint8_t>(3, 0)),
                         "encode_png: width must be in 1..2^31-1 (got 0)", invalid_input);
    CHECK_THROWS_WITH_AS((void)encode_png(2, 2, 2, rgb.data(), 4),
                         "encode_png: channels must be 1 (gray) or 3 (RGB) (got 2)", invalid_input);
    CHECK(io_test::runtime_error_of([&] { write_png_rgb(dir.file("none/x.png"), w, h, rgb); }) ==
          dir.file("none/x.png") + ": cannot open for writing");
}

TEST_CASE("io/encode_png: with zlib a smooth picture takes a small fraction of its raw size")
{
    if (!deflate_available()) {
        MESSAGE("built without zlib: PNGs are stored uncompressed");
        return;
    }
    raster<std::uint8_t> ramp(300, 400);
    for (std::ptrdiff_t r = 0; r < 300; ++r)
        for (std::ptrdiff_t c = 0; c < 400; ++c) ramp(r, c) = static_cast<std::uint8_t>((r + c) / 3);
    const auto png = encode_png(400, 300, 1, ramp.data(), 400);
    CHECK(png.size() < 300 * 400 / 20);
    CHECK(decode_png(png).pixels == std::vector<std::uint8_t>(ramp.begin(), ramp.end()));
}
