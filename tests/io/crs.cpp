// SPDX-License-Identifier: Apache-2.0
// The CRS and units of LAS files (examples/io/crs) and the program in metres (read_survey, outputs), on files
// generated here: EPSG codes in metres and feet, unit overrides, user-defined projections, WKT records.
#include <doctest/doctest.h>

#include "cli/cli_common.hpp"
#include "cli/outputs.hpp"
#include "io/ascii_grid.hpp"
#include "io/crs.hpp"
#include "io/geotiff.hpp"
#include "io/las_writer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <lidarfx/pipelines/water/extract_waterbodies.hpp>
#include <lidarfx/synth/scenes.hpp>

#ifdef LIDARFX_HAVE_GDAL
#include <ogr_srs_api.h>
#endif

#include "io_test_util.hpp"

using namespace lidarfx;
using namespace lidarfx::io;
using io_test::contains;
using io_test::error_of;

namespace {

/// n x n points `step` apart from (x0, y0), z rising gently: coordinates in whatever unit the file declares.
las_points square(int n, double x0, double y0, double step = 1.0)
{
    las_points p;
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            p.x.push_back(x0 + j * step);
            p.y.push_back(y0 + i * step);
            p.z.push_back(100.0 + 0.01 * i * j);
        }
    }
    return p;
}

/// The CRS of a file written with `o` (read back through the LAS reader, as the program reads it).
survey_crs crs_written(const las_write_options& o, bool use_gdal = true)
{
    const auto bytes = encode_las(square(2, 1000.0, 1000.0), o);
    return crs_of(las_reader(std::vector<std::uint8_t>(bytes), "test.las").header(), use_gdal);
}

las_geo_key key(std::uint16_t id, std::uint16_t value)
{
    return {id, 0, 1, value};
}
las_geo_key key_at(std::uint16_t id, std::uint16_t tag, std::uint16_t count, std::uint16_t index)
{
    return {id, tag, count, index};
}

bool any_warning(const survey_crs& c, const std::string& part)
{
    for (const auto& w : c.warnings)
        if (contains(w, part)) return true;
    return false;
}

cli::survey_options quiet(double cell_m)
{
    cli::survey_options o;
    o.cell_m = cell_m;
    o.show_progress = false;
    return o;
}

/// GeoKeys of Autzen's CRS given by parameters, as the survey gives them: Lambert conformal conic on
/// NAD83(HARN) in international feet (no EPSG code for the projection).
las_write_options user_defined_lambert_in_feet()
{
    las_write_options o;
    o.geo_keys = {key(1024, 1),
                  key(1025, 1),
                  key_at(1026, 34737, 38, 0),
                  key(2048, 32767),
                  key_at(2049, 34737, 60, 38),
                  key(2050, 6152),
                  key(2054, 9102),
                  key_at(2057, 34736, 1, 7),
                  key_at(2059, 34736, 1, 6),
                  key_at(2061, 34736, 1, 8),
                  key(3059, 1),
                  key(3072, 32767),
                  key(3074, 32767),
                  key(3075, 8),
                  key(3076, 9002),
                  key_at(3078, 34736, 1, 2),
                  key_at(3079, 34736, 1, 3),
                  key_at(3084, 34736, 1, 1),
                  key_at(3085, 34736, 1, 0),
                  key_at(3086, 34736, 1, 4),
                  key_at(3087, 34736, 1, 5)};
    o.geo_doubles = {41.75, -120.5, 43.0, 45.5, 1312335.958005249, 0.0, 298.257222101, 6378137.0, 0.0};
    o.geo_ascii = "NAD_1983_HARN_Lambert_Conformal_Conic|GCS Name = GCS_North_American_1983_HARN|Primem = Greenwich||";
    return o;
}

// A projected CRS in US survey feet as OGC WKT 1 (NAD83 / Texas Central (ftUS), written out by hand).
const std::string texas_ftus_wkt =
    R"w(PROJCS["NAD83 / Texas Central (ftUS)",GEOGCS["NAD83",DATUM["North_American_Datum_1983",)w"
    R"w(SPHEROID["GRS 1980",6378137,298.257222101]],PRIMEM["Greenwich",0],UNIT["degree",0.0174532925199433]],)w"
    R"w(PROJECTION["Lambert_Conformal_Conic_2SP"],PARAMETER["latitude_of_origin",29.6666666666667],)w"
    R"w(PARAMETER["central_meridian",-100.333333333333],PARAMETER["standard_parallel_1",31.8833333333333],)w"
    R"w(PARAMETER["standard_parallel_2",30.1166666666667],PARAMETER["false_easting",2296583.333],)w"
    R"w(PARAMETER["false_northing",9842500],UNIT["US survey foot",0.304800609601219],AXIS["Easting",EAST],)w"
    R"w(AXIS["Northing",NORTH],AUTHORITY["EPSG","2277"]])w";

