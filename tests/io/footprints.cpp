// SPDX-License-Identifier: Apache-2.0
// Building footprints from GeoJSON: what is read, what is refused and what is reported per building.
#include <doctest/doctest.h>

#include <lidarfx/core/error.hpp>

#include "io/footprints.hpp"

#include <cstdio>
#include <fstream>
#include <string>

using namespace lidarfx;

namespace {

std::string feature(const std::string& id, const std::string& geometry)
{
    return R"({"type":"Feature","properties":{"building_id":)" + id + R"(,"name":"x"},"geometry":)" + geometry + "}";
}

std::string collection(const std::string& features)
{
    return R"({"type":"FeatureCollection","features":[)" + features + "]}";
}

const std::string square = R"({"type":"Polygon","coordinates":[[[0,0],[0,10],[10,10],[10,0],[0,0]]]})";

}  // namespace

TEST_CASE("io/footprints: polygons and multipolygons with holes are read, rings oriented and closed")
{
    const std::string holed =
        R"({"type":"Polygon","coordinates":[[[20,0],[30,0],[30,10],[20,10]],[[22,2],[28,2],[28,8],[22,8],[22,2]]]})";
    const std::string multi =
        R"({"type":"MultiPolygon","coordinates":[[[[40,0],[45,0],[45,5],[40,5],[40,0]]],[[[50,0],[55,0],[55,5],[50,5],[50,0]]]]})";
    const auto c = io::parse_footprints_geojson(
        collection(feature("1", square) + "," + feature("7", holed) + "," + feature("3.0", multi)), "f.geojson");
    REQUIRE(c.footprints.size() == 3);
    CHECK(c.problems.empty());
    CHECK(c.footprints[0].building_id == 1);
    const auto& outer = c.footprints[0].parts[0].rings[0];
    double area2 = 0;
    for (std::size_t i = 0; i + 1 < outer.size(); ++i)
        area2 += outer[i][0] * outer[i + 1][1] - outer[i + 1][0] * outer[i][1];
    CHECK(area2 == 200.0);  // counter-clockwise now (it was drawn clockwise)
    CHECK(c.footprints[1].parts[0].rings.size() == 2);
    CHECK(c.footprints[1].parts[0].rings[0].front() == c.footprints[1].parts[0].rings[0].back());  // closed
    CHECK(c.footprints[2].building_id == 3);
    CHECK(c.footprints[2].parts.size() == 2);
    CHECK(c.footprints[2].feature == 2);
}

TEST_CASE("io/footprints: a self-intersecting or empty footprint is reported for its building, not dropped")
{
    const std::string bowtie = R"({"type":"Polygon","coordinates":[[[0,0],[10,10],[10,0],[0,10],[0,0]]]})";
    const std::string flat = R"({"type":"Polygon","coordinates":[[[0,0],[5,0],[10,0],[0,0]]]})";
    const auto c = io::parse_footprints_geojson(
        collection(feature("5", bowtie) + "," + feature("6", square) + "," + feature("8", flat)), "f.geojson");
    REQUIRE(c.footprints.size() == 1);
    CHECK(c.footprints[0].building_id == 6);
    REQUIRE(c.problems.size() == 2);
    CHECK(c.problems[0].building_id == 5);
    CHECK(c.problems[0].problem.find("invalid polygon") != std::string::npos);
    CHECK(c.problems[1].building_id == 8);
    CHECK(c.problems[1].problem.find("zero area") != std::string::npos);
}

TEST_CASE("io/footprints: missing, fractional and duplicated ids and wrong structures are refused by name")
{
    const auto refused = [](const std::string& text, const std::string& words) {
        try {
            io::parse_footprints_geojson(text, "fp.geojson");
        } catch (const invalid_input& e) {
            const std::string m = e.what();
            INFO(m);
            CHECK(m.find("fp.geojson") != std::string::npos);
            CHECK(m.find(words) != std::string::npos);
            return;
        }
        FAIL("accepted: " << text);
    };
    refused(collection(R"({"type":"Feature","properties":{},"geometry":)" + square + "}"), "building_id");
    refused(collection(R"({"type":"Feature","properties":null,"geometry":)" + square + "}"), "building_id");
    refused(collection(feature("\"12\"", square)), "feature 0: building_id \"12\" is not an integer");
    refused(collection(feature("[1]", square)), "building_id [1] is not an integer");
    refused(collection(feature("2.5", square)), "not an integer");
    refused(collection(feature("0", square)), "not an integer");
    refused(collection(feature("4", square) + "," + feature("4", square)), "used by feature 0");
    refused(collection(feature("4", "null")), "no Polygon");
    refused(collection(feature("4", R"({"type":"Point","coordinates":[1,2]})")), "Point");
    refused(collection(feature("4", R"({"type":"Polygon","coordinates":[[[0,0],[1,1],[0,0]]]})")), "4 positions");
    refused(collection(feature("4", R"({"type":"Polygon","coordinates":[[[0,0],[1,"a"],[1,0],[0,0]]]})")),
            "feature 0 (building_id 4): a position must be an array of numbers [x, y] (vertex 1 has \"a\")");
    refused(R"({"type":"Feature"})", "FeatureCollection");
    refused(R"({"type":"FeatureCollection"})", "features");
    refused(R"({"type":"FeatureCollection","features":[)", "not valid JSON");
    refused("[1, 2] trailing", "not valid JSON");
    CHECK(io::parse_footprints_geojson(collection(""), "e").footprints.empty());
}

