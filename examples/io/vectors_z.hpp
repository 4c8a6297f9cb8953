// SPDX-License-Identifier: Apache-2.0
// 3D vector layers (polygons and breaklines with heights) written as one GeoPackage through OGR, when lidarfx_io was
// built with GDAL (LIDARFX_HAVE_GDAL).
#pragma once

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "io/tables.hpp"

namespace lidarfx::io {

/// A vertex with height: x, y in the CRS's units, z in metres.
using xyz = std::array<double, 3>;

/// A feature of a 3D layer: for a polygon layer, parts[0] is the outer ring and the others holes (a ring is
/// closed on writing when its first and last x, y differ, else its last vertex is written with the first's z;
/// oriented outer counter-clockwise, holes clockwise, as checked_rings does on x, y); for a line layer, each part
/// is one line string of >= 2 distinct vertices. Properties as in geojson_feature (table_value from io/tables.hpp).
struct feature_z {
    std::vector<std::vector<xyz>> parts;
    std::vector<std::pair<std::string, table_value>> properties;
};

/// The geometry of every feature of a layer_z.
enum class geometry_z { polygon, line };

/// A named layer of 3D features of one geometry.
struct layer_z {
    std::string name;  ///< the GeoPackage table: not empty, unique in the file (ignoring ASCII case)
    geometry_z geometry = geometry_z::polygon;
    std::vector<feature_z> features;
};

/// Writes every layer into one new GeoPackage at `path`: a polygon layer declared Polygon Z, a line layer
/// MultiLineString Z whatever its features' part counts (one declared type per layer; ogrinfo reports "3D Polygon"
/// and "3D Multi Line String"). Fields come from the first feature's properties (every feature of a layer has the
/// same names in the same order) and are typed, the CRS chosen and the time stamp fixed as write_geopackage does,
/// so that the same layers give the same bytes. O(total vertices).
/// @throws invalid_input when epsg < 0, a layer name is empty or repeated, a coordinate is not finite, a polygon has
/// no ring or a ring fewer than 3 distinct x, y, a line feature has no part or a part fewer than 2 distinct vertices,
/// a property list differs from the layer's first feature, or the CRS is not understood; std::runtime_error naming
/// the file when it cannot be written or lidarfx has no GDAL.
void write_geopackage_z(const std::string& path, const std::vector<layer_z>& layers, const std::string& crs_wkt,
                        int epsg);

}  // namespace lidarfx::io