// The same horizontally in metres (UTM 14N), with heights in US survey feet: a compound WKT.
const std::string compound_wkt =
    R"w(COMPD_CS["WGS 84 / UTM zone 14N + NAVD88 height (ftUS)",PROJCS["WGS 84 / UTM zone 14N",GEOGCS["WGS 84",)w"
    R"w(DATUM["WGS_1984",SPHEROID["WGS 84",6378137,298.257223563]],PRIMEM["Greenwich",0],)w"
    R"w(UNIT["degree",0.0174532925199433]],PROJECTION["Transverse_Mercator"],PARAMETER["latitude_of_origin",0],)w"
    R"w(PARAMETER["central_meridian",-99],PARAMETER["scale_factor",0.9996],PARAMETER["false_easting",500000],)w"
    R"w(PARAMETER["false_northing",0],UNIT["metre",1],AXIS["Easting",EAST],AXIS["Northing",NORTH],)w"
    R"w(AUTHORITY["EPSG","32614"]],VERT_CS["NAVD88 height (ftUS)",VERT_DATUM["North American Vertical Datum 1988",)w"
    R"w(2005],UNIT["US survey foot",0.304800609601219],AXIS["Gravity-related height",UP]]])w";

#ifdef LIDARFX_HAVE_GDAL
/// Metres per linear unit of a CRS given as WKT, read back by OGR (0 when it cannot be read).
double ogr_linear_unit(const std::string& wkt)
{
    OGRSpatialReferenceH s = OSRNewSpatialReference(nullptr);
    const double m = OSRSetFromUserInput(s, wkt.c_str()) == OGRERR_NONE ? OSRGetLinearUnits(s, nullptr) : 0.0;
    OSRDestroySpatialReference(s);
    return m;
}
#endif

}  // namespace

TEST_CASE("io/crs_of: an EPSG code in metres; no CRS at all is metres with a warning")
{
    for (const bool gdal : {true, false}) {
        CAPTURE(gdal);
        const auto c = crs_written({.epsg_projected = 32633}, gdal);
        CHECK(c.source == "GeoKeys");
        CHECK(c.epsg == 32633);
        CHECK(!c.geographic);
        CHECK(c.horizontal_unit_m == 1.0);
        CHECK(c.vertical_unit_m == 1.0);
        CHECK(c.for_outputs() == (gdal && crs_gdal_available() ? c.wkt : "EPSG:32633"));
        if (gdal && crs_gdal_available()) {
            CHECK(contains(c.wkt, "UTM zone 33N"));
            CHECK(c.warnings.empty());
        }
        const auto none = crs_written({}, gdal);
        CHECK(none.source.empty());
        CHECK(none.for_outputs().empty());
        CHECK(none.horizontal_unit_m == 1.0);
        CHECK(any_warning(none, "names no coordinate system"));
    }
}

TEST_CASE(
    "io/crs_of: EPSG codes whose unit is the foot or the US survey foot (with GDAL); without GDAL the "
    "unit keys alone count")
{
    if (crs_gdal_available()) {
        // No ProjLinearUnitsGeoKey: the unit comes from the code; z takes the unit of x and y.
        const auto ft = crs_written({.geo_keys = {key(1024, 1), key(3072, 2994)}});
        CHECK(ft.epsg == 2994);
        CHECK(ft.horizontal_unit_m == international_foot_m);
        CHECK(ft.horizontal_unit == "foot");
        CHECK(ft.vertical_unit_m == international_foot_m);
        const auto us = crs_written({.geo_keys = {key(1024, 1), key(3072, 2286)}});
        CHECK(us.epsg == 2286);
        CHECK(us.horizontal_unit_m == doctest::Approx(us_survey_foot_m).epsilon(1e-14));  // GDAL prints 15 digits
        CHECK(us.horizontal_unit == "US survey foot");
        const auto mi = crs_written({.geo_keys = {key(1024, 1), key(3072, 6494), key(3076, 9002)}});
        CHECK(mi.horizontal_unit_m == international_foot_m);
    }
    // Without GDAL the code's unit is unknown: metres, said in a warning; an explicit unit key is honoured.
    const auto unknown = crs_written({.geo_keys = {key(1024, 1), key(3072, 2994)}}, false);
    CHECK(unknown.epsg == 2994);
    CHECK(unknown.horizontal_unit_m == 1.0);
    CHECK(any_warning(unknown, "not known without GDAL; metres are assumed"));
    const auto keyed =
        crs_written({.geo_keys = {key(1024, 1), key(3072, 2994), key(3076, 9002), key(4099, 9003)}}, false);
    CHECK(keyed.horizontal_unit_m == international_foot_m);
    CHECK(keyed.vertical_unit_m == us_survey_foot_m);
    CHECK(keyed.vertical_unit == "US survey foot");
}

