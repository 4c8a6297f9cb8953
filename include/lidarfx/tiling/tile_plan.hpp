// SPDX-License-Identifier: Apache-2.0
// tile_plan: a tiling of a survey's grid into square cores with halos, the files each tile must read, and the
// memory the run will need (docs/scale.md).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/grid.hpp"

namespace lidarfx {

/// One file of a survey as its header describes it: the extent of its points and how many there are.
struct survey_file_extent {
    bounds box;                ///< extent of the file's points (LAS header min/max), projected metres
    std::uint64_t points = 0;  ///< number of points in the file
};

/// Settings of make_tile_plan. The byte counts are the host's model of its own memory use (docs/scale.md);
/// the defaults fit `lidarfx water` (stage B's raster stack, a raster_accumulator, LAS chunk buffers).
struct tile_plan_options {
    /// Core edge in metres, rounded to whole cells (at least 1 cell); 0 = the largest edge that fits
    /// memory_budget_bytes (the whole grid in one tile when there is no budget). Finite, >= 0.
    double tile_edge_m = 0;
    std::ptrdiff_t halo_cells = 0;          ///< halo around each core, cells (the reach of the local steps), >= 0
    std::uint64_t memory_budget_bytes = 0;  ///< bytes the run may use; 0 = no limit
    double bytes_per_cell = 64;             ///< bytes kept per survey cell for the whole run (stage B's rasters), >= 0
    double bytes_per_tile_cell = 48;        ///< bytes per cell (halo included) of a tile in flight (accumulator), >= 0
    double bytes_per_point = 40;            ///< bytes per point of a chunk in flight (read buffer), >= 0
    std::size_t chunk_points = 1 << 20;     ///< points read at a time by each tile in flight
    int tiles_in_flight = 1;                ///< tiles worked on at once (threads or ranks), >= 1
};

/// One tile of a plan.
struct survey_tile {
    std::size_t index = 0;              ///< position in tile_plan::tiles (row-major over the tile lattice)
    cell_box core;                      ///< cells this tile owns; the cores partition the survey grid
    cell_box with_halo;                 ///< core grown by halo_cells on every side, clipped to the grid
    std::vector<std::size_t> files;     ///< ascending indices of the files that may hold a point in with_halo
    std::uint64_t points_estimate = 0;  ///< points expected in the core (uniform density in each file's box)
};

/// A tiling of a survey grid (make_tile_plan).
struct tile_plan {
    grid g;                          ///< the survey grid that is tiled
    std::ptrdiff_t tile_cells = 1;   ///< core edge, cells (the last row / column of tiles may be smaller)
    std::ptrdiff_t tile_rows = 0;    ///< tiles from north to south
    std::ptrdiff_t tile_cols = 0;    ///< tiles from west to east
    std::vector<survey_tile> tiles;  ///< tile_rows x tile_cols tiles, row-major
    double peak_bytes_estimate = 0;  ///< the memory model's peak for this plan, bytes (see make_tile_plan)
};

/// Tiles the survey grid `g` (the survey lattice, e.g. snapped_grid of the union of the files' extents) into
/// square cores of tile_cells cells, row-major, the last row and column of tiles cut by the grid border, so
/// the cores partition g. Each tile's with_halo is its core grown by halo_cells and clipped to g. A file is
/// listed for a tile when the cell range its box can land in (grid::cell_of on the box corners; exact because
/// cell coordinates are monotone in x and y) meets with_halo: every file that may hold a point of with_halo
/// is listed, provided its header box holds all its points. Tiles that no file touches are kept (empty: their
/// cells are no data, as in an untiled run). points_estimate = sum over files of points x (area of the file
/// box inside the core's extent / area of the file box). Memory model, bytes:
///   peak = g cells x bytes_per_cell + tiles_in_flight x (largest with_halo cells x bytes_per_tile_cell
///          + chunk_points x bytes_per_point).
/// O(tiles x files). @throws invalid_input if g is invalid or empty, an option is negative or not finite,
/// tiles_in_flight < 1, a file box is not finite with min <= max, or peak exceeds memory_budget_bytes (the
/// message names the largest tile edge that fits, or, when even 1-cell tiles do not fit, the cell size at
/// which the survey grid would).
inline tile_plan make_tile_plan(const grid& g, std::span<const survey_file_extent> files,
                                const tile_plan_options& opt = {});

/// Who reads one file of a tile plan (assign_file_readers).
struct file_readers {
    std::size_t home = 0;                ///< the tile that reads the file; tiles.size() when no tile lists it
    std::vector<std::size_t> handed_to;  ///< tiles next to home that home hands their points instead
};

/// Lets most files be read once instead of by every tile they touch. A file whose box ends on a tile border
/// (files cut along the tile lines, points on the line, or a box grown for rounding) is listed by up to four
/// tiles, and each would read all of it for a sliver of cells. For each file: home = the listing tile whose
/// with_halo shares the most cells with the file's cell range (ties: the lowest index); a listing tile next
/// to home (the 8 neighbours on the tile lattice) is handed its points by home when its share is small:
/// points x shared cells / cells of the range <= max_handed_points (uniform density, as points_estimate);
/// every other listing tile reads the file itself. A host keeps a tile open until the homes of its handed
/// files have read them: with tiles started in index order, that is at most tile_cols + 1 tiles beyond those
/// in flight. handed_per_tile (when not null) gets, for each tile, the sum of the shares handed to it, points
/// (uniform density): what a host holds for the tile until it is finished. max_handed_points = 0 hands
/// nothing. O(tiles x files). @throws invalid_input if the plan lists a file index >= files.size().
inline std::vector<file_readers> assign_file_readers(const tile_plan& plan, std::span<const survey_file_extent> files,
                                                     std::uint64_t max_handed_points,
                                                     std::vector<double>* handed_per_tile = nullptr);

/// The tile whose core holds world point (x, y): the cell is found on the survey grid, plan.g.cell_of(x, y)
/// (never on a tile's own window grid, whose corner rounds differently), so every point goes to exactly one
/// tile and lands in the very cell an untiled run gives it. nullopt when the point is outside the grid or NaN.
/// O(1).
inline std::optional<std::size_t> tile_index_of(const tile_plan& plan, double x, double y) noexcept;

}  // namespace lidarfx

#include "lidarfx/tiling/detail/tile_plan_impl.hpp"
