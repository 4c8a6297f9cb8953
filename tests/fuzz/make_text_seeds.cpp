// SPDX-License-Identifier: Apache-2.0
// Writes the seed corpora of the text-format fuzz targets: <out>/footprints (GeoJSON footprint collections:
// polygons with holes, multipolygons, a byte order mark, members out of order, a bow tie, a zero-area ring, a
// coordinate of 1e300), <out>/tmy3 (a whole generated TMY3 year in NREL's column layout, its first day alone,
// a year with -9900 and a repeated hour) and <out>/ascii_grid (corner and centre registration, NoData, nan and
// inf text, one cell, CRLF). Usage: make_text_seeds <out_dir>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

namespace {

namespace fs = std::filesystem;

void save(const fs::path& path, const std::string& text)
{
    fs::create_directories(path.parent_path());
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << text;
}

std::string feature(int id, const std::string& geometry)
{
    return R"({"type":"Feature","properties":{"building_id":)" + std::to_string(id) + R"(,"name":"b"},"geometry":)" +
           geometry + "}";
}

std::string collection(const std::string& features)
{
    return R"({"type":"FeatureCollection","features":[)" + features + "]}";
}

std::string two(int v)
{
    return (v < 10 ? "0" : "") + std::to_string(v);
}

// A TMY3 year (8760 rows, 01/01 01:00 .. 12/31 24:00) in the first 13 columns of NREL's layout.
std::string tmy3_year(int days, bool with_faults)
{
    static const int days_in[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    std::string text =
        "723170,\"GREENSBORO PIEDMONT TRIAD INT\",NC,-5.0,36.100,-79.950,273\n"
        "Date (MM/DD/YYYY),Time (HH:MM),ETR (W/m^2),ETRN (W/m^2),GHI (W/m^2),GHI source,GHI uncert (%),"
        "DNI (W/m^2),DNI source,DNI uncert (%),DHI (W/m^2),DHI source,DHI uncert (%)\n";
    int day = 0;
    for (int m = 1; m <= 12 && day < days; ++m) {
        for (int d = 1; d <= days_in[m - 1] && day < days; ++d, ++day) {
            for (int h = 1; h <= 24; ++h) {
                const bool sun = h >= 8 && h <= 17;
                int ghi = sun ? 500 : 0, dni = sun ? 600 : 0;
                if (with_faults && m == 6 && d == 1 && h == 12) ghi = dni = -9900;
                text += two(m) + "/" + two(d) + "/1988," + two(h) + ":00,0,0," + std::to_string(ghi) + ",1,0," +
                        std::to_string(dni) + ",1,0," + (sun ? "100" : "0") + ",1,0\n";
                if (with_faults && m == 7 && d == 2 && h == 3) text += "07/02/1988,03:00,0,0,0,1,0,0,1,0,0,1,0\n";
            }
        }
    }
    return text;
}

}  // namespace

int main(int argc, char** argv)
{
    if (argc < 2) {
        std::cerr << "usage: make_text_seeds <out_dir>\n";
        return 2;
    }
    const fs::path out = argv[1];

    const std::string square = R"({"type":"Polygon","coordinates":[[[0,0],[0,10],[10,10],[10,0],[0,0]]]})";
    const std::string holed =
        R"({"type":"Polygon","coordinates":[[[20,0],[30,0],[30,10],[20,10]],[[22,2],[28,2],[28,8],[22,8],[22,2]]]})";
    const std::string multi =
        R"({"type":"MultiPolygon","coordinates":[[[[40,0],[45,0],[45,5],[40,5],[40,0]]],[[[50,0],[55,0],[55,5],[50,5],[50,0]]]]})";
    const std::string bowtie = R"({"type":"Polygon","coordinates":[[[0,0],[10,10],[10,0],[0,10],[0,0]]]})";
    const std::string flat = R"({"type":"Polygon","coordinates":[[[0,0],[5,0],[10,0],[0,0]]]})";
    const fs::path fp = out / "footprints";
    save(fp / "three.geojson", collection(feature(1, square) + "," + feature(7, holed) + "," + feature(3, multi)));
    save(fp / "problems.geojson",
         collection(feature(5, bowtie) + ",\n" + feature(6, square) + ",\n" + feature(8, flat)));
    save(fp / "bom.geojson", "\xEF\xBB\xBF" + collection(feature(2, square)));
    save(fp / "order.geojson",
         R"({"features":[{"geometry":{"coordinates":[[[500000.5,5000000.25,12.5],[500010.5,5000000.25,12.5],)"
         R"([500010.5,5000010.25,12.5],[500000.5,5000000.25,12.5]]],"type":"Polygon"},"type":"Feature",)"
         R"("properties":{"name":"a\"b\u00e9","building_id":9}}],"type":"FeatureCollection","crs":{"type":"name"}})");
    save(fp / "huge.geojson",
         collection(feature(4, R"({"type":"Polygon","coordinates":[[[1e300,0],[0,10],[10,10],[10,0],[1e300,0]]]})")));
    save(fp / "empty.geojson", collection(""));

    const fs::path tmy = out / "tmy3";
    save(tmy / "year.csv", tmy3_year(365, false));
    save(tmy / "faults.csv", tmy3_year(365, true));
    save(tmy / "day.csv", tmy3_year(1, false));

    const fs::path asc = out / "ascii_grid";
    save(asc / "corner.asc",
         "ncols 4\nnrows 3\nxllcorner 1000\nyllcorner 2000\ncellsize 0.5\nNODATA_value -9999\n"
         "1 2 3 4\n5 -9999 7 8.25\n9 10 11 1e3\n");
    save(asc / "center.asc",
         "NCOLS 2\r\nNROWS 2\r\nXLLCENTER 0.25\r\nYLLCENTER -10\r\nCELLSIZE 0.5\r\n1.5 2\r\n3 4\r\n");
    save(asc / "nan.asc", "ncols 3\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 1\nnan inf -inf\n");
    save(asc / "one.asc", "ncols 1\nnrows 1\nxllcorner -5e5\nyllcorner 4e6\ncellsize 2\nnodata_value 0\n0\n");
    return 0;
}
