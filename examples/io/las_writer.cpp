// SPDX-License-Identifier: Apache-2.0
#include "io/las_writer.hpp"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <lidarfx/core/error.hpp>

#include "io/las_format.hpp"

namespace lidarfx::io {

using namespace las_format;

namespace {

constexpr const char* fn = "las_writer";
constexpr std::size_t block_points = 1 << 16;

void put_string(std::uint8_t* p, const std::string& s, std::size_t n)
{
    std::memcpy(p, s.data(), std::min(s.size(), n - 1));  // keep a terminating NUL
}

std::vector<std::uint8_t> vlr(const char* user_id, std::uint16_t record_id, const char* description,
                              const std::vector<std::uint8_t>& payload)
{
    std::vector<std::uint8_t> out(vlr_header_size + payload.size(), 0);
    put_string(out.data() + 2, user_id, 17);  // 16 chars, no NUL needed
    store<std::uint16_t>(out.data() + 18, record_id);
    store<std::uint16_t>(out.data() + 20, static_cast<std::uint16_t>(payload.size()));
    put_string(out.data() + 22, description, 32);
    std::copy(payload.begin(), payload.end(), out.begin() + static_cast<std::ptrdiff_t>(vlr_header_size));
    return out;
}

/// GeoKeyDirectory payload (keys sorted by id, values stored in place).
std::vector<std::uint8_t> geo_key_directory(const las_write_options& o)
{
    std::vector<std::array<std::uint16_t, 4>> keys;
    const auto key = [&](int id, int value) {
        keys.push_back({static_cast<std::uint16_t>(id), 0, 1, static_cast<std::uint16_t>(value)});
    };
    for (const las_geo_key& k : o.geo_keys) keys.push_back({k.id, k.location, k.count, k.value});
    if (keys.empty()) {
        key(1024, o.epsg_projected > 0 ? 1 : 2);  // GTModelTypeGeoKey: projected / geographic
        if (o.epsg_geographic > 0) key(2048, o.epsg_geographic);
        if (o.epsg_projected > 0) {
            key(3072, o.epsg_projected);
            key(3076, 9001);  // ProjLinearUnitsGeoKey: metre
        }
        if (o.epsg_vertical > 0) {
            key(4096, o.epsg_vertical);
            key(4099, 9001);  // VerticalUnitsGeoKey: metre
        }
    }
    std::vector<std::uint8_t> out(8 + 8 * keys.size());
    const std::array<std::uint16_t, 4> head{1, 1, 0, static_cast<std::uint16_t>(keys.size())};
    for (std::size_t i = 0; i < 4; ++i) store(out.data() + 2 * i, head[i]);
    for (std::size_t k = 0; k < keys.size(); ++k)
        for (std::size_t i = 0; i < 4; ++i) store(out.data() + 8 + 8 * k + 2 * i, keys[k][i]);
    return out;
}

std::vector<std::vector<std::uint8_t>> vlrs_for(const las_write_options& o)
{
    std::vector<std::vector<std::uint8_t>> out;
    if (o.epsg_projected > 0 || o.epsg_geographic > 0 || o.epsg_vertical > 0 || !o.geo_keys.empty()) {
        out.push_back(vlr("LASF_Projection", 34735, "GeoKeyDirectoryTag", geo_key_directory(o)));
    }
    if (!o.geo_doubles.empty()) {
        std::vector<std::uint8_t> doubles(8 * o.geo_doubles.size());
        for (std::size_t k = 0; k < o.geo_doubles.size(); ++k) store(doubles.data() + 8 * k, o.geo_doubles[k]);
        out.push_back(vlr("LASF_Projection", 34736, "GeoDoubleParamsTag", doubles));
    }
    if (!o.geo_ascii.empty()) {
        std::vector<std::uint8_t> text(o.geo_ascii.begin(), o.geo_ascii.end());
        text.push_back(0);
        out.push_back(vlr("LASF_Projection", 34737, "GeoAsciiParamsTag", text));
    }
    if (!o.wkt.empty() || o.empty_wkt_record) {
        std::vector<std::uint8_t> text(o.wkt.begin(), o.wkt.end());
        text.push_back(0);
        out.push_back(vlr("LASF_Projection", 2112, "OGC WKT coordinate system", text));
    }
    return out;
}

void validate(const las_write_options& o)
{
    detail::require(o.point_format >= 0 && o.point_format <= 10, fn, "point_format", "in 0..10", o.point_format);
    detail::require(o.version_minor >= 0 && o.version_minor <= 4, fn, "version_minor", "in 0..4", o.version_minor);
    const int needed = o.point_format >= 6 ? 4 : o.point_format >= 4 ? 3 : o.point_format >= 2 ? 2 : 0;
    if (o.version_minor < needed) {
        throw invalid_input(detail::concat(fn, ": point format ", o.point_format, " needs LAS 1.", needed,
                                           " or later (got version_minor ", o.version_minor, ")"));
    }
    for (int k = 0; k < 3; ++k) detail::require_positive(o.scale[static_cast<std::size_t>(k)], fn, "scale");
    if (o.offset) {
        for (double v : *o.offset) detail::require(std::isfinite(v), fn, "offset must be finite");
    }
    detail::require(o.extra_bytes >= 0 && o.extra_bytes <= 1000, fn, "extra_bytes", "in 0..1000", o.extra_bytes);
    for (int code : {o.epsg_projected, o.epsg_geographic, o.epsg_vertical}) {
        detail::require(code >= 0 && code < 32767, fn, "EPSG codes", "in 0..32766", code);
    }
    detail::require(o.wkt.size() < 65535 - 1, fn, "wkt", "shorter than 65534 bytes", o.wkt.size());
    detail::require(o.geo_keys.size() < 8000 && o.geo_doubles.size() < 8000 && o.geo_ascii.size() < 65534, fn,
                    "geo_keys, geo_doubles and geo_ascii must fit in VLRs");
}

template <class V>
void require_length(const std::vector<V>& v, std::size_t n, const char* name)
{
    if (!v.empty() && v.size() != n) {
        throw invalid_input(
            detail::concat(fn, ": ", name, " must be empty or of length x.size() = ", n, " (got ", v.size(), ")"));
    }
}

[[noreturn]] void bad_value(const char* name, double value, std::size_t i, const char* requirement)
{
    throw invalid_input(
        detail::concat(fn, ": ", name, " of point ", i, " must be ", requirement, " (got ", value, ")"));
}

}  // namespace

las_writer::las_writer(const std::string& path, const las_write_options& options) : path_(path), opt_(options)
{
    validate(opt_);
    file_.open(path, std::ios::binary | std::ios::trunc);
    if (!file_) throw std::runtime_error(path + ": cannot open for writing");
    out_ = &file_;
    start();
}

las_writer::las_writer(std::ostream& out, const las_write_options& options, std::string name)
    : path_(std::move(name)), opt_(options), out_(&out)
{
    validate(opt_);
    start();
}

las_writer::~las_writer()
{
    if (!open_) return;
    try {
        close();
    } catch (...) {  // a destructor must not throw; close() reports errors to callers who ask
    }
}

void las_writer::start()
{
    record_length_ = static_cast<std::uint16_t>(las_min_record_length(opt_.point_format) + opt_.extra_bytes);
    if (opt_.offset) {
        offset_ = *opt_.offset;
        offset_known_ = true;
    }
    const auto records = vlrs_for(opt_);
    vlr_count_ = static_cast<std::uint32_t>(records.size());
    std::uint32_t offset = header_size_for(opt_.version_minor);
    for (const auto& r : records) offset += static_cast<std::uint32_t>(r.size());
    offset_to_points_ = offset;
    qmin_.fill(std::numeric_limits<std::int32_t>::max());
    qmax_.fill(std::numeric_limits<std::int32_t>::min());
    open_ = true;
    write_header();  // placeholder with zero counts; close() writes the final one
    for (const auto& r : records)
        out_->write(reinterpret_cast<const char*>(r.data()), static_cast<std::streamsize>(r.size()));
    if (!*out_) throw std::runtime_error(path_ + ": write failed");
}

void las_writer::write_header()
{
    const las_write_options& o = opt_;
    std::vector<std::uint8_t> h(header_size_for(o.version_minor), 0);
    std::uint8_t* p = h.data();
    std::memcpy(p, "LASF", 4);
    store<std::uint16_t>(p + 6, o.version_minor >= 4 && !o.wkt.empty() ? 16 : 0);  // bit 4: CRS is WKT
    p[24] = 1;
    p[25] = static_cast<std::uint8_t>(o.version_minor);
    put_string(p + 26, o.system_identifier, 32);
    put_string(p + 58, o.generating_software, 32);
    const std::time_t now = std::time(nullptr);
    std::tm utc{};
    gmtime_r(&now, &utc);
    store<std::uint16_t>(p + 90, static_cast<std::uint16_t>(utc.tm_yday + 1));
    store<std::uint16_t>(p + 92, static_cast<std::uint16_t>(utc.tm_year + 1900));
    store<std::uint16_t>(p + 94, static_cast<std::uint16_t>(h.size()));
    store<std::uint32_t>(p + 96, offset_to_points_);
    store<std::uint32_t>(p + 100, vlr_count_);
    p[104] = static_cast<std::uint8_t>(o.point_format);
    store<std::uint16_t>(p + 105, record_length_);
    // Legacy 32-bit counts: required before 1.4; in 1.4 set for formats 0–5 when they fit, else 0.
    const bool legacy =
        count_ <= std::numeric_limits<std::uint32_t>::max() && (o.version_minor < 4 || o.point_format < 6);
    if (legacy) {
        store<std::uint32_t>(p + 107, static_cast<std::uint32_t>(count_));
        for (std::size_t k = 0; k < 5; ++k)
            store<std::uint32_t>(p + 111 + 4 * k, static_cast<std::uint32_t>(by_return_[k]));
    }
    const bool any = count_ > 0;
    for (std::size_t k = 0; k < 3; ++k) {
        store<double>(p + 131 + 8 * k, o.scale[k]);
        store<double>(p + 155 + 8 * k, offset_[k]);
        store<double>(p + 179 + 16 * k, any ? static_cast<double>(qmax_[k]) * o.scale[k] + offset_[k] : 0.0);
        store<double>(p + 187 + 16 * k, any ? static_cast<double>(qmin_[k]) * o.scale[k] + offset_[k] : 0.0);
    }
    if (o.version_minor >= 4) {
        store<std::uint64_t>(p + 247, count_);
        for (std::size_t k = 0; k < 15; ++k) store<std::uint64_t>(p + 255 + 8 * k, by_return_[k]);
    }
    out_->seekp(0);
    out_->write(reinterpret_cast<const char*>(p), static_cast<std::streamsize>(h.size()));
}

void las_writer::write(const las_points& pts)
{
    if (!open_) throw std::runtime_error(path_ + ": write after close");
    const std::size_t n = pts.size();
    detail::require(pts.y.size() == n && pts.z.size() == n, fn, "x, y and z must have the same length");
    require_length(pts.intensity, n, "intensity");
    require_length(pts.return_number, n, "return_number");
    require_length(pts.number_of_returns, n, "number_of_returns");
    require_length(pts.classification, n, "classification");
    require_length(pts.classification_flags, n, "classification_flags");
    require_length(pts.scan_angle_deg, n, "scan_angle_deg");
    require_length(pts.gps_time, n, "gps_time");
    if (n == 0) return;
    const std::array<const std::vector<double>*, 3> xyz{&pts.x, &pts.y, &pts.z};
    if (!offset_known_) {
        for (std::size_t k = 0; k < 3; ++k) {
            const auto [lo, hi] = std::minmax_element(xyz[k]->begin(), xyz[k]->end());
            if (!std::isfinite(*lo) || !std::isfinite(*hi)) break;  // the quantization below reports it
            offset_[k] = std::floor(*lo / 1000.0) * 1000.0;
        }
        offset_known_ = true;
    }
    if (opt_.version_minor < 4 && count_ + n > std::numeric_limits<std::uint32_t>::max()) {
        throw invalid_input(detail::concat(fn, ": more than 4294967295 points need LAS 1.4 (version_minor = 4)"));
    }

    const bool extended = opt_.point_format >= 6;
    const int max_return = extended ? 15 : 7;
    const int max_class = extended ? 255 : 31;
    const int max_flags = extended ? 15 : 7;
    const std::size_t gps_at = extended ? 22 : 20;
    const bool gps = las_format_has_gps_time(opt_.point_format);
    const std::size_t stride = record_length_;

    for (std::size_t first = 0; first < n; first += block_points) {
        // Bounds and return counts of a block are committed only once it is written.
        const std::size_t count = std::min(block_points, n - first);
        auto qmin = qmin_, qmax = qmax_;
        auto by_return = by_return_;
        block_.assign(count * stride, 0);
        for (std::size_t j = 0; j < count; ++j) {
            const std::size_t i = first + j;
            std::uint8_t* r = block_.data() + j * stride;
            for (std::size_t k = 0; k < 3; ++k) {
                const double q = ((*xyz[k])[i] - offset_[k]) / opt_.scale[k];
                if (!(q >= -2147483648.5 && q < 2147483647.5)) {
                    bad_value(k == 0   ? "x"
                              : k == 1 ? "y"
                                       : "z",
                              (*xyz[k])[i], i, "finite and within 2^31 quanta of scale from the offset");
                }
                const auto v = static_cast<std::int32_t>(std::llround(q));
                store<std::int32_t>(r + 4 * k, v);
                qmin[k] = std::min(qmin[k], v);
                qmax[k] = std::max(qmax[k], v);
            }
            if (!pts.intensity.empty()) store<std::uint16_t>(r + 12, pts.intensity[i]);
            const int rn = pts.return_number.empty() ? 1 : pts.return_number[i];
            const int nr = pts.number_of_returns.empty() ? 1 : pts.number_of_returns[i];
            const int cls = pts.classification.empty() ? 0 : pts.classification[i];
            const int flags = pts.classification_flags.empty() ? 0 : pts.classification_flags[i];
            const double angle = pts.scan_angle_deg.empty() ? 0.0 : pts.scan_angle_deg[i];
            if (rn > max_return) bad_value("return_number", rn, i, extended ? "<= 15" : "<= 7 in formats 0-5");
            if (nr > max_return) bad_value("number_of_returns", nr, i, extended ? "<= 15" : "<= 7 in formats 0-5");
            if (cls > max_class) bad_value("classification", cls, i, "<= 31 in formats 0-5");
            if (flags > max_flags) {
                bad_value("classification_flags", flags, i,
                          extended ? "<= 15" : "<= 7 (no overlap bit) in formats 0-5");
            }
            if (rn >= 1 && rn <= 15) ++by_return[static_cast<std::size_t>(rn - 1)];
            if (extended) {
                const double steps = std::round(angle / static_cast<double>(extended_scan_angle_step_deg));
                if (!(steps >= -30000 && steps <= 30000)) bad_value("scan_angle_deg", angle, i, "in [-180, 180]");
                r[14] = static_cast<std::uint8_t>(rn | (nr << 4));
                r[15] = static_cast<std::uint8_t>(flags);
                r[16] = static_cast<std::uint8_t>(cls);
                store<std::int16_t>(r + 18, static_cast<std::int16_t>(steps));
            } else {
                const double rank = std::round(angle);
                if (!(rank >= -90 && rank <= 90)) bad_value("scan_angle_deg", angle, i, "in [-90, 90] in formats 0-5");
                r[14] = static_cast<std::uint8_t>(rn | (nr << 3));
                r[15] = static_cast<std::uint8_t>(cls | (flags << 5));
                r[16] = static_cast<std::uint8_t>(static_cast<std::int8_t>(rank));
            }
            if (gps && !pts.gps_time.empty()) store<double>(r + gps_at, pts.gps_time[i]);
        }
        out_->seekp(0, std::ios::end);
        out_->write(reinterpret_cast<const char*>(block_.data()), static_cast<std::streamsize>(block_.size()));
        if (!*out_) throw std::runtime_error(path_ + ": write failed");
        count_ += count;
        qmin_ = qmin;
        qmax_ = qmax;
        by_return_ = by_return;
    }
}

void las_writer::close()
{
    if (!open_) return;
    open_ = false;
    write_header();
    out_->flush();
    if (!*out_) throw std::runtime_error(path_ + ": write failed");
    if (file_.is_open()) {
        file_.close();
        if (!file_) throw std::runtime_error(path_ + ": write failed on close");
    }
}

void write_las(const std::string& path, const las_points& points, const las_write_options& options)
{
    las_writer w(path, options);
    w.write(points);
    w.close();
}

std::vector<std::uint8_t> encode_las(const las_points& points, const las_write_options& options)
{
    std::stringstream buffer;
    las_writer w(buffer, options, "<memory>");
    w.write(points);
    w.close();
    const std::string bytes = buffer.str();
    return std::vector<std::uint8_t>(bytes.begin(), bytes.end());
}

}  // namespace lidarfx::io
