// SPDX-License-Identifier: Apache-2.0
#include "io/las.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>
#include <filesystem>
#include <iomanip>
#include <mutex>
#include <sstream>
#include <stdexcept>

#include <unistd.h>

#include <lidarfx/core/error.hpp>
#include <lidarfx/core/parallel.hpp>

#include "io/las_format.hpp"
#include "io/laz.hpp"

namespace lidarfx::io {

using namespace las_format;

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what)
{
    throw std::runtime_error(path + ": " + what);
}

/// Bytes as MiB with up to 4 significant digits ("256 MiB", "1032 MiB", "0.5 MiB").
std::string mib(double bytes)
{
    std::ostringstream s;
    s << std::setprecision(4) << bytes / 1048576.0 << " MiB";
    return s.str();
}

std::string fixed_string(const std::uint8_t* p, std::size_t n)
{
    std::size_t len = 0;
    while (len < n && p[len] != 0) ++len;
    return std::string(reinterpret_cast<const char*>(p), len);
}

/// Decodes `n` records of `stride` bytes at `p` into `out` from index `at`. Field offsets are fixed per
/// format family (0–5 legacy, 6–10 extended); GPS time sits at byte 20 (legacy) or 22 (extended).
template <bool Extended, bool Gps>
void decode(const std::uint8_t* p, std::size_t n, std::size_t stride, const las_header& h, las_points& out,
            std::size_t at)
{
    const double sx = h.scale[0], sy = h.scale[1], sz = h.scale[2];
    const double ox = h.offset[0], oy = h.offset[1], oz = h.offset[2];
    double* x = out.x.data() + at;
    double* y = out.y.data() + at;
    double* z = out.z.data() + at;
    std::uint16_t* intensity = out.intensity.data() + at;
    std::uint8_t* rn = out.return_number.data() + at;
    std::uint8_t* nr = out.number_of_returns.data() + at;
    std::uint8_t* cls = out.classification.data() + at;
    std::uint8_t* flags = out.classification_flags.data() + at;
    float* angle = out.scan_angle_deg.data() + at;
    double* gps = Gps ? out.gps_time.data() + at : nullptr;
    for (std::size_t i = 0; i < n; ++i, p += stride) {
        x[i] = static_cast<double>(load<std::int32_t>(p)) * sx + ox;
        y[i] = static_cast<double>(load<std::int32_t>(p + 4)) * sy + oy;
        z[i] = static_cast<double>(load<std::int32_t>(p + 8)) * sz + oz;
        intensity[i] = load<std::uint16_t>(p + 12);
        const std::uint8_t returns = p[14];
        if constexpr (Extended) {
            rn[i] = returns & 0x0F;
            nr[i] = static_cast<std::uint8_t>(returns >> 4);
            flags[i] = p[15] & 0x0F;
            cls[i] = p[16];
            angle[i] = static_cast<float>(load<std::int16_t>(p + 18)) * extended_scan_angle_step_deg;
            if constexpr (Gps) gps[i] = load<double>(p + 22);
        } else {
            rn[i] = returns & 0x07;
            nr[i] = static_cast<std::uint8_t>((returns >> 3) & 0x07);
            cls[i] = p[15] & 0x1F;
            flags[i] = static_cast<std::uint8_t>(p[15] >> 5);
            angle[i] = static_cast<float>(static_cast<std::int8_t>(p[16]));
            if constexpr (Gps) gps[i] = load<double>(p + 20);
        }
    }
}

using decoder = void (*)(const std::uint8_t*, std::size_t, std::size_t, const las_header&, las_points&, std::size_t);

decoder decoder_for(int format)
{
    const bool gps = las_format_has_gps_time(format);
    if (format >= 6) return gps ? &decode<true, true> : &decode<true, false>;
    return gps ? &decode<false, true> : &decode<false, false>;
}

constexpr std::size_t block_bytes = std::size_t{2} << 20;  // decode in ~2 MiB blocks: one read call each

}  // namespace

