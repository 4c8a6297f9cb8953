// SPDX-License-Identifier: Apache-2.0
#include "io/laz.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "io/las_format.hpp"
#include "io/laz_arithmetic.hpp"
#include "io/laz_items_v2.hpp"
#include "io/laz_items_v3.hpp"

namespace lidarfx::io {

using las_format::load;

namespace {

[[noreturn]] void fail(const std::string& name, const std::string& what)
{
    throw std::runtime_error(name + ": " + what);
}

std::string item_name(std::uint16_t type)
{
    switch (static_cast<laz_item_type>(type)) {
        case laz_item_type::byte:
            return "BYTE";
        case laz_item_type::point10:
            return "POINT10";
        case laz_item_type::gpstime11:
            return "GPSTIME11";
        case laz_item_type::rgb12:
            return "RGB12";
        case laz_item_type::point14:
            return "POINT14";
        case laz_item_type::rgb14:
            return "RGB14";
        case laz_item_type::rgbnir14:
            return "RGBNIR14";
        case laz_item_type::byte14:
            return "BYTE14";
    }
    return "item type " + std::to_string(type);
}

/// The item list LASzip writes for a point format (extra bytes, if any, follow as one BYTE item).
std::vector<laz_item_type> items_for(int point_format)
{
    using t = laz_item_type;
    switch (point_format) {
        case 0:
            return {t::point10};
        case 1:
            return {t::point10, t::gpstime11};
        case 2:
            return {t::point10, t::rgb12};
        case 3:
            return {t::point10, t::gpstime11, t::rgb12};
        case 6:
            return {t::point14};
        case 7:
            return {t::point14, t::rgb14};
        case 8:
            return {t::point14, t::rgbnir14};
        default:
            return {};
    }
}

std::uint16_t item_size(laz_item_type type)
{
    switch (type) {
        case laz_item_type::point10:
            return 20;
        case laz_item_type::gpstime11:
            return 8;
        case laz_item_type::rgb12:
            return 6;
        case laz_item_type::point14:
            return 30;
        case laz_item_type::rgb14:
            return 6;
        case laz_item_type::rgbnir14:
            return 8;
        default:
            return 0;
    }
}

// A valid stream never makes the decoder read past its chunk; allow the few bytes of look-ahead an
// encoder's final flush may leave out.
constexpr std::size_t overrun_slack = 0;

}  // namespace

laz_vlr parse_laz_vlr(std::span<const std::uint8_t> payload, int point_format, std::uint16_t record_length,
                      const std::string& name)
{
    if (payload.size() < 34) {
        fail(name, "the laszip VLR holds " + std::to_string(payload.size()) + " bytes (at least 34 needed)");
    }
    const std::uint8_t* p = payload.data();
    laz_vlr v;
    v.compressor = load<std::uint16_t>(p);
    v.coder = load<std::uint16_t>(p + 2);
    v.version_major = p[4];
    v.version_minor = p[5];
    v.version_revision = load<std::uint16_t>(p + 6);
    v.options = load<std::uint32_t>(p + 8);
    v.chunk_size = load<std::uint32_t>(p + 12);
    const std::size_t n = load<std::uint16_t>(p + 32);
    if (34 + 6 * n > payload.size()) {
        fail(name, "the laszip VLR lists " + std::to_string(n) + " items but holds room for " +
                       std::to_string((payload.size() - 34) / 6));
    }
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint8_t* e = p + 34 + 6 * i;
        v.items.push_back({load<std::uint16_t>(e), load<std::uint16_t>(e + 2), load<std::uint16_t>(e + 4)});
    }
    const std::string version = std::to_string(v.version_major) + "." + std::to_string(v.version_minor) + "r" +
                                std::to_string(v.version_revision);
    if (v.coder != 0)
        fail(name, "LAZ coder " + std::to_string(v.coder) + " is unknown (only 0, arithmetic, is defined)");
    if (v.compressor == 1) {
        fail(name, "LAZ from LASzip " + version +
                       " (point-wise, unchunked compressor 1) is not supported; "
                       "recompress it with a current laszip or pdal");
    }
    if (v.compressor != 2 && v.compressor != 3) {
        fail(name, "LAZ compressor " + std::to_string(v.compressor) + " is not supported (2 and 3 are)");
    }
    if (v.chunk_size == 0) fail(name, "the laszip VLR gives a chunk size of 0 points");

