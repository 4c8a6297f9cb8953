// SPDX-License-Identifier: Apache-2.0
// idw_fill: fills the NaN cells of an elevation raster by inverse distance weighting of the nearest data cells,
// and idw_fill_reach_cells, how far from a hole those cells can lie. Implementation in detail/idw_fill_impl.hpp.
#pragma once

#include <cstddef>
#include <type_traits>

#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// Settings of idw_fill (the cell size is an argument of idw_fill, cell_m).
struct idw_fill_options {
    int k = 8;            ///< data cells averaged per hole, >= 1
    double radius_m = 0;  ///< search radius, metres between cell centres (inclusive, 1e-9 cell slack); 0 = unlimited
    double power = 1.0;   ///< weight exponent: w = 1 / d^power (1 = dissertation eq. 3); finite, > 0
    execution run = {};   ///< threads, progress, cancellation (core/parallel.hpp); never changes the result
};

/// What idw_fill did to the holes (NaN cells) of its input.
struct idw_fill_counts {
    std::size_t filled_cells = 0;    ///< NaN cells given a value
    std::size_t unfilled_cells = 0;  ///< NaN cells with no data cell within radius_m (left NaN)
};

/// Result of the returning form of idw_fill.
struct idw_fill_result {
    raster<float> filled;            ///< input with its holes filled; same shape
    std::size_t filled_cells = 0;    ///< NaN cells given a value
    std::size_t unfilled_cells = 0;  ///< NaN cells with no data cell within radius_m (left NaN)
};

/// Fills the NaN cells (holes) of an elevation raster by inverse distance weighting of the k nearest data
/// (finite) cells, dissertation eq. 3: z = sum(w_i z_i) / sum(w_i), w_i = 1 / d_i^power, d_i the distance
/// between cell centres in metres (cells x cell_m, the cell size of z). The neighbours are a brute force's:
/// data cells within radius_m sorted by (distance, row, col), first k. Data cells are copied; infinite cells
/// are copied but never used; holes with nothing in reach stay NaN (unfilled). Same bits for any thread
/// count; `out` must not overlap `z`. Ring search skipping empty rings and runs of holes: per hole
/// O(rings searched + cells offered), plus a 12-byte-per-cell index. Details in docs/rasters.md.
/// @throws invalid_input if shapes differ, k < 1, power or cell_m <= 0, radius_m < 0, run.threads < 0, out
/// overlaps z, or z has no finite cell ("idw_fill: z has no finite cell to interpolate from"); cancelled if
/// run.progress returns false.
template <raster_input In, class Out>
requires raster_output_of<Out, float> && std::is_floating_point_v<typename In::value_type> idw_fill_counts
idw_fill(const In& z, Out&& out, double cell_m, const idw_fill_options& opt = {});

/// Returning form of idw_fill: a new raster<float> with the holes of `z` (cells of cell_m metres) filled,
/// and the counts.
template <raster_input In>
requires std::is_floating_point_v<typename In::value_type> idw_fill_result idw_fill(const In& z, double cell_m,
                                                                                    const idw_fill_options& opt = {});

/// Reach of idw_fill in cells: the largest whole number of cells n with n <= radius_m / cell_m + 1e-9 (idw_fill's
/// own inclusive radius test, so 0.3 m at 0.1 m cells is 3); every data cell a hole can use lies within n cells
/// (Chebyshev) of it, so a tile computed with a halo of n cells fills its core exactly. O(1).
/// @throws invalid_input if radius_m is 0 (unlimited: idw_fill is then not local; give a radius) or not finite
/// and > 0, or cell_m is not finite and > 0.
inline std::ptrdiff_t idw_fill_reach_cells(const idw_fill_options& opt, double cell_m);

}  // namespace lidarfx

#include "lidarfx/kernels/interpolate/detail/idw_fill_impl.hpp"
