// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include "io/las.hpp"
#include "io/las_writer.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>

#include "io_test_util.hpp"

using namespace lidarfx;
using namespace lidarfx::io;
using io_test::contains;
using io_test::identical;
using io_test::read_in_chunks;
using io_test::runtime_error_of;
using io_test::starts_with;

namespace {

/// Random points that point format `format` can hold exactly, with their integer coordinates.
struct sample {
    las_points points;
    std::vector<std::int32_t> qx, qy, qz;
};

sample random_sample(std::mt19937& rng, std::size_t n, int format, const std::array<double, 3>& scale,
                     const std::array<double, 3>& offset)
{
    const bool extended = format >= 6;
    std::uniform_int_distribution<std::int32_t> q(-2'000'000, 2'000'000);
    std::uniform_int_distribution<std::int32_t> q_any(std::numeric_limits<std::int32_t>::min(),
                                                      std::numeric_limits<std::int32_t>::max());
    std::uniform_int_distribution<int> byte(0, 255), ret(0, extended ? 15 : 7), cls(0, extended ? 255 : 31),
        flags(0, extended ? 15 : 7), angle(extended ? -30000 : -90, extended ? 30000 : 90), word(0, 65535);
    std::uniform_real_distribution<double> gps(0.0, 5.0e8);
    sample s;
    las_points& p = s.points;
    for (std::size_t i = 0; i < n; ++i) {
        // Every 97th point uses the whole 32-bit range to probe the extremes.
        const auto pick = [&] { return i % 97 == 5 ? q_any(rng) : q(rng); };
        s.qx.push_back(pick());
        s.qy.push_back(pick());
        s.qz.push_back(pick());
        p.x.push_back(static_cast<double>(s.qx.back()) * scale[0] + offset[0]);
        p.y.push_back(static_cast<double>(s.qy.back()) * scale[1] + offset[1]);
        p.z.push_back(static_cast<double>(s.qz.back()) * scale[2] + offset[2]);
        p.intensity.push_back(static_cast<std::uint16_t>(word(rng)));
        p.return_number.push_back(static_cast<std::uint8_t>(ret(rng)));
        p.number_of_returns.push_back(static_cast<std::uint8_t>(ret(rng)));
        p.classification.push_back(static_cast<std::uint8_t>(cls(rng)));
        p.classification_flags.push_back(static_cast<std::uint8_t>(flags(rng)));
        p.scan_angle_deg.push_back(extended ? static_cast<float>(angle(rng)) * 0.006f : static_cast<float>(angle(rng)));
        if (las_format_has_gps_time(format)) p.gps_time.push_back(gps(rng));
    }
    return s;
}

std::int32_t quantum(double v, double scale, double offset)
{
    return static_cast<std::int32_t>(std::llround((v - offset) / scale));
}

/// Checks that `got` holds the points of `want` (coordinates compared on their integer lattice).
void check_same(const las_points& got, const sample& want, const las_header& h)
{
    const las_points& w = want.points;
    REQUIRE(got.size() == w.size());
    for (std::size_t i = 0; i < got.size(); ++i) {
        if (quantum(got.x[i], h.scale[0], h.offset[0]) != want.qx[i] ||
            quantum(got.y[i], h.scale[1], h.offset[1]) != want.qy[i] ||
            quantum(got.z[i], h.scale[2], h.offset[2]) != want.qz[i]) {
            FAIL("coordinates of point " << i << " differ");
        }
    }
    CHECK(got.intensity == w.intensity);
    CHECK(got.return_number == w.return_number);
    CHECK(got.number_of_returns == w.number_of_returns);
    CHECK(got.classification == w.classification);
    CHECK(got.classification_flags == w.classification_flags);
    CHECK(got.scan_angle_deg == w.scan_angle_deg);
    CHECK(got.gps_time == w.gps_time);
}

template <class T>
void put(std::vector<std::uint8_t>& bytes, std::size_t at, T value)
{
    std::memcpy(bytes.data() + at, &value, sizeof(T));
}

template <class T>
T get(const std::vector<std::uint8_t>& bytes, std::size_t at)
{
    T v;
    std::memcpy(&v, bytes.data() + at, sizeof(T));
    return v;
}

/// The error a reader gives for `bytes`, read both from a file and from memory (they must agree).
std::string error_for(const io_test::temp_dir& dir, const std::vector<std::uint8_t>& bytes,
                      const std::string& name = "bad.las")
{
    const std::string path = dir.file(name);
    io_test::write_bytes(path, bytes);
    const auto read_everything = [](las_reader r) {
        las_points p;
        while (r.read(p, 1000) > 0) {
        }
    };
    const std::string from_file = runtime_error_of([&] { read_everything(las_reader(path)); });
    const std::string from_memory = runtime_error_of([&] { read_everything(las_reader(bytes, path)); });
    CHECK(from_file == from_memory);
    if (from_file != "<no error>") CHECK(starts_with(from_file, path + ": "));
    return from_file;
}

/// Appends an EVLR holding `payload` to a LAS 1.4 file and points the header at it.
void append_evlr(std::vector<std::uint8_t>& bytes, std::uint16_t record_id, const std::string& payload)
{
    const std::uint64_t at = bytes.size();
    std::vector<std::uint8_t> e(60, 0);
    std::memcpy(e.data() + 2, "LASF_Projection", 15);
    put<std::uint16_t>(e, 18, record_id);
    put<std::uint64_t>(e, 20, payload.size() + 1);
    bytes.insert(bytes.end(), e.begin(), e.end());
    bytes.insert(bytes.end(), payload.begin(), payload.end());
    bytes.push_back(0);
    put<std::uint64_t>(bytes, 235, at);
    put<std::uint32_t>(bytes, 243, get<std::uint32_t>(bytes, 243) + 1);
}

}  // namespace

