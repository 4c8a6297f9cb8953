// SPDX-License-Identifier: Apache-2.0
#include "io/png.hpp"

#include <algorithm>
#include <array>
#include <fstream>
#include <limits>
#include <stdexcept>

#include <lidarfx/core/error.hpp>

#include "io/file_output.hpp"

#ifdef LIDARFX_HAVE_ZLIB
#include <zlib.h>
#endif

namespace lidarfx::io {

namespace {

constexpr std::array<std::uint32_t, 256> make_crc_table() noexcept
{
    std::array<std::uint32_t, 256> table{};
    for (std::uint32_t n = 0; n < 256; ++n) {
        std::uint32_t c = n;
        for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
        table[n] = c;
    }
    return table;
}

constexpr auto crc_table = make_crc_table();

void put_u32_be(std::vector<std::uint8_t>& out, std::uint32_t v)
{
    out.push_back(static_cast<std::uint8_t>(v >> 24));
    out.push_back(static_cast<std::uint8_t>(v >> 16));
    out.push_back(static_cast<std::uint8_t>(v >> 8));
    out.push_back(static_cast<std::uint8_t>(v));
}

/// Appends a chunk: length, type, data, CRC-32 of type and data.
void put_chunk(std::vector<std::uint8_t>& out, const char (&type)[5], std::span<const std::uint8_t> data)
{
    put_u32_be(out, static_cast<std::uint32_t>(data.size()));
    const std::size_t type_at = out.size();
    out.insert(out.end(), type, type + 4);
    out.insert(out.end(), data.begin(), data.end());
    put_u32_be(out, crc32(std::span<const std::uint8_t>(out).subspan(type_at)));
}

/// Byte i of a scanline under PNG filter `type` (0 none, 1 Sub, 2 Up); `up` is the previous row or null.
std::uint8_t filtered(int type, const std::uint8_t* row, const std::uint8_t* up, std::size_t i, std::size_t bpp)
{
    switch (type) {
        case 1:
            return static_cast<std::uint8_t>(row[i] - (i >= bpp ? row[i - bpp] : 0));
        case 2:
            return static_cast<std::uint8_t>(row[i] - (up ? up[i] : 0));
        default:
            return row[i];
    }
}

/// zlib stream of stored (uncompressed) deflate blocks of <= 65535 bytes: header, blocks, Adler-32.
std::vector<std::uint8_t> zlib_stored(const std::vector<std::uint8_t>& raw)
{
    constexpr std::size_t max_block = 65535;
    std::vector<std::uint8_t> z;
    z.reserve(raw.size() + raw.size() / max_block * 5 + 16);
    z.push_back(0x78);
    z.push_back(0x01);  // (0x78 * 256 + 0x01) % 31 == 0
    for (std::size_t at = 0; at < raw.size();) {
        const std::size_t n = std::min(max_block, raw.size() - at);
        const bool last = at + n == raw.size();
        z.push_back(last ? 1 : 0);  // BFINAL, BTYPE 00 (stored); the rest of the byte pads to a boundary
        z.push_back(static_cast<std::uint8_t>(n));
        z.push_back(static_cast<std::uint8_t>(n >> 8));
        z.push_back(static_cast<std::uint8_t>(~n));
        z.push_back(static_cast<std::uint8_t>(~n >> 8));
        z.insert(z.end(), raw.begin() + static_cast<std::ptrdiff_t>(at),
                 raw.begin() + static_cast<std::ptrdiff_t>(at + n));
        at += n;
    }
    put_u32_be(z, adler32(raw));
    return z;
}

/// zlib stream of `raw` compressed by zlib at level 1, its fastest (needs LIDARFX_HAVE_ZLIB): pictures are
/// quick looks; level 6 took 4x as long for files 10-20 % smaller.
std::vector<std::uint8_t> zlib_deflate(const std::vector<std::uint8_t>& raw)
{
#ifdef LIDARFX_HAVE_ZLIB
    uLongf size = compressBound(static_cast<uLong>(raw.size()));
    std::vector<std::uint8_t> z(size);
    if (compress2(z.data(), &size, raw.data(), static_cast<uLong>(raw.size()), 1) != Z_OK) {
        throw std::runtime_error("encode_png: zlib could not compress the image");
    }
    z.resize(size);
    return z;
#else
    return zlib_stored(raw);
#endif
}

}  // namespace

bool deflate_available() noexcept
{
#ifdef LIDARFX_HAVE_ZLIB
    return true;
#else
    return false;
#endif
}

std::uint32_t crc32(std::span<const std::uint8_t> bytes, std::uint32_t crc) noexcept
{
    std::uint32_t c = ~crc;
    for (const std::uint8_t b : bytes) c = crc_table[(c ^ b) & 0xFFu] ^ (c >> 8);
    return ~c;
}

std::uint32_t adler32(std::span<const std::uint8_t> bytes, std::uint32_t adler) noexcept
{
    constexpr std::uint32_t mod = 65521;
    constexpr std::size_t nmax = 5552;  // largest run whose sums cannot overflow 32 bits before the modulo
    std::uint32_t a = adler & 0xFFFFu, b = adler >> 16;
    for (std::size_t i = 0; i < bytes.size();) {
        const std::size_t end = std::min(bytes.size(), i + nmax);
        for (; i < end; ++i) {
            a += bytes[i];
            b += a;
        }
        a %= mod;
        b %= mod;
    }
    return (b << 16) | a;
}

std::vector<std::uint8_t> encode_png(std::ptrdiff_t width, std::ptrdiff_t height, int channels,
                                     const std::uint8_t* pixels, std::ptrdiff_t row_stride)
{
    constexpr const char* fn = "encode_png";
    constexpr std::ptrdiff_t max_side = std::numeric_limits<std::int32_t>::max();
    detail::require(width >= 1 && width <= max_side, fn, "width", "in 1..2^31-1", width);
    detail::require(height >= 1 && height <= max_side, fn, "height", "in 1..2^31-1", height);
    detail::require(channels == 1 || channels == 3, fn, "channels", "1 (gray) or 3 (RGB)", channels);
    const std::ptrdiff_t row_bytes = width * channels;
    detail::require(row_stride >= row_bytes, fn, "row_stride", ">= width * channels", row_stride);
    detail::require(pixels != nullptr, fn, "pixels must not be null");

    // Scanlines, each led by its filter type: 0 (none) without zlib; with zlib, per row the one of none,
    // Sub and Up whose bytes have the smallest sum as signed values (the usual heuristic), then DEFLATE.
    const std::size_t line = static_cast<std::size_t>(row_bytes) + 1;
    std::vector<std::uint8_t> raw(line * static_cast<std::size_t>(height));
    const auto bpp = static_cast<std::size_t>(channels);
    for (std::ptrdiff_t r = 0; r < height; ++r) {
        std::uint8_t* dst = raw.data() + static_cast<std::size_t>(r) * line;
        const std::uint8_t* row = pixels + r * row_stride;
        dst[0] = 0;
        std::copy_n(row, row_bytes, dst + 1);
        if (!deflate_available()) continue;
        const std::uint8_t* up = r > 0 ? pixels + (r - 1) * row_stride : nullptr;
        const auto cost = [&](int type) {
            std::uint64_t sum = 0;
            for (std::size_t i = 0; i < static_cast<std::size_t>(row_bytes); ++i) {
                const std::uint8_t v = filtered(type, row, up, i, bpp);
                sum += v < 128 ? v : 256u - v;
            }
            return sum;
        };
        int best = 0;
        std::uint64_t best_cost = cost(0);
        for (const int type : {1, 2}) {
            if (const auto c = cost(type); c < best_cost) best = type, best_cost = c;
        }
        dst[0] = static_cast<std::uint8_t>(best);
        for (std::size_t i = 0; i < static_cast<std::size_t>(row_bytes); ++i)
            dst[1 + i] = filtered(best, row, up, i, bpp);
    }
    const std::vector<std::uint8_t> z = deflate_available() ? zlib_deflate(raw) : zlib_stored(raw);

    std::vector<std::uint8_t> png{0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    std::vector<std::uint8_t> ihdr;
    put_u32_be(ihdr, static_cast<std::uint32_t>(width));
    put_u32_be(ihdr, static_cast<std::uint32_t>(height));
    ihdr.insert(ihdr.end(), {8, static_cast<std::uint8_t>(channels == 1 ? 0 : 2), 0, 0, 0});  // depth, colour, methods
    put_chunk(png, "IHDR", ihdr);
    constexpr std::size_t max_idat = std::size_t{1} << 24;  // several IDAT chunks keep each one well below 2^31
    for (std::size_t at = 0; at < z.size(); at += max_idat) {
        put_chunk(png, "IDAT", std::span<const std::uint8_t>(z).subspan(at, std::min(max_idat, z.size() - at)));
    }
    put_chunk(png, "IEND", {});
    return png;
}

void write_png_gray(const std::string& path, raster_view<const std::uint8_t> gray)
{
    write_file(path, encode_png(gray.cols(), gray.rows(), 1, gray.data(), gray.row_stride()));
}

void write_png_rgb(const std::string& path, std::ptrdiff_t width, std::ptrdiff_t height,
                   const std::vector<std::uint8_t>& rgb)
{
    detail::require(width >= 0 && height >= 0 && rgb.size() == static_cast<std::size_t>(width * height * 3),
                    "write_png_rgb", "rgb.size()", "width * height * 3", rgb.size());
    write_file(path, encode_png(width, height, 3, rgb.data(), width * 3));
}

void write_png_rgb(const std::string& path, const rgb_image& image)
{
    write_png_rgb(path, image.width, image.height, image.rgb);
}

}  // namespace lidarfx::io
