// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include "io/geographic.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "io_test_util.hpp"

using namespace lidarfx::io;
using io_test::contains;

namespace {

constexpr double deg = std::numbers::pi / 180.0;

// UTM (transverse Mercator on WGS 84, k0 0.9996, false easting 500 km) by Snyder's series (Map Projections - A
// Working Manual, 1987, eq. 3-21, 8-9, 8-10): an independent forward projection, good to millimetres within a
// few degrees of the central meridian.
struct easting_northing {
    double x, y;
};
easting_northing utm(double lat_deg, double lon_deg, double lon0_deg, bool south)
{
    const double a = 6378137.0, f = 1.0 / 298.257223563, e2 = f * (2.0 - f), ep2 = e2 / (1.0 - e2), k0 = 0.9996;
    const double phi = lat_deg * deg;
    const double e4 = e2 * e2, e6 = e4 * e2;
    const double m = a * ((1 - e2 / 4 - 3 * e4 / 64 - 5 * e6 / 256) * phi -
                          (3 * e2 / 8 + 3 * e4 / 32 + 45 * e6 / 1024) * std::sin(2 * phi) +
                          (15 * e4 / 256 + 45 * e6 / 1024) * std::sin(4 * phi) - (35 * e6 / 3072) * std::sin(6 * phi));
    const double n = a / std::sqrt(1 - e2 * std::sin(phi) * std::sin(phi));
    const double t = std::tan(phi) * std::tan(phi), c = ep2 * std::cos(phi) * std::cos(phi);
    const double A = (lon_deg - lon0_deg) * deg * std::cos(phi);
    const double x =
        k0 * n *
        (A + (1 - t + c) * std::pow(A, 3) / 6 + (5 - 18 * t + t * t + 72 * c - 58 * ep2) * std::pow(A, 5) / 120);
    const double y = k0 * (m + n * std::tan(phi) *
                                   (A * A / 2 + (5 - t + 9 * c + 4 * c * c) * std::pow(A, 4) / 24 +
                                    (61 - 58 * t + t * t + 600 * c - 330 * ep2) * std::pow(A, 6) / 720));
    return {500000.0 + x, south ? 10000000.0 + y : y};
}

// Meridian convergence of transverse Mercator to first order (the sphere's): atan(tan(lon - lon0) sin(lat)).
double first_order_convergence_deg(double lat_deg, double lon_deg, double lon0_deg)
{
    return std::atan(std::tan((lon_deg - lon0_deg) * deg) * std::sin(lat_deg * deg)) / deg;
}

}  // namespace

TEST_CASE(
    "io/place_of: UTM points give their latitude and longitude and the meridian convergence, whose sign puts "
    "grid north east of true north east of the central meridian in the north (with PROJ)")
{
    if (!proj_available()) {
        MESSAGE("PROJ not built in: checking the error instead");
        CHECK(contains(io_test::runtime_error_of([] { place_of("EPSG:32613", 500000, 4400000); }), "--lat and --lon"));
        return;
    }
    struct site {
        const char* crs;
        double lat, lon, lon0;
        bool south;
    };
    // Zone 13N (central meridian -105) on, east and west of the meridian; zone 33S (15 E) east of it.
    for (const site s :
         {site{"EPSG:32613", 40.0, -105.0, -105.0, false}, site{"EPSG:32613", 40.0, -103.0, -105.0, false},
          site{"EPSG:32613", 55.5, -107.5, -105.0, false}, site{"EPSG:32733", -20.0, 17.0, 15.0, true}}) {
        CAPTURE(s.crs);
        CAPTURE(s.lat);
        CAPTURE(s.lon);
        const easting_northing p = utm(s.lat, s.lon, s.lon0, s.south);
        const geographic_place g = place_of(s.crs, p.x, p.y);
        CHECK(std::abs(g.latitude_deg - s.lat) < 1e-6);  // about 0.1 m
        CHECK(std::abs(g.longitude_deg - s.lon) < 1e-6);
        const double expected = first_order_convergence_deg(s.lat, s.lon, s.lon0);
        CHECK(std::abs(g.convergence_deg - expected) < 0.01);
        if (s.lon == s.lon0)
            CHECK(std::abs(g.convergence_deg) < 1e-6);
        else
            CHECK((g.convergence_deg > 0.5) == ((s.lon > s.lon0) == (s.lat > 0)));  // the sign, not only the size
    }
    // Compound CRSs (UTM + a height) are placed by their projected part.
    const easting_northing p = utm(40.0, -103.0, -105.0, false);
    CHECK(std::abs(place_of("EPSG:32613+5703", p.x, p.y).latitude_deg - 40.0) < 1e-6);
}

TEST_CASE(
    "io/place_of: a CRS in feet gives what its metre twin gives; geographic and unknown CRSs are "
    "refused naming the CRS (with PROJ)")
{
    if (!proj_available()) return;
    // NAD83 / Oregon North in metres (EPSG:32126) and in international feet (EPSG:2269): one Lambert projection.
    const double x_m = 2300000.0, y_m = 200000.0, ft = 0.3048;
    const geographic_place m = place_of("EPSG:32126", x_m, y_m), f = place_of("EPSG:2269", x_m / ft, y_m / ft);
    MESSAGE("Oregon North at (", x_m, ", ", y_m, ") m: latitude ", m.latitude_deg, ", longitude ", m.longitude_deg,
            ", convergence ", m.convergence_deg);
    CHECK(std::abs(f.latitude_deg - m.latitude_deg) < 1e-8);
    CHECK(std::abs(f.longitude_deg - m.longitude_deg) < 1e-8);
    CHECK(std::abs(f.convergence_deg - m.convergence_deg) < 1e-6);
    // Lambert conformal conic: convergence = n (lon - lon0), n = sin of about the mean standard parallel (44.33 and
    // 46 N; central meridian -120.5).
    CHECK(std::abs(m.convergence_deg - std::sin(45.17 * deg) * (m.longitude_deg + 120.5)) < 0.01);

    CHECK(contains(io_test::runtime_error_of([] { place_of("EPSG:4326", -105, 40); }), "not a projected"));
    CHECK(contains(io_test::runtime_error_of([] { place_of("EPSG:4326", -105, 40); }), "EPSG:4326"));
    CHECK(
        contains(io_test::runtime_error_of([] { place_of("no such CRS", 0, 0); }), "'no such CRS' is not understood"));
}