TEST_CASE("io/las: every point format 0-10 round-trips through the writer, read whole or in odd chunks")
{
    io_test::temp_dir dir;
    std::mt19937 rng(20240611);
    const std::array<double, 3> scale{0.01, 0.005, 0.001};
    const std::array<double, 3> offset{2230000.0, 252000.0, -100.0};
    for (int format = 0; format <= 10; ++format) {
        const int first_version = format >= 6 ? 4 : format >= 4 ? 3 : format >= 2 ? 2 : 0;
        for (int version = first_version; version <= 4; ++version) {
            CAPTURE(format);
            CAPTURE(version);
            const std::size_t n = 1 + rng() % 3000;
            const int extra = static_cast<int>(rng() % 3) * 7;  // records longer than the format's fields
            const auto s = random_sample(rng, n, format, scale, offset);
            const las_write_options opt{.version_minor = version,
                                        .point_format = format,
                                        .scale = scale,
                                        .offset = offset,
                                        .extra_bytes = extra,
                                        .epsg_projected = 3645};
            const std::string path = dir.file(detail::concat("f", format, "v", version, ".las"));
            write_las(path, s.points, opt);

            las_reader r(path);
            const las_header& h = r.header();
            CHECK(h.version_minor == version);
            CHECK(h.point_format == format);
            CHECK(h.point_record_length == las_min_record_length(format) + extra);
            CHECK(h.point_count == n);
            CHECK(h.scale == scale);
            CHECK(h.offset == offset);
            CHECK(h.epsg_projected == 3645);
            for (int k = 0; k < (version >= 4 ? 15 : 5); ++k) {
                const auto expected = static_cast<std::uint64_t>(
                    std::count(s.points.return_number.begin(), s.points.return_number.end(), k + 1));
                CHECK(h.points_by_return[static_cast<std::size_t>(k)] == expected);
            }
            const las_points all = r.read_all();
            check_same(all, s, h);
            const std::array<const std::vector<double>*, 3> xyz{&all.x, &all.y, &all.z};
            for (std::size_t k = 0; k < 3; ++k) {
                const auto [lo, hi] = std::minmax_element(xyz[k]->begin(), xyz[k]->end());
                CHECK(h.min[k] == *lo);
                CHECK(h.max[k] == *hi);
            }
            for (std::size_t chunk : {std::size_t{1}, std::size_t{3}, std::size_t{7}, n - 1 + (n == 1), n + 13}) {
                CAPTURE(chunk);
                CHECK(identical(read_in_chunks(r, chunk), all));
            }
            const auto bytes = encode_las(s.points, opt);
            const auto file_bytes = io_test::read_bytes(path);
            // Same bytes in memory and on disk, apart from the creation date (a run may cross midnight).
            REQUIRE(bytes.size() == file_bytes.size());
            CHECK(std::equal(bytes.begin() + 94, bytes.end(), file_bytes.begin() + 94));
            las_reader from_memory(bytes);
            CHECK(identical(from_memory.read_all(), all));
        }
    }
}

