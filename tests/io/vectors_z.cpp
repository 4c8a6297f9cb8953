// SPDX-License-Identifier: Apache-2.0
// 3D layers written as GeoPackage (examples/io/vectors_z), read back through OGR: 3D geometry types, exact heights,
// ring orientation, the CRS, typed fields, identical bytes for the same layers, and the refusals.
#include <doctest/doctest.h>

#include <lidarfx/core/error.hpp>

#include "io/vectors.hpp"
#include "io/vectors_z.hpp"
#include "io_test_util.hpp"

#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#ifdef LIDARFX_HAVE_GDAL
#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include "io/gdal_session.hpp"
#endif

using namespace lidarfx;

namespace vectors_z_test {

// A roof polygon layer and a breakline layer; the rings are given against the right-hand rule, the roof's second
// ring open and with a height per vertex.
std::vector<io::layer_z> two_layers()
{
    const double x = 500000, y = 5700000;
    io::layer_z roofs{"roofs", io::geometry_z::polygon, {}};
    io::feature_z holed;
    holed.parts = {{{x, y, 100.25}, {x, y + 10, 100.25}, {x + 10, y + 10, 100.25}, {x + 10, y, 100.25}, {x, y, 100.25}},
                   {{x + 2, y + 2, 100.25}, {x + 4, y + 2, 100.25}, {x + 4, y + 4, 100.25}, {x + 2, y + 4, 100.25}}};
    holed.properties = {{"id", 7}, {"slope_deg", 12.5}, {"kind", "flat"}};
    io::feature_z sloped;
    sloped.parts = {{{x + 20, y, 101.5}, {x + 20, y + 8, 103.75}, {x + 26, y + 8, 103.75}, {x + 26, y, 101.5}}};
    sloped.properties = {{"id", 8}, {"slope_deg", 15.0}, {"kind", "gable"}};
    roofs.features = {holed, sloped};

    io::layer_z lines{"breaklines", io::geometry_z::line, {}};
    io::feature_z ridge;
    ridge.parts = {{{x, y, 98.125}, {x + 5, y + 1, 99.0625}, {x + 9, y + 3, 100.1}},
                   {{x + 1, y + 9, 97.3}, {x + 8, y + 9, 96.999999999}}};
    ridge.properties = {{"id", 1}, {"drop_m", 1.975}, {"kind", "ridge"}};
    lines.features = {ridge};
    return {roofs, lines};
}

#ifdef LIDARFX_HAVE_GDAL
struct dataset_closer {
    void operator()(GDALDataset* ds) const { GDALClose(GDALDataset::ToHandle(ds)); }
};

std::unique_ptr<GDALDataset, dataset_closer> open_vectors(const std::string& path)
{
    io::register_gdal_drivers();
    return std::unique_ptr<GDALDataset, dataset_closer>(GDALDataset::FromHandle(
        GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
}
#endif

}  // namespace vectors_z_test

#ifdef LIDARFX_HAVE_GDAL

TEST_CASE("io/vectors_z: two 3D layers read back through OGR with their heights, orientation, CRS and fields")
{
    io_test::temp_dir dir;
    const std::string path = dir.file("z.gpkg");
    const auto layers = vectors_z_test::two_layers();
    io::write_geopackage_z(path, layers, "", 25832);
    const auto ds = vectors_z_test::open_vectors(path);
    REQUIRE(ds);
    REQUIRE(ds->GetLayerCount() == 2);
    OGRLayer* roofs = ds->GetLayerByName("roofs");
    OGRLayer* lines = ds->GetLayerByName("breaklines");
    REQUIRE(roofs != nullptr);
    REQUIRE(lines != nullptr);
    CHECK(roofs->GetGeomType() == wkbPolygon25D);  // "3D Polygon"
    CHECK(lines->GetGeomType() == wkbMultiLineString25D);
    for (OGRLayer* layer : {roofs, lines}) {
        CHECK(OGR_GT_HasZ(layer->GetGeomType()));
        const OGRSpatialReference* srs = layer->GetSpatialRef();
        REQUIRE(srs != nullptr);
        CHECK(std::string(srs->GetAuthorityName(nullptr)) == "EPSG");
        CHECK(std::string(srs->GetAuthorityCode(nullptr)) == "25832");
        CHECK(layer->GetFeatureCount() == static_cast<GIntBig>(layer == roofs ? 2 : 1));
    }
    CHECK(roofs->GetLayerDefn()->GetFieldDefn(0)->GetType() == OFTInteger64);
    CHECK(roofs->GetLayerDefn()->GetFieldDefn(1)->GetType() == OFTReal);
    CHECK(roofs->GetLayerDefn()->GetFieldDefn(2)->GetType() == OFTString);

    roofs->ResetReading();
    for (std::size_t f = 0; f < 2; ++f) {
        const OGRFeatureUniquePtr feature(roofs->GetNextFeature());
        REQUIRE(feature);
        CHECK(feature->GetFieldAsInteger64("id") == 7 + static_cast<GIntBig>(f));
        CHECK(feature->GetFieldAsDouble("slope_deg") == (f == 0 ? 12.5 : 15.0));
        CHECK(std::string(feature->GetFieldAsString("kind")) == (f == 0 ? "flat" : "gable"));
        const OGRGeometry* g = feature->GetGeometryRef();
        REQUIRE(g != nullptr);
        REQUIRE(g->getGeometryType() == wkbPolygon25D);
        const OGRPolygon* poly = g->toPolygon();
        const auto& in = layers[0].features[f].parts;
        REQUIRE(poly->getNumInteriorRings() == static_cast<int>(in.size()) - 1);
        CHECK_FALSE(poly->getExteriorRing()->isClockwise());  // outer counter-clockwise, holes clockwise
        if (f == 0) CHECK(poly->getInteriorRing(0)->isClockwise());
        // Each vertex keeps its own height (exactly), although the rings were reversed; the first vertex stays first.
        for (std::size_t k = 0; k < in.size(); ++k) {
            const OGRLinearRing* ring =
                k == 0 ? poly->getExteriorRing() : poly->getInteriorRing(static_cast<int>(k) - 1);
            std::map<std::pair<double, double>, double> z_at;
            for (const io::xyz& p : in[k]) z_at[{p[0], p[1]}] = p[2];
            REQUIRE(ring->getNumPoints() == 5);
            CHECK(ring->getX(0) == in[k][0][0]);
            CHECK(ring->getY(0) == in[k][0][1]);
            CHECK(ring->get_IsClosed());
            for (int i = 0; i < ring->getNumPoints(); ++i)
                CHECK(ring->getZ(i) == z_at.at({ring->getX(i), ring->getY(i)}));
        }
    }

    lines->ResetReading();
    const OGRFeatureUniquePtr ridge(lines->GetNextFeature());
    REQUIRE(ridge);
    CHECK(ridge->GetFieldAsInteger64("id") == 1);
    CHECK(ridge->GetFieldAsDouble("drop_m") == 1.975);
    CHECK(std::string(ridge->GetFieldAsString("kind")) == "ridge");
    const OGRGeometry* g = ridge->GetGeometryRef();
    REQUIRE(g != nullptr);
    REQUIRE(g->getGeometryType() == wkbMultiLineString25D);
    const OGRMultiLineString* multi = g->toMultiLineString();
    const auto& in = layers[1].features[0].parts;
    REQUIRE(multi->getNumGeometries() == 2);
    for (int k = 0; k < 2; ++k) {
        const OGRLineString* line = multi->getGeometryRef(k);
        const auto& part = in[static_cast<std::size_t>(k)];
        REQUIRE(line->getNumPoints() == static_cast<int>(part.size()));
        for (int i = 0; i < line->getNumPoints(); ++i) {
            const io::xyz& p = part[static_cast<std::size_t>(i)];
            CHECK(line->getX(i) == p[0]);
            CHECK(line->getY(i) == p[1]);
            CHECK(line->getZ(i) == p[2]);
        }
    }
}

TEST_CASE("io/vectors_z: the same layers give the same bytes; no CRS gives the undefined cartesian SRS")
{
    io_test::temp_dir dir;
    const auto layers = vectors_z_test::two_layers();
    io::write_geopackage_z(dir.file("a.gpkg"), layers, "", 25832);
    io::write_geopackage_z(dir.file("b.gpkg"), layers, "", 25832);
    CHECK(io_test::read_bytes(dir.file("a.gpkg")) == io_test::read_bytes(dir.file("b.gpkg")));

    io::write_geopackage_z(dir.file("bare.gpkg"), layers, "", 0);
    const auto ds = vectors_z_test::open_vectors(dir.file("bare.gpkg"));
    REQUIRE(ds);
    const OGRSpatialReference* srs = ds->GetLayerByName("roofs")->GetSpatialRef();
    CHECK((srs == nullptr || srs->IsLocal()));
}

TEST_CASE("io/vectors_z: non-finite heights, short lines and rings, and differing properties are refused")
{
    io_test::temp_dir dir;
    const std::string path = dir.file("bad.gpkg");
    const auto write = [&](const std::vector<io::layer_z>& layers) {
        return io_test::invalid_input_of([&] { io::write_geopackage_z(path, layers, "", 25832); });
    };
    auto nan_z = vectors_z_test::two_layers();
    nan_z[1].features[0].parts[1][1][2] = std::nan("");
    CHECK(io_test::contains(write(nan_z), "layer 'breaklines': feature 0 part 1 has a non-finite coordinate"));

    auto one_vertex = vectors_z_test::two_layers();
    one_vertex[1].features[0].parts[1].resize(1);
    CHECK(io_test::contains(write(one_vertex), "feature 0 line 1 must have at least 2 distinct positions"));

    auto flat_ring = vectors_z_test::two_layers();
    flat_ring[0].features[1].parts[0] = {{0, 0, 1}, {1, 0, 2}, {0, 0, 3}, {1, 0, 4}};
    CHECK(io_test::contains(write(flat_ring), "layer 'roofs': feature 1 ring 0 must have at least 3 distinct"));

    auto renamed = vectors_z_test::two_layers();
    renamed[0].features[1].properties[1].first = "pitch_deg";
    CHECK(io_test::contains(write(renamed),
                            "feature 1 has the properties (id, pitch_deg, kind), feature 0 (id, "
                            "slope_deg, kind)"));
    auto fewer = vectors_z_test::two_layers();
    fewer[0].features[1].properties.pop_back();
    CHECK(io_test::contains(write(fewer), "the same names in order"));

    auto twice = vectors_z_test::two_layers();
    twice[1].name = "ROOFS";
    CHECK(io_test::contains(write(twice), "layer name 'ROOFS' is empty or used twice"));
    CHECK_FALSE(std::filesystem::exists(path));  // refused before the file exists
}

#else

TEST_CASE("io/vectors_z: without GDAL, writing a GeoPackage says how to get it")
{
    const std::string m =
        io_test::runtime_error_of([] { io::write_geopackage_z("x.gpkg", vectors_z_test::two_layers(), "", 25832); });
    CHECK(io_test::contains(m, "x.gpkg: GeoPackage output needs OGR"));
}

#endif
