// SPDX-License-Identifier: Apache-2.0
// Vector files through OGR, when lidarfx_io was built with GDAL (LIDARFX_HAVE_GDAL): footprints from any
// polygon source OGR opens, their reprojection, and polygon layers written as GeoPackage with their CRS.
#pragma once

#include <string>
#include <vector>

#include "io/footprints.hpp"
#include "io/tables.hpp"

namespace lidarfx::io {

/// True when OGR support was compiled in (GDAL found by CMake).
bool vectors_available() noexcept;

/// What to do to get OGR formats in a build without GDAL, for messages.
inline constexpr const char* vectors_rebuild_hint =
    "this lidarfx was built without GDAL; rebuild it with GDAL (apt-get install libgdal-dev, then cmake again)";

/// Building footprints from the first layer of any vector source OGR opens (GeoPackage, Shapefile,
/// FlatGeobuf, GeoJSON, ...), with the checks and messages of parse_footprints_geojson: Polygon and
/// MultiPolygon geometries only (z and m dropped), coordinates finite and within footprint_max_abs_coordinate,
/// rings of at least 4 positions, integer ids in 1 .. 2^31 - 1 used once, geometric faults reported per
/// building in `problems`. The id comes from the field `opt.id_field` ("" = building_id; a name longer than
/// 10 characters also matches its first 10, as a Shapefile truncates it: building_i); when that field is
/// absent and `opt.id_field` is "", from the feature id (FID; plus 1 when the source numbers its features from
/// 0, as Shapefile and FlatGeobuf do), which `notes` says. The memory estimate counts the kept footprints and
/// the feature being read as parse_footprints_geojson does (OGR streams the file: no text is held).
/// The layer's CRS is returned in `crs` as WKT ("" when the layer has none, or only an engineering CRS or
/// GeoPackage's "Undefined geographic SRS", which place nothing).
/// @throws invalid_input naming the file, the feature and what to fix; std::runtime_error when the file
/// cannot be opened or lidarfx has no GDAL.
footprint_collection read_footprints_ogr(const std::string& path, const footprint_read_options& opt = {});

/// The EPSG code that names `crs` (WKT, "EPSG:n" or a URN), 0 when none does: the authority code of its
/// root, else OGR's AutoIdentifyEPSG, else its one match of full confidence (FindMatches). Without GDAL only
/// the code at the end of "EPSG:n" or a URN.
int epsg_of_crs(const std::string& crs);

/// True when `a` and `b` (WKT, "EPSG:n" or a URN) describe the same horizontal CRS (OGR's IsSame of their
/// horizontal parts; data axis order ignored) or identify as the same EPSG code. Without GDAL: equal texts or the same
/// code at their ends.
bool same_crs(const std::string& a, const std::string& b);

/// Transforms every vertex of `c` from `from` to `to` (WKT, "EPSG:n" or a URN) through OGR/PROJ, x = easting
/// or longitude (OAMS_TRADITIONAL_GIS_ORDER), and checks each footprint again: one whose polygon is no
/// longer valid moves to `problems`. @throws invalid_input naming `source` when either CRS is not understood
/// or a vertex cannot be transformed; std::runtime_error without GDAL.
void reproject_footprints(footprint_collection& c, const std::string& from, const std::string& to,
                          const std::string& source);

/// Writes `features` as the layer `layer` of a new GeoPackage at `path` (polygons and multi-part outlines
/// one feature each, properties as fields: integers as Integer64, reals as Real, booleans as Integer (0/1),
/// text as String), in the CRS `crs` ("EPSG:n" when `epsg` > 0, else the WKT `crs_wkt`; when both are empty,
/// GeoPackage's "Undefined cartesian SRS", srs_id -1). Rings are closed and oriented as to_geojson does.
/// Its time stamp (gpkg_contents.last_change) is 1970-01-01, so that the same features give the same bytes. @throws
/// invalid_input as to_geojson; std::runtime_error naming the file when it cannot be written or lidarfx has no GDAL.
void write_geopackage(const std::string& path, const std::string& layer, const std::vector<geojson_feature>& features,
                      const std::string& crs_wkt, int epsg);

}  // namespace lidarfx::io