std::uint16_t las_min_record_length(int point_format) noexcept
{
    return point_format >= 0 && point_format <= 10 ? record_lengths[static_cast<std::size_t>(point_format)] : 0;
}

bool las_format_has_gps_time(int point_format) noexcept
{
    return point_format == 1 || (point_format >= 3 && point_format <= 10);
}

void las_points::resize(std::size_t n, bool with_gps_time)
{
    x.resize(n);
    y.resize(n);
    z.resize(n);
    intensity.resize(n);
    return_number.resize(n);
    number_of_returns.resize(n);
    classification.resize(n);
    classification_flags.resize(n);
    scan_angle_deg.resize(n);
    gps_time.resize(with_gps_time ? n : 0);
}

void las_points::append(const las_points& other)
{
    const bool gps =
        (empty() || !gps_time.empty()) && (other.empty() || !other.gps_time.empty()) && !(empty() && other.empty());
    const auto cat = [](auto& to, const auto& from) { to.insert(to.end(), from.begin(), from.end()); };
    cat(x, other.x);
    cat(y, other.y);
    cat(z, other.z);
    cat(intensity, other.intensity);
    cat(return_number, other.return_number);
    cat(number_of_returns, other.number_of_returns);
    cat(classification, other.classification);
    cat(classification_flags, other.classification_flags);
    cat(scan_angle_deg, other.scan_angle_deg);
    if (gps)
        cat(gps_time, other.gps_time);
    else
        gps_time.clear();
}

soa_cloud<> las_points::cloud() const
{
    return soa_cloud<>(x, y, z, intensity, return_number, number_of_returns, classification);
}

las_reader::las_reader(const std::string& path) : path_(path)
{
    std::error_code ec;
    const auto size = std::filesystem::file_size(path, ec);
    if (ec) fail(path_, "cannot open (" + ec.message() + ")");
    file_.open(path, std::ios::binary);
    if (!file_) fail(path_, "cannot open for reading");
    file_size_ = size;
    parse();
}

las_reader::las_reader(std::span<const std::uint8_t> bytes, std::string name)
    : path_(std::move(name)), memory_(bytes), file_size_(bytes.size())
{
    parse();
}

las_reader::las_reader(std::vector<std::uint8_t>&& bytes, std::string name)
    : path_(std::move(name)), owned_(std::move(bytes))
{
    memory_ = owned_;  // the heap block stays put when the reader is moved
    file_size_ = owned_.size();
    parse();
}

las_reader::las_reader(las_reader&&) noexcept = default;
las_reader& las_reader::operator=(las_reader&&) noexcept = default;
las_reader::~las_reader() = default;

const std::uint8_t* las_reader::bytes_at(std::uint64_t offset, std::size_t size)
{
    if (offset > file_size_ || size > file_size_ - offset) {
        fail(path_, "unexpected end of file reading " + std::to_string(size) + " bytes at byte " +
                        std::to_string(offset) + " (the file has " + std::to_string(file_size_) + " bytes)");
    }
    if (!file_.is_open()) return memory_.data() + offset;
    if (buffer_.size() < size) buffer_.resize(size);
    file_.clear();
    file_.seekg(static_cast<std::streamoff>(offset));
    file_.read(reinterpret_cast<char*>(buffer_.data()), static_cast<std::streamsize>(size));
    if (file_.gcount() != static_cast<std::streamsize>(size)) {
        fail(path_, "unexpected end of file at byte " + std::to_string(offset + file_.gcount()) +
                        " (did the file change while it was read?)");
    }
    return buffer_.data();
}

