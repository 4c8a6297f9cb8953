// SPDX-License-Identifier: Apache-2.0
// LAZ reading: decoded points equal their uncompressed twins bit for bit (PDAL's test data, when
// LIDARFX_PDAL_DATA names its test/data folder), the committed fixtures decode to recorded checksums
// without the twins, chunk-parallel reads equal sequential ones, and truncated or corrupt files give
// a clean error naming the file.
#include <doctest/doctest.h>

#include "io/las.hpp"
#include "io/laz.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <tuple>

#include "io_test_util.hpp"

using namespace lidarfx::io;
using io_test::read_bytes;
using io_test::runtime_error_of;
using io_test::starts_with;

namespace {

/// A committed fixture (tests/data, see its README for source and license).
std::string fixture(const std::string& name)
{
    return std::string(LIDARFX_TEST_DATA_DIR) + "/" + name;
}

/// A file of PDAL's test data ($LIDARFX_PDAL_DATA/<relative>), or "" when the variable or the file is
/// missing (the case then passes with a message: CI has no copy of the data).
std::string pdal_file(const std::string& relative)
{
    const char* root = std::getenv("LIDARFX_PDAL_DATA");
    if (root == nullptr || *root == 0) {
        MESSAGE("LIDARFX_PDAL_DATA is not set: skipped the comparison with " << relative);
        return "";
    }
    for (const std::string& base : {std::string(root), std::string(root) + "/test/data"}) {
        const std::string path = base + "/" + relative;
        if (std::filesystem::exists(path)) return path;
    }
    MESSAGE("no " << relative << " under LIDARFX_PDAL_DATA=" << root << ": skipped");
    return "";
}

std::vector<std::uint8_t> all_records(las_reader& r, int threads = 1)
{
    r.set_threads(threads);
    r.seek(0);
    std::vector<std::uint8_t> records;
    r.read_records(records, static_cast<std::size_t>(r.point_count()));
    return records;
}

/// FNV-1a 64 of the bytes (the checksums below are of decoded point records).
std::uint64_t fnv1a(const std::vector<std::uint8_t>& bytes)
{
    std::uint64_t h = 14695981039346656037ull;
    for (const std::uint8_t b : bytes) {
        h ^= b;
        h *= 1099511628211ull;
    }
    return h;
}

/// Every point of a file as a sortable row: the las_points fields and the record's RGB (0 when none).
using row = std::tuple<double, double, double, std::uint16_t, std::uint8_t, std::uint8_t, std::uint8_t, std::uint8_t,
                       double, std::uint16_t, std::uint16_t, std::uint16_t>;

std::vector<row> sorted_rows(const std::string& path)
{
    las_reader r(path);
    const las_points p = r.read_all();
    const std::vector<std::uint8_t> rec = all_records(r);
    const las_header& h = r.header();
    const int f = h.point_format;
    const std::size_t rgb_at = f == 2 ? 20 : f == 3 ? 28 : f == 7 || f == 8 ? 30 : 0;
    std::vector<row> rows;
    for (std::size_t i = 0; i < p.size(); ++i) {
        std::uint16_t rgb[3]{};
        if (rgb_at) std::memcpy(rgb, rec.data() + i * h.point_record_length + rgb_at, 6);
        rows.emplace_back(p.x[i], p.y[i], p.z[i], p.intensity[i], p.return_number[i], p.number_of_returns[i],
                          p.classification[i], p.classification_flags[i], p.gps_time.empty() ? 0.0 : p.gps_time[i],
                          rgb[0], rgb[1], rgb[2]);
    }
    std::sort(rows.begin(), rows.end());
    return rows;
}

/// Both files hold the same points in any order. Coordinates are compared to 1e-6 units because the two
/// files quantize against different offsets (x = integer * scale + offset rounds differently in the last
/// bit); every other field must be equal.
void check_same_multiset(const std::string& a, const std::string& b)
{
    const auto ra = sorted_rows(a), rb = sorted_rows(b);
    REQUIRE(ra.size() == rb.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < ra.size(); ++i) {
        auto x = ra[i], y = rb[i];
        const bool close = std::abs(std::get<0>(x) - std::get<0>(y)) < 1e-6 &&
                           std::abs(std::get<1>(x) - std::get<1>(y)) < 1e-6 &&
                           std::abs(std::get<2>(x) - std::get<2>(y)) < 1e-6;
        std::get<0>(x) = std::get<0>(y);
        std::get<1>(x) = std::get<1>(y);
        std::get<2>(x) = std::get<2>(y);
        if (!close || x != y) ++differ;
    }
    CHECK(differ == 0);
}

/// The twin's records and points equal the LAZ file's, read whole, in odd chunks and on 2 threads.
void check_twin(const std::string& laz, const std::string& las)
{
    las_reader z(laz), s(las);
    CHECK(z.header().compressed);
    CHECK_FALSE(s.header().compressed);
    REQUIRE(z.point_count() == s.point_count());
    CHECK(z.header().point_format == s.header().point_format);
    const auto want = all_records(s);
    CHECK(all_records(z) == want);
    CHECK(all_records(z, 2) == want);
    CHECK(io_test::identical(las_reader(laz).read_all(), las_reader(las).read_all()));
    las_reader odd(laz);
    odd.set_threads(2);
    CHECK(io_test::identical(io_test::read_in_chunks(odd, 7919), las_reader(las).read_all()));
}

/// Reads every point of `bytes` through the in-memory reader; the error message, or "<no error>".
std::string error_reading(const std::vector<std::uint8_t>& bytes, int threads = 1)
{
    return runtime_error_of([&] {
        las_reader r(bytes, "corrupt.laz");
        r.set_threads(threads);
        las_points p;
        while (r.read(p, 300) > 0) {
        }
    });
}

}  // namespace

