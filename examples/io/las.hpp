// SPDX-License-Identifier: Apache-2.0
// LAS 1.0–1.4 reader (point formats 0–10, and LAZ-compressed formats 0–3 and 6–8): validated header, CRS
// metadata, chunked reads.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <lidarfx/core/point_cloud.hpp>

namespace lidarfx::io {

/// Bits of las_points::classification_flags (the same meaning for every point format).
inline constexpr std::uint8_t las_flag_synthetic = 1;  ///< created by other means than the scanner
inline constexpr std::uint8_t las_flag_key_point = 2;  ///< model key-point (keep when thinning)
inline constexpr std::uint8_t las_flag_withheld = 4;   ///< to be ignored (deleted)
inline constexpr std::uint8_t las_flag_overlap = 8;    ///< overlap of flight lines (point formats 6–10 only)

/// Size in bytes of the fields of point data format 0..10 (a record may be longer: extra bytes follow).
/// Returns 0 for an unknown format.
std::uint16_t las_min_record_length(int point_format) noexcept;

/// True for the point formats that carry a GPS time (1, 3, 4, 5, 6, 7, 8, 9, 10).
bool las_format_has_gps_time(int point_format) noexcept;

/// One entry of the GeoKeyDirectory VLR (LASF_Projection 34735): key id, TIFF tag location (0 = the
/// value is stored in `value` itself), count, and value or index.
struct las_geo_key {
    std::uint16_t id = 0, location = 0, count = 0, value = 0;
    friend bool operator==(const las_geo_key&, const las_geo_key&) = default;
};

/// A variable-length record (VLR) or, in LAS 1.4, an extended one (EVLR): its identity and where its
/// payload lies in the file.
struct las_vlr {
    std::string user_id;          ///< e.g. "LASF_Projection"
    std::uint16_t record_id = 0;  ///< e.g. 34735 GeoKeyDirectory, 2112 OGC WKT
    std::string description;
    std::uint64_t data_offset = 0;  ///< byte offset of the payload in the file
    std::uint64_t data_size = 0;    ///< payload size in bytes
    bool extended = false;          ///< true for an EVLR (after the point data)
};

/// The public header block of a LAS file after validation, plus the CRS found in its (E)VLRs.
/// Counts are resolved across versions: `point_count` is the 64-bit count of LAS 1.4 when set, else the
/// legacy 32-bit count; `points_by_return` likewise (entries 5..14 are 0 before 1.4).
struct las_header {
    int version_major = 1, version_minor = 2;
    std::uint16_t file_source_id = 0;
    std::uint16_t global_encoding = 0;  ///< bit 0 GPS time type, bit 4 CRS as WKT (1.4)
    std::string system_identifier;
    std::string generating_software;
    std::uint16_t creation_day = 0, creation_year = 0;
    std::uint16_t header_size = 0;           ///< bytes; >= 227 (1.0–1.2), 235 (1.3), 375 (1.4)
    std::uint32_t offset_to_point_data = 0;  ///< bytes from the file start to the first point record
    std::uint32_t vlr_count = 0;
    int point_format = 0;                   ///< 0..10 (the compression bits of LAZ removed)
    bool compressed = false;                ///< LAZ: point data compressed by LASzip
    std::uint16_t point_record_length = 0;  ///< bytes per record, >= las_min_record_length(point_format)
    std::uint64_t point_count = 0;
    std::array<std::uint64_t, 15> points_by_return{};
    std::array<double, 3> scale{1, 1, 1};  ///< x, y, z: coordinate = integer * scale + offset
    std::array<double, 3> offset{};
    std::array<double, 3> min{}, max{};  ///< x, y, z bounds as written in the header, metres
    std::uint64_t evlr_offset = 0;       ///< LAS 1.4: byte offset of the first EVLR (0 when none)
    std::uint32_t evlr_count = 0;
    std::vector<las_vlr> vlrs;  ///< every VLR, then every EVLR, in file order

