// SPDX-License-Identifier: Apache-2.0
// LASzip (LAZ) decoding for the LAS reader: the laszip VLR, the chunk table, and a decoder that turns one
// compressed chunk back into uncompressed LAS point records. Written from the LASzip format description
// (Isenburg, "LASzip: lossless compression of LiDAR data", PE&RS 2013, and the LAZ 1.4 layered items).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace lidarfx::io {

/// LASzip item types (the laszip VLR lists one per part of the point record, in record order).
enum class laz_item_type : std::uint16_t {
    byte = 0,       ///< extra bytes, point formats 0–5
    point10 = 6,    ///< the 20 bytes of point formats 0–5
    gpstime11 = 7,  ///< GPS time, 8 bytes
    rgb12 = 8,      ///< red, green, blue, 6 bytes
    point14 = 10,   ///< the 30 bytes of point formats 6–10
    rgb14 = 11,     ///< red, green, blue of formats 7 and 8
    rgbnir14 = 12,  ///< red, green, blue, near infrared of format 8
    byte14 = 14,    ///< extra bytes, point formats 6–10
};

struct laz_item {
    std::uint16_t type = 0, size = 0, version = 0;
};

/// The laszip VLR (user id "laszip encoded", record 22204).
struct laz_vlr {
    static constexpr std::uint32_t variable_chunk_size = 0xFFFFFFFFu;
    std::uint16_t compressor = 0;  ///< 1 point-wise, 2 point-wise chunked, 3 layered chunked (LAS 1.4)
    std::uint16_t coder = 0;       ///< 0 arithmetic (the only one defined)
    std::uint8_t version_major = 0, version_minor = 0;
    std::uint16_t version_revision = 0;
    std::uint32_t options = 0;
    std::uint32_t chunk_size = 0;  ///< points per chunk; variable_chunk_size: listed in the chunk table
    std::vector<laz_item> items;
};

/// One compressed chunk: its points [first_point, first_point + point_count) and its bytes in the file.
struct laz_chunk {
    std::uint64_t first_point = 0, point_count = 0;
    std::uint64_t offset = 0, byte_count = 0;
};

/// Most points a chunk may hold per compressed byte, after its raw first point: a chunk of B bytes holds at
/// most 1 + laz_max_points_per_byte * B points. Derived from the arithmetic decoder, not measured:
///  - a symbol of an n-symbol model (counts >= 1, total <= 2^15 after each update, distribution in units of
///    2^-15, n <= 513) leaves at most 1 - (n - 2) / 2^15 of the coder's interval, the truncations included,
///    so it costs at least -log2(1 - (n - 2) / 2^15) bits; bits (2^-13 models) and raw bits cost more than
///    nothing and are not counted;
///  - every point after the first decodes at least its changed-values symbol (POINT10: 64 symbols) and the
///    bit count k of dx, dy and z (33 symbols each): 0.0027323 + 3 x 0.0013655 = 0.0068288 bits. POINT14
///    decodes 128-symbol changed values and 33-symbol dx, dy in its XY layer alone (0.0082892 bits); other
///    items only add symbols;
///  - a stream of B bytes read with no byte past its end shrinks the interval from 2^32 to no less than
///    2^24 with at most B - 4 renormalisations, so its symbols cost less than 8 B bits in all.
/// Hence at most 8 / 0.0068288 = 1171.5 points per byte. A POINT10 chunk of all-zero bytes (symbol 0 every
/// time, the models learn it) runs out after 340 to 452 points a byte (tests/io/laz.cpp); real files take a
/// few bytes per point.
/// The bound turns a corrupt count into an error before anything is allocated; the memory budget of
/// las_reader::set_memory_budget bounds what a chunk under it may take.
inline constexpr std::uint64_t laz_max_points_per_byte = 1172;

/// Parses and checks the laszip VLR payload against the point format and record length of the header.
/// @throws std::runtime_error "<name>: ..." for an unknown compressor, item or item version, or items
/// that do not make up the record.
laz_vlr parse_laz_vlr(std::span<const std::uint8_t> payload, int point_format, std::uint16_t record_length,
                      const std::string& name);

/// Decodes the chunk table. `table` holds the bytes from the table's start (its 8-byte header: version,
/// chunk count) to at most the end of the file; chunks start at `first_chunk_offset` (the point data
/// offset + 8) and must end by `table_offset`. Fixed-size chunks hold vlr.chunk_size points (the last one
/// the rest). @throws std::runtime_error "<name>: ..." when counts or sizes disagree with the header
/// (`point_count`) or the file.
std::vector<laz_chunk> parse_laz_chunk_table(std::span<const std::uint8_t> table, const laz_vlr& vlr,
                                             std::uint64_t first_chunk_offset, std::uint64_t table_offset,
                                             std::uint64_t point_count, std::uint16_t record_length,
                                             const std::string& name);

/// Decodes chunks into uncompressed LAS records; holds the models, so one per thread, reused across chunks.
class laz_chunk_decoder {
public:
    laz_chunk_decoder(const laz_vlr& vlr, std::uint16_t record_length);
    laz_chunk_decoder(laz_chunk_decoder&&) noexcept;
    laz_chunk_decoder& operator=(laz_chunk_decoder&&) noexcept;
    ~laz_chunk_decoder();

    /// Decodes the `point_count` points of the chunk held in `bytes` into `records` (resized to
    /// point_count records of record_length bytes, one after the other; it grows as points are decoded,
    /// so a corrupt count fails before it is allocated). O(point_count).
    /// @throws std::runtime_error "<what>: ..." when the chunk's data is corrupt or ends early.
    void decode(std::span<const std::uint8_t> bytes, std::uint64_t point_count, std::vector<std::uint8_t>& records,
                const std::string& what);

private:
    struct impl;
    std::unique_ptr<impl> impl_;
};

}  // namespace lidarfx::io