TEST_CASE("io/laz: point formats 0-3 decode bit for bit as their uncompressed twins (PDAL data)")
{
    for (const auto& [laz, las] : {std::pair{"laz/simple.laz", "las/simple.las"},
                                   std::pair{"laz/autzen_trim.laz", "las/autzen_trim.las"}}) {
        const std::string a = pdal_file(laz), b = pdal_file(las);
        if (a.empty() || b.empty()) continue;
        CAPTURE(a);
        check_twin(a, b);
    }
}

TEST_CASE("io/laz: point formats 6-8 (COPC, layered chunks) hold the same points as their twins (PDAL data)")
{
    // COPC reorders the points into octree nodes, so the files are compared as sorted multisets.
    for (const auto& [laz, twin] : {std::pair{"copc/1.2-with-color.copc.laz", "las/1.2-with-color.las"},
                                    std::pair{"copc/lone-star.copc.laz", "ept/source/lone-star.laz"}}) {
        const std::string a = pdal_file(laz), b = pdal_file(twin);
        if (a.empty() || b.empty()) continue;
        CAPTURE(a);
        check_same_multiset(a, b);
    }
    // Format 8 (RGBNIR14) with BYTE14 extra bytes: no twin; every point lies in the header bounds and
    // any thread count decodes the same bytes.
    if (const std::string path = pdal_file("laz/las_with_several_extra_byte_bloc.laz"); !path.empty()) {
        las_reader r(path);
        CHECK(r.header().point_format == 8);
        const las_points p = r.read_all();
        CHECK(p.size() == r.point_count());
        const las_header& h = r.header();
        CHECK(*std::min_element(p.x.begin(), p.x.end()) >= h.min[0] - h.scale[0]);
        CHECK(*std::max_element(p.x.begin(), p.x.end()) <= h.max[0] + h.scale[0]);
        CHECK(*std::min_element(p.z.begin(), p.z.end()) >= h.min[2] - h.scale[2]);
        CHECK(*std::max_element(p.z.begin(), p.z.end()) <= h.max[2] + h.scale[2]);
        CHECK(all_records(r, 2) == all_records(r, 1));
    }
}

TEST_CASE("io/laz: LAZ from LASzip 1.x (unchunked compressor 1) is refused with what to do (PDAL data)")
{
    const std::string path = pdal_file("laz/simple-laszip-compressor-version-1.2r0.laz");
    if (path.empty()) return;
    CHECK(runtime_error_of([&] { las_reader r(path); }) ==
          path + ": LAZ from LASzip 1.2r0 (point-wise, unchunked compressor 1) is not supported; recompress it "
                 "with a current laszip or pdal");
}