TEST_CASE(
    "io/crs_of: ProjLinearUnitsGeoKey overrides the unit of EPSG 26995 (US survey feet), and the CRS "
    "carried says so")
{
    const las_write_options o{.geo_keys = {key(1024, 1), key(3072, 26995), key(3076, 9003)}};
    for (const bool gdal : {true, false}) {
        CAPTURE(gdal);
        const auto c = crs_written(o, gdal);
        CHECK(c.horizontal_unit_m == us_survey_foot_m);
        CHECK(c.vertical_unit_m == us_survey_foot_m);
    }
    if (!crs_gdal_available()) return;
    const auto c = crs_written(o);
    CHECK(c.epsg != 26995);  // 26995 names the CRS in metres: GeoJSON must not claim it
    CHECK(any_warning(c, "no EPSG code names its CRS exactly"));
#ifdef LIDARFX_HAVE_GDAL
    CHECK(ogr_linear_unit(c.wkt) == doctest::Approx(us_survey_foot_m).epsilon(1e-14));
    CHECK(contains(c.wkt, "Mississippi West"));
    CHECK(contains(c.wkt, "2296583.333"));  // false easting 700 km in US survey feet
#endif
}

TEST_CASE(
    "io/crs_of: a projection defined by parameters (GeoKeys with doubles and text) gives a CRS through "
    "GDAL, and a warning without it")
{
    const auto o = user_defined_lambert_in_feet();
    if (crs_gdal_available()) {
        const auto c = crs_written(o);
        CHECK(c.source == "GeoKeys");
        CHECK(contains(c.wkt, "Lambert_Conformal_Conic"));
        CHECK(contains(c.wkt, "1312335.958"));
        CHECK(c.horizontal_unit_m == international_foot_m);
        CHECK(c.vertical_unit_m == international_foot_m);
        CHECK(c.epsg == 0);  // EPSG:2994 is close (70 % for GDAL) but not the same CRS
    }
    const auto alone = crs_written(o, false);
    CHECK(alone.for_outputs().empty());
    CHECK(alone.horizontal_unit_m == international_foot_m);  // the unit key still holds
    CHECK(any_warning(alone, "by parameters, which needs GDAL"));
}

TEST_CASE("io/crs_of: WKT records give the units, horizontal and vertical (compound), with or without GDAL")
{
    for (const bool gdal : {true, false}) {
        CAPTURE(gdal);
        const auto ft = crs_written({.version_minor = 4, .point_format = 6, .wkt = texas_ftus_wkt}, gdal);
        CHECK(ft.source == "WKT");
        CHECK(ft.epsg == 2277);
        CHECK(ft.horizontal_unit_m == doctest::Approx(us_survey_foot_m).epsilon(1e-14));
        CHECK(ft.vertical_unit_m == ft.horizontal_unit_m);
        const auto compound = crs_written({.wkt = compound_wkt}, gdal);
        CHECK(compound.epsg == 32614);
        CHECK(compound.horizontal_unit_m == 1.0);
        CHECK(compound.vertical_unit_m == doctest::Approx(us_survey_foot_m).epsilon(1e-14));
        CHECK(!contains(compound.wkt, "VERT_CS") == (gdal && crs_gdal_available()));  // outputs: horizontal only
        const auto degrees = crs_written({.wkt = R"w(GEOGCS["WGS 84",DATUM["WGS_1984",SPHEROID["WGS 84",6378137,)w"
                                                 R"w(298.257223563]],PRIMEM["Greenwich",0],UNIT["degree",)w"
                                                 R"w(0.0174532925199433],AUTHORITY["EPSG","4326"]])w"},
                                         gdal);
        CHECK(degrees.geographic);
        CHECK(degrees.epsg == 4326);
    }
}

