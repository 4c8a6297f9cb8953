// SPDX-License-Identifier: Apache-2.0
// Building footprints from GeoJSON: what is read, what is refused and what is reported per building.
#include <doctest/doctest.h>

#include <lidarfx/core/error.hpp>

#include "io/footprints.hpp"

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
    for (std::size_t i = 0; i + 1 < outer.size(); ++i) area2 += outer[i][0] * outer[i + 1][1] - outer[i + 1][0] * outer[i][1];
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
    refused(collection(feature("\"12\"", square)), "building_id");
    refused(collection(feature("2.5", square)), "not an integer");
    refused(collection(feature("0", square)), "not an integer");
    refused(collection(feature("4", square) + "," + feature("4", square)), "used by feature 0");
    refused(collection(feature("4", "null")), "no Polygon");
    refused(collection(feature("4", R"({"type":"Point","coordinates":[1,2]})")), "Point");
    refused(collection(feature("4", R"({"type":"Polygon","coordinates":[[[0,0],[1,1],[0,0]]]})")), "4 positions");
    refused(collection(feature("4", R"({"type":"Polygon","coordinates":[[[0,0],[1,"a"],[1,0],[0,0]]]})")), "numbers");
    refused(R"({"type":"Feature"})", "FeatureCollection");
    refused(R"({"type":"FeatureCollection"})", "features");
    refused(R"({"type":"FeatureCollection","features":[)", "not valid JSON");
    refused("[1, 2] trailing", "not valid JSON");
    CHECK(io::parse_footprints_geojson(collection(""), "e").footprints.empty());
}