namespace {

// The message of the invalid_input that parsing `text` throws ("" if it is accepted).
std::string refusal(const std::string& text, const io::footprint_read_options& opt = {})
{
    try {
        io::parse_footprints_geojson(text, "fp.geojson", opt);
    } catch (const invalid_input& e) {
        return e.what();
    }
    return "";
}

std::string ring_at(const std::string& x0, const std::string& y0)
{
    return R"({"type":"Polygon","coordinates":[[[)" + x0 + "," + y0 + R"(],[0,10],[10,10],[10,0],[)" + x0 + "," + y0 +
           "]]]}";
}

// `n` square footprints with realistic projected coordinates (about 24 bytes of text per vertex).
std::string many_squares(int n)
{
    std::string features;
    for (int i = 0; i < n; ++i) {
        const std::string x = std::to_string(500000 + 20 * i) + ".25", x1 = std::to_string(500010 + 20 * i) + ".25";
        if (i) features += ',';
        features += feature(std::to_string(i + 1), R"({"type":"Polygon","coordinates":[[[)" + x + ",5000000.5],[" + x1 +
                                                       ",5000000.5],[" + x1 + ",5000010.5],[" + x + ",5000010.5],[" +
                                                       x + ",5000000.5]]]}");
    }
    return collection(features);
}

}  // namespace

TEST_CASE("io/footprints: a coordinate beyond 1e9 or a double's range is refused naming file, feature, id and value")
{
    // 1e300 made Boost.Geometry's checks throw "bad numeric conversion: positive overflow" (no file, no feature).
    const std::string m = refusal(collection(feature("4", square) + "," + feature("12", ring_at("1e300", "-1e300"))));
    INFO(m);
    CHECK(m.find("fp.geojson: feature 1 (building_id 12): coordinate x = 1e300 of vertex 0") != std::string::npos);
    CHECK(m.find("beyond +-1e9") != std::string::npos);
    const std::string y = refusal(collection(feature("5", ring_at("0", "-2.5e19"))));
    CHECK(y.find("feature 0 (building_id 5): coordinate y = -2.5e19 of vertex 0") != std::string::npos);
    // Beyond a double: the value as written, not "inf".
    const std::string big = refusal(collection(feature("6", ring_at("1e999", "0"))));
    CHECK(big.find("coordinate x = 1e999 of vertex 0 is beyond the range of a double") != std::string::npos);
    // The properties after the geometry: the id is still named.
    const std::string later = refusal(
        collection(R"({"type":"Feature","geometry":)" + ring_at("0", "1e10") + R"(,"properties":{"building_id":77}})"));
    CHECK(later.find("feature 0 (building_id 77): coordinate y = 1e10") != std::string::npos);
    // The limit itself is accepted, and a z of any size is not read.
    CHECK(refusal(collection(feature("7", ring_at("-1e9", "1e9")))).empty());
    CHECK(refusal(collection(feature(
                      "8", R"({"type":"Polygon","coordinates":[[[0,0,1e300],[0,10,1],[10,10,1],[10,0,1],[0,0,1]]]})")))
              .empty());
    CHECK(refusal(collection(feature("9", ring_at("1000000000.001", "0")))).find("beyond +-1e9") != std::string::npos);
    // A building_id beyond a double's range is named as written.
    CHECK(refusal(collection(feature("1e999", square))).find("building_id 1e999 is not an integer") !=
          std::string::npos);
}

TEST_CASE("io/footprints: a UTF-8 byte order mark is skipped; JSON errors give byte and line")
{
    const auto c = io::parse_footprints_geojson("\xEF\xBB\xBF" + collection(feature("1", square)), "bom.geojson");
    CHECK(c.footprints.size() == 1);
    // Only at the start, and only the whole mark.
    CHECK(refusal(" \xEF\xBB\xBF" + collection(feature("1", square))).find("not valid JSON at byte 1 (line 1)") !=
          std::string::npos);
    CHECK(refusal("\xEF\xBB" + collection(feature("1", square))).find("not valid JSON at byte 0") != std::string::npos);
    CHECK(refusal("{\"type\":\"FeatureCollection\",\n\"features\":[\n{\"type\":\"Feature\" 1}]}")
              .find("(line 3): expected '}'") != std::string::npos);
}