TEST_CASE("io/crs_of: an empty or unreadable WKT record is ignored with a warning; the GeoKeys' EPSG code stays")
{
    for (const bool gdal : {true, false}) {
        CAPTURE(gdal);
        const auto empty = crs_written({.epsg_projected = 32633, .empty_wkt_record = true}, gdal);
        CHECK(empty.epsg == 32633);
        CHECK(any_warning(empty, "WKT record is empty; it is ignored"));
        // A LAS 1.4 file that says its CRS is WKT, with nonsense there: the GeoKeys are used instead.
        const auto odd = crs_written(
            {.version_minor = 4, .point_format = 6, .epsg_projected = 32633, .wkt = "NOT A COORDINATE SYSTEM["}, gdal);
        CHECK(odd.source == "GeoKeys");
        CHECK(odd.epsg == 32633);
        CHECK(any_warning(odd, "WKT record is unreadable"));
    }
}

TEST_CASE("io/crs_of: geographic CRSs are degrees, by EPSG code or model type, with or without GDAL")
{
    for (const bool gdal : {true, false}) {
        CAPTURE(gdal);
        for (const int code : {4326, 4269, 4047}) {
            const auto c = crs_written({.epsg_geographic = code}, gdal);
            CHECK(c.geographic);
            CHECK(c.epsg == code);
            CHECK(c.horizontal_unit == "degree");
            CHECK(c.vertical_unit_m == 1.0);
        }
    }
}

TEST_CASE("io/read_survey: a survey in feet is read in metres and written back in its CRS's units")
{
    io_test::temp_dir dir;
    const double ft = us_survey_foot_m;
    // 100 x 100 points 1 ft apart, 26995 overridden to US survey feet (as mvk-thin.las from PDAL's tests).
    const auto feet = dir.file("feet.las");
    write_las(feet, square(100, 2296583.0, 1000000.0), {.geo_keys = {key(1024, 1), key(3072, 26995), key(3076, 9003)}});
    const auto s = cli::read_survey({feet}, quiet(2.0));
    CHECK(s.crs.horizontal_unit_m == ft);
    CHECK(s.rasters.g.cell == 2.0);  // --cell is metres
    // The grid covers the points in metres: 99 ft = 30.2 m wide, 16 or 17 cells of 2 m (50 if read as metres).
    CHECK(s.rasters.g.cols <= 17);
    CHECK(s.rasters.g.x0 <= 2296583.0 * ft);
    CHECK(s.rasters.g.x1() >= 2296682.0 * ft);
    // Heights in metres: 100 ft and up.
    float lowest = INFINITY;
    for (const float z : s.rasters.min_z)
        if (std::isfinite(z)) lowest = std::min(lowest, z);
    CHECK(lowest == doctest::Approx(100.0 * ft).epsilon(1e-6));
    // Outputs are in the CRS's units: origin and cell size divided by the unit, and so are the heights.
    const grid out = cli::to_crs_units(s.rasters.g, s);
    CHECK(out.cell == doctest::Approx(2.0 / ft).epsilon(1e-12));
    CHECK(out.x0 == doctest::Approx(s.rasters.g.x0 / ft).epsilon(1e-12));
    io::output_folder folder(dir.file("out"));
    cli::write_point_rasters(folder, s);
    folder.commit("test");
    grid asc_grid;
    const auto min_z = read_ascii_grid(dir.file("out/min_z.asc"), asc_grid);
    CHECK(asc_grid.cell == doctest::Approx(2.0 / ft).epsilon(1e-9));
    CHECK(asc_grid.x0 == doctest::Approx(out.x0).epsilon(1e-12));
    REQUIRE(min_z.rows() == s.rasters.min_z.rows());
    REQUIRE(min_z.cols() == s.rasters.min_z.cols());
    std::size_t off = 0, finite = 0;
    for (std::ptrdiff_t r = 0; r < min_z.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < min_z.cols(); ++c) {
            const float metres = s.rasters.min_z(r, c);
            if (std::isnan(metres) != std::isnan(min_z(r, c))) ++off;
            if (std::isnan(metres)) continue;
            ++finite;
            if (std::abs(min_z(r, c) * ft - metres) > 1e-5 * std::abs(metres)) ++off;  // feet in the file
        }
    }
    CHECK(finite > 0);
    CHECK(off == 0);
    if (geotiff_available()) {
        const auto tif = read_geotiff(dir.file("out/min_z.tif"));
        CHECK(tif.g.cell == doctest::Approx(2.0 / ft).epsilon(1e-9));
        CHECK(tif.g.y0 == doctest::Approx(out.y0).epsilon(1e-12));
#ifdef LIDARFX_HAVE_GDAL
        // Read back by GDAL: the GeoTIFF's CRS is in US survey feet (not EPSG 26995's metres).
        CHECK(ogr_linear_unit(tif.crs_wkt) == doctest::Approx(ft).epsilon(1e-14));
        CHECK(contains(tif.crs_wkt, "Mississippi West"));
#endif
    }
}