    // The items must be those of the header's point format, in record order, at the versions we decode.
    const std::vector<laz_item_type> want = items_for(point_format);
    if (want.empty()) {
        fail(name, "LAZ point format " + std::to_string(point_format) + " is not supported (formats 0–3 and 6–8 are)");
    }
    const bool layered = point_format >= 6;
    if ((v.compressor == 3) != layered) {
        fail(name, "LAZ compressor " + std::to_string(v.compressor) + " does not match point format " +
                       std::to_string(point_format) + " (formats 0–5 use compressor 2, formats 6–10 compressor 3)");
    }
    std::size_t total = 0;
    for (std::size_t i = 0; i < v.items.size(); ++i) {
        const laz_item& it = v.items[i];
        const auto type = static_cast<laz_item_type>(it.type);
        const bool extra = i == want.size() && i + 1 == v.items.size() &&
                           type == (layered ? laz_item_type::byte14 : laz_item_type::byte) && it.size > 0;
        if (i >= want.size() && !extra) {
            fail(name, "unexpected LAZ item " + item_name(it.type) + " (item " + std::to_string(i + 1) + " of " +
                           std::to_string(v.items.size()) + ") for point format " + std::to_string(point_format));
        }
        if (!extra && (type != want[i] || it.size != item_size(type))) {
            fail(name, "LAZ item " + std::to_string(i + 1) + " is " + item_name(it.type) + " of " +
                           std::to_string(it.size) + " bytes; point format " + std::to_string(point_format) +
                           " needs " + item_name(static_cast<std::uint16_t>(want[i])) + " of " +
                           std::to_string(item_size(want[i])) + " bytes");
        }
        const std::uint16_t need = layered ? 3 : 2;
        if (it.version != need) {
            fail(name, "LAZ item " + item_name(it.type) + " version " + std::to_string(it.version) + " (from LASzip " +
                           version + ") is not supported (version " + std::to_string(need) +
                           " is); recompress with a current laszip or pdal");
        }
        total += it.size;
    }
    if (v.items.size() < want.size()) {
        fail(name, "the laszip VLR lists " + std::to_string(v.items.size()) + " items; point format " +
                       std::to_string(point_format) + " needs " + std::to_string(want.size()));
    }
    if (total != record_length) {
        fail(name, "the LAZ items make records of " + std::to_string(total) + " bytes, the header says " +
                       std::to_string(record_length));
    }
    return v;
}

std::vector<laz_chunk> parse_laz_chunk_table(std::span<const std::uint8_t> table, const laz_vlr& vlr,
                                             std::uint64_t first_chunk_offset, std::uint64_t table_offset,
                                             std::uint64_t point_count, std::uint16_t record_length,
                                             const std::string& name)
{
    if (table.size() < 8) fail(name, "truncated LAZ chunk table at byte " + std::to_string(table_offset));
    const std::uint32_t version = load<std::uint32_t>(table.data());
    const std::uint32_t count = load<std::uint32_t>(table.data() + 4);
    if (version != 0) fail(name, "LAZ chunk table version " + std::to_string(version) + " is unknown (0 is)");
    if (table_offset < first_chunk_offset) {
        fail(name, "the LAZ chunk table (byte " + std::to_string(table_offset) + ") starts before the point data");
    }
    const std::uint64_t room = table_offset - first_chunk_offset;
    // Every chunk holds at least its first point uncompressed.
    if (count > room / record_length) {
        fail(name, "the LAZ chunk table lists " + std::to_string(count) + " chunks but the " + std::to_string(room) +
                       " bytes of point data hold at most " + std::to_string(room / record_length));
    }
    if (count == 0 && point_count > 0) {
        fail(name, "the LAZ chunk table lists no chunk for " + std::to_string(point_count) + " points");
    }
    std::vector<laz_chunk> chunks(count);
    laz::decoder dec(table.data() + 8, table.data() + table.size());
    laz::integer_decoder ic(32, 2);
    const bool variable = vlr.chunk_size == laz_vlr::variable_chunk_size;
    std::uint32_t last_points = 0, last_bytes = 0;
    std::uint64_t first = 0, offset = first_chunk_offset;
    for (std::uint32_t i = 0; i < count; ++i) {
        laz_chunk& c = chunks[i];
        if (variable) {
            last_points = static_cast<std::uint32_t>(ic.decompress(dec, static_cast<std::int32_t>(last_points), 0));
            c.point_count = last_points;
        } else {
            c.point_count = std::min<std::uint64_t>(vlr.chunk_size, point_count - std::min(point_count, first));
        }
        last_bytes = static_cast<std::uint32_t>(ic.decompress(dec, static_cast<std::int32_t>(last_bytes), 1));
        c.byte_count = last_bytes;
        c.first_point = first;
        c.offset = offset;
        const std::string which = "LAZ chunk " + std::to_string(i + 1) + " of " + std::to_string(count);
        if (c.byte_count > table_offset - offset) {
            fail(name, which + " (" + std::to_string(c.byte_count) + " bytes at byte " + std::to_string(offset) +
                           ") runs past the chunk table at byte " + std::to_string(table_offset));
        }
        if (c.point_count == 0 || c.point_count > laz_max_points_per_byte * c.byte_count + 1) {
            fail(name, which + " claims " + std::to_string(c.point_count) + " points in " +
                           std::to_string(c.byte_count) + " compressed bytes, which hold at most " +
                           std::to_string(laz_max_points_per_byte * c.byte_count + 1) +
                           " (the chunk table is corrupt)");
        }
        first += c.point_count;
        offset += c.byte_count;
    }
    if (dec.overrun() > overrun_slack) fail(name, "the LAZ chunk table is truncated");
    if (first != point_count) {
        fail(name, "the LAZ chunks hold " + std::to_string(first) + " points, the header declares " +
                       std::to_string(point_count));
    }
    return chunks;
}

