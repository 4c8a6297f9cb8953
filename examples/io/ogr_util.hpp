// SPDX-License-Identifier: Apache-2.0
// What the GeoPackage writers of examples/io share (only when built with GDAL): one new file holding layers whose
// fields come from their features' properties, in one CRS, with a fixed time stamp. Internal to lidarfx_io.
#pragma once

#ifdef LIDARFX_HAVE_GDAL
#include <ogrsf_frmts.h>

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "io/tables.hpp"

namespace lidarfx::io {

/// The named properties of one feature, as geojson_feature holds them.
using property_list = std::vector<std::pair<std::string, table_value>>;

/// One layer for write_geopackage_layers: its name, its declared geometry type (wkbPolygon, wkbPolygon25D, ...),
/// per feature its properties, and the geometry of feature f (checked already: this makes no refusal).
struct geopackage_layer_source {
    std::string name;
    OGRwkbGeometryType type = wkbUnknown;
    std::vector<const property_list*> properties;
    std::function<std::unique_ptr<OGRGeometry>(std::size_t)> geometry;
};

/// Writes `layers` into a new GeoPackage at `path` as write_geopackage describes: fields in the order they first
/// appear in a layer, typed by their first non-null value; the CRS "EPSG:n" when `epsg` > 0, else the WKT `crs_wkt`,
/// else GeoPackage's "Undefined cartesian SRS"; gpkg_contents.last_change 1970-01-01. `fn` names the caller in
/// messages. @throws invalid_input when a feature has a property twice or the CRS is not understood;
/// std::runtime_error naming the file when it cannot be written.
void write_geopackage_layers(const std::string& path, const std::vector<geopackage_layer_source>& layers,
                             const std::string& crs_wkt, int epsg, const char* fn);

}  // namespace lidarfx::io
#endif