TEST_CASE(
    "io/read_survey: degrees are refused (exit code 2) suggesting a reprojection; files in different "
    "units are refused; an empty WKT record is not")
{
    io_test::temp_dir dir;
    const auto degrees = dir.file("degrees.las");
    write_las(degrees, square(10, -122.5, 45.0, 1e-5),
              {.scale = {1e-7, 1e-7, 0.01}, .offset = std::array<double, 3>{0.0, 0.0, 0.0}, .epsg_geographic = 4326});
    try {
        cli::read_survey({degrees}, quiet(2.0));
        FAIL("a survey in degrees was read");
    } catch (const cli::usage_error& e) {  // main() turns it into exit code 2
        const std::string why = e.what();
        CHECK(contains(why, degrees + ": x and y are longitude and latitude in degrees"));
        CHECK(contains(why, "Reproject"));
        CHECK(contains(why, "filters.reprojection"));
    }
    const auto metres = dir.file("metres.las"), feet = dir.file("feet.las");
    write_las(metres, square(20, 500000.0, 4000000.0), {.epsg_projected = 32633});
    write_las(feet, square(20, 1640420.0, 13123360.0), {.geo_keys = {key(1024, 1), key(3072, 32633), key(3076, 9002)}});
    const auto mixed = error_of([&] { cli::read_survey({metres, feet}, quiet(2.0)); });
    CHECK(contains(mixed, feet + " is in"));
    CHECK(contains(mixed, "reproject the files to one CRS first"));
    const auto careless = dir.file("careless.las");
    write_las(careless, square(20, 500000.0, 4000000.0), {.epsg_projected = 32633, .empty_wkt_record = true});
    const auto s = cli::read_survey({careless}, quiet(2.0));
    CHECK(s.epsg == 32633);
    CHECK(s.rasters.points_used == 400);
}

TEST_CASE("io/water: a scene written in feet gives the areas and levels of the scene in metres")
{
    // The synthetic lake scene once in metres and once in international feet (x, y and z divided by 0.3048,
    // millimetre and milli-foot quanta): the waterbodies must agree in m2 and m.
    io_test::temp_dir dir;
    const auto scene = synth::lake_scene({.seed = 3, .size_m = 400});
    const las_points m = las_points_from(scene.points);
    las_points f = m;
    for (auto* v : {&f.x, &f.y, &f.z})
        for (double& value : *v) value /= international_foot_m;
    const auto in_metres = dir.file("lake_m.las"), in_feet = dir.file("lake_ft.las");
    write_las(in_metres, m, {.scale = {0.001, 0.001, 0.001}, .epsg_projected = 32633});
    write_las(in_feet, f,
              {.scale = {0.001, 0.001, 0.001},
               .geo_keys = {key(1024, 1), key(3072, 32633), key(3076, 9002), key(4099, 9002)}});
    const auto sm = cli::read_survey({in_metres}, quiet(2.0)), sf = cli::read_survey({in_feet}, quiet(2.0));
    CHECK(sf.crs.horizontal_unit_m == international_foot_m);
    CHECK(sf.rasters.g.rows == sm.rasters.g.rows);
    CHECK(sf.rasters.g.cols == sm.rasters.g.cols);
    extract_waterbodies_options opt;
    const auto fm = cli::find_waterbodies(sm, opt), ff = cli::find_waterbodies(sf, opt);
    const auto &wm = fm.result, &wf = ff.result;
    REQUIRE(wm.ran);
    REQUIRE(wf.ran);
    REQUIRE(!wm.bodies.empty());
    REQUIRE(wf.bodies.size() == wm.bodies.size());
    for (std::size_t i = 0; i < wm.bodies.size(); ++i) {
        // Quantization moves a few points across cell edges: 1 % of the area, 1 cm of level.
        CHECK(wf.bodies[i].area_m2 == doctest::Approx(wm.bodies[i].area_m2).epsilon(0.01));
        CHECK(wf.bodies[i].water_level_m == doctest::Approx(wm.bodies[i].water_level_m).epsilon(1e-4));
    }
    // The files written: the CSV in m2 and m, the maps on the feet grid.
    io::output_folder folder(dir.file("out_ft"));
    cli::write_waterbodies(folder, sf, wf, ff.footprint);
    folder.commit("test");
    grid g;
    read_ascii_grid(dir.file("out_ft/water.asc"), g);
    CHECK(g.cell == doctest::Approx(2.0 / international_foot_m).epsilon(1e-9));
    const std::string csv = [&] {
        const auto b = io_test::read_bytes(dir.file("out_ft/waterbodies.csv"));
        return std::string(b.begin(), b.end());
    }();
    CHECK(contains(csv, "area_m2"));
    // The manifest says which values are metres and where the places are.
    const auto manifest = io_test::read_bytes(dir.file("out_ft/manifest.json"));
    const std::string text(manifest.begin(), manifest.end());
    CHECK(contains(text,
                   "\"units\": \"cell values (heights, levels) in metres, areas in m2; grids, bounding boxes and "
                   "polygons in the CRS of the input, "));
    // GDAL names the CRS; without it the description says what the keys give.
    if (geotiff_available()) CHECK(contains(text, "WGS 84 / UTM zone 33N (foot)"));
}

