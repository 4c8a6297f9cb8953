// SPDX-License-Identifier: Apache-2.0
// Umbrella header: includes every public lidarfx header.
#pragma once

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/grid.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/point_cloud.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
