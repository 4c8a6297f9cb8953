// SPDX-License-Identifier: Apache-2.0
// las_class: the ASPRS standard point classification codes of LAS 1.4 (R15, table 17).
#pragma once

#include <cstdint>

/// ASPRS standard point classes (LAS 1.4 R15, table 17: point data record formats 6-10; formats 0-5 share
/// codes 0-12 and keep 5 bits). Codes 8 and 12 are reserved, 19-63 reserved, 64-255 user definable.
/// Classified points, rasters of classes (`surface` truth) and class filters all use these values.
namespace lidarfx::las_class {

inline constexpr std::uint8_t never_classified = 0;     ///< created, never classified
inline constexpr std::uint8_t unclassified = 1;         ///< unclassified
inline constexpr std::uint8_t ground = 2;               ///< ground
inline constexpr std::uint8_t low_vegetation = 3;       ///< low vegetation
inline constexpr std::uint8_t medium_vegetation = 4;    ///< medium vegetation
inline constexpr std::uint8_t high_vegetation = 5;      ///< high vegetation
inline constexpr std::uint8_t building = 6;             ///< building
inline constexpr std::uint8_t low_point = 7;            ///< low point (noise)
inline constexpr std::uint8_t water = 9;                ///< water
inline constexpr std::uint8_t rail = 10;                ///< rail
inline constexpr std::uint8_t road_surface = 11;        ///< road surface
inline constexpr std::uint8_t wire_guard = 13;          ///< wire - guard (shield)
inline constexpr std::uint8_t wire_conductor = 14;      ///< wire - conductor (phase)
inline constexpr std::uint8_t transmission_tower = 15;  ///< transmission tower
inline constexpr std::uint8_t wire_connector = 16;      ///< wire-structure connector (e.g. insulator)
inline constexpr std::uint8_t bridge_deck = 17;         ///< bridge deck
inline constexpr std::uint8_t high_noise = 18;          ///< high noise

}  // namespace lidarfx::las_class