TEST_CASE("io/crs_of: PDAL's test surveys (optional: LIDARFX_PDAL_DATA)")
{
    const char* root = std::getenv("LIDARFX_PDAL_DATA");
    if (root == nullptr) {
        MESSAGE("LIDARFX_PDAL_DATA is not set: PDAL's test surveys are skipped");
        return;
    }
    const auto crs = [&](const std::string& name) -> std::optional<survey_crs> {
        const auto path = std::filesystem::path(root) / "test/data/las" / name;
        if (!std::filesystem::exists(path)) {
            const std::string skipped = path.string() + " is missing: skipped";
            MESSAGE(skipped);
            return std::nullopt;
        }
        return crs_of(las_reader(path.string()).header());
    };
    if (const auto c = crs("autzen_trim.las")) {  // Oregon GIC Lambert on NAD83(HARN), international feet
        CHECK(c->horizontal_unit_m == international_foot_m);
        CHECK(c->vertical_unit_m == international_foot_m);
        if (crs_gdal_available()) CHECK(contains(c->wkt, "Lambert_Conformal_Conic"));
    }
    if (const auto c = crs("mvk-thin.las")) {  // EPSG 26995 with ProjLinearUnitsGeoKey = US survey foot
        CHECK(c->horizontal_unit_m == us_survey_foot_m);
        if (crs_gdal_available()) CHECK(c->epsg != 26995);
    }
    if (const auto c = crs("4_6_crop.las")) {  // EPSG 2903, NAD83(HARN) / New Mexico Central (ftUS)
        CHECK(c->epsg == 2903);
        CHECK(c->horizontal_unit_m == us_survey_foot_m);
        CHECK(c->vertical_unit_m == us_survey_foot_m);
    }
    if (const auto c = crs("epsg_4326.las")) CHECK(c->geographic);
    if (const auto c = crs("test_epsg_4047.las")) CHECK(c->geographic);
    for (const char* name : {"test_utm16.las", "test_utm17.las", "utm15.las", "bad-geotiff-keys.las"}) {
        if (const auto c = crs(name)) {
            CAPTURE(name);
            CHECK(c->horizontal_unit_m == 1.0);
            CHECK(c->epsg != 0);
        }
    }
    if (const auto c = crs("test1_4.las")) {  // LAS 1.4, WKT: New Mexico Central (ftUS)
        CHECK(c->source == "WKT");
        CHECK(c->horizontal_unit_m == doctest::Approx(us_survey_foot_m).epsilon(1e-14));
    }
    if (const auto c = crs("warsaw_small.las")) CHECK(any_warning(*c, "WKT record is empty"));
    if (const auto c = crs("1.2-empty-geotiff-vlrs.las")) {
        CHECK(c->for_outputs().empty());
        CHECK(c->horizontal_unit_m == 1.0);
    }
}

