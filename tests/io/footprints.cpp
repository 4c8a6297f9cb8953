// SPDX-License-Identifier: Apache-2.0
// Building footprints from GeoJSON and (with GDAL) any OGR source: what is read, what is refused and what is
// reported per building; their CRS, reprojection and GeoPackage outputs.
#include <doctest/doctest.h>

#include <lidarfx/core/error.hpp>

#include "io/footprints.hpp"
#include "io/vectors.hpp"
#include "io_test_util.hpp"

#include <cmath>
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

const std::string square_polygon = R"({"type":"Polygon","coordinates":[[[0,0],[0,10],[10,10],[10,0],[0,0]]]})";

}  // namespace

TEST_CASE("io/footprints: polygons and multipolygons with holes are read, rings oriented and closed")
{
    const std::string holed =
        R"({"type":"Polygon","coordinates":[[[20,0],[30,0],[30,10],[20,10]],[[22,2],[28,2],[28,8],[22,8],[22,2]]]})";
    const std::string multi =
        R"({"type":"MultiPolygon","coordinates":[[[[40,0],[45,0],[45,5],[40,5],[40,0]]],[[[50,0],[55,0],[55,5],[50,5],[50,0]]]]})";
    const auto c = io::parse_footprints_geojson(
        collection(feature("1", square_polygon) + "," + feature("7", holed) + "," + feature("3.0", multi)),
        "f.geojson");
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
        collection(feature("5", bowtie) + "," + feature("6", square_polygon) + "," + feature("8", flat)), "f.geojson");
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
    refused(collection(R"({"type":"Feature","properties":{},"geometry":)" + square_polygon + "}"), "building_id");
    refused(collection(R"({"type":"Feature","properties":null,"geometry":)" + square_polygon + "}"), "building_id");
    refused(collection(feature("\"12\"", square_polygon)), "feature 0: building_id \"12\" is not an integer");
    refused(collection(feature("[1]", square_polygon)), "building_id [1] is not an integer");
    refused(collection(feature("2.5", square_polygon)), "not an integer");
    refused(collection(feature("0", square_polygon)), "not an integer");
    refused(collection(feature("4", square_polygon) + "," + feature("4", square_polygon)), "used by feature 0");
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

// `n` square_polygon footprints with realistic projected coordinates (about 24 bytes of text per vertex).
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
    const std::string m =
        refusal(collection(feature("4", square_polygon) + "," + feature("12", ring_at("1e300", "-1e300"))));
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
    CHECK(refusal(collection(feature("1e999", square_polygon))).find("building_id 1e999 is not an integer") !=
          std::string::npos);
}

