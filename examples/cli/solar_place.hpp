// SPDX-License-Identifier: Apache-2.0
// Where `lidarfx solar` and `lidarfx roofs` put the sun: the weather year's station, --lat/--lon, the survey's
// centre and its meridian convergence, resolved by one rule into a solar_site.
#pragma once

#include <string>

#include <lidarfx/core/grid.hpp>
#include <lidarfx/kernels/solar/daylight_suns.hpp>

#include "cli_common.hpp"

namespace lidarfx::cli {

/// What the place of a solar run may come from besides --lat/--lon.
struct solar_place_sources {
    grid g;                 ///< the DSM's cells in the CRS's units (its centre is placed with PROJ)
    std::string place_crs;  ///< the CRS PROJ may place the centre in ("" when none is known)
    std::string input;      ///< the first input's name, for messages
    double station_latitude_deg = 0, station_longitude_deg = 0;  ///< the TMY station's (NaN without --tmy)
    double utc_offset_h = 0;                                     ///< the weather's time zone (0 without --tmy)
};

/// The site of a solar run and the sentence that says where it comes from.
struct solar_place {
    solar_site site;
    std::string description;  ///< "latitude L from S, longitude ... ; meridian convergence ..." (the "place:" line)
};

/// The site of a solar run: latitude and longitude from --lat/--lon when given, else the survey's centre (PROJ,
/// when place_crs is known), else the TMY station; the meridian convergence at the survey's centre when PROJ
/// places it (sun azimuths are turned to grid north by it), else 0; months in UTC + utc_offset_h. Warns on stderr
/// when PROJ cannot place the centre or the place is more than half a degree from it. @throws usage_error (exit
/// code 2) when no latitude or longitude can be found, naming why.
solar_place resolve_solar_place(const arguments& a, const solar_place_sources& from);

/// Refuses (usage_error, exit code 2) a missing or out-of-range latitude or longitude, saying why none was found.
void require_place(double lat, double lon, const std::string& why_none);

}  // namespace lidarfx::cli
