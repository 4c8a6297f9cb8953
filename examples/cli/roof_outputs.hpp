// SPDX-License-Identifier: Apache-2.0
// The roof outputs of `lidarfx roofs` and `lidarfx demo`: roof patches as a table, polygons and a picture.
#pragma once

#include <span>
#include <string>
#include <vector>

#include <lidarfx/core/grid.hpp>
#include <lidarfx/core/raster.hpp>
#include <lidarfx/pipelines/pv/roof_suitability.hpp>
#include <lidarfx/pipelines/pv/roof_yield.hpp>

#include "cli_common.hpp"
#include "io/output_folder.hpp"

namespace lidarfx::cli {

/// Where the patches of a roof_suitability result lie: the DSM in metres on a grid of `cell_m` cells, the same
/// cells in the input's CRS units (`grid_crs`, `unit_m` metres per CRS unit), the CRS's EPSG code (0 = none)
/// and its WKT ("" = none).
struct roof_output_frame {
    raster_view<const float> dsm;
    double cell_m = 1;
    grid grid_crs;
    double unit_m = 1;
    int epsg = 0;
    std::string crs_wkt{};
};

/// The names write_roof_patches gives its files (for output_folder::declare before long work).
std::vector<std::string> roof_patch_file_names(const output_formats& formats = {});

/// roof_patches.csv (building_id,patch_id,tilt_deg,azimuth_deg,area_m2,sloped_area_m2,kwp,suitable,
/// centroid_x_crs,centroid_y_crs,flat,reason; areas in m2, centroids in CRS units; when formats.csv), the patches'
/// outlines as roof_patches.geojson and roof_patches.gpkg (write_polygons, as `formats` asks) and, when formats.png,
/// roof_patches.png (a figure: patches coloured by azimuth on a cyclic wheel over a hillshade of the DSM, flat
/// ones white, suitable ones outlined in black). Sets
/// the folder's units note. With `yields` (roof_yield, one per patch in the same order) the table and the polygons also
/// carry annual_kwh_m2 (irradiation on the patch's plane) and annual_kwh.
void write_roof_patches(io::output_folder& out, const roof_suitability_result& r, const roof_output_frame& frame,
                        const output_formats& formats = {}, std::span<const roof_patch_yield> yields = {});

}  // namespace lidarfx::cli
