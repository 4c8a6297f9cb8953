// SPDX-License-Identifier: Apache-2.0
// rasterize: per-cell min/max elevation, mean intensity, point count and return statistics of a point cloud,
// and raster_accumulator, the streaming form. Implementation in detail/rasterize_impl.hpp.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "lidarfx/core/grid.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/point_cloud.hpp"
#include "lidarfx/core/raster.hpp"

namespace lidarfx {

/// Which returns of each laser pulse rasterize bins.
enum class return_selection {
    all,    ///< every return (the default)
    first,  ///< return_number == 1: the top surface (a DSM of canopy and roofs)
    last,   ///< return_number == number_of_returns: the lowest surface each pulse reached
};

/// ASPRS class codes (0..255) rasterize bins: a point is kept when `include` is empty or holds its class,
/// and `exclude` does not hold it. Both empty (the default) keep every point; e.g. include = {2} bins the
/// ground of a classified file, exclude = {7, 18} drops noise.
struct class_selection {
    std::vector<int> include = {};  ///< codes to keep (empty = all); each in [0, 255]
    std::vector<int> exclude = {};  ///< codes to drop; each in [0, 255]

    bool selects_all() const noexcept { return include.empty() && exclude.empty(); }
};

/// Settings of rasterize.
struct rasterize_options {
    std::size_t chunk_points = 1 << 20;  ///< points per work unit (progress step and parallel split); >= 1
    /// Returns binned (default all). first / last need return numbers (has_return_number; last also
    /// has_number_of_returns) in the cloud type.
    return_selection returns = return_selection::all;
    class_selection classes = {};  ///< classes binned (default all); a choice needs has_classification
    execution run = {};            ///< threads, progress, cancellation (core/parallel.hpp); same result
};

/// The per-cell rasters of a point cloud, all on the grid `g`, plus what happened to the points.
struct rasterize_result {
    grid g;                                 ///< georeferencing shared by every raster below
    raster<float> min_z, max_z;             ///< lowest / highest z in the cell, metres; NaN where no point
    raster<float> mean_intensity;           ///< mean intensity of the cell's points; 0 where no point (dropout)
    raster<std::uint32_t> count;            ///< points in the cell
    raster<std::uint8_t> dropout;           ///< 1 = no return in the cell
    raster<std::uint8_t> multiple_returns;  ///< 1 = some point of the cell has number_of_returns > 1
    /// Points of the cell whose pulse had more than one return (number_of_returns > 1): leaves and branches
    /// split a pulse, roofs rarely do (vegetation_by_returns)
    raster<std::uint32_t> multiple_return_count;
    std::size_t points_used = 0;        ///< points written into a cell
    std::size_t points_outside = 0;     ///< finite points outside the grid (ignored)
    std::size_t points_nan = 0;         ///< points with a NaN or infinite x, y or z (ignored)
    std::size_t points_unselected = 0;  ///< points left out by returns / classes (never binned or counted above)
};

namespace detail {
struct cell_stats;          // one cell's running statistics (detail/rasterize_impl.hpp)
struct accumulator_access;  // what rasterize needs beyond raster_accumulator's public interface
}  // namespace detail

/// Streaming per-cell statistics on a fixed grid. Add points in chunks (any split, any order), merge
/// partial accumulators built elsewhere (other threads, other files of a tile), then finish(): every
/// sequence of add/merge over the same points gives bit-identical rasters, because min/max are
/// order-free and intensities are summed as exact integers (see rasterize for the conventions).
///
/// Memory follows the data. The statistics (24 bytes per cell) start in tiles of 32 x 32 cells (24 KiB;
/// 1024 x 1 or 1 x 1024 on grids narrower than 32 cells), allocated when a point first falls in one, under
/// a directory of 8 bytes per tile of the grid: 1,000 points over 5000 x 5000 cells hold at most 1,000
/// tiles (24 MB) instead of 600 MB. Once as many points were added as the grid has cells, or half the
/// tiles are held, or an eighth of them with fewer than 4 points per tile held (points scattered at random
/// over the grid, which would soon hold every tile), the accumulator turns dense (one row-major array of every
/// cell, the faster layout for dense data; then 24 bytes per cell, no more than 24 bytes per point added, twice
/// the tiles held, or eight times the tiles held for scattered points).
/// The layout never changes a result.
class raster_accumulator {
public:
    /// Empty statistics on `g`; allocates only the tile directory (8 bytes per 1024 cells).
    /// @throws invalid_input if g is invalid (see grid::validate: more than 2^40 cells included).
    explicit raster_accumulator(const grid& g);
    raster_accumulator(const raster_accumulator& other);  ///< a deep copy of the statistics
    raster_accumulator(raster_accumulator&&) noexcept = default;
    raster_accumulator& operator=(const raster_accumulator& other);
    raster_accumulator& operator=(raster_accumulator&&) noexcept = default;
    ~raster_accumulator() = default;

    /// Adds every point of `cloud`.
    template <point_cloud C>
    void add(const C& cloud);

    /// Adds points [first, last) of `cloud`. O(last - first), plus 24 KiB for each tile touched first (and
    /// O(cells) once, when the accumulator turns dense).
    /// @throws invalid_input unless first <= last <= cloud.size(); std::bad_alloc if storage cannot be
    /// allocated (points of the block of 256 at hand are then lost).
    template <point_cloud C>
    void add(const C& cloud, std::size_t first, std::size_t last);

    /// Adds the statistics of `other` (same grid), as if its points had been added here.
    /// O(tiles of the grid + cells other holds). @throws invalid_input if other.grid differs from this
    /// grid; std::bad_alloc if storage cannot be allocated (this accumulator is then partly merged).
    void merge(const raster_accumulator& other);

