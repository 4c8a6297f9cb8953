// SPDX-License-Identifier: Apache-2.0
// Where `lidarfx solar` and `lidarfx roofs` put the sun (solar_place.hpp).
#include "solar_place.hpp"

#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>

#include "io/geographic.hpp"

namespace lidarfx::cli {

void require_place(double lat, double lon, const std::string& why_none)
{
    if (!(lat >= -90.0 && lat <= 90.0)) {
        throw usage_error("--lat must be given, in [-90, 90] degrees, with --lon: " + why_none);
    }
    if (!(lon >= -180.0 && lon <= 180.0)) {
        throw usage_error("--lon must be given, in [-180, 180] degrees, with --lat: " + why_none);
    }
}

solar_place resolve_solar_place(const arguments& a, const solar_place_sources& from)
{
    const double nan = std::numeric_limits<double>::quiet_NaN();
    double lat = a.number("lat", nan), lon = a.number("lon", nan);
    std::optional<io::geographic_place> centre;
    std::string no_centre = from.input + " has no coordinate system";
    if (!from.place_crs.empty() && !io::proj_available()) no_centre = "this lidarfx was built without PROJ";
    if (!from.place_crs.empty() && io::proj_available()) {
        try {
            centre = io::place_of(from.place_crs, from.g.x0 + 0.5 * static_cast<double>(from.g.cols) * from.g.cell,
                                  from.g.y0 - 0.5 * static_cast<double>(from.g.rows) * from.g.cell);
        } catch (const std::exception& e) {
            no_centre = std::string("PROJ cannot place its centre: ") + e.what();
            std::cerr << "lidarfx: warning: " << from.input << ": " << no_centre
                      << "; grid north is taken as true north\n";
        }
    }
    const char* lat_from = "--lat";
    const char* lon_from = "--lon";
    if (!a.has("lat")) {
        lat = centre ? centre->latitude_deg : from.station_latitude_deg;
        lat_from = centre ? "the survey's centre (PROJ)" : "the TMY station";
    }
    if (!a.has("lon")) {
        lon = centre ? centre->longitude_deg : from.station_longitude_deg;
        lon_from = centre ? "the survey's centre (PROJ)" : "the TMY station";
    }
    require_place(lat, lon, no_centre);
    if (centre && (std::abs(lat - centre->latitude_deg) > 0.5 || std::abs(lon - centre->longitude_deg) > 0.5)) {
        std::cerr << "lidarfx: warning: the sun is placed at latitude " << lat << ", longitude " << lon
                  << ", but the survey's centre is at " << centre->latitude_deg << ", " << centre->longitude_deg
                  << "\n";
    }
    const double convergence_deg = centre ? centre->convergence_deg : 0.0;
    std::ostringstream convergence;
    convergence << std::fixed << std::setprecision(4) << convergence_deg;
    std::ostringstream place;
    place << std::fixed << std::setprecision(6) << "latitude " << lat << " from " << lat_from << ", longitude " << lon
          << " from " << lon_from << "; "
          << (centre ? "meridian convergence " + convergence.str() +
                           " degrees at the survey's centre (grid north east of true north when positive; sun "
                           "azimuths turned to grid north by it)"
                     : std::string("grid north taken as true north (no convergence: ") + no_centre + ")");
    return {{.latitude_deg = lat,
             .longitude_deg = lon,
             .utc_offset_h = from.utc_offset_h,
             .meridian_convergence_deg = convergence_deg},
            place.str()};
}

}  // namespace lidarfx::cli
