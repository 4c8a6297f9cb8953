// SPDX-License-Identifier: Apache-2.0
// Umbrella header: includes every public lidarfx header (adapters/ needs third-party headers: include it apart).
#pragma once

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/grid.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/point_cloud.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/filter/angular_filter.hpp"
#include "lidarfx/filter/morphology.hpp"
#include "lidarfx/filter/slope_aspect.hpp"
#include "lidarfx/label/connected_components.hpp"
#include "lidarfx/label/polygonize.hpp"
#include "lidarfx/metrics/confusion.hpp"
#include "lidarfx/raster/idw_fill.hpp"
#include "lidarfx/raster/rasterize.hpp"
#include "lidarfx/raster/vegetation_mask.hpp"
#include "lidarfx/stats/ks_one_sided.hpp"
#include "lidarfx/synth/scenes.hpp"
#include "lidarfx/water/grow_waterbody.hpp"
#include "lidarfx/water/waterbodies.hpp"
