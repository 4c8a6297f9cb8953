// SPDX-License-Identifier: Apache-2.0
// Small LAS 1.0–1.4 writer (uncompressed, point formats 0–10) for tests, benchmarks and synthetic scenes.
#pragma once

#include <array>
#include <cstdint>
#include <fstream>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "io/las.hpp"

namespace lidarfx::io {

/// How to write a LAS file. Defaults: LAS 1.2, point format 0, centimetre scale, offset chosen from the data.
struct las_write_options {
    int version_minor = 2;  ///< LAS 1.x, 0..4; formats 2–3 need >= 2, 4–5 need >= 3, 6–10 need 4
    int point_format = 0;   ///< 0..10; RGB, NIR and wave-packet fields are written as zeros
    std::array<double, 3> scale{0.01, 0.01, 0.01};  ///< x, y, z quantum in metres, finite and > 0
    /// x, y, z offsets in metres; nullopt = the minimum of the first points written, floored to 1000 m.
    std::optional<std::array<double, 3>> offset{};
    int extra_bytes = 0;            ///< zero bytes appended to each record (record length grows), 0..1000
    int epsg_projected = 0;         ///< > 0: GeoKeyDirectory with ProjectedCSTypeGeoKey (3072), metres
    int epsg_geographic = 0;        ///< > 0: GeographicTypeGeoKey (2048)
    int epsg_vertical = 0;          ///< > 0: VerticalCSTypeGeoKey (4096), metres
    std::string wkt{};              ///< non-empty: an OGC WKT VLR (2112); LAS 1.4 also sets global encoding bit 4
    bool empty_wkt_record = false;  ///< with an empty `wkt`: write an empty WKT record (as careless writers do)
    /// Non-empty: the GeoKeyDirectory entries written as they are (instead of the keys of the EPSG codes above),
    /// with GeoDoubleParams (34736) and GeoAsciiParams (34737) VLRs when those are non-empty.
    std::vector<las_geo_key> geo_keys{};
    std::vector<double> geo_doubles{};
    std::string geo_ascii{};  ///< '|'-ended fields; a NUL is appended
    std::string system_identifier = "lidarfx";
    std::string generating_software = "lidarfx las_writer";
};

/// Streams points into a LAS file: the header (counts, returns histogram, bounds) is completed by close().
///     las_writer w(path, {.version_minor = 4, .point_format = 6}); w.write(chunk); ...; w.close();
/// Coordinates are quantized as round((v - offset) / scale) into 32-bit integers; the header bounds are those
/// of the quantized coordinates. Attributes missing from a las_points (empty arrays) get defaults: intensity
/// 0, return 1 of 1, class 0, no flags, angle 0, GPS time 0. O(points); records are written in blocks.
/// @throws invalid_input for bad options or values a format cannot hold (return number > 7 or class > 31
/// in formats 0–5, coordinates out of the 32-bit range, non-finite values, scan angle out of range);
/// std::runtime_error naming the file on I/O failure.
class las_writer {
public:
    /// Creates (truncates) the file `path`. @throws invalid_input for bad options, std::runtime_error if
    /// the file cannot be created.
    las_writer(const std::string& path, const las_write_options& options = {});
    /// Writes into a seekable stream (a std::stringstream for in-memory files); `name` starts error messages.
    las_writer(std::ostream& out, const las_write_options& options = {}, std::string name = "<stream>");
    las_writer(const las_writer&) = delete;
    las_writer& operator=(const las_writer&) = delete;
    /// Closes the file if close() was not called (errors are then swallowed: call close() to see them).
    ~las_writer();

    /// Appends the points (all arrays of x.size() elements, or empty for defaults). Points are encoded in
    /// blocks: if a value is rejected, the blocks before it have been written.
    void write(const las_points& points);
    /// Writes the final header; further writes throw. @throws std::runtime_error on I/O failure.
    void close();

    std::uint64_t points_written() const noexcept { return count_; }

private:
    void start();
    void write_header();

    std::string path_;
    las_write_options opt_;
    std::ofstream file_;
    std::ostream* out_ = nullptr;
    bool open_ = false;
    std::uint16_t record_length_ = 0;
    std::uint32_t offset_to_points_ = 0;
    std::uint32_t vlr_count_ = 0;
    std::array<double, 3> offset_{};
    bool offset_known_ = false;
    std::uint64_t count_ = 0;
    std::array<std::uint64_t, 15> by_return_{};
    std::array<std::int32_t, 3> qmin_{}, qmax_{};
    std::vector<std::uint8_t> block_;
};

/// Writes `points` to a new LAS file. @throws as las_writer.
void write_las(const std::string& path, const las_points& points, const las_write_options& options = {});

/// The bytes of a LAS file holding `points` (the same bytes write_las writes). @throws as las_writer.
std::vector<std::uint8_t> encode_las(const las_points& points, const las_write_options& options = {});

}  // namespace lidarfx::io
