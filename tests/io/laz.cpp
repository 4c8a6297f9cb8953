// SPDX-License-Identifier: Apache-2.0
// LAZ reading: decoded points equal their uncompressed twins bit for bit (PDAL's test data, when
// LIDARFX_PDAL_DATA names its test/data folder), the committed fixtures decode to recorded checksums
// without the twins, chunk-parallel reads equal sequential ones, and truncated or corrupt files give
// a clean error naming the file.
#include <doctest/doctest.h>

#include "io/las.hpp"
#include "io/laz.hpp"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <tuple>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <lidarfx/core/error.hpp>

#include "io_test_util.hpp"

using namespace lidarfx::io;
using io_test::contains;
using io_test::error_of;
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
using point_row = std::tuple<double, double, double, std::uint16_t, std::uint8_t, std::uint8_t, std::uint8_t,
                             std::uint8_t, double, std::uint16_t, std::uint16_t, std::uint16_t>;

std::vector<point_row> sorted_rows(const std::string& path)
{
    las_reader r(path);
    const las_points p = r.read_all();
    const std::vector<std::uint8_t> rec = all_records(r);
    const las_header& h = r.header();
    const int f = h.point_format;
    const std::size_t rgb_at = f == 2 ? 20 : f == 3 ? 28 : f == 7 || f == 8 ? 30 : 0;
    std::vector<point_row> rows;
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
    for (const auto& [laz, las] :
         {std::pair{"laz/simple.laz", "las/simple.las"}, std::pair{"laz/autzen_trim.laz", "las/autzen_trim.las"}}) {
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
          path +
              ": LAZ from LASzip 1.2r0 (point-wise, unchunked compressor 1) is not supported; recompress it "
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
        for (const std::uint64_t start :
             {std::uint64_t{0}, std::uint64_t{1}, std::uint64_t{517}, std::uint64_t{n - 1}}) {
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
    CHECK(starts_with(error_reading(patched(data, std::int64_t{12})),
                      "corrupt.laz: the LAZ chunk table offset 12 lies outside"));
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
    v.items.push_back({0, 2, 2});  // two extra bytes
    CHECK(error(v, 3, 36) == "<no error>");
    v.chunk_size = 0;
    CHECK(error(v, 3, 36) == "f.laz: the laszip VLR gives a chunk size of 0 points");
}

namespace {

/// simple.laz (format 3, one chunk of 1065 points) whose chunk claims `claimed` points: the laszip VLR's
/// chunk size and the header's point count say so, and the chunk's compressed bytes after its raw first
/// point are zeroed (the cheapest symbols every time: the most points a byte can give).
std::vector<std::uint8_t> chunk_bomb(std::uint32_t claimed)
{
    auto b = read_bytes(fixture("simple.laz"));
    const las_reader r(b, "simple.laz");
    const las_header& h = r.header();
    REQUIRE(h.version_minor < 4);  // the 32-bit legacy count is the count
    for (const las_vlr& v : h.vlrs) {
        if (v.user_id == "laszip encoded") std::memcpy(b.data() + v.data_offset + 12, &claimed, 4);
    }
    std::memcpy(b.data() + 107, &claimed, 4);
    std::int64_t table = 0;
    std::memcpy(&table, b.data() + h.offset_to_point_data, 8);
    const std::size_t from = h.offset_to_point_data + 8 + h.point_record_length;
    std::fill(b.begin() + static_cast<std::ptrdiff_t>(from), b.begin() + table, std::uint8_t{0});
    return b;
}

/// Compressed bytes of simple.laz's one chunk (its raw first point included).
std::uint64_t simple_chunk_bytes()
{
    const auto b = read_bytes(fixture("simple.laz"));
    const las_reader r(b, "simple.laz");
    std::int64_t table = 0;
    std::memcpy(&table, b.data() + r.header().offset_to_point_data, 8);
    return static_cast<std::uint64_t>(table) - r.header().offset_to_point_data - 8;
}

}  // namespace

TEST_CASE("io/laz: no chunk decodes more points than laz_max_points_per_byte allows, whatever its bytes")
{
    // POINT10 alone is the cheapest item set the bound is derived for; POINT10 + GPSTIME11 + RGB12 (format 3)
    // codes more symbols a point. Every chunk claims the most points the bound lets through; all-zero, all-one
    // and random bytes (the adaptive models then learn the cheapest symbols) must run out of bytes first.
    struct item_set {
        int format;
        std::uint16_t length;
        std::vector<laz_item> items;
    };
    const std::vector<item_set> sets{{0, 20, {{6, 20, 2}}}, {3, 34, {{6, 20, 2}, {7, 8, 2}, {8, 6, 2}}}};
    for (const item_set& set : sets) {
        laz_vlr vlr;
        vlr.compressor = 2;
        vlr.chunk_size = laz_vlr::variable_chunk_size;
        vlr.items = set.items;
        laz_chunk_decoder dec(vlr, set.length);
        for (const int fill : {0x00, 0xFF, 0x55, -1}) {
            CAPTURE(set.format);
            CAPTURE(fill);
            const std::size_t bytes = 600;
            std::vector<std::uint8_t> chunk(bytes, static_cast<std::uint8_t>(fill));
            if (fill < 0) {
                std::mt19937 rng(7);
                for (auto& c : chunk) c = static_cast<std::uint8_t>(rng());
            }
            std::fill(chunk.begin(), chunk.begin() + set.length, std::uint8_t{0});  // the raw first point
            const std::uint64_t claim = 1 + laz_max_points_per_byte * bytes;
            std::vector<std::uint8_t> records;
            const std::string e = runtime_error_of([&] { dec.decode(chunk, claim, records, "bomb"); });
            CHECK(starts_with(e, "bomb: the compressed data ends early, after "));
            // The error comes within 65536 points of where the bytes ran out (the decoder checks in steps).
            const std::uint64_t decoded = records.size() / set.length;
            MESSAGE("format " << set.format << ", bytes " << (fill < 0 ? std::string("random") : std::to_string(fill))
                              << ": ran out within " << decoded << " points of " << bytes << " bytes ("
                              << decoded / bytes << " a byte at most; the bound " << laz_max_points_per_byte << ")");
        }
    }
}

TEST_CASE("io/laz: the chunk table refuses a chunk claiming more points than its bytes can hold")
{
    const std::uint64_t bytes = simple_chunk_bytes();
    const std::uint64_t most = 1 + laz_max_points_per_byte * bytes;
    REQUIRE(most < 0xFFFFFFFFu);
    // 1e9 points in some 18 KB, as the reported bomb claimed (it named 1e9 a chunk): refused on opening.
    const std::string e = runtime_error_of([&] { las_reader r(chunk_bomb(1000000000u), "bomb.laz"); });
    CHECK(e == "bomb.laz: LAZ chunk 1 of 1 claims 1000000000 points in " + std::to_string(bytes) +
                   " compressed bytes, which hold at most " + std::to_string(most) + " (the chunk table is corrupt)");
    CHECK(starts_with(runtime_error_of([&] { las_reader r(chunk_bomb(static_cast<std::uint32_t>(most + 1)), "b"); }),
                      "b: LAZ chunk 1 of 1 claims " + std::to_string(most + 1) + " points"));
    // The bound itself opens (and fails on decoding, or on the budget).
    CHECK(runtime_error_of([&] { las_reader r(chunk_bomb(static_cast<std::uint32_t>(most)), "b"); }) == "<no error>");
}

TEST_CASE("io/laz: a chunk over half the memory budget is refused before decoding, naming it and the budget")
{
    // 10 M points of 34 bytes (340 MB decoded) in one 18 KB chunk of zeros: within the bytes' bound, over
    // half of a 256 MiB budget. Without the budget it decodes millions of points before it runs out.
    const auto bomb = chunk_bomb(10000000u);
    for (const int threads : {1, 2}) {
        CAPTURE(threads);
        las_reader r(bomb, "bomb.laz");
        r.set_threads(threads);
        r.set_memory_budget(std::uint64_t{256} << 20);
        las_points p;
        const auto start = std::chrono::steady_clock::now();
        std::string e = "<no error>";
        try {
            r.read(p, 1 << 16);
        } catch (const lidarfx::invalid_input& x) {
            e = x.what();
        }
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        CHECK(e == "bomb.laz: LAZ chunk 1 of 1 (first point 0) claims 10000000 points in " +
                       std::to_string(simple_chunk_bytes()) +
                       " compressed bytes: 324.2 MiB decoded (34 bytes a point), over half the memory budget of "
                       "256 MiB (a chunk decoding and the one kept must fit); raise the memory budget (--memory) to "
                       "at least 648.5 MiB, or check the file (a corrupt chunk table claims more points than its "
                       "chunk holds)");
        CHECK(seconds < 0.5);  // nothing decoded
        CHECK(p.size() == 0);
    }
    // read_records and read_all refuse the same way; a budget over twice the chunk lets it decode (and fail
    // on its zeros, as a corrupt chunk).
    las_reader r(bomb, "bomb.laz");
    r.set_memory_budget(std::uint64_t{256} << 20);
    std::vector<std::uint8_t> records;
    CHECK(contains(error_of([&] { r.read_records(records, 10); }), "over half the memory budget of 256 MiB"));
    CHECK(contains(error_of([&] { r.read_all(); }), "over half the memory budget of 256 MiB"));
    CHECK(r.memory_budget() == std::uint64_t{256} << 20);
    r.set_memory_budget(0);
    CHECK(r.memory_budget() > 0);  // half the physical memory
}

TEST_CASE("io/laz: any memory budget that holds two chunks, any thread count: the same records")
{
    // The COPC fixture's variable chunks (the largest decides how many decode at once) and simple.laz's one.
    for (const std::string name : {"1.2-with-color.copc.laz", "simple.laz"}) {
        CAPTURE(name);
        las_reader r(fixture(name));
        const std::vector<std::uint8_t> want = all_records(r);
        const std::uint64_t whole = want.size();  // every chunk is at most this
        for (const std::uint64_t budget : {2 * whole, 3 * whole, 5 * whole + 7, std::uint64_t{1} << 30}) {
            for (const int threads : {1, 2, 3, 0}) {
                CAPTURE(budget);
                CAPTURE(threads);
                r.set_memory_budget(budget);
                CHECK(all_records(r, threads) == want);
                r.set_threads(threads);
                CHECK(io_test::identical(io_test::read_in_chunks(r, 211), las_reader(fixture(name)).read_all()));
            }
        }
        // Chunks in flight: (k + 1) x the largest within the budget, k at most the threads asked for.
        const std::uint64_t largest = [&] {  // decoded bytes of the largest chunk, found as the budget's edge
            std::uint64_t lo = 1, hi = whole;
            while (lo < hi) {
                const std::uint64_t mid = (lo + hi) / 2;
                r.set_memory_budget(2 * mid);
                r.seek(0);
                las_points p;
                if (error_of([&] { r.read_all(); }) == "<no error>")
                    hi = mid;
                else
                    lo = mid + 1;
            }
            return lo;
        }();
        MESSAGE(name << ": largest chunk " << largest << " bytes decoded");
        CHECK(r.largest_chunk_bytes() == largest);
        r.set_threads(4);
        for (std::uint64_t k = 1; k <= 5; ++k) {
            r.set_memory_budget((k + 1) * largest);
            CHECK(r.decode_threads() == static_cast<int>(std::min<std::uint64_t>(k, 4)));
            r.set_memory_budget((k + 1) * largest - 1);
            CHECK(r.decode_threads() ==
                  static_cast<int>(std::max<std::uint64_t>(1, std::min<std::uint64_t>(k - 1, 4))));
        }
        r.set_memory_budget(std::uint64_t{1} << 30);
        CHECK(r.decode_threads() == 4);
        r.set_threads(1);
        CHECK(r.decode_threads() == 1);
        // A budget that cannot hold two of its largest chunk: refused on the first read.
        r.set_memory_budget(64);
        r.seek(0);
        las_points p;
        CHECK(contains(error_of([&] { r.read(p, 10); }), ": LAZ chunk 1 of "));
    }
}

namespace {

/// Runs `args` (argv[0] the program), its stdout and stderr into `log`; the exit code, wall seconds and peak
/// resident memory (ru_maxrss, bytes) of the child.
struct child_run {
    int code = -1;
    double seconds = 0;
    std::uint64_t peak_rss = 0;
    std::string output;
};

child_run run_child(const std::vector<std::string>& args, const std::string& log)
{
    std::vector<char*> argv;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    const auto start = std::chrono::steady_clock::now();
    const pid_t pid = ::fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
        const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (fd >= 0) {
            ::dup2(fd, 1);
            ::dup2(fd, 2);
        }
        ::execv(argv[0], argv.data());
        ::_exit(127);
    }
    int status = 0;
    rusage use{};
    REQUIRE(::wait4(pid, &status, 0, &use) == pid);
    child_run out;
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    out.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    out.peak_rss = static_cast<std::uint64_t>(use.ru_maxrss) * 1024;
    std::ifstream in(log);
    std::ostringstream text;
    text << in.rdbuf();
    out.output = text.str();
    return out;
}

}  // namespace

TEST_CASE("io/laz: the program refuses a LAZ chunk bomb within --memory, fast (LIDARFX_CLI)")
{
    // Run by the cli_laz_bomb test, which names the program in LIDARFX_CLI; skipped otherwise.
    const char* cli = std::getenv("LIDARFX_CLI");
    if (cli == nullptr || *cli == 0) {
        MESSAGE("LIDARFX_CLI is not set: skipped (run by the cli_laz_bomb test)");
        return;
    }
    io_test::temp_dir dir;
    const std::string bomb = dir.file("bomb.laz");
    // 10 M points claimed in one 18 KB chunk of zeros (340 MB decoded; before the budget it decoded millions
    // of points, some 7 s and 240+ MB, before "ends early").
    io_test::write_bytes(bomb, chunk_bomb(10000000u));
    const std::uint64_t budget = std::uint64_t{256} << 20;
    for (const std::string threads : {"1", "2"}) {
        for (const std::string command : {"rasterize", "water"}) {
            CAPTURE(threads);
            CAPTURE(command);
            const child_run run = run_child({cli, command, bomb, "--memory", "256MiB", "--threads", threads, "--out",
                                             dir.file("out_" + command + threads)},
                                            dir.file("log.txt"));
            CAPTURE(run.output);
            MESSAGE(command << " --threads " << threads << ": exit " << run.code << " after " << run.seconds
                            << " s, peak RSS " << static_cast<double>(run.peak_rss) / 1048576.0 << " MiB");
            CHECK(run.code == 2);
            CHECK(contains(run.output, "bomb.laz: LAZ chunk 1 of 1 (first point 0) claims 10000000 points"));
            CHECK(contains(run.output, "over half the memory budget of 256 MiB"));
            CHECK(contains(run.output, "raise the memory budget (--memory)"));
            CHECK(run.seconds < 5);
            CHECK(run.peak_rss < budget / 2);
            CHECK_FALSE(std::filesystem::exists(dir.file("out_" + command + threads)));
        }
    }
    // The 1e9-point claim of the report: refused as a corrupt chunk table when the file is opened.
    io_test::write_bytes(bomb, chunk_bomb(1000000000u));
    const child_run run =
        run_child({cli, "rasterize", bomb, "--memory", "256MiB", "--out", dir.file("out")}, dir.file("log.txt"));
    CAPTURE(run.output);
    CHECK(run.code != 0);
    CHECK(contains(run.output, "LAZ chunk 1 of 1 claims 1000000000 points in "));
    CHECK(run.seconds < 5);
    CHECK(run.peak_rss < budget / 2);
}
