// SPDX-License-Identifier: Apache-2.0
// polygonize: outlines of labelled regions as polygons along cell edges (for GeoJSON and GIS export).
// Implementation in detail/polygonize_impl.hpp.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "lidarfx/core/grid.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"

namespace lidarfx {

/// A polygon of world coordinates: rings[0] is the exterior (counter-clockwise, x east, y north), the
/// others are holes (clockwise), as RFC 7946 GeoJSON orders them. Rings are closed (last point = first).
struct polygon {
    std::vector<std::vector<std::array<double, 2>>> rings;
};

/// The polygons of one label; a region whose parts touch only at corners gives several polygons.
struct label_polygons {
    std::int32_t label = 0;
    std::vector<polygon> polygons;
};

/// Options of polygonize.
struct polygonize_options {
    execution run = {};  ///< progress and cancellation (core/parallel.hpp); run.threads (>= 0) is ignored:
                         ///< polygonize runs on the caller's thread
};

/// Outlines every label > 0 of `labels` along cell edges and returns them in world coordinates of `g`,
/// sorted by label. Rings follow the region with the region on their left; where two cells of a label
/// touch only at a corner the outline separates there (parts become separate polygons or touch a hole at
/// a point), so every ring is simple. Collinear vertices are dropped. Each polygon is one 4-connected
/// part: its exterior ring (counter-clockwise, GeoJSON) then its holes (clockwise), rings of a label in
/// the raster order of their top-left corners. O(cells + boundary length · log(boundary length)).
/// @throws invalid_input if the labels' shape differs from the grid's or run.threads < 0; cancelled if
/// run.progress returns false.
template <raster_input Labels>
std::vector<label_polygons> polygonize(const Labels& labels, const grid& g, const polygonize_options& opt = {});

}  // namespace lidarfx

#include "lidarfx/kernels/vector/detail/polygonize_impl.hpp"
