// SPDX-License-Identifier: Apache-2.0
// Remembered CRS answers (examples/io/crs_cache): the same answer as crs_of, read back from disk, never trusted
// when damaged, never in the way when the folder cannot be written.
#include <doctest/doctest.h>

#include "io/crs.hpp"
#include "io/crs_cache.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "io_test_util.hpp"

using namespace lidarfx::io;
using io_test::temp_dir;

namespace {

/// A LAS 1.4 header whose CRS is a WKT record (the global encoding says so).
las_header header_with_wkt(const std::string& wkt)
{
    las_header h;
    h.version_minor = 4;
    h.global_encoding = 16;
    h.wkt = wkt;
    h.has_wkt_record = true;
    return h;
}

// NAD83 / Texas Central in US survey feet, without its EPSG code: crs_of searches for the code (the costly case).
const std::string texas_ftus_without_code =
    R"w(PROJCS["Texas Central in feet",GEOGCS["NAD83",DATUM["North_American_Datum_1983",)w"
    R"w(SPHEROID["GRS 1980",6378137,298.257222101]],PRIMEM["Greenwich",0],UNIT["degree",0.0174532925199433]],)w"
    R"w(PROJECTION["Lambert_Conformal_Conic_2SP"],PARAMETER["latitude_of_origin",29.6666666666667],)w"
    R"w(PARAMETER["central_meridian",-100.333333333333],PARAMETER["standard_parallel_1",31.8833333333333],)w"
    R"w(PARAMETER["standard_parallel_2",30.1166666666667],PARAMETER["false_easting",2296583.333],)w"
    R"w(PARAMETER["false_northing",9842500],UNIT["US survey foot",0.304800609601219]])w";

void check_same(const survey_crs& a, const survey_crs& b)
{
    CHECK(a.wkt == b.wkt);
    CHECK(a.epsg == b.epsg);
    CHECK(a.geographic == b.geographic);
    CHECK(a.horizontal_unit_m == b.horizontal_unit_m);  // exactly: written in hexadecimal
    CHECK(a.vertical_unit_m == b.vertical_unit_m);
    CHECK(a.horizontal_unit == b.horizontal_unit);
    CHECK(a.vertical_unit == b.vertical_unit);
    CHECK(a.source == b.source);
    CHECK(a.warnings == b.warnings);
}

std::vector<std::filesystem::path> files_in(const std::filesystem::path& folder)
{
    std::vector<std::filesystem::path> out;
    if (!std::filesystem::exists(folder)) return out;
    for (const auto& e : std::filesystem::directory_iterator(folder)) out.push_back(e.path());
    return out;
}

std::string text_of(const std::filesystem::path& p)
{
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_text(const std::filesystem::path& p, const std::string& text)
{
    std::ofstream(p, std::ios::binary | std::ios::trunc) << text;
}

}  // namespace

TEST_CASE("io/crs_of_remembered: the answer of crs_of, kept in one file per CRS and read back from it")
{
    const temp_dir dir;
    const std::filesystem::path folder = dir.file("crs");
    const auto h = header_with_wkt(texas_ftus_without_code);
    const survey_crs truth = crs_of(h);
    check_same(crs_of_remembered(h, folder), truth);
    if (!crs_gdal_available()) {
        CHECK(files_in(folder).empty());  // without GDAL crs_of is cheap: nothing is kept
        return;
    }
    const auto kept = files_in(folder);
    REQUIRE(kept.size() == 1);
    const std::string answer = text_of(kept[0]);
    check_same(crs_of_remembered(h, folder), truth);  // read back: the same
    CHECK(files_in(folder).size() == 1);

    SUBCASE("a kept answer is what later runs get (the file is read, not the CRS interpreted again)")
    {
        // The third line holds the EPSG code first; a different code there must come back.
        const auto line2 = answer.find('\n', answer.find('\n') + 1);
        const auto space = answer.find(' ', line2);
        write_text(kept[0], answer.substr(0, line2 + 1) + "4321" + answer.substr(space));
        CHECK(crs_of_remembered(h, folder).epsg == 4321);
    }
    SUBCASE("a damaged answer is ignored and written again")
    {
        for (const std::string& damaged : {answer.substr(0, answer.size() / 2), answer + "more\n", std::string()}) {
            write_text(kept[0], damaged);
            check_same(crs_of_remembered(h, folder), truth);
            CHECK(text_of(kept[0]) == answer);
        }
    }
    SUBCASE("other CRS records are another answer; the same records in another header are the same one")
    {
        auto other = header_with_wkt(texas_ftus_without_code + " ");
        check_same(crs_of_remembered(other, folder), crs_of(other));
        CHECK(files_in(folder).size() == 2);
        auto same = h;
        same.point_count = 12345;  // not a CRS record
        check_same(crs_of_remembered(same, folder), truth);
        CHECK(files_in(folder).size() == 2);
    }
}

TEST_CASE("io/crs_of_remembered: a folder that cannot be written, or none, changes nothing but the time")
{
    const temp_dir dir;
    const auto h = header_with_wkt(texas_ftus_without_code);
    const survey_crs truth = crs_of(h);
    write_text(dir.file("a_file"), "not a folder");
    check_same(crs_of_remembered(h, std::filesystem::path(dir.file("a_file")) / "crs"), truth);
    check_same(crs_of_remembered(h, std::nullopt), truth);
    CHECK(files_in(dir.file("")).size() == 1);  // only a_file
}

TEST_CASE("io/crs_cache_folder: LIDARFX_CACHE_DIR names it; empty turns remembering off")
{
    const char* before = std::getenv("LIDARFX_CACHE_DIR");
    const std::optional<std::string> saved = before ? std::optional<std::string>(before) : std::nullopt;
    ::setenv("LIDARFX_CACHE_DIR", "/somewhere/cache", 1);
    CHECK(crs_cache_folder() == std::filesystem::path("/somewhere/cache/crs"));
    ::setenv("LIDARFX_CACHE_DIR", "", 1);
    CHECK_FALSE(crs_cache_folder().has_value());
    if (saved) {
        ::setenv("LIDARFX_CACHE_DIR", saved->c_str(), 1);
    } else {
        ::unsetenv("LIDARFX_CACHE_DIR");
    }
}
