// SPDX-License-Identifier: Apache-2.0
// burn_polygons: polygons with holes (and several parts per id) burned into a label raster on a grid by the
// cell-centre rule, with a per-polygon account of the cells it got and lost, so nothing is dropped silently.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/grid.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/kernels/vector/polygonize.hpp"

namespace lidarfx {

/// One footprint to burn: its label (> 0) and its parts (a multipolygon: each part an exterior ring and
/// holes, as lidarfx::polygon; ring orientation does not matter, rings need not be closed).
struct labelled_polygon {
    std::int32_t label = 0;
    std::vector<polygon> parts;
};

/// What happened to one footprint (same order as the input).
struct burn_account {
    std::int32_t label = 0;
    std::size_t cells = 0;      ///< cells whose centre it contains, owned by it in the output
    std::size_t contested = 0;  ///< cells whose centre it contains but an earlier footprint of the list owns
    std::size_t outside = 0;    ///< 0, or 1 when its bounding box does not meet the grid at all
};

/// A label raster and the per-footprint account.
struct burn_result {
    raster<std::int32_t>
        labels;  ///< 0 = no footprint, else the label of the first footprint containing the cell centre
    std::vector<burn_account> footprints;  ///< one per input footprint, in input order
};

/// Burns footprints into a label raster on grid `g` (cell-centre rule): cell (r, c) gets the label of the
/// first footprint in `footprints` whose parts contain its centre g.center(r, c) by the even-odd rule over all
/// its rings: holes stay out; parts of one footprint must not overlap (overlaps cancel). A centre exactly on an edge
/// belongs to the footprint west of a vertical edge and north of a horizontal one (half-open crossing test), so
/// footprints sharing an edge never share a cell. Later footprints never overwrite earlier ones; their lost cells are
/// counted in `contested`. Coordinates in the grid's world units. O(sum over footprints of rows spanned * vertices).
/// @throws invalid_input if g is invalid, a label is <= 0, or a vertex is not finite.
inline burn_result burn_polygons(std::span<const labelled_polygon> footprints, const grid& g);

}  // namespace lidarfx

#include "lidarfx/kernels/vector/detail/burn_polygons_impl.hpp"