TEST_CASE("io/las_reader: reads cross the decode blocks exactly (large file, chunks not dividing them)")
{
    io_test::temp_dir dir;
    std::mt19937 rng(7);
    const std::array<double, 3> scale{0.01, 0.01, 0.01}, offset{0, 0, 0};
    const auto s = random_sample(rng, 250'003, 1, scale, offset);  // > two 2 MiB blocks of 28-byte records
    const std::string path = dir.file("large.las");
    write_las(path, s.points, {.point_format = 1, .scale = scale, .offset = offset});
    las_reader r(path);
    const las_points all = r.read_all();
    check_same(all, s, r.header());
    CHECK(identical(read_in_chunks(r, 74'899), all));
    r.seek(100'000);
    las_points part;
    CHECK(r.read(part, 150'000) == 150'000);
    CHECK(r.position() == 250'000);
    CHECK(part.x.front() == all.x[100'000]);
    CHECK(part.gps_time.back() == all.gps_time[249'999]);
    CHECK(r.read(part, 10) == 3);
    CHECK(r.read(part, 10) == 0);
    CHECK(part.empty());
    CHECK(starts_with(runtime_error_of([&] { r.seek(250'004); }), path + ": seek to point 250004 beyond"));
}

TEST_CASE("io/las: CRS metadata round-trips (GeoKeys, geographic, vertical, WKT in a VLR and an EVLR)")
{
    io_test::temp_dir dir;
    las_points p;
    p.x = {10.0, 11.5};
    p.y = {20.0, 19.25};
    p.z = {0.5, 3.0};
    const std::string wkt = "PROJCS[\"NAD83(NSRS2007) / Oregon North\",UNIT[\"metre\",1]]";
    auto bytes = encode_las(
        p, {.version_minor = 4, .point_format = 6, .epsg_geographic = 4759, .epsg_vertical = 5703, .wkt = wkt});
    {
        las_reader r(bytes);
        const las_header& h = r.header();
        CHECK(h.epsg_projected == 0);
        CHECK(h.epsg_geographic == 4759);
        CHECK(h.epsg() == 4759);
        CHECK(h.epsg_vertical == 5703);
        CHECK(h.wkt == wkt);
        CHECK((h.global_encoding & 16) != 0);
        CHECK(h.geo_keys.size() == 4);  // model type, geographic, vertical, vertical units
        CHECK(h.point_count == 2);
        const auto q = r.read_all();
        CHECK(q.x == p.x);
        CHECK(q.y == p.y);
        CHECK(q.z == p.z);
        CHECK(q.return_number == std::vector<std::uint8_t>{1, 1});  // defaults of absent attributes
    }
    // LAS 1.4 may carry the WKT after the points, in an EVLR; the later record wins.
    append_evlr(bytes, 2112, "GEOGCS[\"late\"]");
    las_reader r(bytes);
    CHECK(r.header().wkt == "GEOGCS[\"late\"]");
    REQUIRE(r.header().vlrs.size() == 3);
    CHECK(r.header().vlrs[2].extended);
    CHECK(r.read_all().size() == 2);
}

TEST_CASE("io/las: the writer picks an offset from the data when none is given")
{
    las_points p;
    p.x = {512345.678, 512999.991};
    p.y = {5400123.456, 5400000.004};
    p.z = {-12.3456, 250.0};
    las_reader r(encode_las(p, {.scale = {0.001, 0.001, 0.0001}}));
    CHECK(r.header().offset == std::array<double, 3>{512000.0, 5400000.0, -1000.0});
    const auto q = r.read_all();
    for (std::size_t i = 0; i < 2; ++i) {
        CHECK(std::abs(q.x[i] - p.x[i]) <= 0.0005 + 1e-9);
        CHECK(std::abs(q.y[i] - p.y[i]) <= 0.0005 + 1e-9);
        CHECK(std::abs(q.z[i] - p.z[i]) <= 0.00005 + 1e-9);
    }
    // The reader owns a temporary buffer, also after a move.
    las_reader moved = std::move(r);
    moved.seek(0);
    CHECK(moved.read_all().x == q.x);
    las_reader empty(encode_las(las_points{}));
    CHECK(empty.point_count() == 0);
    CHECK(empty.read_all().empty());
}

TEST_CASE("io/las_writer: rejects values the point format cannot hold and bad options")
{
    const auto message = [](const las_points& p, const las_write_options& opt) -> std::string {
        try {
            (void)encode_las(p, opt);
        } catch (const invalid_input& e) {
            return e.what();
        }
        return "<no error>";
    };
    las_points p;
    p.x = {1, 2};
    p.y = {1, 2};
    p.z = {1, 2};
    p.return_number = {1, 8};
    CHECK(message(p, {}) == "las_writer: return_number of point 1 must be <= 7 in formats 0-5 (got 8)");
    CHECK(message(p, {.version_minor = 4, .point_format = 6}) == "<no error>");
    p.return_number.clear();
    p.classification = {32, 0};
    CHECK(message(p, {}) == "las_writer: classification of point 0 must be <= 31 in formats 0-5 (got 32)");
    p.classification.clear();
    p.classification_flags = {0, las_flag_overlap};
    CHECK(contains(message(p, {}), "classification_flags of point 1 must be <= 7 (no overlap bit)"));
    p.classification_flags.clear();
    p.scan_angle_deg = {0.0f, 91.0f};
    CHECK(contains(message(p, {}), "scan_angle_deg of point 1 must be in [-90, 90]"));
    p.scan_angle_deg = {0.0f};
    CHECK(message(p, {}) == "las_writer: scan_angle_deg must be empty or of length x.size() = 2 (got 1)");
    p.scan_angle_deg.clear();
    p.x[1] = NAN;
    CHECK(contains(message(p, {}), "las_writer: x of point 1 must be finite"));
    p.x[1] = 1e9;
    CHECK(contains(message(p, {.offset = std::array<double, 3>{0, 0, 0}}),
                   "x of point 1 must be finite and within 2^31"));
    p.x[1] = 2;
    CHECK(message(p, {.point_format = 6}) == "las_writer: point format 6 needs LAS 1.4 or later (got version_minor 2)");
    CHECK(message(p, {.version_minor = 2, .point_format = 4}) ==
          "las_writer: point format 4 needs LAS 1.3 or later (got version_minor 2)");
    CHECK(message(p, {.point_format = 11}) == "las_writer: point_format must be in 0..10 (got 11)");
    CHECK(message(p, {.version_minor = 5}) == "las_writer: version_minor must be in 0..4 (got 5)");
    CHECK(message(p, {.scale = {0.01, 0.0, 0.01}}) == "las_writer: scale must be finite and > 0 (got 0)");
    io_test::temp_dir dir;
    CHECK(starts_with(runtime_error_of([&] { las_writer w(dir.file("no/such/dir.las")); }),
                      dir.file("no/such/dir.las") + ": cannot open for writing"));
}

TEST_CASE("io/las_reader: each kind of corrupt or unsupported file is rejected with its reason")
{
    io_test::temp_dir dir;
    std::mt19937 rng(99);
    const std::array<double, 3> scale{0.01, 0.01, 0.01}, offset{0, 0, 0};
    const auto s12 = random_sample(rng, 100, 1, scale, offset);
    const auto v12 =
        encode_las(s12.points, {.point_format = 1, .scale = scale, .offset = offset, .epsg_projected = 3645});
    const auto s14 = random_sample(rng, 100, 6, scale, offset);
    const auto v14 = encode_las(s14.points, {.version_minor = 4, .point_format = 6, .scale = scale, .offset = offset});
    CHECK(error_for(dir, v12) == "<no error>");  // the unmodified files are fine
    const auto mutated = [](std::vector<std::uint8_t> bytes, auto&& change) {
        change(bytes);
        return bytes;
    };
    const std::size_t points12 = get<std::uint32_t>(v12, 96);

    SUBCASE("LAZ marks without LAZ data")
    {
        // The LASzip bits of the format id say "compressed"; without the laszip VLR nothing can decode it.
        for (const auto& base : {v12, v14}) {
            for (const std::uint8_t bit : {std::uint8_t{0x80}, std::uint8_t{0x40}}) {
                CHECK(contains(
                    error_for(dir, mutated(base, [bit](auto& b) { b[104] = static_cast<std::uint8_t>(b[104] | bit); })),
                    "the point format says LAZ (compressed) but the file has no laszip VLR"));
            }
        }
        // The name does not decide: an uncompressed file called .laz is read as LAS.
        CHECK(error_for(dir, v12, "valid_but_named.laz") == "<no error>");
        CHECK(error_for(dir, v12, "UPPER.LAZ") == "<no error>");
        // Nor does a laszip VLR alone (the format bits do): the points are read as stored.
        CHECK(error_for(dir, mutated(v12, [](auto& b) {
                            std::memset(b.data() + 227 + 2, 0, 16);
                            std::memcpy(b.data() + 227 + 2, "laszip encoded", 14);
                            put<std::uint16_t>(b, 227 + 18, 22204);
                        })) == "<no error>");
    }
    SUBCASE("signature")
    {
        CHECK(contains(error_for(dir, mutated(v12, [](auto& b) { b[3] = 'X'; })),
                       "not a LAS file (the signature is not 'LASF')"));
        CHECK(contains(error_for(dir, {}), "not a LAS file (only 0 bytes)"));
        CHECK(contains(error_for(dir, {'L', 'A', 'S'}), "not a LAS file (only 3 bytes)"));
        const std::vector<std::uint8_t> text{'x', ',', 'y', ',', 'z', '\n', '1', ',', '2', ',', '3', '\n'};
        CHECK(contains(error_for(dir, text), "not a LAS file"));
        CHECK(starts_with(runtime_error_of([&] { las_reader r(dir.file("missing.las")); }),
                          dir.file("missing.las") + ": cannot open"));
    }
    SUBCASE("truncated")
    {
        CHECK(contains(error_for(dir, std::vector<std::uint8_t>(v12.begin(), v12.end() - 1)),
                       "truncated: the header declares 100 points of 28 bytes from byte " + std::to_string(points12) +
                           " but the file has " + std::to_string(v12.size() - 1) + " bytes (room for 99 points)"));
        CHECK(contains(error_for(dir, mutated(v12, [](auto& b) { put<std::uint32_t>(b, 107, 101); })),
                       "truncated: the header declares 101 points"));
        CHECK(contains(error_for(dir, mutated(v14, [](auto& b) { put<std::uint64_t>(b, 247, 1ull << 62); })),
                       "truncated: the header declares 4611686018427387904 points"));
        CHECK(contains(error_for(dir, std::vector<std::uint8_t>(v12.begin(), v12.begin() + 200)),
                       "truncated header: the file has 200 bytes, a LAS header at least 227"));
        // Every prefix of a file is rejected, never read as fewer points.
        for (std::size_t len = 0; len < v14.size(); len += 1 + len / 50) {
            CAPTURE(len);
            CHECK(error_for(dir, std::vector<std::uint8_t>(
                                     v14.begin(), v14.begin() + static_cast<std::ptrdiff_t>(len))) != "<no error>");
        }
    }
    SUBCASE("header fields that disagree with the file or the format")
    {
        CHECK(contains(error_for(dir, mutated(v12, [](auto& b) { put<std::uint32_t>(b, 96, 1'000'000); })),
                       "offset to point data 1000000 is beyond the file size " + std::to_string(v12.size())));
        CHECK(contains(error_for(dir, mutated(v12, [](auto& b) { put<std::uint32_t>(b, 96, 200); })),
                       "offset to point data 200 lies inside the header (header size 227)"));
        CHECK(contains(error_for(dir, mutated(v12, [](auto& b) { put<std::uint16_t>(b, 105, 27); })),
                       "point record length 27 is smaller than the 28 bytes of point format 1"));
        CHECK(contains(error_for(dir, mutated(v12, [](auto& b) { put<std::uint16_t>(b, 94, 226); })),
                       "header size 226 is too small for LAS 1.2 (at least 227 bytes)"));
        CHECK(contains(error_for(dir, mutated(v14, [](auto& b) { put<std::uint16_t>(b, 94, 235); })),
                       "header size 235 is too small for LAS 1.4 (at least 375 bytes)"));
        CHECK(contains(error_for(dir, mutated(v12, [](auto& b) { b[104] = 11; })),
                       "unknown point data format 11 (expected 0 to 10)"));
        CHECK(contains(error_for(dir, mutated(v12, [](auto& b) { b[24] = 2; })),
                       "unsupported LAS version 2.2 (this reader handles 1.0 to 1.4)"));
        CHECK(contains(error_for(dir, mutated(v12, [](auto& b) { b[25] = 5; })), "unsupported LAS version 1.5"));
        CHECK(contains(error_for(dir, mutated(v14, [](auto& b) { put<std::uint32_t>(b, 107, 7); })),
                       "legacy point count 7 disagrees with the 64-bit point count 100"));
        CHECK(contains(error_for(dir, mutated(v12, [](auto& b) { put<double>(b, 139, 0.0); })),
                       "y scale factor 0 must be finite and non-zero"));
        CHECK(contains(error_for(dir, mutated(v12, [](auto& b) { put<double>(b, 171, NAN); })),
                       "z offset must be finite"));
    }
    SUBCASE("VLRs and EVLRs that do not fit")
    {
        CHECK(contains(error_for(dir, mutated(v12, [](auto& b) { put<std::uint32_t>(b, 100, 2); })),
                       "VLR 2 of 2 at byte " + std::to_string(points12) + " does not fit before the point data"));
        CHECK(contains(error_for(dir, mutated(v12, [](auto& b) { put<std::uint16_t>(b, 227 + 20, 5000); })),
                       "VLR 1 of 1 ('LASF_Projection' 34735) declares 5000 bytes, past the start of the point data"));
        CHECK(contains(error_for(dir, mutated(v12, [](auto& b) { put<std::uint16_t>(b, 227 + 54 + 6, 100); })),
                       "GeoKeyDirectory VLR declares 100 keys but holds room for"));
        const auto with_evlr = mutated(v14, [](auto& b) { append_evlr(b, 2112, "GEOGCS[]"); });
        CHECK(error_for(dir, with_evlr) == "<no error>");
        CHECK(contains(error_for(dir, mutated(with_evlr, [](auto& b) { put<std::uint64_t>(b, 235, 400); })),
                       "start of the first EVLR (byte 400) lies inside the header or the point data"));
        CHECK(contains(error_for(dir, mutated(with_evlr, [](auto& b) { put<std::uint64_t>(b, 235, b.size() - 10); })),
                       "EVLR 1 of 1 at byte " + std::to_string(with_evlr.size() - 10) + " does not fit in the file"));
        CHECK(contains(error_for(dir, mutated(with_evlr, [](auto& b) { put<std::uint32_t>(b, 243, 2); })),
                       "EVLR 2 of 2 at byte " + std::to_string(with_evlr.size()) + " does not fit in the file"));
        CHECK(
            contains(error_for(dir, mutated(with_evlr, [&](auto& b) { put<std::uint64_t>(b, v14.size() + 20, 1000); })),
                     "declares 1000 bytes, past the end of the file"));
    }
}

TEST_CASE("io/las_reader: random corruption of valid files gives a clean error or valid points, never a crash")
{
    io_test::temp_dir dir;
    std::mt19937 rng(2024);
    const std::array<double, 3> scale{0.01, 0.01, 0.01}, offset{0, 0, 0};
    std::vector<std::vector<std::uint8_t>> bases;
    for (int format : {0, 3, 6, 10}) {
        const auto s = random_sample(rng, 20, format, scale, offset);
        bases.push_back(encode_las(s.points, {.version_minor = 4,
                                              .point_format = format,
                                              .scale = scale,
                                              .offset = offset,
                                              .epsg_projected = 3645,
                                              .wkt = "PROJCS[]"}));
    }
    int rejected = 0, accepted = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        auto bytes = bases[static_cast<std::size_t>(trial) % bases.size()];
        const int edits = 1 + static_cast<int>(rng() % 4);
        for (int e = 0; e < edits; ++e) {
            // Mostly the header and VLRs, where the structure lives.
            const std::size_t at =
                rng() % 4 == 0 ? rng() % bytes.size() : rng() % std::min<std::size_t>(bytes.size(), 500);
            bytes[at] = static_cast<std::uint8_t>(rng());
        }
        try {
            las_reader r(bytes, "mutant");
            const auto p = r.read_all();
            CHECK(p.size() == r.point_count());
            CHECK(p.size() * r.header().point_record_length + r.header().offset_to_point_data <= bytes.size());
            ++accepted;
        } catch (const std::runtime_error& e) {
            CHECK(starts_with(e.what(), "mutant: "));
            ++rejected;
        }
    }
    MESSAGE(accepted << " mutants read, " << rejected << " rejected");
    CHECK(rejected > 0);
    CHECK(accepted > 0);
}

TEST_CASE("io/las_points: append and cloud() view the arrays without copies")
{
    las_points a, b;
    a.resize(2, true);
    b.resize(3, true);
    a.x = {1, 2};
    b.x = {3, 4, 5};
    a.append(b);
    CHECK(a.size() == 5);
    CHECK(a.x == std::vector<double>{1, 2, 3, 4, 5});
    CHECK(a.gps_time.size() == 5);
    las_points no_gps;
    no_gps.resize(1, false);
    a.append(no_gps);
    CHECK(a.size() == 6);
    CHECK(a.gps_time.empty());  // one chunk had no GPS time: the column cannot be kept
    const auto c = a.cloud();
    CHECK(c.size() == 6);
    CHECK(c.x(4) == 5);
    CHECK(c.has_intensity_values());
}