    // Coordinate reference system, kept as metadata (nothing is reprojected).
    std::vector<las_geo_key> geo_keys;  ///< GeoKeyDirectory entries, empty when absent
    std::vector<double> geo_doubles;    ///< GeoDoubleParams (34736) the keys point into, empty when absent
    std::string geo_ascii;              ///< GeoAsciiParams (34737) as stored ('|'-ended fields, NULs kept)
    int epsg_projected = 0;             ///< ProjectedCSTypeGeoKey (3072); 0 = absent or user-defined
    int epsg_geographic = 0;            ///< GeographicTypeGeoKey (2048); 0 = absent or user-defined
    int epsg_vertical = 0;              ///< VerticalCSTypeGeoKey (4096); 0 = absent or user-defined
    std::string wkt;                    ///< OGC coordinate system WKT (record 2112), empty when absent
    bool has_wkt_record = false;        ///< a WKT record (2112) is present, even an empty one

    bool has_gps_time() const noexcept { return las_format_has_gps_time(point_format); }
    /// The horizontal EPSG code: projected when known, else geographic, else 0.
    int epsg() const noexcept { return epsg_projected != 0 ? epsg_projected : epsg_geographic; }
};

/// Points as a struct of arrays, all of the same length (gps_time is empty for formats without it).
/// Fields are decoded from the record: return numbers have 3 bits in formats 0–5 and 4 bits in 6–10;
/// classification has 5 bits (flags apart) in 0–5 and 8 bits in 6–10; flags use the las_flag_* bits.
struct las_points {
    std::vector<double> x, y, z;  ///< metres (scale and offset applied)
    std::vector<std::uint16_t> intensity;
    std::vector<std::uint8_t> return_number, number_of_returns, classification;
    std::vector<std::uint8_t> classification_flags;  ///< las_flag_synthetic | key_point | withheld | overlap
    std::vector<float> scan_angle_deg;  ///< degrees, negative = left of nadir (formats 6–10: 0.006° steps)
    std::vector<double> gps_time;       ///< empty when the point format has no GPS time

    std::size_t size() const noexcept { return x.size(); }
    bool empty() const noexcept { return x.empty(); }
    /// Sets every array to n elements (gps_time to n or 0); keeps capacity, so reused chunks do not allocate.
    void resize(std::size_t n, bool with_gps_time);
    /// Appends the points of `other` (gps_time is kept only if both have it or this one is empty).
    void append(const las_points& other);
    /// Zero-copy view of x, y, z, intensity, return numbers and classification for the library's algorithms.
    soa_cloud<> cloud() const;
};

/// A las_points holding the fields of any struct-of-arrays point set with vectors x, y, z, intensity,
/// return_number, number_of_returns, classification and gps_time (a synthetic scene's points, say), with
/// no flags and nadir scan angles. O(points).
template <class PointSet>
las_points las_points_from(const PointSet& p)
{
    las_points out;
    out.x = p.x;
    out.y = p.y;
    out.z = p.z;
    out.intensity = p.intensity;
    out.return_number = p.return_number;
    out.number_of_returns = p.number_of_returns;
    out.classification = p.classification;
    out.classification_flags.assign(out.size(), 0);
    out.scan_angle_deg.assign(out.size(), 0.0f);
    out.gps_time = p.gps_time;
    return out;
}

/// Reads a LAS 1.0–1.4 file (point formats 0–10) or a LAZ file (LASzip, formats 0–3 and 6–8) in chunks:
///     las_reader r(path); r.header(); las_points chunk; while (r.read(chunk, 1 << 20)) { ... }
/// The constructor reads and validates the header and (E)VLRs: signature, version, header size, format
/// id, record length, point-data offset, counts against the file size, VLR extents, GeoKeys; for LAZ the
/// laszip VLR and the chunk table. Reads then decode large blocks (one read call each) with fixed field
/// offsets per format, O(points); LAZ chunks are decoded one at a time (memory of one chunk) or, with
/// set_threads(), several chunks of one read in parallel, with identical results, all within the memory
/// budget of set_memory_budget().
/// Every error is a std::runtime_error whose message starts with the file path (or the buffer's name):
/// "<path>: not a LAS file ...", "<path>: truncated ...", "<path>: LAZ chunk 3 of 9: the compressed data
/// ends early ...", and so on for each inconsistent header field.
/// The one exception is a LAZ chunk over the memory budget (set_memory_budget), refused with a
/// lidarfx::invalid_input naming the chunk, its claimed points and the budget.
class las_reader {
public:
    /// Opens and validates `path`. @throws std::runtime_error naming the file.
    explicit las_reader(const std::string& path);

    /// Reads LAS bytes held in memory (they must outlive the reader); `name` starts error messages.
    /// @throws std::runtime_error as for a file.
    explicit las_reader(std::span<const std::uint8_t> bytes, std::string name = "<memory>");