TEST_CASE("io/footprints: members in any order; values footprints do not need are passed over")
{
    const std::string text =
        R"({"features":[{"geometry":{"coordinates":[[[0,0],[0,10],[10,10],[10,0],[0,0]]],"bbox":[0,0,10,10],"type":"Polygon"},)"
        R"("type":"Feature","properties":{"name":{"a":[1,2,{"b":null}]},"building_id":3,"building_id":4,"height":[1e999]}}],)"
        R"("name":"x\"y\u00e9","type":"FeatureCollection","crs":{"type":"name","properties":{"name":"EPSG:25832"}}})";
    const auto c = io::parse_footprints_geojson(text, "order.geojson");
    REQUIRE(c.footprints.size() == 1);
    CHECK(c.footprints[0].building_id == 3);  // the first of two keys, as before
    CHECK(refusal(R"({"features":[],"type":"Topology"})").find("FeatureCollection") != std::string::npos);
    CHECK(refusal(collection("[1,2]")).find("feature 0: not a GeoJSON Feature object") != std::string::npos);
    CHECK(refusal(collection(feature("4", R"({"type":"Polygon","coordinates":[]})"))).find("exterior ring") !=
          std::string::npos);
    CHECK(refusal(collection(feature("4", R"({"type":"MultiPolygon","coordinates":[]})"))).find("empty MultiPolygon") !=
          std::string::npos);
    CHECK(refusal(collection(feature("4", R"({"type":"MultiPolygon","coordinates":[[[0,0],[0,1],[1,1],[0,0]]]})")))
              .find("MultiPolygon's coordinates must be") != std::string::npos);
    CHECK(refusal(collection(feature("4", R"({"type":"Polygon","coordinates":[[[0,0],[0,1],[1,1],[0,0]],[]]})")))
              .find("4 positions") != std::string::npos);
    CHECK(refusal(collection(feature("4", R"({"type":"Polygon","coordinates":[[[0,0],[0,1],[1,1],[[0,0]]]]})")))
              .find("mix arrays of different depths") != std::string::npos);
    CHECK(refusal(collection(feature("4", R"({"type":"Polygon","coordinates":[[[0,0],[0,1],[1,[1]],[0,0]]]})")))
              .find("numbers [x, y]") != std::string::npos);
    CHECK(refusal(std::string(70, '[') + std::string(70, ']')).find("deeper than 64") != std::string::npos);
}

TEST_CASE("io/footprints: memory follows the footprints kept and is held to the budget")
{
    const std::string text = many_squares(2000);  // ~250 KB
    const auto c = io::parse_footprints_geojson(text, "many.geojson");
    REQUIRE(c.footprints.size() == 2000);
    // The text plus, per 222-byte feature, 5 vertices of 16 bytes, 48 per ring and part and 144 per footprint:
    // 2.45x the text (the document tree of the parser before took about 11x).
    const double ratio = static_cast<double>(c.peak_bytes) / static_cast<double>(text.size());
    INFO("peak " << c.peak_bytes << " bytes for " << text.size() << " bytes of text");
    CHECK(ratio > 1.0);
    CHECK(ratio < 2.6);
    // A budget between the text and the peak: refused part way, naming the budget and the feature reached.
    const std::uint64_t budget = text.size() + (c.peak_bytes - text.size()) / 2;
    const std::string m = refusal(text, {.memory_budget_bytes = budget});
    INFO(m);
    CHECK(m.find("fp.geojson: reading the footprints needs about") != std::string::npos);
    CHECK(m.find("over the memory budget of") != std::string::npos);
    CHECK(m.find("--memory") != std::string::npos);
    CHECK(m.find("feature 0 ") == std::string::npos);  // not at once: after about half the footprints
    CHECK(refusal(text, {.memory_budget_bytes = c.peak_bytes}).empty());
    // One feature of many vertices counts while it is read, not after.
    std::string ring = "[[0,0]";
    for (int i = 1; i < 200000; ++i) ring += ",[" + std::to_string(i % 7) + ",1]";
    ring += ",[0,0]]";
    const std::string one = collection(feature("1", R"({"type":"Polygon","coordinates":[)" + ring + "]}"));
    const std::string m1 = refusal(one, {.memory_budget_bytes = one.size() + 1000000});
    CHECK(m1.find("and 0 vertices kept by feature 0 in its first") != std::string::npos);
}

TEST_CASE("io/footprints: a file larger than the budget is refused before it is read")
{
    const std::string path = "footprints_budget_test.geojson";
    {
        std::ofstream out(path, std::ios::binary);
        out << many_squares(100);
    }
    try {
        io::read_footprints_geojson(path, {.memory_budget_bytes = 1000});
        FAIL("accepted");
    } catch (const invalid_input& e) {
        const std::string m = e.what();
        INFO(m);
        CHECK(m.find(path + ": reading the footprints needs more than the file's") != std::string::npos);
        CHECK(m.find("over the memory budget of 0.000954 MiB") != std::string::npos);
    }
    CHECK(io::read_footprints_geojson(path, {.memory_budget_bytes = 1 << 20}).footprints.size() == 100);
    std::remove(path.c_str());
}
