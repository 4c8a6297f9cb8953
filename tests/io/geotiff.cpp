// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include "io/geotiff.hpp"

#include <cmath>
#include <random>

#include "io_test_util.hpp"

using namespace lidarfx;
using namespace lidarfx::io;
using io_test::contains;
using io_test::starts_with;

TEST_CASE("io/write_geotiff: float32 round trip with NoData, geotransform and CRS (when GDAL is built in)")
{
    io_test::temp_dir dir;
    const std::string path = dir.file("dsm.tif");
    std::mt19937 rng(12);
    std::uniform_real_distribution<float> u(-5.0f, 90.0f);
    raster<float> big(40, 60);
    for (auto& v : big) v = rng() % 9 == 0 ? NAN : u(rng);
    const auto values = big.view().window(2, 4, 37, 53);  // strided
    const grid g{2230738.5, 252410.0, 0.5, 37, 53};
    if (!geotiff_available()) {
        MESSAGE("GDAL not built in: checking the error instead of a round trip");
        CHECK(starts_with(io_test::runtime_error_of([&] { write_geotiff(path, values, g, "EPSG:3645"); }),
                          path + ": GeoTIFF support needs GDAL"));
        return;
    }
    write_geotiff(path, values, g, "EPSG:3645");
    const auto back = read_geotiff(path);
    CHECK(back.g == g);
    CHECK(io_test::same_cells(back.values, values));
    CHECK(contains(back.crs_wkt, "3645"));
    CHECK(contains(back.crs_wkt, "Oregon North"));

    write_geotiff(path, values, g, "3645");  // a bare EPSG code
    CHECK(contains(read_geotiff(path).crs_wkt, "Oregon North"));
    write_geotiff(path, values, g, back.crs_wkt);  // WKT
    CHECK(contains(read_geotiff(path).crs_wkt, "Oregon North"));
    write_geotiff(path, values, g);  // no CRS
    CHECK(read_geotiff(path).crs_wkt.empty());

    raster<float> one(1, 1, -9999.0f);  // the NoData value itself reads back as NaN (documented)
    write_geotiff(path, one, {0, 1, 1, 1, 1});
    CHECK(std::isnan(read_geotiff(path).values(0, 0)));

    CHECK_THROWS_WITH_AS(write_geotiff(path, values, {0, 0, 1, 37, 52}),
                         "write_geotiff: values and grid must have the same shape", invalid_input);
    CHECK_THROWS_WITH_AS(write_geotiff(path, values, {0, 0, 0, 37, 53}),
                         "write_geotiff: grid.cell must be finite and > 0 (got 0)", invalid_input);
    CHECK_THROWS_WITH_AS(write_geotiff(path, values, g, "EPSG:not-a-code"),
                         "write_geotiff: crs_wkt_or_epsg must name a coordinate system GDAL understands (got "
                         "'EPSG:not-a-code')",
                         invalid_input);
    CHECK(starts_with(io_test::runtime_error_of([&] { write_geotiff(dir.file("no/dir.tif"), values, g); }),
                      dir.file("no/dir.tif") + ": writing the Cloud-Optimized GeoTIFF failed"));
    io_test::write_bytes(dir.file("text.tif"), {'n', 'o', 't', ' ', 'a', ' ', 't', 'i', 'f', 'f'});
    CHECK(starts_with(io_test::runtime_error_of([&] { (void)read_geotiff(dir.file("text.tif")); }),
                      dir.file("text.tif") + ": cannot open as a raster"));
}
