// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include "io/tables.hpp"

#include "cli/cli_common.hpp"
#include "io/footprints.hpp"
#include "io/vectors.hpp"

#include <lidarfx/core/error.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "io_test_util.hpp"

using namespace lidarfx;
using namespace lidarfx::io;

namespace {

/// A plain RFC 4180 reader: fields split by commas, quoted fields may hold commas, quotes ("") and line breaks.
std::vector<std::vector<std::string>> parse_csv(const std::string& text)
{
    std::vector<std::vector<std::string>> rows(1);
    std::string field;
    bool quoted = false, was_quoted = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char ch = text[i];
        if (quoted) {
            if (ch == '"' && i + 1 < text.size() && text[i + 1] == '"') {
                field += '"';
                ++i;
            } else if (ch == '"') {
                quoted = false;
            } else {
                field += ch;
            }
        } else if (ch == '"') {
            REQUIRE(field.empty());  // quotes only open a field
            quoted = was_quoted = true;
        } else if (ch == ',') {
            rows.back().push_back(field);
            field.clear();
            was_quoted = false;
        } else if (ch == '\n') {
            rows.back().push_back(field);
            field.clear();
            was_quoted = false;
            rows.emplace_back();
        } else {
            REQUIRE_FALSE(was_quoted);  // nothing may follow a closing quote
            field += ch;
        }
    }
    REQUIRE_FALSE(quoted);
    REQUIRE(rows.back().empty());  // the text ends with a line break
    rows.pop_back();
    return rows;
}

}  // namespace

TEST_CASE("io/csv_field: quotes exactly the fields that need it")
{
    CHECK(csv_field("plain") == "plain");
    CHECK(csv_field("") == "");
    CHECK(csv_field("a,b") == "\"a,b\"");
    CHECK(csv_field("say \"hi\"") == "\"say \"\"hi\"\"\"");
    CHECK(csv_field("two\nlines") == "\"two\nlines\"");
    CHECK(csv_field("cr\r") == "\"cr\r\"");
    CHECK(csv_field(" padded") == "\" padded\"");
    CHECK(csv_field("Zürich") == "Zürich");
}

TEST_CASE("io/to_csv: header and rows with numbers, text, booleans and empty cells")
{
    const std::vector<std::string> header{"id", "area m2", "name", "ok", "note"};
    const std::vector<std::vector<table_value>> rows{
        {1, 12.5, "lake, north", true, {}},
        {std::size_t{2}, 0.1, "quote \"q\"", false, NAN},
        {std::int64_t{-9007199254740993}, 1e-300, "", std::numeric_limits<std::uint64_t>::max(), -0.0f}};
    CHECK(to_csv(header, rows) ==
          "id,area m2,name,ok,note\n"
          "1,12.5,\"lake, north\",true,\n"
          "2,0.1,\"quote \"\"q\"\"\",false,\n"
          "-9007199254740993,1e-300,,18446744073709551615,-0\n");
    CHECK_THROWS_WITH_AS(to_csv(header, {{1, 2}}), "to_csv: row 0 has 2 fields, the header 5", invalid_input);
    CHECK_THROWS_WITH_AS(to_csv({}, {}), "to_csv: header must not be empty", invalid_input);

    io_test::temp_dir dir;
    write_csv(dir.file("t.csv"), header, rows);
    const auto bytes = io_test::read_bytes(dir.file("t.csv"));
    CHECK(std::string(bytes.begin(), bytes.end()) == to_csv(header, rows));
    CHECK(io_test::starts_with(io_test::runtime_error_of([&] { write_csv(dir.file("x/y.csv"), header, rows); }),
                               dir.file("x/y.csv") + ": cannot open for writing"));
}

