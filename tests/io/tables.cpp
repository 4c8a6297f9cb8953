// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include "io/tables.hpp"

#include "cli/cli_common.hpp"
#include "cli/outputs.hpp"
#include "io/crs.hpp"
#include "io/footprints.hpp"
#include "io/las_writer.hpp"
#include "io/output_folder.hpp"
#include "io/vectors.hpp"

#include <lidarfx/core/error.hpp>
#include <lidarfx/pipelines/water/extract_waterbodies.hpp>
#include <lidarfx/synth/scenes.hpp>

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
    const std::vector<csv_column> header{text_column("id"), area_column("area_m2"), text_column("name"),
                                         text_column("ok"), metres_column("note_m")};
    const std::vector<std::vector<table_value>> rows{
        {1, 12.5, "lake, north", true, {}},
        {std::size_t{2}, 0.1, "quote \"q\"", false, NAN},
        {std::int64_t{-9007199254740993}, 1e-300, "", std::numeric_limits<std::uint64_t>::max(), -0.0f}};
    CHECK(to_csv(header, rows) ==
          "id,area_m2,name,ok,note_m\n"
          "1,12.5,\"lake, north\",true,\n"
          "2,0.1,\"quote \"\"q\"\"\",false,\n"
          "-9007199254740993,0.0,,18446744073709551615,0.000\n");
    CHECK_THROWS_WITH_AS(to_csv(header, {{1, 2}}), "to_csv: row 0 has 2 fields, the header 5", invalid_input);
    CHECK_THROWS_WITH_AS(to_csv({}, {}), "to_csv: header must not be empty", invalid_input);
    // A column of ids or text refuses a real number: every real is written by a kind's rounding rule.
    CHECK_THROWS_WITH_AS(to_csv({text_column("cells")}, {{2.5}}),
                         "to_csv: column 'cells' takes no real numbers (got 2.5); give it a kind with decimals",
                         invalid_input);

    io_test::temp_dir dir;
    write_csv(dir.file("t.csv"), header, rows);
    const auto bytes = io_test::read_bytes(dir.file("t.csv"));
    CHECK(std::string(bytes.begin(), bytes.end()) == to_csv(header, rows));
    CHECK(io_test::starts_with(io_test::runtime_error_of([&] { write_csv(dir.file("x/y.csv"), header, rows); }),
                               dir.file("x/y.csv") + ": cannot open for writing"));
}

TEST_CASE("io/csv_column: each kind names its unit and rounds to what the data supports")
{
    // Known values, rounded right (the float of a rasterized level prints as 111.648, not 111.64775848388672).
    CHECK(csv_text(111.64775848388672, metres_column("water_level_m")) == "111.648");
    CHECK(csv_text(static_cast<double>(111.64775848388672f), metres_column("height_m")) == "111.648");
    CHECK(csv_text(1234.56, area_column("area_m2")) == "1234.6");
    CHECK(csv_text(2230738.84449, crs_column("xmin_crs")) == "2230738.844");
    CHECK(csv_text(179.96, degrees_column("azimuth_deg")) == "180.0");
    CHECK(csv_text(1803.97449, kwh_m2_column("annual_kwh_m2")) == "1803.974");
    CHECK(csv_text(4.2, kwh_m2_column("q1_kwh_m2_day")) == "4.200");
    CHECK(csv_text(12345.6789, kwh_column("annual_kwh")) == "12345.679");
    CHECK(csv_text(3.14159, kwp_column("kwp")) == "3.14");
    CHECK(csv_text(0.126, fraction_column("dropout_fraction")) == "0.13");
    CHECK(csv_text(99.7349, percent_column("accuracy_pct")) == "99.73");
    CHECK(csv_text(1.23456, seconds_column("run_time_s")) == "1.23");
    CHECK(csv_text(123.456, money_column("annual_savings")) == "123.46");
    CHECK(csv_text(87.25, intensity_column("mean_intensity")) == "87.2");  // 87.25 is exact: ties to even
    CHECK(csv_text(-0.0004, metres_column("z_m")) == "0.000");             // no "-0.000"
    CHECK(csv_text(-0.0006, metres_column("z_m")) == "-0.001");
    CHECK(csv_text(NAN, metres_column("z_m")) == "");
    CHECK(csv_text(std::numeric_limits<double>::max(), area_column("a_m2")).size() == 311);  // 309 digits + ".0"
    // Integers, booleans and text are written as they are, whatever the column.
    CHECK(csv_text(7, area_column("area_m2")) == "7");
    CHECK(csv_text(true, text_column("suitable")) == "true");
    CHECK(csv_text("north", text_column("surface")) == "north");

    // The unit is in the name, or the column is refused.
    const auto refused = [](auto&& make, const char* name) { CHECK_THROWS_AS(make(name), invalid_input); };
    refused(metres_column, "height");
    refused(metres_column, "height_m2");
    refused(area_column, "area");
    refused(crs_column, "xmin");
    refused(degrees_column, "tilt");
    refused(kwh_m2_column, "annual_kwh");
    refused(kwh_column, "annual_kwh_m2");
    refused(kwp_column, "power");
    refused(fraction_column, "dropout");
    refused(percent_column, "accuracy");
    refused(seconds_column, "seconds");
    refused(money_column, "annual");
    refused(intensity_column, "mean");
    CHECK_THROWS_WITH_AS(area_column("area"), "csv column 'area' must end in '_m2' (its unit)", invalid_input);
    CHECK(kwp_column("peak_kwp").decimals == 2);
    CHECK(money_column("jan_mar_savings_per_day").decimals == 2);
}