TEST_CASE("io/laz: the committed fixtures decode to their verified checksums without the twins")
{
    // simple.laz (format 3, one chunk): the checksum is that of the point records of PDAL's
    // las/simple.las, to which the decoded records are byte-identical (checked above when the data is
    // present). 1.2-with-color.copc.laz (format 7, variable chunks): the checksum was recorded from a run
    // whose points equalled las/1.2-with-color.las as a sorted multiset (test above).
    struct expected {
        const char* name;
        int format;
        std::uint64_t count;
        std::uint64_t checksum;
    };
    for (const expected& e : {expected{"simple.laz", 3, 1065, 0xac5ceed2077b659cull},
                              expected{"1.2-with-color.copc.laz", 7, 1065, 0x2b9c1be162ecbe35ull}}) {
        CAPTURE(e.name);
        las_reader r(fixture(e.name));
        const las_header& h = r.header();
        CHECK(h.compressed);
        CHECK(h.point_format == e.format);
        CHECK(r.point_count() == e.count);
        CHECK(fnv1a(all_records(r)) == e.checksum);
        CHECK(fnv1a(all_records(r, 2)) == e.checksum);
        CHECK(fnv1a(all_records(r, 0)) == e.checksum);
        // The points span exactly the header bounds (to the quantum: the header stores the doubles).
        const las_points p = r.read_all();
        REQUIRE(p.size() == e.count);
        const std::vector<double>* axes[3] = {&p.x, &p.y, &p.z};
        for (std::size_t k = 0; k < 3; ++k) {
            const auto [lo, hi] = std::minmax_element(axes[k]->begin(), axes[k]->end());
            CHECK(std::abs(*lo - h.min[k]) < h.scale[k] / 2);
            CHECK(std::abs(*hi - h.max[k]) < h.scale[k] / 2);
        }
    }
}

TEST_CASE("io/laz: seek and chunked reads inside and across chunks equal the whole read")
{
    las_reader r(fixture("1.2-with-color.copc.laz"));
    const las_points all = r.read_all();
    const std::size_t n = all.size();
    for (const int threads : {1, 2}) {
        r.set_threads(threads);
        for (const std::uint64_t start : {std::uint64_t{0}, std::uint64_t{1}, std::uint64_t{517}, std::uint64_t{n - 1}}) {
            for (const std::size_t step : {std::size_t{1}, std::size_t{97}, std::size_t{700}, n}) {
                r.seek(start);
                las_points chunk;
                const std::size_t got = r.read(chunk, step);
                REQUIRE(got == std::min<std::size_t>(step, n - start));
                bool same = true;
                for (std::size_t i = 0; i < got; ++i) {
                    same = same && chunk.x[i] == all.x[start + i] && chunk.gps_time[i] == all.gps_time[start + i] &&
                           chunk.intensity[i] == all.intensity[start + i];
                }
                CHECK(same);
                CHECK(r.position() == start + got);
            }
        }
    }
    CHECK(runtime_error_of([&] { r.set_threads(-1); }) != "<no error>");
}

TEST_CASE("io/laz: every truncation of a LAZ file is rejected with a message naming it")
{
    // The chunk table sits at the end of the file, so no prefix is a valid LAZ file.
    for (const char* name : {"simple.laz", "1.2-with-color.copc.laz"}) {
        CAPTURE(name);
        const auto bytes = read_bytes(fixture(name));
        std::size_t clean = 0, tried = 0;
        for (std::size_t len = 0; len < bytes.size(); len += 1 + len / 50) {
            const std::vector<std::uint8_t> cut(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(len));
            const std::string e = error_reading(cut);
            ++tried;
            if (starts_with(e, "corrupt.laz: ")) ++clean;
        }
        CHECK(clean == tried);
        // The last bytes cut (the end of the chunk table or of an EVLR after it).
        for (std::size_t cut_bytes = 1; cut_bytes <= 8; ++cut_bytes) {
            const std::vector<std::uint8_t> cut(bytes.begin(), bytes.end() - static_cast<std::ptrdiff_t>(cut_bytes));
            CHECK(starts_with(error_reading(cut), "corrupt.laz: "));
        }
    }
}

