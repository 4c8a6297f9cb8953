// SPDX-License-Identifier: Apache-2.0
// Umbrella header: every public lidarfx header, layer by layer (docs/architecture.md). adapters/ needs
// third-party headers and synthetic scenes are a separate target (lidarfx::synth): include them apart.
#pragma once

// core: types, errors, execution
#include "lidarfx/core/bit_mask.hpp"
#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/grid.hpp"
#include "lidarfx/core/las_class.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/point_cloud.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

// kernels: single-purpose algorithms
#include "lidarfx/kernels/filter/angular_filter.hpp"
#include "lidarfx/kernels/filter/distance_transform.hpp"
#include "lidarfx/kernels/filter/morphology.hpp"
#include "lidarfx/kernels/filter/slope_aspect.hpp"
#include "lidarfx/kernels/filter/survey_footprint.hpp"
#include "lidarfx/kernels/filter/vegetation_mask.hpp"
#include "lidarfx/kernels/interpolate/idw_fill.hpp"
#include "lidarfx/kernels/label/connected_components.hpp"
#include "lidarfx/kernels/metrics/confusion.hpp"
#include "lidarfx/kernels/points/rasterize.hpp"
#include "lidarfx/kernels/points/scan_coverage.hpp"
#include "lidarfx/kernels/solar/horizon_map.hpp"
#include "lidarfx/kernels/solar/ray_lines.hpp"
#include "lidarfx/kernels/solar/raylines_shadow.hpp"
#include "lidarfx/kernels/solar/sky_view_factor.hpp"
#include "lidarfx/kernels/solar/spa_tables.hpp"
#include "lidarfx/kernels/solar/sun_position.hpp"
#include "lidarfx/kernels/stats/ks_one_sided.hpp"
#include "lidarfx/kernels/vector/polygonize.hpp"

// pipelines: methods composed of kernels
#include "lidarfx/pipelines/water/assess_water_inputs.hpp"
#include "lidarfx/pipelines/water/bridges.hpp"
#include "lidarfx/pipelines/water/extract_waterbodies.hpp"
#include "lidarfx/pipelines/water/grow_waterbodies.hpp"
#include "lidarfx/pipelines/water/grow_waterbody.hpp"
#include "lidarfx/pipelines/water/intensity_bins.hpp"
#include "lidarfx/pipelines/water/islands.hpp"
#include "lidarfx/pipelines/water/level_refinement.hpp"
#include "lidarfx/pipelines/water/measure_waterbodies.hpp"
#include "lidarfx/pipelines/water/water_angles.hpp"
#include "lidarfx/pipelines/water/water_rasters.hpp"
#include "lidarfx/pipelines/water/water_seeds.hpp"
#include "lidarfx/pipelines/water/water_vegetation.hpp"
