// SPDX-License-Identifier: Apache-2.0
// Dependency-free PNG writer (8-bit gray and RGB, zlib stored blocks) for quicklook pictures.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <lidarfx/core/raster_view.hpp>

namespace lidarfx::io {

/// An 8-bit RGB picture: `height` rows of `width` pixels, 3 bytes (r, g, b) each, row 0 at the top.
struct rgb_image {
    std::ptrdiff_t width = 0, height = 0;
    std::vector<std::uint8_t> rgb;  ///< width * height * 3 bytes, row-major
};

/// CRC-32 of `bytes` as used by PNG and zlib (reflected polynomial 0xEDB88320, initial and final XOR
/// 0xFFFFFFFF); pass the previous result as `crc` to continue over several buffers. O(n), table-driven.
std::uint32_t crc32(std::span<const std::uint8_t> bytes, std::uint32_t crc = 0) noexcept;

/// Adler-32 checksum of `bytes` (RFC 1950): a = 1 + sum of bytes, b = sum of the a's, both mod 65521,
/// result b * 65536 + a; pass the previous result as `adler` to continue. O(n).
std::uint32_t adler32(std::span<const std::uint8_t> bytes, std::uint32_t adler = 1) noexcept;

/// True when PNGs are DEFLATE-compressed (lidarfx_io built with zlib, LIDARFX_HAVE_ZLIB).
bool deflate_available() noexcept;

/// The bytes of a PNG file of `height` rows of `width` pixels with `channels` 8-bit samples each
/// (1 = gray, 3 = RGB), read from `pixels` with rows `row_stride` bytes apart. With zlib
/// (deflate_available()): per row the filter (none, Sub or Up) with the smallest sum of signed bytes, then
/// DEFLATE level 6. Without: filter 0 and stored deflate blocks (about the raw pixel size).
/// @throws invalid_input on a zero or too large size, channels not 1 or 3, or row_stride < width * channels.
std::vector<std::uint8_t> encode_png(std::ptrdiff_t width, std::ptrdiff_t height, int channels,
                                     const std::uint8_t* pixels, std::ptrdiff_t row_stride);

/// Writes an 8-bit grayscale PNG of `gray` (any row stride; row 0 at the top).
/// @throws invalid_input for an empty raster, std::runtime_error naming the file when it cannot be written.
void write_png_gray(const std::string& path, raster_view<const std::uint8_t> gray);

/// Writes an 8-bit RGB PNG from width * height * 3 bytes (r, g, b per pixel, row-major, top row first).
/// @throws invalid_input if rgb.size() != width * height * 3 or the size is zero; std::runtime_error on I/O.
void write_png_rgb(const std::string& path, std::ptrdiff_t width, std::ptrdiff_t height,
                   const std::vector<std::uint8_t>& rgb);

/// Writes an rgb_image as an 8-bit RGB PNG. @throws as the overload above.
void write_png_rgb(const std::string& path, const rgb_image& image);

}  // namespace lidarfx::io