TEST_CASE("io/laz: corrupt headers, chunk tables and chunk bytes give a clean error or garbage points, never a crash")
{
    const auto bytes = read_bytes(fixture("1.2-with-color.copc.laz"));
    las_reader good(bytes, "good");
    const std::uint32_t data = good.header().offset_to_point_data;
    const auto patched = [&](std::size_t at, auto value) {
        auto b = bytes;
        std::memcpy(b.data() + at, &value, sizeof(value));
        return b;
    };
    // The point count disagrees with the chunk table.
    const auto with_count = [&](std::uint64_t n) {
        auto b = bytes;
        const auto legacy = static_cast<std::uint32_t>(n < (std::uint64_t{1} << 32) ? n : 0);
        std::memcpy(b.data() + 107, &legacy, 4);
        std::memcpy(b.data() + 247, &n, 8);
        return b;
    };
    CHECK(error_reading(with_count(1066)) == "corrupt.laz: the LAZ chunks hold 1065 points, the header declares 1066");
    CHECK(error_reading(with_count(std::uint64_t{1} << 40)) ==
          "corrupt.laz: the LAZ chunks hold 1065 points, the header declares 1099511627776");
    // The chunk table offset points outside the point data.
    CHECK(starts_with(error_reading(patched(data, std::int64_t{12})), "corrupt.laz: the LAZ chunk table offset 12 lies outside"));
    CHECK(starts_with(error_reading(patched(data, std::int64_t{-5})), "corrupt.laz: the LAZ chunk table offset -5"));
    // The laszip VLR names items that do not make up the point format.
    CHECK(starts_with(error_reading(patched(104, std::uint8_t{0x80 | 6})), "corrupt.laz: "));
    // Every single-byte change in the compressed points (and in the chunk table) decodes to an error that
    // names the file or to points, identically on 1 and 2 threads; never a crash or a hang.
    std::size_t errors = 0;
    for (std::size_t at = data; at < bytes.size(); at += 89) {
        auto b = bytes;
        b[at] ^= 0x5A;
        const std::string one = error_reading(b, 1);
        CHECK(one == error_reading(b, 2));
        if (one != "<no error>") {
            CHECK(starts_with(one, "corrupt.laz: "));
            ++errors;
        }
    }
    MESSAGE(errors << " of the corrupted copies were rejected, the others decoded to (wrong) points");
}

TEST_CASE("io/laz: unknown compressors, coders and item versions are refused by name")
{
    const laz_vlr ok = [] {
        las_reader r(fixture("simple.laz"));
        for (const las_vlr& v : r.header().vlrs) {
            if (v.user_id == "laszip encoded") {
                const auto bytes = read_bytes(fixture("simple.laz"));
                return parse_laz_vlr({bytes.data() + v.data_offset, static_cast<std::size_t>(v.data_size)}, 3, 34, "x");
            }
        }
        return laz_vlr{};
    }();
    REQUIRE(ok.items.size() == 3);
    CHECK(ok.compressor == 2);
    const auto payload = [](const laz_vlr& v) {
        std::vector<std::uint8_t> b(34 + 6 * v.items.size(), 0);
        std::memcpy(b.data(), &v.compressor, 2);
        std::memcpy(b.data() + 2, &v.coder, 2);
        std::memcpy(b.data() + 12, &v.chunk_size, 4);
        const auto n = static_cast<std::uint16_t>(v.items.size());
        std::memcpy(b.data() + 32, &n, 2);
        for (std::size_t i = 0; i < v.items.size(); ++i) std::memcpy(b.data() + 34 + 6 * i, &v.items[i], 6);
        return b;
    };
    const auto error = [&](laz_vlr v, int format = 3, std::uint16_t length = 34) {
        return runtime_error_of([&] { parse_laz_vlr(payload(v), format, length, "f.laz"); });
    };
    CHECK(error(ok) == "<no error>");
    laz_vlr v = ok;
    v.coder = 1;
    CHECK(error(v) == "f.laz: LAZ coder 1 is unknown (only 0, arithmetic, is defined)");
    v = ok;
    v.compressor = 7;
    CHECK(error(v) == "f.laz: LAZ compressor 7 is not supported (2 and 3 are)");
    v = ok;
    v.items[0].version = 1;
    CHECK(starts_with(error(v), "f.laz: LAZ item POINT10 version 1 (from LASzip 0.0r0) is not supported"));
    v = ok;
    v.items.pop_back();
    CHECK(error(v) == "f.laz: the laszip VLR lists 2 items; point format 3 needs 3");
    CHECK(error(ok, 3, 36) == "f.laz: the LAZ items make records of 34 bytes, the header says 36");
    CHECK(error(ok, 4, 34) == "f.laz: LAZ point format 4 is not supported (formats 0–3 and 6–8 are)");
    v = ok;
    v.items.push_back({0, 2, 2});   // two extra bytes
    CHECK(error(v, 3, 36) == "<no error>");
    v.chunk_size = 0;
    CHECK(error(v, 3, 36) == "f.laz: the laszip VLR gives a chunk size of 0 points");
}