void las_reader::parse()
{
    las_header& h = header_;
    if (file_size_ < 4) fail(path_, "not a LAS file (only " + std::to_string(file_size_) + " bytes)");
    const std::size_t head_size = static_cast<std::size_t>(std::min<std::uint64_t>(file_size_, header_size_14));
    std::vector<std::uint8_t> head;
    {
        const std::uint8_t* p = bytes_at(0, head_size);
        head.assign(p, p + head_size);
    }
    const std::uint8_t* p = head.data();
    if (std::memcmp(p, "LASF", 4) != 0) fail(path_, "not a LAS file (the signature is not 'LASF')");
    if (head_size < header_size_10) {
        fail(path_, "truncated header: the file has " + std::to_string(file_size_) + " bytes, a LAS header at least " +
                        std::to_string(header_size_10));
    }

    h.version_major = p[24];
    h.version_minor = p[25];
    if (h.version_major != 1 || h.version_minor > 4) {
        fail(path_, "unsupported LAS version " + std::to_string(h.version_major) + "." +
                        std::to_string(h.version_minor) + " (this reader handles 1.0 to 1.4)");
    }
    h.file_source_id = load<std::uint16_t>(p + 4);
    h.global_encoding = load<std::uint16_t>(p + 6);
    h.system_identifier = fixed_string(p + 26, 32);
    h.generating_software = fixed_string(p + 58, 32);
    h.creation_day = load<std::uint16_t>(p + 90);
    h.creation_year = load<std::uint16_t>(p + 92);
    h.header_size = load<std::uint16_t>(p + 94);
    h.offset_to_point_data = load<std::uint32_t>(p + 96);
    h.vlr_count = load<std::uint32_t>(p + 100);
    // LASzip marks compressed point data with bit 7 (older writers bit 6) of the format id.
    h.point_format = p[104] & 0x3F;
    h.compressed = (p[104] & 0xC0) != 0;
    h.point_record_length = load<std::uint16_t>(p + 105);

    const std::uint16_t min_header = header_size_for(h.version_minor);
    if (h.header_size < min_header) {
        fail(path_, "header size " + std::to_string(h.header_size) + " is too small for LAS 1." +
                        std::to_string(h.version_minor) + " (at least " + std::to_string(min_header) + " bytes)");
    }
    if (h.header_size > file_size_) {
        fail(path_, "truncated header: header size " + std::to_string(h.header_size) + " exceeds the file size " +
                        std::to_string(file_size_));
    }
    if (h.point_format > 10) {
        fail(path_, "unknown point data format " + std::to_string(h.point_format) + " (expected 0 to 10)");
    }
    const std::uint16_t min_record = las_min_record_length(h.point_format);
    if (h.point_record_length < min_record) {
        fail(path_, "point record length " + std::to_string(h.point_record_length) + " is smaller than the " +
                        std::to_string(min_record) + " bytes of point format " + std::to_string(h.point_format));
    }
    if (h.offset_to_point_data < h.header_size) {
        fail(path_, "offset to point data " + std::to_string(h.offset_to_point_data) +
                        " lies inside the header (header size " + std::to_string(h.header_size) + ")");
    }
    if (h.offset_to_point_data > file_size_) {
        fail(path_, "offset to point data " + std::to_string(h.offset_to_point_data) + " is beyond the file size " +
                        std::to_string(file_size_));
    }

    // Counts: LAS 1.4 adds 64-bit counts; the legacy ones must then be 0 or equal.
    const std::uint64_t legacy_count = load<std::uint32_t>(p + 107);
    h.point_count = legacy_count;
    for (std::size_t k = 0; k < 5; ++k) h.points_by_return[k] = load<std::uint32_t>(p + 111 + 4 * k);
    if (h.version_minor >= 4) {
        h.evlr_offset = load<std::uint64_t>(p + 235);
        h.evlr_count = load<std::uint32_t>(p + 243);
        const std::uint64_t count = load<std::uint64_t>(p + 247);
        if (count != 0) {
            if (legacy_count != 0 && legacy_count != count) {
                fail(path_, "legacy point count " + std::to_string(legacy_count) +
                                " disagrees with the 64-bit point count " + std::to_string(count));
            }
            h.point_count = count;
        }
        std::array<std::uint64_t, 15> by_return{};
        bool any = false;
        for (std::size_t k = 0; k < 15; ++k) {
            by_return[k] = load<std::uint64_t>(p + 255 + 8 * k);
            any = any || by_return[k] != 0;
        }
        if (any) h.points_by_return = by_return;
    }

    // The point records must lie inside the file (LAZ: checked against the chunk table).
    const std::uint64_t room = file_size_ - h.offset_to_point_data;
    if (!h.compressed && h.point_count > room / h.point_record_length) {
        fail(path_, "truncated: the header declares " + std::to_string(h.point_count) + " points of " +
                        std::to_string(h.point_record_length) + " bytes from byte " +
                        std::to_string(h.offset_to_point_data) + " but the file has " + std::to_string(file_size_) +
                        " bytes (room for " + std::to_string(room / h.point_record_length) + " points)");
    }

    static constexpr const char* axis[3] = {"x", "y", "z"};
    for (std::size_t k = 0; k < 3; ++k) {
        h.scale[k] = load<double>(p + 131 + 8 * k);
        h.offset[k] = load<double>(p + 155 + 8 * k);
        h.max[k] = load<double>(p + 179 + 16 * k);
        h.min[k] = load<double>(p + 187 + 16 * k);
        if (!std::isfinite(h.scale[k]) || h.scale[k] == 0) {
            fail(path_, detail::concat(axis[k], " scale factor ", h.scale[k], " must be finite and non-zero"));
        }
        if (!std::isfinite(h.offset[k])) fail(path_, std::string(axis[k]) + " offset must be finite");
    }

    // VLRs sit between the header and the point data.
    std::uint64_t pos = h.header_size;
    const std::uint64_t vlr_end = h.offset_to_point_data;
    const auto read_record = [&](std::uint64_t at, std::size_t fixed, bool extended, std::uint64_t end,
                                 std::uint32_t index, std::uint32_t total) {
        const char* kind = extended ? "EVLR " : "VLR ";
        const std::string which = kind + std::to_string(index + 1) + " of " + std::to_string(total);
        if (at > end || end - at < fixed) {
            fail(path_, which + " at byte " + std::to_string(at) + " does not fit " +
                            (extended ? "in the file" : "before the point data (offset " + std::to_string(end) + ")"));
        }
        const std::uint8_t* r = bytes_at(at, fixed);
        las_vlr v;
        v.user_id = fixed_string(r + 2, 16);
        v.record_id = load<std::uint16_t>(r + 18);
        v.data_size = extended ? load<std::uint64_t>(r + 20) : load<std::uint16_t>(r + 20);
        v.description = fixed_string(r + (extended ? 28 : 22), 32);
        v.data_offset = at + fixed;
        v.extended = extended;
        if (v.data_size > end - v.data_offset) {
            fail(path_, which + " ('" + v.user_id + "' " + std::to_string(v.record_id) + ") declares " +
                            std::to_string(v.data_size) + " bytes, past " +
                            (extended ? "the end of the file" : "the start of the point data"));
        }
        return v;
    };
    for (std::uint32_t i = 0; i < h.vlr_count; ++i) {
        las_vlr v = read_record(pos, vlr_header_size, false, vlr_end, i, h.vlr_count);
        pos = v.data_offset + v.data_size;
        h.vlrs.push_back(std::move(v));
    }
    if (h.evlr_count > 0) {
        const std::uint64_t points_end =
            h.offset_to_point_data + (h.compressed ? 0 : h.point_count * h.point_record_length);
        if (h.evlr_offset < points_end) {
            fail(path_, "start of the first EVLR (byte " + std::to_string(h.evlr_offset) +
                            ") lies inside the header or the point data (which ends at byte " +
                            std::to_string(points_end) + ")");
        }
        pos = h.evlr_offset;
        for (std::uint32_t i = 0; i < h.evlr_count; ++i) {
            las_vlr v = read_record(pos, evlr_header_size, true, file_size_, i, h.evlr_count);
            pos = v.data_offset + v.data_size;
            h.vlrs.push_back(std::move(v));
        }
    }

    for (const las_vlr& v : h.vlrs) {
        if (v.user_id != "LASF_Projection" ||
            (v.record_id != 34735 && v.record_id != 34736 && v.record_id != 34737 && v.record_id != 2112)) {
            continue;
        }
        const std::uint8_t* data = bytes_at(v.data_offset, static_cast<std::size_t>(v.data_size));
        if (v.record_id == 2112) {
            h.wkt = fixed_string(data, static_cast<std::size_t>(v.data_size));
            h.has_wkt_record = true;
            continue;
        }
        if (v.record_id == 34736) {  // GeoDoubleParams: the doubles GeoKeys point into (a partial one is dropped)
            h.geo_doubles.resize(static_cast<std::size_t>(v.data_size / 8));
            for (std::size_t k = 0; k < h.geo_doubles.size(); ++k) h.geo_doubles[k] = load<double>(data + 8 * k);
            continue;
        }
        if (v.record_id == 34737) {  // GeoAsciiParams: kept byte for byte, since keys index into it
            h.geo_ascii.assign(reinterpret_cast<const char*>(data), static_cast<std::size_t>(v.data_size));
            continue;
        }
        // GeoKeyDirectory: a header {version, revision, minor, key count} then 4 x u16 per key.
        if (v.data_size < 8) {
            fail(path_, "GeoKeyDirectory VLR holds " + std::to_string(v.data_size) + " bytes (at least 8 needed)");
        }
        const std::size_t keys = load<std::uint16_t>(data + 6);
        if (8 + 8 * keys > v.data_size) {
            fail(path_, "GeoKeyDirectory VLR declares " + std::to_string(keys) + " keys but holds room for " +
                            std::to_string((v.data_size - 8) / 8));
        }
        h.geo_keys.clear();
        for (std::size_t k = 0; k < keys; ++k) {
            const std::uint8_t* e = data + 8 + 8 * k;
            const las_geo_key key{load<std::uint16_t>(e), load<std::uint16_t>(e + 2), load<std::uint16_t>(e + 4),
                                  load<std::uint16_t>(e + 6)};
            h.geo_keys.push_back(key);
            // Only codes stored in place are EPSG codes; 32767 means "user-defined".
            const int code = key.location == 0 && key.value != 32767 ? key.value : 0;
            if (key.id == 3072)
                h.epsg_projected = code;
            else if (key.id == 2048)
                h.epsg_geographic = code;
            else if (key.id == 4096)
                h.epsg_vertical = code;
        }
    }
    if (h.compressed) open_laz();
}