TEST_CASE("io/footprints: a UTF-8 byte order mark is skipped; JSON errors give byte and line")
{
    const auto c =
        io::parse_footprints_geojson("\xEF\xBB\xBF" + collection(feature("1", square_polygon)), "bom.geojson");
    CHECK(c.footprints.size() == 1);
    // Only at the start, and only the whole mark.
    CHECK(
        refusal(" \xEF\xBB\xBF" + collection(feature("1", square_polygon))).find("not valid JSON at byte 1 (line 1)") !=
        std::string::npos);
    CHECK(refusal("\xEF\xBB" + collection(feature("1", square_polygon))).find("not valid JSON at byte 0") !=
          std::string::npos);
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

TEST_CASE("io/footprints: a GeoJSON crs member is kept as written; --id-field reads another property")
{
    const std::string named = R"({"type":"FeatureCollection","crs":{"type":"name","properties":{"name":)"
                              R"("urn:ogc:def:crs:EPSG::32613"}},"features":[)" +
                              feature("4", square_polygon) + "]}";
    const auto c = io::parse_footprints_geojson(named, "f.geojson");
    CHECK(c.crs == "urn:ogc:def:crs:EPSG::32613");
    CHECK(io::parse_footprints_geojson(collection(feature("4", square_polygon)), "f.geojson").crs.empty());
    const std::string other =
        collection(R"({"type":"Feature","properties":{"objid":12},"geometry":)" + square_polygon + "}");
    const auto by_field = io::parse_footprints_geojson(other, "f.geojson", {.id_field = "objid"});
    REQUIRE(by_field.footprints.size() == 1);
    CHECK(by_field.footprints[0].building_id == 12);
    try {
        io::parse_footprints_geojson(other, "f.geojson");
        FAIL("accepted");
    } catch (const invalid_input& e) {
        CHECK(std::string(e.what()).find("no integer \"building_id\" property") != std::string::npos);
    }
    CHECK(io::same_crs("urn:ogc:def:crs:EPSG::32613", "EPSG:32613"));
    CHECK(!io::same_crs("urn:ogc:def:crs:EPSG::32613", "EPSG:32612"));
}

TEST_CASE("io/footprints: files other than GeoJSON go through OGR, or are refused saying how to get it")
{
    CHECK(io::is_geojson_name("a/B.GeoJSON"));
    CHECK(io::is_geojson_name("b.json"));
    CHECK(!io::is_geojson_name("b.gpkg"));
    if (io::vectors_available()) return;  // the GDAL cases follow
    try {
        io::read_footprints("roofs.gpkg");
        FAIL("accepted");
    } catch (const std::runtime_error& e) {
        CHECK(std::string(e.what()).find("apt-get install libgdal-dev") != std::string::npos);
    }
}

namespace {

// Footprints 7 (a square_polygon with a hole) and 9 (two squares) near (500000, 4400000) as polygons to write, with
// building_id and objid = building_id + 100.
std::vector<io::geojson_feature> utm_features(bool with_building_id)
{
    const double x = 500000, y = 4400000;
    std::vector<io::geojson_feature> f(3);
    f[0].rings = {{{x, y}, {x + 20, y}, {x + 20, y + 12}, {x, y + 12}},
                  {{x + 5, y + 3}, {x + 5, y + 6}, {x + 8, y + 6}, {x + 8, y + 3}}};
    f[1].rings = {{{x + 40, y}, {x + 50, y}, {x + 50, y + 10}, {x + 40, y + 10}}};
    f[2].rings = {{{x + 60, y}, {x + 65, y}, {x + 65, y + 5}, {x + 60, y + 5}}};
    const int ids[] = {7, 9, 11};
    for (int i = 0; i < 3; ++i) {
        if (with_building_id) f[static_cast<std::size_t>(i)].properties.emplace_back("building_id", ids[i]);
        f[static_cast<std::size_t>(i)].properties.emplace_back("objid", ids[i] + 100);
    }
    return f;
}

double area_of(const io::footprint& fp)
{
    double a = 0;
    for (const auto& part : fp.parts)
        for (const auto& ring : part.rings)
            for (std::size_t i = 0; i + 1 < ring.size(); ++i)
                a += 0.5 * (ring[i][0] * ring[i + 1][1] - ring[i + 1][0] * ring[i][1]);
    return a;
}

}  // namespace

TEST_CASE("io/vectors: a GeoPackage gives its footprints, its CRS and ids from building_id, --id-field or the FID")
{
    if (!io::vectors_available()) return;
    io_test::temp_dir dir;
    const std::string path = dir.file("fp.gpkg");
    io::write_geopackage(path, "footprints", utm_features(true), "", 32613);
    const auto c = io::read_footprints(path);
    REQUIRE(c.footprints.size() == 3);
    CHECK(c.problems.empty());
    CHECK(c.notes.empty());
    CHECK(io::epsg_of_crs(c.crs) == 32613);
    CHECK(c.footprints[0].building_id == 7);
    CHECK(c.footprints[0].parts[0].rings.size() == 2);
    CHECK(area_of(c.footprints[0]) == doctest::Approx(240.0 - 9.0));  // oriented: outer ccw, hole cw
    CHECK(c.footprints[2].feature == 2);
    CHECK(c.peak_bytes > 0);

    const auto by_field = io::read_footprints(path, {.id_field = "objid"});
    CHECK(by_field.footprints[1].building_id == 109);
    try {
        io::read_footprints(path, {.id_field = "parcel"});
        FAIL("accepted");
    } catch (const invalid_input& e) {
        const std::string m = e.what();
        CHECK(m.find("no field \"parcel\"") != std::string::npos);
        CHECK(m.find("building_id, objid") != std::string::npos);
    }
    // Without building_id: the FIDs (GeoPackage numbers from 1), said in a note.
    const std::string bare = dir.file("bare.gpkg");
    io::write_geopackage(bare, "footprints", utm_features(false), "", 0);
    const auto by_fid = io::read_footprints(bare);
    REQUIRE(by_fid.footprints.size() == 3);
    CHECK(by_fid.footprints[2].building_id == 3);
    REQUIRE(by_fid.notes.size() == 1);
    CHECK(by_fid.notes[0].find("feature ids (FID)") != std::string::npos);
    CHECK(by_fid.crs.empty());  // written without a CRS: GeoPackage's undefined cartesian SRS

    // The memory budget counts the footprints as they are read.
    try {
        io::read_footprints(path, {.memory_budget_bytes = 600});
        FAIL("accepted");
    } catch (const invalid_input& e) {
        CHECK(std::string(e.what()).find("over the memory budget of") != std::string::npos);
    }
}

TEST_CASE("io/vectors: footprints reprojected to WGS 84 put x = longitude; back in UTM they land within 1 mm")
{
    if (!io::vectors_available()) return;
    io_test::temp_dir dir;
    const std::string path = dir.file("fp.gpkg");
    io::write_geopackage(path, "footprints", utm_features(true), "", 32613);
    const auto utm = io::read_footprints(path);
    auto c = utm;
    io::reproject_footprints(c, c.crs, "EPSG:4326", "fp.gpkg");
    REQUIRE(c.footprints.size() == 3);
    // x = 500000 is zone 13's central meridian, 105 W; y = 4.4e6 m is about 39.75 N.
    const auto corner = c.footprints[0].parts[0].rings[0][0];
    CHECK(corner[0] == doctest::Approx(-105.0).epsilon(1e-9));
    CHECK(corner[1] > 39.7);
    CHECK(corner[1] < 39.8);
    io::reproject_footprints(c, "EPSG:4326", utm.crs, "fp.gpkg");
    for (std::size_t f = 0; f < 3; ++f) {
        const auto& a = utm.footprints[f].parts[0].rings[0];
        const auto& b = c.footprints[f].parts[0].rings[0];
        REQUIRE(a.size() == b.size());
        for (std::size_t i = 0; i < a.size(); ++i) {
            CHECK(std::abs(a[i][0] - b[i][0]) < 1e-3);
            CHECK(std::abs(a[i][1] - b[i][1]) < 1e-3);
        }
    }
    // In the neighbouring zone (central meridian 111 W, 6 degrees away) the same buildings, their areas larger by
    // the squared scale factor there: (1 + (6 deg * cos 39.75 deg)^2 / 2)^2 = 1.0065.
    auto west = utm;
    io::reproject_footprints(west, utm.crs, "EPSG:32612", "fp.gpkg");
    for (std::size_t f = 0; f < 3; ++f) {
        CHECK(west.footprints[f].building_id == utm.footprints[f].building_id);
        CHECK(area_of(west.footprints[f]) / area_of(utm.footprints[f]) == doctest::Approx(1.0065).epsilon(3e-4));
        CHECK(std::abs(west.footprints[f].parts[0].rings[0][0][0] - 500000.0) > 200000.0);  // moved
    }
    // A survey with a vertical CRS too (UTM 13N + NAVD88 height): the footprints are placed by its horizontal CRS.
    auto compound = utm;
    io::reproject_footprints(compound, utm.crs, "EPSG:32613+5703", "fp.gpkg");
    CHECK(std::abs(compound.footprints[0].parts[0].rings[0][0][0] - utm.footprints[0].parts[0].rings[0][0][0]) < 1e-6);
    CHECK(std::abs(compound.footprints[0].parts[0].rings[0][0][1] - utm.footprints[0].parts[0].rings[0][0][1]) < 1e-6);
    try {
        io::reproject_footprints(c, "not a CRS", "EPSG:4326", "fp.gpkg");
        FAIL("accepted");
    } catch (const invalid_input& e) {
        CHECK(std::string(e.what()).find("fp.gpkg: the footprints' CRS is not one OGR understands") !=
              std::string::npos);
    }
}

TEST_CASE("io/vectors: GeoPackage outputs keep fields, types and the CRS; a WKT-only CRS is identified")
{
    if (!io::vectors_available()) return;
    io_test::temp_dir dir;
    std::vector<io::geojson_feature> f = utm_features(true);
    f[0].properties.emplace_back("kwp", 3.25);
    f[0].properties.emplace_back("suitable", true);
    f[0].properties.emplace_back("reason", "flat");
    f[1].properties.emplace_back("kwp", std::nan(""));
    const std::string path = dir.file("out.gpkg");
    const std::string utm13 =
        R"(PROJCS["WGS_1984_UTM_Zone_13N",GEOGCS["GCS_WGS_1984",DATUM["D_WGS_1984",SPHEROID["WGS_1984",6378137.0,)"
        R"(298.257223563]],PRIMEM["Greenwich",0.0],UNIT["Degree",0.0174532925199433]],)"
        R"(PROJECTION["Transverse_Mercator"],PARAMETER["False_Easting",500000.0],PARAMETER["False_Northing",0.0],)"
        R"(PARAMETER["Central_Meridian",-105.0],PARAMETER["Scale_Factor",0.9996],PARAMETER["Latitude_Of_Origin",0.0],)"
        R"(UNIT["Meter",1.0]])";
    CHECK(io::epsg_of_crs(utm13) == 32613);  // an ESRI WKT without authority codes
    io::write_geopackage(path, "roof_patches", f, utm13, 0);
    const auto back = io::read_footprints(path);
    REQUIRE(back.footprints.size() == 3);
    CHECK(io::epsg_of_crs(back.crs) == 32613);
    CHECK(io::same_crs(back.crs, "EPSG:32613"));
    CHECK(area_of(back.footprints[1]) == doctest::Approx(100.0));
    try {
        io::write_geopackage(dir.file("bad.gpkg"), "x", {io::geojson_feature{}}, "", 0);
        FAIL("accepted");
    } catch (const invalid_input& e) {
        CHECK(std::string(e.what()).find("feature 0 has no ring") != std::string::npos);
    }
}