struct laz_chunk_decoder::impl {
    std::uint16_t record_length = 0;
    bool layered = false;
    laz::decoder dec;
    std::vector<std::unique_ptr<laz::item_decoder>> items;           // point-wise
    std::vector<std::unique_ptr<laz::layered_item_decoder>> layers;  // layered
    std::vector<std::size_t> offsets;                                // of each item in the record
};

laz_chunk_decoder::laz_chunk_decoder(const laz_vlr& vlr, std::uint16_t record_length) : impl_(std::make_unique<impl>())
{
    impl& m = *impl_;
    m.record_length = record_length;
    m.layered = vlr.compressor == 3;
    std::size_t offset = 0;
    for (const laz_item& it : vlr.items) {
        m.offsets.push_back(offset);
        offset += it.size;
        switch (static_cast<laz_item_type>(it.type)) {
            case laz_item_type::point10:
                m.items.push_back(std::make_unique<laz::point10_v2>(m.dec));
                break;
            case laz_item_type::gpstime11:
                m.items.push_back(std::make_unique<laz::gpstime11_v2>(m.dec));
                break;
            case laz_item_type::rgb12:
                m.items.push_back(std::make_unique<laz::rgb12_v2>(m.dec));
                break;
            case laz_item_type::byte:
                m.items.push_back(std::make_unique<laz::bytes_v2>(m.dec, it.size));
                break;
            case laz_item_type::point14:
                m.layers.push_back(std::make_unique<laz::point14_v3>());
                break;
            case laz_item_type::rgb14:
                m.layers.push_back(std::make_unique<laz::rgb14_v3>(false));
                break;
            case laz_item_type::rgbnir14:
                m.layers.push_back(std::make_unique<laz::rgb14_v3>(true));
                break;
            case laz_item_type::byte14:
                m.layers.push_back(std::make_unique<laz::bytes14_v3>(it.size));
                break;
        }
    }
}

laz_chunk_decoder::laz_chunk_decoder(laz_chunk_decoder&&) noexcept = default;
laz_chunk_decoder& laz_chunk_decoder::operator=(laz_chunk_decoder&&) noexcept = default;
laz_chunk_decoder::~laz_chunk_decoder() = default;

void laz_chunk_decoder::decode(std::span<const std::uint8_t> bytes, std::uint64_t point_count,
                               std::vector<std::uint8_t>& records, const std::string& what)
{
    impl& m = *impl_;
    const std::size_t stride = m.record_length;
    records.clear();
    if (point_count == 0) return;
    if (bytes.size() < stride)
        fail(what, "the chunk's " + std::to_string(bytes.size()) + " bytes end inside its first point");
    records.resize(stride);
    std::memcpy(records.data(), bytes.data(), stride);
    const std::uint8_t* const end = bytes.data() + bytes.size();
    std::uint32_t context = 0;
    if (!m.layered) {
        for (std::size_t k = 0; k < m.items.size(); ++k) m.items[k]->init(records.data() + m.offsets[k]);
        if (point_count > 1) m.dec.init(bytes.data() + stride, end);
    } else {
        // Layered: the point count, every item's layer sizes, then the layers, each with its own decoder.
        const std::uint8_t* p = bytes.data() + stride;
        if (end - p < 4) fail(what, "the chunk ends before its point count");
        const std::uint32_t count = load<std::uint32_t>(p);
        p += 4;
        if (count != point_count) {
            fail(what, "the chunk holds " + std::to_string(count) + " points, its chunk table entry " +
                           std::to_string(point_count));
        }
        for (auto& layer : m.layers) {
            if (!layer->read_sizes(p, end)) fail(what, "the chunk ends inside its table of layer sizes");
        }
        for (std::size_t k = 0; k < m.layers.size(); ++k) {
            if (!m.layers[k]->init(records.data() + m.offsets[k], p, end, context)) {
                fail(what, "a layer of the chunk runs past its end");
            }
        }
    }
    // Decode in steps, checking after each that no decoder ran past its bytes: the buffer grows with the
    // points actually decoded, and a corrupt chunk stops early instead of decoding its claimed count.
    constexpr std::uint64_t step = 1 << 16;
    for (std::uint64_t done = 1; done < point_count;) {
        const std::uint64_t upto = std::min(point_count, done + step);
        records.resize(static_cast<std::size_t>(upto) * stride);
        std::uint8_t* rec = records.data() + done * stride;
        for (std::uint64_t i = done; i < upto; ++i, rec += stride) {
            if (!m.layered) {
                for (std::size_t k = 0; k < m.items.size(); ++k) m.items[k]->decode(rec + m.offsets[k]);
            } else {
                for (std::size_t k = 0; k < m.layers.size(); ++k) m.layers[k]->decode(rec + m.offsets[k], context);
            }
        }
        done = upto;
        std::size_t overrun = m.layered ? 0 : m.dec.overrun();
        for (auto& layer : m.layers) overrun = std::max(overrun, layer->overrun());
        if (overrun > overrun_slack) {
            fail(what, "the compressed data ends early, after " + std::to_string(done) + " of " +
                           std::to_string(point_count) + " points (corrupt or truncated)");
        }
    }
}

}  // namespace lidarfx::io