struct las_reader::laz_state {
    laz_vlr vlr;
    std::vector<laz_chunk> chunks;
    std::uint64_t largest_points = 0;  // of a chunk
    std::mutex file_mutex;             // guards the file stream when worker threads fetch chunks
    /// What one thread needs to decode a chunk; kept in a pool so decoders are reused across reads.
    struct worker {
        laz_chunk_decoder decoder;
        std::vector<std::uint8_t> compressed, records;
    };
    std::mutex pool_mutex;
    std::vector<std::unique_ptr<worker>> pool;
    // The last chunk decoded (a read that ends inside a chunk continues there without decoding it again).
    std::size_t cached = SIZE_MAX;
    std::vector<std::uint8_t> cached_records;

    std::unique_ptr<worker> take(std::uint16_t record_length)
    {
        std::lock_guard lock(pool_mutex);
        if (pool.empty()) return std::make_unique<worker>(worker{laz_chunk_decoder(vlr, record_length), {}, {}});
        auto w = std::move(pool.back());
        pool.pop_back();
        return w;
    }
    void give(std::unique_ptr<worker> w)
    {
        std::lock_guard lock(pool_mutex);
        pool.push_back(std::move(w));
    }
    /// Index of the chunk holding point `index` (< point count).
    std::size_t chunk_of(std::uint64_t index) const
    {
        const auto it = std::upper_bound(chunks.begin(), chunks.end(), index,
                                         [](std::uint64_t i, const laz_chunk& c) { return i < c.first_point; });
        return static_cast<std::size_t>(it - chunks.begin()) - 1;
    }
};

