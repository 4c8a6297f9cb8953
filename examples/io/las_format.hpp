// SPDX-License-Identifier: Apache-2.0
// LAS layout constants and little-endian field access shared by the LAS reader and writer (internal).
#pragma once

#include <array>
#include <bit>
#include <cstdint>
#include <cstring>

namespace lidarfx::io::las_format {

static_assert(std::endian::native == std::endian::little, "the LAS reader/writer assume a little-endian host");

/// Minimum record length of point formats 0..10 (ASPRS LAS 1.4 R15, tables 7–17).
inline constexpr std::array<std::uint16_t, 11> record_lengths{20, 28, 26, 34, 57, 63, 30, 36, 38, 59, 67};

inline constexpr std::uint16_t header_size_10 = 227;  // LAS 1.0–1.2
inline constexpr std::uint16_t header_size_13 = 235;  // + start of waveform data
inline constexpr std::uint16_t header_size_14 = 375;  // + EVLRs and 64-bit counts
inline constexpr std::size_t vlr_header_size = 54;
inline constexpr std::size_t evlr_header_size = 60;
inline constexpr float extended_scan_angle_step_deg = 0.006f;  // formats 6–10 store the angle in 0.006° steps

inline constexpr std::uint16_t header_size_for(int version_minor)
{
    return version_minor >= 4 ? header_size_14 : version_minor == 3 ? header_size_13 : header_size_10;
}

/// Reads a T stored little-endian at p (any alignment).
template <class T>
inline T load(const std::uint8_t* p) noexcept
{
    T v;
    std::memcpy(&v, p, sizeof(T));
    return v;
}

/// Stores v little-endian at p (any alignment).
template <class T>
inline void store(std::uint8_t* p, T v) noexcept
{
    std::memcpy(p, &v, sizeof(T));
}

}  // namespace lidarfx::io::las_format
