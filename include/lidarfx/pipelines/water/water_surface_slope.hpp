// SPDX-License-Identifier: Apache-2.0
// water_surface_slope: the slope of the least-squares plane through the lowest returns around each cell.
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

namespace detail {
class slope_scratch;  // row buffers of the slope computation (detail/water_surface_slope_impl.hpp)
}  // namespace detail

/// Options of water_surface_slope.
struct water_surface_slope_options {
    int radius_cells = 3;        ///< the plane is fitted to the (2 r + 1)² window around a cell (7 × 7: with 2-3 cm
                                 ///< range noise its slope is known to about 0.1 % at 2 m cells), >= 1. Default 3
    std::size_t min_cells = 12;  ///< fewer cells with a return in the window give NaN (unknown), >= 3. Default 12
    double band_m = 0.15;        ///< only returns within this of the cell's own min z are fitted (water next to a
                                 ///< bank sees the water, not the bank; on a beach rising 1-6 % the band still
                                 ///< spans several cells), metres, > 0. Default 0.15 (the level gate)
};

/// Slope of the water surface test: per cell, the magnitude of the gradient of the least-squares plane
/// z = a + b·x + c·y through the min z of the (2·radius_cells + 1)² window (clipped at the raster border)
/// that lie within band_m of the cell's own, sqrt(b² + c²) in metres per metre (0 = level); NaN where the
/// cell has no return, the window holds fewer than min_cells such returns, or they lie on a line. A water
/// surface is level to the range noise (a river falls a few mm per metre at most); beaches, banks and
/// meadows rising from the water are not. cell_m in metres.
/// O(cells · (2·radius_cells + 1)²), vectorized along rows, the window unrolled for radius_cells <= 4.
/// `run`: threads (rows are independent; its progress is not called); never changes the result.
/// @throws invalid_input on cell_m <= 0 or options or run out of range.
inline raster<float> water_surface_slope(raster_view<const float> min_z, double cell_m,
                                         const water_surface_slope_options& opt = {}, const execution& run = {});

/// water_surface_slope computed where it is read: a tile of 16 rows × 64 columns on the first read of one
/// of its cells. Its readers (the growth's level gate, the flat and bridge seeds' slope tests) look only
/// around water, often a fifth of a survey or less. The values are those of water_surface_slope bit for bit.
/// Only the tiles read take memory (in chunks of 256 tiles, 1 MiB). Keeps a view of min z (keep it alive).
/// Threads may read it at once (the parallel growth of grow_waterbodies): a tile is computed once, by the first
/// thread that reads it, while threads reading that tile wait for it; other tiles are computed at the same time,
/// and reading a computed tile takes no lock.
/// @throws invalid_input on cell_m <= 0 or options out of range.
class lazy_water_surface_slope {
public:
    static constexpr std::ptrdiff_t tile_rows = 16, tile_cols = 64;

    /// @throws invalid_input on cell_m <= 0 or options out of range.
    lazy_water_surface_slope(raster_view<const float> min_z, double cell_m,
                             const water_surface_slope_options& opt = {});
    lazy_water_surface_slope(const lazy_water_surface_slope&) = delete;  // readers keep its address
    lazy_water_surface_slope& operator=(const lazy_water_surface_slope&) = delete;

    std::ptrdiff_t rows() const noexcept { return min_z_.rows(); }
    std::ptrdiff_t cols() const noexcept { return min_z_.cols(); }

    /// The slope of cell (r, c), m/m (NaN: unknown); computes its tile on first use.
    float operator()(std::ptrdiff_t r, std::ptrdiff_t c);

private:
    static constexpr std::size_t chunk_tiles = 256, tile_size = tile_rows * tile_cols;

    static constexpr std::int32_t unread = -1, computing = -2;  // a tile's slot before it holds one

    float* tile_cells(std::int32_t slot) noexcept;
    std::int32_t publish(std::atomic<std::int32_t>& tile, std::ptrdiff_t tr, std::ptrdiff_t tc);  // its slot
    std::int32_t compute(std::ptrdiff_t tr, std::ptrdiff_t tc);  // a new slot, with the tile's cells

    raster_view<const float> min_z_;
    double cell_m_;
    water_surface_slope_options opt_;
    std::ptrdiff_t tiles_across_;
    std::vector<std::atomic<std::int32_t>> tile_;   // each tile's slot in the chunks, or unread, or computing
    std::vector<std::unique_ptr<float[]>> chunks_;  // as many as the tiles can fill, allocated as they fill
    std::mutex reserve_;                            // held while a slot is taken (used_, chunks_)
    std::size_t used_ = 0;
};

/// The surface slope a step reads: a raster's cells (water_surface_slope), a lazy_water_surface_slope, or
/// none (empty). Converts implicitly from either; a view: keep what it shows alive while it is read.
class surface_slope_source {
public:
    surface_slope_source() = default;
    surface_slope_source(raster_view<const float> cells) noexcept : cells_(cells) {}
    surface_slope_source(raster_view<float> cells) noexcept : cells_(cells) {}
    surface_slope_source(const raster<float>& cells) noexcept : cells_(cells) {}
    surface_slope_source(raster<float>&&) = delete;  // would show a temporary's cells
    surface_slope_source(lazy_water_surface_slope& lazy) noexcept : lazy_(&lazy) {}

    std::ptrdiff_t rows() const noexcept { return lazy_ ? lazy_->rows() : cells_.rows(); }
    std::ptrdiff_t cols() const noexcept { return lazy_ ? lazy_->cols() : cells_.cols(); }
    bool empty() const noexcept { return rows() == 0 || cols() == 0; }
    /// The slope of cell (r, c), m/m (NaN: unknown).
    float operator()(std::ptrdiff_t r, std::ptrdiff_t c) const { return lazy_ ? (*lazy_)(r, c) : cells_(r, c); }

private:
    raster_view<const float> cells_;
    lazy_water_surface_slope* lazy_ = nullptr;
};

}  // namespace lidarfx

#include "lidarfx/pipelines/water/detail/water_surface_slope_impl.hpp"
