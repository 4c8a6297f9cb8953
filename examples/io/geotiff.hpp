// SPDX-License-Identifier: Apache-2.0
// Float32 GeoTIFF output and input through GDAL, when lidarfx_io was built with it (LIDARFX_HAVE_GDAL).
#pragma once

#include <cstddef>
#include <string>

#include <lidarfx/core/grid.hpp>
#include <lidarfx/core/raster.hpp>

namespace lidarfx::io {

/// The NoData value written for NaN cells (and read back as NaN).
inline constexpr double geotiff_nodata = -9999.0;

/// True when GeoTIFF support was compiled in (GDAL found by CMake).
bool geotiff_available() noexcept;

/// True when write_geotiff understands `crs` ("" included); always true without GDAL (no GeoTIFF is written).
bool crs_understood(const std::string& crs) noexcept;

/// Writes `values` on `g` as a single-band float32 Cloud-Optimized GeoTIFF (GDAL's COG driver: 256 x 256 tiles,
/// nearest-neighbour overviews down to one tile, DEFLATE level 1 with the floating-point predictor: level 1 is 2-3
/// times faster than 6 for files 4 % larger; memory: a second copy of the grid while writing): geotransform
/// lidarfx::to_gdal(g) (north-up, square cells), NaN cells as NoData -9999. `crs` names the coordinate
/// system: "EPSG:3645", a bare code "3645", any WKT or PROJ string GDAL understands, or "" for none.
/// @throws invalid_input when the shapes differ, the raster is empty or the CRS is not understood;
/// std::runtime_error naming the file when it cannot be written or GDAL is not available.
void write_geotiff(const std::string& path, raster_view<const float> values, const grid& g,
                   const std::string& crs_wkt_or_epsg = "");

/// A raster read from a GeoTIFF (or any single-band raster GDAL reads), with its georeferencing.
struct geotiff_raster {
    raster<float> values;              ///< band 1 as float; NoData cells are NaN
    grid g;                            ///< from the geotransform (north-up, square cells)
    std::string crs_wkt;               ///< the file's CRS as WKT, empty when it has none
    std::size_t non_finite_cells = 0;  ///< cells holding inf, -inf (or NaN when NaN is not the NoData value): NaN now
};

/// The grid of band 1 of a raster file (size and geotransform), read from its header without its values, so that
/// a caller can check it against a memory budget first. @throws as read_geotiff.
grid read_geotiff_grid(const std::string& path);

/// The CRS of a raster file as WKT (GDAL's projection), "" when it has none, without reading its values.
/// @throws as read_geotiff.
std::string read_geotiff_crs(const std::string& path);

/// Reads band 1 of a raster file through GDAL (memory: the grid). Non-finite values are no data (NaN), counted. @throws
/// std::runtime_error naming the file when it cannot be read, its geotransform is rotated or its cells are not square,
/// or GDAL is not available.
geotiff_raster read_geotiff(const std::string& path);

}  // namespace lidarfx::io