TEST_CASE("io/water: a survey in feet clipped to a circle - water in m2 and m, none outside the footprint")
{
    // The lake scene cut to a circle of 180 m (the tile's corners were never flown), written in international
    // feet with its pulses' GPS times (format 1, acquisition order), as lidarfx water reads a real survey.
    io_test::temp_dir dir;
    const auto scene = synth::lake_scene({.seed = 5, .size_m = 400});
    const double cx = 200.0, cy = 200.0, radius_m = 180.0;
    las_points f;
    const auto& p = scene.points;
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (std::hypot(p.x[i] - cx, p.y[i] - cy) > radius_m) continue;
        f.x.push_back(p.x[i] / international_foot_m);
        f.y.push_back(p.y[i] / international_foot_m);
        f.z.push_back(p.z[i] / international_foot_m);
        f.intensity.push_back(p.intensity[i]);
        f.return_number.push_back(p.return_number[i]);
        f.number_of_returns.push_back(p.number_of_returns[i]);
        f.classification.push_back(p.classification[i]);
        f.gps_time.push_back(p.gps_time[i]);
    }
    const auto path = dir.file("circle_ft.las");
    write_las(path, f,
              {.point_format = 1,
               .scale = {0.001, 0.001, 0.001},
               .geo_keys = {key(1024, 1), key(3072, 32633), key(3076, 9002), key(4099, 9002)}});
    const auto s = cli::read_survey({path}, quiet(2.0));
    REQUIRE(!s.scan_covered.empty());  // the GPS times were read and the scan lines followed
    const auto found = cli::find_waterbodies(s, {});
    REQUIRE(found.result.ran);
    REQUIRE(!found.result.bodies.empty());
    const auto& g = s.rasters.g;  // metres
    std::size_t outside = 0, water_cells = 0;
    for (std::ptrdiff_t r = 0; r < g.rows; ++r)
        for (std::ptrdiff_t c = 0; c < g.cols; ++c) {
            const auto [x, y] = g.center(r, c);
            const bool beyond = std::hypot(x - cx, y - cy) > radius_m + g.cell;
            water_cells += found.result.water(r, c);
            outside += beyond && found.result.water(r, c);
            if (beyond && std::hypot(x - cx, y - cy) > radius_m + 60.0) CHECK(found.footprint(r, c) == 0);
        }
    CHECK(outside == 0);
    // Areas in m2: the bodies' areas add up to the water cells times the cell area in m2 (2 m cells).
    double area = 0;
    for (const auto& b : found.result.bodies) area += b.area_m2;
    CHECK(area == doctest::Approx(4.0 * static_cast<double>(water_cells)));
    // Levels in m: each body's level lies within the range of the scene's water surfaces (metres, not feet).
    float lo = INFINITY, hi = -INFINITY;
    for (const float z : scene.truth.water_z)
        if (std::isfinite(z)) lo = std::min(lo, z), hi = std::max(hi, z);
    for (const auto& b : found.result.bodies) {
        CHECK(b.water_level_m >= lo - 0.5);
        CHECK(b.water_level_m <= hi + 0.5);
    }
}

TEST_CASE("io/esri_prj_text: the CRS of a .prj beside an ESRI ASCII grid, read back in its units")
{
    CHECK(esri_prj_text("").empty());
    CHECK(esri_prj_text("  ").empty());
    if (!crs_gdal_available()) {
        CHECK(esri_prj_text("EPSG:2994").empty());  // without GDAL only WKT passes
        CHECK(esri_prj_text("PROJCS[\"x\"]") == "PROJCS[\"x\"]");
        return;
    }
    CHECK(esri_prj_text("EPSG:not-a-code").empty());
    for (const auto& crs_and_unit : {std::pair<std::string, double>{"EPSG:2994", international_foot_m},
                                     {"32617", metre_m},
                                     {"EPSG:2269", international_foot_m}}) {
        const std::string& crs = crs_and_unit.first;  // a plain reference: Clang 14's CAPTURE cannot take a binding
        const double unit_m = crs_and_unit.second;
        CAPTURE(crs);
        const std::string prj = esri_prj_text(crs);
        CHECK(prj.rfind("PROJCS[", 0) == 0);  // ESRI WKT: WKT1 without AUTHORITY nodes
        CHECK(!contains(prj, "AUTHORITY"));
        const survey_crs back = crs_of_wkt(prj);
        CHECK(back.horizontal_unit_m == doctest::Approx(unit_m).epsilon(1e-12));
        CHECK(back.vertical_unit_m == doctest::Approx(unit_m).epsilon(1e-12));
        CHECK(!back.geographic);
    }
    // A compound CRS keeps its horizontal part (ESRI WKT has no compound form GDAL reads from a .prj).
    const std::string compound_prj = esri_prj_text("EPSG:32613+5703");
    CHECK(!contains(compound_prj, "VERTCS"));
    const survey_crs compound = crs_of_wkt(compound_prj);
    CHECK(compound.horizontal_unit_m == doctest::Approx(1.0));
    CHECK(!compound.source.empty());
}