TEST_CASE("io/to_csv: random text and numbers read back unchanged by an RFC 4180 reader")
{
    std::mt19937 rng(4180);
    const std::string alphabet[] = {"a", "b", ",", "\"", "\n", "\r", " ", "\xC3\xA9", ";", "'"};
    std::uniform_real_distribution<double> real(-1e6, 1e6);
    for (int trial = 0; trial < 50; ++trial) {
        const std::size_t cols = 1 + rng() % 5, n = rng() % 8;
        std::vector<std::string> header;
        std::vector<std::vector<table_value>> rows(n);
        std::vector<std::vector<std::string>> expected;
        const auto text = [&] {
            std::string s;
            for (std::size_t k = rng() % 6; k > 0; --k) s += alphabet[rng() % std::size(alphabet)];
            return s;
        };
        for (std::size_t c = 0; c < cols; ++c) header.push_back(text());
        expected.push_back(header);
        for (auto& row : rows) {
            std::vector<std::string> want;
            for (std::size_t c = 0; c < cols; ++c) {
                if (rng() % 2) {
                    row.emplace_back(text());
                    want.push_back(row.back().format());
                } else {
                    const double v = real(rng);
                    row.emplace_back(v);
                    want.push_back(row.back().format());
                    CHECK(std::stod(want.back()) == v);  // shortest form, yet exact
                }
            }
            expected.push_back(want);
        }
        CHECK(parse_csv(to_csv(header, rows)) == expected);
    }
}

TEST_CASE("io/json_string: escapes quotes, backslashes and control characters")
{
    CHECK(json_string("plain") == "\"plain\"");
    CHECK(json_string("a\"b\\c") == "\"a\\\"b\\\\c\"");
    CHECK(json_string("\n\r\t\b\f") == "\"\\n\\r\\t\\b\\f\"");
    CHECK(json_string(std::string_view("\x01\x1f", 2)) == "\"\\u0001\\u001f\"");
    CHECK(json_string("Zürich") == "\"Zürich\"");
}

TEST_CASE("io/to_geojson: polygons with holes, right-hand-rule rings, properties and a named CRS")
{
    // Outer ring given clockwise and unclosed, hole given counter-clockwise and closed: both are flipped.
    const geojson_feature lake{{{{0, 0}, {0, 10}, {10, 10}, {10, 0}}, {{2, 2}, {4, 2}, {4, 4}, {2, 2}}},
                               {{"id", 1}, {"area_m2", 99.5}, {"name", "Haystack \"pond\""}, {"seed", nullptr}}};
    const geojson_feature roof{{{{2230738.84, 252070.78}, {2230740.5, 252070.78}, {2230740.5, 252072.25}}},
                               {{"ok", true}, {"kw", NAN}}};
    CHECK(to_geojson({lake, roof}, 3645) ==
          "{\"type\":\"FeatureCollection\",\"crs\":{\"type\":\"name\",\"properties\":{\"name\":"
          "\"urn:ogc:def:crs:EPSG::3645\"}},\"features\":[\n"
          "{\"type\":\"Feature\",\"properties\":{\"id\":1,\"area_m2\":99.5,\"name\":\"Haystack \\\"pond\\\"\","
          "\"seed\":null},\"geometry\":{\"type\":\"Polygon\",\"coordinates\":["
          "[[0,0],[10,0],[10,10],[0,10],[0,0]],[[2,2],[4,4],[4,2],[2,2]]]}},\n"
          "{\"type\":\"Feature\",\"properties\":{\"ok\":true,\"kw\":null},\"geometry\":{\"type\":\"Polygon\","
          "\"coordinates\":[[[2230738.84,252070.78],[2230740.5,252070.78],[2230740.5,252072.25],"
          "[2230738.84,252070.78]]]}}\n"
          "]}\n");
    CHECK(to_geojson({}) == "{\"type\":\"FeatureCollection\",\"features\":[\n]}\n");

    io_test::temp_dir dir;
    write_geojson(dir.file("w.geojson"), {lake}, 3645);
    const auto bytes = io_test::read_bytes(dir.file("w.geojson"));
    CHECK(std::string(bytes.begin(), bytes.end()) == to_geojson({lake}, 3645));

    CHECK_THROWS_WITH_AS(to_geojson({geojson_feature{}}), "to_geojson: feature 0 has no ring", invalid_input);
    CHECK_THROWS_WITH_AS(to_geojson({{{{{0, 0}, {1, 1}, {0, 0}, {1, 1}}}, {}}}),
                         "to_geojson: feature 0 ring 0 must have at least 3 distinct positions", invalid_input);
    CHECK_THROWS_WITH_AS(to_geojson({lake, {{{{0, 0}, {1, NAN}, {1, 1}}}, {}}}),
                         "to_geojson: feature 1 ring 0 has a non-finite coordinate (1, nan)", invalid_input);
    CHECK_THROWS_WITH_AS(to_geojson({{lake.rings, {{"a", 1}, {"a", 2}}}}),
                         "to_geojson: feature 0 has property 'a' twice", invalid_input);
    CHECK_THROWS_WITH_AS(to_geojson({lake}, -1), "to_geojson: epsg must be >= 0 (got -1)", invalid_input);
}

