// SPDX-License-Identifier: Apache-2.0
// Where a point of a projected CRS lies (latitude, longitude) and how far its grid north is turned from true
// north (meridian convergence), through PROJ when lidarfx_io was built with it (LIDARFX_HAVE_PROJ).
#pragma once

#include <string>

namespace lidarfx::io {

/// A point of a projected CRS on the globe.
struct geographic_place {
    double latitude_deg = 0;   ///< north, WGS 84
    double longitude_deg = 0;  ///< east of Greenwich, WGS 84
    /// Meridian convergence, degrees: the angle from true north to grid north (the CRS's +y), positive when grid
    /// north lies east (clockwise) of true north. An azimuth turns from true to grid north as
    /// a_grid = a_true - convergence_deg. Transverse Mercator: about atan(tan(lon - lon0) sin(lat)), positive east
    /// of the central meridian in the northern hemisphere.
    double convergence_deg = 0;
};

/// True when place_of can be used (PROJ found by CMake).
bool proj_available() noexcept;

/// The latitude and longitude of the point (x, y) of the projected CRS `crs` ("EPSG:n", WKT or a PROJ string;
/// x and y in the CRS's own units, e.g. US survey feet), by PROJ's best available transformation between the CRS
/// and WGS 84 (axes normalised to longitude, latitude; a datum shift without its grid files is good to metres),
/// and the meridian convergence there, measured as the grid bearing of the meridian: the points 1e-5 degrees of
/// latitude either side are projected and
/// convergence = -atan2(dx, dy). (PROJ's proj_factors gives the same for CRSs in metres, but not for CRSs in
/// feet in PROJ 9.1.) Compound and bound CRSs are reduced to their projected part.
/// @throws std::runtime_error naming the CRS when PROJ does not understand it, it is not projected (a geographic
/// CRS has no grid to turn), the point cannot be transformed, or PROJ is not available.
geographic_place place_of(const std::string& crs, double x, double y);

}  // namespace lidarfx::io