void las_reader::open_laz()
{
    const las_header& h = header_;
    const las_vlr* found = nullptr;
    for (const las_vlr& v : h.vlrs) {
        if (v.user_id == "laszip encoded" && v.record_id == 22204) found = &v;
    }
    if (!found) {
        fail(path_,
             "the point format says LAZ (compressed) but the file has no laszip VLR (user id 'laszip "
             "encoded', record 22204)");
    }
    laz_ = std::make_unique<laz_state>();
    {
        const std::uint8_t* data = bytes_at(found->data_offset, static_cast<std::size_t>(found->data_size));
        laz_->vlr = parse_laz_vlr({data, static_cast<std::size_t>(found->data_size)}, h.point_format,
                                  h.point_record_length, path_);
    }
    // The point data starts with the 64-bit offset of the chunk table; -1 (a writer that could not seek
    // back) means the offset is in the last 8 bytes of the file.
    const std::uint64_t first_chunk = std::uint64_t{h.offset_to_point_data} + 8;
    std::int64_t table = load<std::int64_t>(bytes_at(h.offset_to_point_data, 8));
    if (table == -1) {
        if (file_size_ < first_chunk + 8) fail(path_, "truncated LAZ file: no chunk table offset at its end");
        table = load<std::int64_t>(bytes_at(file_size_ - 8, 8));
    }
    if (table < 0 || static_cast<std::uint64_t>(table) < first_chunk ||
        static_cast<std::uint64_t>(table) > file_size_ - 8) {
        fail(path_, "the LAZ chunk table offset " + std::to_string(table) + " lies outside the point data (bytes " +
                        std::to_string(first_chunk) + " to " + std::to_string(file_size_) +
                        "); is the file truncated?");
    }
    const auto table_offset = static_cast<std::uint64_t>(table);
    // The compressed table takes at most a few bytes per chunk; there are at most `room / record` chunks.
    const std::uint64_t max_chunks = (table_offset - first_chunk) / h.point_record_length;
    const std::uint64_t table_bytes = std::min<std::uint64_t>(file_size_ - table_offset, 16 + 24 * max_chunks);
    const std::uint8_t* t = bytes_at(table_offset, static_cast<std::size_t>(table_bytes));
    const std::vector<std::uint8_t> copy(t, t + table_bytes);
    laz_->chunks =
        parse_laz_chunk_table(copy, laz_->vlr, first_chunk, table_offset, h.point_count, h.point_record_length, path_);
    for (const laz_chunk& c : laz_->chunks) laz_->largest_points = std::max(laz_->largest_points, c.point_count);
}