TEST_CASE("io/checked_rings: rings closed, outer counter-clockwise and holes clockwise, first position kept")
{
    io::geojson_feature f;
    f.rings = {{{0, 0}, {0, 10}, {10, 10}, {10, 0}}, {{2, 2}, {4, 2}, {4, 4}, {2, 4}, {2, 2}}};
    const auto rings = io::checked_rings(f, 3, "test");
    REQUIRE(rings.size() == 2);
    CHECK(rings[0] == io::geo_ring{{0, 0}, {10, 0}, {10, 10}, {0, 10}, {0, 0}});
    CHECK(rings[1] == io::geo_ring{{2, 2}, {2, 4}, {4, 4}, {4, 2}, {2, 2}});
    io::geojson_feature line;
    line.rings = {{{0, 0}, {1, 1}, {0, 0}, {1, 1}}};
    CHECK(io_test::error_of([&] { io::checked_rings(line, 3, "test"); }) ==
          "test: feature 3 ring 0 must have at least 3 distinct positions");
}

namespace {

cli::output_formats vector_formats_of(const std::string& list)
{
    return cli::output_formats_from(cli::arguments({"in.las", "--formats", list}, {"formats"}, {}));
}

}  // namespace

TEST_CASE("cli/--formats: csv, geojson and gpkg pick the vector files; each kind keeps its defaults when not named")
{
    const cli::output_formats defaults;
    CHECK((defaults.csv && defaults.geojson));
    CHECK(defaults.gpkg == io::vectors_available());
    const auto png = vector_formats_of("png");
    CHECK((!png.asc && !png.tif && png.png && png.csv && png.geojson && png.gpkg == io::vectors_available()));
    const auto geojson = vector_formats_of("geojson");
    CHECK((geojson.asc && geojson.tif && geojson.png && !geojson.csv && geojson.geojson && !geojson.gpkg));
    CHECK(cli::polygon_file_names("waterbodies", geojson) == std::vector<std::string>{"waterbodies.geojson"});
    if (!io::vectors_available()) {
        CHECK(io_test::error_of([] { vector_formats_of("gpkg"); }).find("apt-get install libgdal-dev") !=
              std::string::npos);
        return;
    }
    // A survey CRS known only as ESRI WKT: the GeoPackage keeps it, the GeoJSON names the EPSG code OGR finds.
    const std::string utm13 =
        R"(PROJCS["WGS_1984_UTM_Zone_13N",GEOGCS["GCS_WGS_1984",DATUM["D_WGS_1984",SPHEROID["WGS_1984",6378137.0,)"
        R"(298.257223563]],PRIMEM["Greenwich",0.0],UNIT["Degree",0.0174532925199433]],)"
        R"(PROJECTION["Transverse_Mercator"],PARAMETER["False_Easting",500000.0],PARAMETER["False_Northing",0.0],)"
        R"(PARAMETER["Central_Meridian",-105.0],PARAMETER["Scale_Factor",0.9996],PARAMETER["Latitude_Of_Origin",0.0],)"
        R"(UNIT["Meter",1.0]])";
    io_test::temp_dir dir;
    const auto both = vector_formats_of("geojson,gpkg");
    CHECK(cli::polygon_file_names("roof_patches", both) ==
          std::vector<std::string>{"roof_patches.geojson", "roof_patches.gpkg"});
    io::geojson_feature f;
    f.rings = {{{500000, 4400000}, {500010, 4400000}, {500010, 4400010}, {500000, 4400010}}};
    f.properties = {{"building_id", 3}, {"kwp", 1.5}};
    {
        io::output_folder out(dir.file("out"));
        cli::write_polygons(out, "roof_patches", {f}, utm13, 0, both);
        out.commit("test");
    }
    const auto text = io_test::read_bytes(dir.file("out/roof_patches.geojson"));
    CHECK(std::string(text.begin(), text.end()).find(R"("name":"urn:ogc:def:crs:EPSG::32613")") != std::string::npos);
    const auto back = io::read_footprints(dir.file("out/roof_patches.gpkg"));
    REQUIRE(back.footprints.size() == 1);
    CHECK(back.footprints[0].building_id == 3);
    CHECK(io::epsg_of_crs(back.crs) == 32613);
}