    /// Reads LAS bytes it takes ownership of (so a temporary buffer cannot dangle).
    explicit las_reader(std::vector<std::uint8_t>&& bytes, std::string name = "<memory>");

    las_reader(las_reader&&) noexcept;
    las_reader& operator=(las_reader&&) noexcept;
    ~las_reader();

    const las_header& header() const noexcept { return header_; }
    const std::string& path() const noexcept { return path_; }
    std::uint64_t point_count() const noexcept { return header_.point_count; }
    /// Index of the next point read() returns (0 after opening).
    std::uint64_t position() const noexcept { return next_; }
    /// Moves to point `index` (0..point_count). @throws std::runtime_error beyond the end.
    void seek(std::uint64_t index);

    /// Reads up to `max_points` points from the current position into `chunk` (resized to the count
    /// read) and returns that count; 0 at the end. @throws std::runtime_error on I/O failure.
    std::size_t read(las_points& chunk, std::size_t max_points);

    /// Reads up to `max_points` point records, as stored in an uncompressed LAS file (LAZ decoded), from the
    /// current position into `records` (resized to count * point_record_length bytes); returns the count.
    std::size_t read_records(std::vector<std::uint8_t>& records, std::size_t max_points);

    /// Reads every point of the file (from the start, whatever the position; the position ends at the end).
    las_points read_all();

    /// Threads that decode the LAZ chunks of one read() (1 by default, 0 = all cores); results do not
    /// depend on it. No effect on uncompressed files. @throws std::runtime_error if threads < 0.
    void set_threads(int threads);

    /// Memory the decoded LAZ chunks may take at once, in bytes (0, the default: half the physical memory);
    /// a chunk's decoded records take its point count x point_record_length bytes. A read refuses at once,
    /// before decoding anything, a chunk over half the budget (the chunk decoding and the one kept for the
    /// next read must fit), throwing lidarfx::invalid_input "<path>: LAZ chunk 3 of 9 (first point ...)
    /// claims N points ... over half the memory budget ...; raise the memory budget (--memory) to at least
    /// ...". Chunks decode on as many threads as keep the largest chunk of the file in flight, plus the kept
    /// one, within the budget: (k + 1) x largest <= budget, so large chunks decode on fewer threads (results
    /// do not change). No effect on uncompressed files.
    void set_memory_budget(std::uint64_t bytes) noexcept { memory_budget_ = bytes; }
    /// The budget in bytes (0 resolved to half the physical memory).
    std::uint64_t memory_budget() const noexcept;
    /// Decoded bytes of the largest LAZ chunk (its points x point_record_length); 0 for uncompressed files.
    std::uint64_t largest_chunk_bytes() const noexcept;
    /// Threads a LAZ read decodes on: set_threads() (0 resolved to the cores), lowered to the k with
    /// (k + 1) x the largest chunk's decoded records within the budget, at least 1; 1 for uncompressed files.
    int decode_threads() const;

private:
    struct laz_state;
    const std::uint8_t* bytes_at(std::uint64_t offset, std::size_t size);
    void parse();
    void open_laz();
    /// Decodes points [position, position + n) of a LAZ file in batches of chunks: grow(m) before each
    /// batch (m = points up to its end), then sink(records, count, index) for every chunk of it (index
    /// counts from the position), possibly from several threads at once.
    using record_sink = std::function<void(const std::uint8_t*, std::size_t, std::size_t)>;
    void read_laz(std::size_t n, const std::function<void(std::size_t)>& grow, const record_sink& sink);

    std::string path_;
    std::ifstream file_;                    // used when reading a file
    std::span<const std::uint8_t> memory_;  // used when reading a buffer
    std::vector<std::uint8_t> owned_;       // the buffer, when the reader owns it
    std::uint64_t file_size_ = 0;
    std::vector<std::uint8_t> buffer_;
    las_header header_;
    std::uint64_t next_ = 0;
    std::unique_ptr<laz_state> laz_;  // LAZ only: chunk table, decoders, the last chunk decoded
    int threads_ = 1;
    std::uint64_t memory_budget_ = 0;  // 0: half the physical memory
};

/// Reads every point of a LAS file. @throws std::runtime_error naming the file.
las_points read_las(const std::string& path);

}  // namespace lidarfx::io
