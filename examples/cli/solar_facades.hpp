// SPDX-License-Identifier: Apache-2.0
// lidarfx solar --facades: buildings, their roofs and facade sub-patches, and the energy each receives.
#pragma once

#include <span>
#include <string>
#include <vector>

#include <lidarfx/core/grid.hpp>
#include <lidarfx/core/raster.hpp>
#include <lidarfx/kernels/solar/daylight_suns.hpp>
#include <lidarfx/kernels/solar/irradiance_record.hpp>
#include <lidarfx/pipelines/buildings/vegetation_by_returns.hpp>

#include "cli_common.hpp"
#include "io/output_folder.hpp"

namespace lidarfx::cli {

/// Where the facade run takes place: the DSM in metres on `grid_crs` (the same cells in the input's CRS units),
/// the sun's place and the weather.
struct facade_run {
    raster_view<const float> dsm;
    /// Points and split-pulse points per cell (LAS input), trees told by them; empty for a DSM raster, which says
    /// nothing of trees (rough parts are dropped)
    pulse_returns returns = pulse_returns();
    raster_view<const float> ground;  ///< the terrain under the buildings (--ground), empty: found from the DSM
    /// --buildings class6: the cells of the vendor's buildings (extract_classified_buildings); empty: found
    raster_view<const std::uint8_t> classified_buildings;
    double cell_m = 1;
    grid grid_crs;
    std::string crs_wkt;
    int epsg = 0;
    solar_site site;  ///< the sun's place, the weather's time zone and the grid's meridian convergence
    std::span<const irradiance_record> records;
    int threads = 0;
    bool png = true;
    output_formats formats{};  ///< the formats of buildings (geojson, gpkg); `png` above decides the picture
};

/// The files --facades adds: buildings.geojson and buildings.gpkg (as `formats` asks), facade_patches.csv,
/// surface_table.csv, bill_savings.csv and (with formats.png) buildings_energy.png.
std::vector<std::string> facade_file_names(const output_formats& formats);

/// facade_file_names with the default vector formats and the picture when `png`.
std::vector<std::string> facade_file_names(bool png);

/// Extracts the buildings (extract_buildings), computes the energy of every roof patch and facade sub-patch
/// (surface_energy) and writes the facade files into `out`; prints a short summary.
void write_facade_outputs(io::output_folder& out, const facade_run& run);

}  // namespace lidarfx::cli