std::uint64_t las_reader::memory_budget() const noexcept
{
    if (memory_budget_ != 0) return memory_budget_;
    const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
    const std::uint64_t physical =
        pages > 0 && page > 0 ? static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page) : 0;
    return physical > 0 ? physical / 2 : std::uint64_t{1} << 31;  // 2 GiB when the system does not say
}

void las_reader::set_threads(int threads)
{
    if (threads < 0) fail(path_, "set_threads: threads must be >= 0 (got " + std::to_string(threads) + ")");
    threads_ = threads;
}

std::uint64_t las_reader::largest_chunk_bytes() const noexcept
{
    return laz_ ? laz_->largest_points * header_.point_record_length : 0;
}

int las_reader::decode_threads() const
{
    if (!laz_) return 1;
    const std::uint64_t largest = std::max<std::uint64_t>(1, largest_chunk_bytes());
    const std::uint64_t in_budget = memory_budget() / largest;  // chunks of the largest size
    const auto fit = static_cast<int>(std::min<std::uint64_t>(in_budget > 1 ? in_budget - 1 : 1, 1024));
    return std::clamp(fit, 1, lidarfx::detail::resolve_threads(threads_, "las_reader"));
}

void las_reader::read_laz(std::size_t n, const std::function<void(std::size_t)>& grow, const record_sink& sink)
{
    const las_header& h = header_;
    laz_state& z = *laz_;
    const std::size_t stride = h.point_record_length;
    const std::uint64_t begin = next_, end = next_ + n;
    const std::size_t c0 = z.chunk_of(begin), c1 = z.chunk_of(end - 1);
    // The memory budget, before anything is decoded: each chunk of the read (its decoded records) within
    // half of it, and as many chunks in flight as fit beside the one kept for the next read.
    const std::uint64_t budget = memory_budget();
    for (std::size_t c = c0; c <= c1; ++c) {
        const laz_chunk& k = z.chunks[c];
        const double decoded = static_cast<double>(k.point_count) * static_cast<double>(stride);
        if (decoded > static_cast<double>(budget) / 2) {
            throw invalid_input(path_ + ": LAZ chunk " + std::to_string(c + 1) + " of " +
                                std::to_string(z.chunks.size()) + " (first point " + std::to_string(k.first_point) +
                                ") claims " + std::to_string(k.point_count) + " points in " +
                                std::to_string(k.byte_count) + " compressed bytes: " + mib(decoded) + " decoded (" +
                                std::to_string(stride) + " bytes a point), over half the memory budget of " +
                                mib(static_cast<double>(budget)) +
                                " (a chunk decoding and the one kept must fit); raise the memory budget (--memory) "
                                "to at least " +
                                mib(2 * decoded) +
                                ", or check the file (a corrupt chunk table "
                                "claims more points than its chunk holds)");
        }
    }
    // Converts the part of chunk c inside [begin, end) from its decoded records into `chunk`.
    const auto take_points = [&](std::size_t c, const std::uint8_t* records) {
        const laz_chunk& k = z.chunks[c];
        const std::uint64_t lo = std::max(begin, k.first_point), hi = std::min(end, k.first_point + k.point_count);
        sink(records + (lo - k.first_point) * stride, static_cast<std::size_t>(hi - lo),
             static_cast<std::size_t>(lo - begin));
    };
    std::vector<std::uint8_t> next_cache;
    const bool file = file_.is_open();
    std::size_t first = c0;                  // of the batch at hand
    std::vector<std::exception_ptr> errors;  // per chunk of the batch
    const auto body = [&](std::ptrdiff_t b0, std::ptrdiff_t b1) {
        for (std::ptrdiff_t b = b0; b < b1; ++b) try {
                const std::size_t c = first + static_cast<std::size_t>(b);
                if (c == z.cached) {
                    take_points(c, z.cached_records.data());
                    continue;
                }
                const laz_chunk& k = z.chunks[c];
                auto w = z.take(h.point_record_length);
                const auto bytes = static_cast<std::size_t>(k.byte_count);
                const std::uint8_t* data;
                if (file) {
                    std::lock_guard lock(z.file_mutex);
                    const std::uint8_t* p = bytes_at(k.offset, bytes);
                    w->compressed.assign(p, p + bytes);
                    data = w->compressed.data();
                } else {
                    data = bytes_at(k.offset, bytes);
                }
                w->decoder.decode(
                    {data, bytes}, k.point_count, w->records,
                    path_ + ": LAZ chunk " + std::to_string(c + 1) + " of " + std::to_string(z.chunks.size()));
                take_points(c, w->records.data());
                if (c == c1) next_cache.swap(w->records);  // kept for the next read: moved, not copied
                z.give(std::move(w));
            } catch (...) {
                errors[static_cast<std::size_t>(b)] = std::current_exception();
            }
    };
    // Batches of a few chunks per thread: the output grows with the points decoded (a corrupt file fails
    // before its claimed count is allocated), and each batch runs in parallel on at most `threads` workers,
    // each holding one chunk: (threads + 1) x the largest chunk within the budget.
    const int threads = decode_threads();
    const std::size_t batch = threads == 1 ? 1 : 2 * static_cast<std::size_t>(threads);
    for (; first <= c1; first += batch) {
        const std::size_t last = std::min(c1, first + batch - 1);
        grow(static_cast<std::size_t>(std::min(end, z.chunks[last].first_point + z.chunks[last].point_count) - begin));
        errors.assign(last - first + 1, nullptr);
        lidarfx::parallel_for_rows(static_cast<std::ptrdiff_t>(last - first + 1), 1, threads, body);
        // The first failing chunk in file order, whatever the thread count (all of the batch ran).
        for (const auto& e : errors) {
            if (e) std::rethrow_exception(e);
        }
    }
    if (z.cached != c1) {
        z.cached_records.swap(next_cache);
        z.cached = c1;
    }
    // Workers beyond this read's threads (from reads on more threads) would keep their chunks' memory.
    {
        std::lock_guard lock(z.pool_mutex);
        if (z.pool.size() > static_cast<std::size_t>(threads)) z.pool.resize(static_cast<std::size_t>(threads));
    }
    next_ = end;
}