    /// The rasters of every point added so far (the accumulator is unchanged). O(cells): every cell of the
    /// six rasters is written once; cells no point fell in are written as empty cells in runs.
    rasterize_result finish() const;

    const grid& target_grid() const noexcept { return g_; }  ///< the grid the points are binned on
    std::size_t points_used() const noexcept { return points_used_; }
    std::size_t points_outside() const noexcept { return points_outside_; }
    std::size_t points_nan() const noexcept { return points_nan_; }
    /// Cells of statistics held: every cell of the grid once dense, else 1024 (fewer on grids under 1024
    /// cells) per tile a point fell in.
    std::size_t allocated_cells() const noexcept;

private:
    // The layout and its helpers; defined, with comments, in detail/rasterize_impl.hpp.
    friend struct detail::accumulator_access;
    using tile_ptr = std::unique_ptr<detail::cell_stats[]>;
    static constexpr int tile_bits = 10;  // a tile holds 2^10 cells: 32 x 32, or 1024 x 1 on a thin grid
    /// Both forms of add bin in two passes per block of points: locate the cells (and prefetch them), then
    /// update them, so that the cache misses of randomly ordered points overlap instead of stalling one by one.
    static constexpr std::size_t block = 256;

    static void fold(detail::cell_stats& s, const detail::cell_stats& o) noexcept;
    std::size_t tile_cells() const noexcept { return std::size_t{1} << (row_bits_ + col_bits_); }
    std::ptrdiff_t tile_height() const noexcept { return std::ptrdiff_t{1} << row_bits_; }
    bool dense_is_due() const noexcept;
    tile_ptr copy_tile(const detail::cell_stats* from) const;
    detail::cell_stats* new_tile(std::size_t t);  // never inlined: kept off the hot loop of add_sparse
    void fold_tile_into_dense(std::size_t t, const detail::cell_stats* tile) noexcept;
    void make_dense();
    template <point_cloud C>
    void add_dense(const C& cloud, std::size_t first, std::size_t last);
    template <point_cloud C>
    void add_sparse(const C& cloud, std::size_t first, std::size_t last);
    template <point_cloud C>
    static void update(detail::cell_stats& s, float z, const C& cloud, std::size_t i);
    void require_same_grid(const raster_accumulator& other, const char* function) const;
    void merge_counters(const raster_accumulator& other) noexcept;
    void merge_dense_rows(const raster_accumulator& other, std::ptrdiff_t r0, std::ptrdiff_t r1) noexcept;
    template <class Other>
    std::size_t merge_tiles(Other& other, std::ptrdiff_t tr0, std::ptrdiff_t tr1);
    rasterize_result unfinished() const;
    static void finish_cells(rasterize_result& out, std::size_t i0, std::size_t n,
                             const detail::cell_stats* cells) noexcept;
    void finish_rows(rasterize_result& out, std::ptrdiff_t r0, std::ptrdiff_t r1) const;

    grid g_;
    int row_bits_ = 0, col_bits_ = 0;  // a tile is 2^row_bits_ x 2^col_bits_ cells, row-major
    std::ptrdiff_t tile_rows_ = 0, tile_cols_ = 0;
    std::vector<tile_ptr> tiles_;  // tile (tr, tc) at tr * tile_cols_ + tc; null until touched
    std::size_t held_tiles_ = 0;   // non-null tiles
    // Every cell, row-major, once is_dense_; in the rasters' blocks (huge pages: a dense grid of hundreds of MB
    // costs its first touch page by page otherwise).
    std::vector<detail::cell_stats, detail::raster_allocator<detail::cell_stats>> dense_;
    bool is_dense_ = false;
    std::size_t points_used_ = 0, points_outside_ = 0, points_nan_ = 0;
};

/// Bins a point cloud on `g` (dissertation 2.3.1): per cell min and max z (float, saturating), mean
/// intensity, count, dropout (no return) and multiple returns (a point with number_of_returns > 1). Points
/// go to grid::cell_of (far east/south edge -> last column/row); outside and NaN/infinite points are
/// counted, never written. Intensities are rounded to multiples of 2^-16 (clamped to +-2^24, NaN as 0) and
/// summed as 64-bit integers, exact for LAS intensities: any chunking, order or thread count gives the
/// same bits. O(points + cells). Memory: the result's 18 bytes per cell, and per worker thread the
/// statistics of raster_accumulator (24 KiB per tile of 32 x 32 cells holding a point, 24 bytes per cell
/// when the points outnumber the cells). Details in docs/rasters.md.
/// Progress is reported after each chunk of chunk_points points (and once more after merging, with threads).
/// Selection: only the returns opt.returns and the classes opt.classes are binned (the others are counted
/// in points_unselected); e.g. returns = first gives the DSM (max_z) and classes.include = {2} the ground
/// of a classified file (min_z), in two calls. The default selects every point and costs nothing; a
/// selection first gathers the kept points' indices (one pass, 8 bytes per kept point).
/// @throws invalid_input on an invalid grid, chunk_points == 0, run.threads < 0, or a selection the cloud
/// type cannot serve (returns = first or last without return numbers, last without number_of_returns, classes
/// without classification codes) or a class code outside [0, 255]; cancelled if run.progress returns false.
template <point_cloud C>
rasterize_result rasterize(const C& cloud, const grid& g, const rasterize_options& opt = {});

/// Bounding box of the points of `cloud` whose x, y and z are all finite (others are ignored); pass it to
/// snapped_grid(bounds, cell_m) for the usual survey grid. O(points).
/// @throws invalid_input if no point has finite x, y and z (an empty cloud included).
template <point_cloud C>
bounds bounds_of(const C& cloud);

}  // namespace lidarfx

#include "lidarfx/kernels/points/detail/rasterize_impl.hpp"