TEST_CASE("io/to_csv: random text and rounded numbers read back by an RFC 4180 reader, within the column's step")
{
    std::mt19937 rng(4180);
    const std::string alphabet[] = {"a", "b", ",", "\"", "\n", "\r", " ", "\xC3\xA9", ";", "'"};
    const csv_column kinds[] = {metres_column("h_m"),         area_column("a_m2"),       crs_column("x_crs"),
                                degrees_column("t_deg"),      kwh_m2_column("e_kwh_m2"), fraction_column("f_fraction"),
                                intensity_column("intensity")};
    std::uniform_real_distribution<double> real(-1e6, 1e6);
    for (int trial = 0; trial < 50; ++trial) {
        CAPTURE(trial);
        const std::size_t cols = 1 + rng() % 5, n = rng() % 8;
        std::vector<csv_column> header;
        std::vector<std::vector<table_value>> rows(n);
        std::vector<std::vector<std::string>> expected;
        const auto text = [&] {
            std::string s;
            for (std::size_t k = rng() % 6; k > 0; --k) s += alphabet[rng() % std::size(alphabet)];
            return s;
        };
        for (std::size_t c = 0; c < cols; ++c) {
            csv_column column = kinds[rng() % std::size(kinds)];
            column.name = text() + column.name;  // any text before the unit
            header.push_back(column);
        }
        expected.emplace_back();
        for (const auto& column : header) expected.back().push_back(column.name);
        for (auto& row : rows) {
            std::vector<std::string> want;
            for (std::size_t c = 0; c < cols; ++c) {
                if (rng() % 2) {
                    row.emplace_back(text());
                    want.push_back(row.back().format());
                } else {
                    const double v = real(rng);
                    row.emplace_back(v);
                    want.push_back(csv_text(row.back(), header[c]));
                    // Exactly `decimals` decimals, and the nearest such number: within half a step.
                    const std::size_t point = want.back().find('.');
                    REQUIRE(point != std::string::npos);
                    CHECK(want.back().size() - point - 1 == static_cast<std::size_t>(header[c].decimals));
                    CHECK(std::abs(std::stod(want.back()) - v) <= 0.5 * std::pow(10.0, -header[c].decimals) * 1.000001);
                }
            }
            expected.push_back(want);
        }
        CHECK(parse_csv(to_csv(header, rows)) == expected);
    }
}

TEST_CASE("io/waterbodies.csv: a lake surveyed in feet gives its boxes in feet (_crs) and its areas and levels in m")
{
    // The synthetic lake in international feet (x, y and z divided by 0.3048), EPSG:32633 with foot units.
    io_test::temp_dir dir;
    las_points feet = las_points_from(synth::lake_scene({.seed = 3, .size_m = 400}).points);
    for (auto* v : {&feet.x, &feet.y, &feet.z})
        for (double& value : *v) value /= international_foot_m;
    const auto las = dir.file("lake_ft.las");
    write_las(las, feet,
              {.scale = {0.001, 0.001, 0.001},
               .geo_keys = {{1024, 0, 1, 1}, {3072, 0, 1, 32633}, {3076, 0, 1, 9002}, {4099, 0, 1, 9002}}});
    cli::survey_options options;
    options.cell_m = 2.0;
    options.show_progress = false;
    const cli::survey s = cli::read_survey({las}, options);
    REQUIRE(s.crs.horizontal_unit_m == international_foot_m);
    const auto found = cli::find_waterbodies(s, {});
    const auto& bodies = found.result.bodies;
    REQUIRE(!bodies.empty());
    io::output_folder folder(dir.file("out"));
    cli::write_waterbodies(folder, s, found.result, found.footprint);
    folder.commit("test");
    const auto bytes = io_test::read_bytes(dir.file("out/waterbodies.csv"));
    const auto rows = parse_csv(std::string(bytes.begin(), bytes.end()));
    REQUIRE(rows.size() == bodies.size() + 1);
    CHECK(rows[0] == std::vector<std::string>{"label", "area_m2", "cells", "xmin_crs", "ymin_crs", "xmax_crs",
                                              "ymax_crs", "theta_deg", "stopped_by_ks", "mean_intensity",
                                              "water_level_m", "dropout_fraction"});
    const auto decimals = [](const std::string& field) {
        const auto point = field.find('.');
        return point == std::string::npos ? 0 : static_cast<int>(field.size() - point - 1);
    };
    const int wanted[] = {0, 1, 0, 3, 3, 3, 3, 1, 0, 1, 3, 2};  // as docs/waterbodies.md documents
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const auto& row = rows[i + 1];
        const waterbody& b = bodies[i];
        CAPTURE(i);
        REQUIRE(row.size() == 12);
        for (std::size_t c = 0; c < row.size(); ++c)
            if (!row[c].empty()) CHECK(decimals(row[c]) == wanted[c]);
        // Metres, rounded: area to 0.1 m2 and the level to the mm, whatever the CRS's unit.
        CHECK(std::abs(std::stod(row[1]) - b.area_m2) <= 0.05 + 1e-9);
        if (std::isfinite(b.water_level_m)) CHECK(std::abs(std::stod(row[10]) - b.water_level_m) <= 0.0005 + 1e-9);
        // The box in feet: times 0.3048 it is the box of the metre grid the survey was read onto (to 0.001 ft).
        const bounds metres = s.rasters.g.extent(b.box);
        const double in_feet[] = {metres.xmin, metres.ymin, metres.xmax, metres.ymax};
        for (int k = 0; k < 4; ++k)
            CHECK(std::abs(std::stod(row[3 + k]) - in_feet[k] / international_foot_m) <= 0.0005 + 1e-6);
        CHECK((row[8] == "0" || row[8] == "1"));
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