std::size_t las_reader::read_records(std::vector<std::uint8_t>& records, std::size_t max_points)
{
    const las_header& h = header_;
    const auto n = static_cast<std::size_t>(std::min<std::uint64_t>(max_points, h.point_count - next_));
    const std::size_t stride = h.point_record_length;
    records.resize(laz_ ? 0 : n * stride);
    if (n == 0) return 0;
    const auto copy = [&](const std::uint8_t* from, std::size_t count, std::size_t at) {
        std::memcpy(records.data() + at * stride, from, count * stride);
    };
    if (laz_) {
        read_laz(
            n, [&](std::size_t points) { records.resize(points * stride); }, copy);
    } else {
        copy(bytes_at(h.offset_to_point_data + next_ * stride, n * stride), n, 0);
        next_ += n;
    }
    return n;
}

void las_reader::seek(std::uint64_t index)
{
    if (index > header_.point_count) {
        fail(path_, "seek to point " + std::to_string(index) + " beyond the " + std::to_string(header_.point_count) +
                        " points of the file");
    }
    next_ = index;
}

std::size_t las_reader::read(las_points& chunk, std::size_t max_points)
{
    const las_header& h = header_;
    const auto n = static_cast<std::size_t>(std::min<std::uint64_t>(max_points, h.point_count - next_));
    chunk.resize(laz_ ? 0 : n, h.has_gps_time());
    if (n == 0) return 0;
    if (laz_) {
        const decoder convert = decoder_for(h.point_format);
        read_laz(
            n, [&](std::size_t points) { chunk.resize(points, h.has_gps_time()); },
            [&](const std::uint8_t* records, std::size_t count, std::size_t at) {
                convert(records, count, h.point_record_length, h, chunk, at);
            });
        return n;
    }
    const std::size_t stride = h.point_record_length;
    const std::size_t block_points = std::max<std::size_t>(1, block_bytes / stride);
    const decoder decode_block = decoder_for(h.point_format);
    for (std::size_t done = 0; done < n;) {
        const std::size_t k = std::min(block_points, n - done);
        const std::uint8_t* records = bytes_at(h.offset_to_point_data + next_ * stride, k * stride);
        decode_block(records, k, stride, h, chunk, done);
        done += k;
        next_ += k;
    }
    return n;
}

las_points las_reader::read_all()
{
    seek(0);
    las_points points;
    read(points, static_cast<std::size_t>(header_.point_count));
    return points;
}

las_points read_las(const std::string& path)
{
    return las_reader(path).read_all();
}

}  // namespace lidarfx::io
