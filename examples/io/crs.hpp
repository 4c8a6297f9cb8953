// SPDX-License-Identifier: Apache-2.0
// The coordinate reference system of a LAS file: WKT and EPSG code for outputs, linear units of x, y and z.
#pragma once

#include <string>
#include <vector>

#include "io/las.hpp"

namespace lidarfx::io {

/// Metres per unit of the linear units surveys use (EPSG units 9001, 9002, 9003).
inline constexpr double metre_m = 1.0;
inline constexpr double international_foot_m = 0.3048;
inline constexpr double us_survey_foot_m = 1200.0 / 3937.0;

/// What a LAS file says about its coordinate reference system (CRS), read from its GeoKeys (GeoKeyDirectory
/// 34735 with GeoDoubleParams 34736 and GeoAsciiParams 34737) or its OGC WKT record (2112, VLR or EVLR).
struct survey_crs {
    std::string wkt;                        ///< the CRS as WKT, for outputs: the horizontal CRS, compound with the
                                            ///< vertical CRS the file names when z has the same unit as x and y
                                            ///< (with GDAL); empty when unknown (always without GDAL unless the
                                            ///< file holds WKT)
    int epsg = 0;                           ///< EPSG code of the horizontal CRS, 0 when none or user-defined
    bool geographic = false;                ///< x and y are longitude and latitude in degrees
    double horizontal_unit_m = 1;           ///< metres per unit of x and y: 1, 0.3048, 1200/3937 (1 when geographic)
    double vertical_unit_m = 1;             ///< metres per unit of z
    std::string horizontal_unit = "metre";  ///< name of the unit of x and y ("degree" when geographic)
    std::string vertical_unit = "metre";    ///< name of the unit of z
    std::string source;                     ///< where the CRS came from: "GeoKeys", "WKT", or "" (the file has none)
    std::vector<std::string> warnings;      ///< what could not be carried or was assumed, one sentence each

    /// The CRS as write_geotiff takes it: the WKT, else "EPSG:n", else "".
    std::string for_outputs() const;
    /// A short description for messages: "EPSG:2994 (foot)", the name in the WKT when no code names it
    /// ("NAD83 / Mississippi West (US survey foot)"), "a user-defined CRS (foot)", "no CRS (metre)".
    std::string describe() const;
};

/// The CRS of a LAS file and the units of its coordinates. Which record is used: the WKT record when the
/// header's global encoding says so (LAS 1.4, bit 4), else the GeoKeys when present, else the WKT record.
/// With GDAL (`use_gdal` and lidarfx_io built with it) the GeoKeys are interpreted by GDAL's GeoTIFF driver
/// (EPSG codes, user-defined projections from their parameters, unit overrides) and the WKT by OGR; the units
/// come from the resulting CRS. Without GDAL: explicit unit keys (ProjLinearUnitsGeoKey 3076,
/// VerticalUnitsGeoKey 4099) are honoured, a few geographic EPSG codes are known, any other EPSG code is
/// assumed in metres (with a warning), and WKT units are read from its top-level UNIT nodes.
/// Rules either way: unit keys override the units of the EPSG code they come with; z without a vertical unit
/// has the horizontal unit (metres when geographic); an empty or unreadable WKT record is ignored with a warning.
/// Never throws for bad CRS data: what cannot be read is a warning.
survey_crs crs_of(const las_header& h, bool use_gdal = true);

/// The CRS and units of a raster file's WKT (GDAL's projection of a GeoTIFF), by the rules of crs_of for a
/// LAS file whose only record is that WKT; "" gives no CRS, metres assumed. Never throws.
survey_crs crs_of_wkt(const std::string& wkt, bool use_gdal = true);

/// The text of the .prj file GDAL's AAIGrid driver writes beside an ESRI ASCII grid and reads back: `crs` ("EPSG:n",
/// a bare code, WKT or PROJ text, as survey_crs::for_outputs gives it) as ESRI WKT (OGR's WKT1_ESRI export) with
/// GDAL; a compound CRS that ESRI WKT cannot hold loses its vertical part. Without GDAL: `crs` itself when it is
/// WKT. "" when `crs` is empty or cannot be read (then no .prj is written). Never throws.
std::string esri_prj_text(const std::string& crs);

/// True when a and b hold the same CRS records (GeoKeys, their parameters, WKT, the WKT flag), so that
/// crs_of gives the same answer for both: tiles of one survey need to be interpreted once (GDAL's search
/// for a matching EPSG code takes a quarter of a second).
bool same_crs_records(const las_header& a, const las_header& b);

/// True when crs_of can use GDAL (lidarfx_io built with it).
bool crs_gdal_available() noexcept;

}  // namespace lidarfx::io