TEST_CASE("io/crs_of: a vertical CRS in the unit of x and y travels to the outputs (GeoTIFF, GeoPackage), not the .prj")
{
    if (!crs_gdal_available()) return;
    // UTM 14N + NAVD88 height in metres, as a compound WKT record and as GeoKeys (VerticalCSTypeGeoKey 5703).
    std::string metres_wkt = compound_wkt;
    for (const auto& [from, to] : {std::pair<std::string, std::string>{"NAVD88 height (ftUS)", "NAVD88 height"},
                                   {R"(UNIT["US survey foot",0.304800609601219])", R"(UNIT["metre",1])"}}) {
        const auto at = metres_wkt.find(from);
        REQUIRE(at != std::string::npos);
        metres_wkt.replace(at, from.size(), to);
    }
    const auto from_wkt = crs_written({.wkt = metres_wkt});
    const auto from_keys = crs_written({.geo_keys = {key(1024, 1), key(3072, 32614), key(4096, 5703)}});
    for (const survey_crs* c : {&from_wkt, &from_keys}) {
        CHECK(c->epsg == 32614);
        CHECK(c->vertical_unit_m == 1.0);
        CHECK(contains(c->wkt, "VERT_CS"));
        CHECK(contains(c->wkt, "32614"));
        CHECK(!contains(esri_prj_text(c->wkt), "VERTCS"));  // the .prj: horizontal only, which GDAL reads
    }
    // Heights in another unit than x and y (2994 in feet + NAVD88 in metres; the compound of the WKT tests
    // above): only the horizontal CRS is carried, as the heights are written in its unit.
    const auto mixed = crs_written({.geo_keys = {key(1024, 1), key(3072, 2994), key(4096, 5703)}});
    CHECK(mixed.horizontal_unit_m == international_foot_m);
    CHECK(mixed.vertical_unit_m == 1.0);
    CHECK(!contains(mixed.wkt, "VERT"));
    CHECK(!contains(crs_written({.wkt = compound_wkt}).wkt, "VERT"));
    // A GeoTIFF written with the compound CRS holds it: GDAL reads the vertical part back.
    if (!geotiff_available()) return;
    io_test::temp_dir tmp;
    const std::string tif = tmp.file("compound.tif");
    raster<float> values(2, 3, 1.5f);
    write_geotiff(tif, values, grid{.x0 = 500000, .y0 = 4000000, .cell = 1, .rows = 2, .cols = 3}, from_keys.wkt);
    const std::string back = read_geotiff(tif).crs_wkt;
    CHECK(contains(back, "NAVD88"));
    CHECK(crs_of_wkt(back).epsg == 32614);
    // A survey with those GeoKeys: max_z.tif names the vertical CRS, max_z.prj the horizontal one, which GDAL
    // reads beside max_z.asc.
    const auto las = tmp.file("navd88.las");
    write_las(las, square(20, 500000.0, 4000000.0), {.geo_keys = {key(1024, 1), key(3072, 32614), key(4096, 5703)}});
    const auto s = cli::read_survey({las}, quiet(2.0));
    io::output_folder folder(tmp.file("out"));
    cli::write_point_rasters(folder, s);
    folder.commit("test");
    CHECK(contains(read_geotiff(tmp.file("out/max_z.tif")).crs_wkt, "NAVD88"));
    const std::string asc_crs = read_geotiff(tmp.file("out/max_z.asc")).crs_wkt;  // GDAL's AAIGrid driver
    CHECK(crs_of_wkt(asc_crs).epsg == 32614);
    CHECK(!contains(asc_crs, "NAVD88"));
}
