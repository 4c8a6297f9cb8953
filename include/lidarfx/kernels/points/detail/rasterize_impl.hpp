// SPDX-License-Identifier: Apache-2.0
// Implementation of kernels/points/rasterize.hpp: raster_accumulator's tiled and dense layouts, the point
// selection, and rasterize's parallel chunks and merge. Included at the end of rasterize.hpp, after the
// declarations it defines; not a public header.
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/grid.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/point_cloud.hpp"
#include "lidarfx/core/raster.hpp"

namespace lidarfx {

namespace detail {

/// Running statistics of one cell (24 bytes; one cache line holds most cells whole).
struct cell_stats {
    float min_z = std::numeric_limits<float>::infinity();
    float max_z = -std::numeric_limits<float>::infinity();
    std::uint32_t count = 0;
    std::uint32_t multiple = 0;       // points whose pulse had number_of_returns > 1
    std::uint64_t intensity_sum = 0;  // sum of intensities in units of 2^-16, two's complement, modulo 2^64
};

/// Intensities are summed as integers of 2^-16 so that every chunking and order gives the same sum.
inline constexpr double intensity_units_per_1 = 65536.0;
inline constexpr double intensity_limit = 16777216.0;  // |intensity| clamps to 2^24

/// `v` rounded (half away from zero) to a multiple of 2^-16, clamped to +-2^24, NaN as 0; in 2^-16 units.
inline std::uint64_t intensity_fixed(double v) noexcept
{
    if (!(std::abs(v) <= intensity_limit)) v = std::isnan(v) ? 0.0 : std::copysign(intensity_limit, v);
    const double scaled = v * intensity_units_per_1;
    return static_cast<std::uint64_t>(static_cast<std::int64_t>(scaled + (scaled >= 0 ? 0.5 : -0.5)));
}

struct accumulator_access;

/// z as the accumulator keeps it: saturated to the float range and rounded to float, a zero (-0, or a tiny
/// negative z that rounds to -0) as +0. Storing the float of the extreme equals taking the extreme of the
/// floats (both steps are monotonic), and without the sign of zero min/max cannot depend on which of two
/// zeros came first.
inline float stored_z(double z) noexcept
{
    constexpr auto float_max = static_cast<double>(std::numeric_limits<float>::max());
    return static_cast<float>(std::clamp(z, -float_max, float_max)) + 0.0f;
}

}  // namespace detail

inline raster_accumulator::raster_accumulator(const grid& g) : g_(g)
{
    g.validate("raster_accumulator");
    const auto bits = [](std::ptrdiff_t n) {  // ceil(log2(n)), at most tile_bits
        int k = 0;
        while (k < tile_bits && (std::ptrdiff_t{1} << k) < n) ++k;
        return k;
    };
    // Square tiles, unless the grid is thinner than a tile: then the tile stretches along the grid.
    row_bits_ = std::min(tile_bits / 2, bits(g.rows));
    col_bits_ = std::min(tile_bits - row_bits_, bits(g.cols));
    row_bits_ = std::min(tile_bits - col_bits_, bits(g.rows));
    tile_rows_ = (g.rows + (std::ptrdiff_t{1} << row_bits_) - 1) >> row_bits_;
    tile_cols_ = (g.cols + (std::ptrdiff_t{1} << col_bits_) - 1) >> col_bits_;
    tiles_.resize(static_cast<std::size_t>(tile_rows_ * tile_cols_));
}

inline raster_accumulator::raster_accumulator(const raster_accumulator& other)
    : g_(other.g_),
      row_bits_(other.row_bits_),
      col_bits_(other.col_bits_),
      tile_rows_(other.tile_rows_),
      tile_cols_(other.tile_cols_),
      tiles_(other.tiles_.size()),
      held_tiles_(other.held_tiles_),
      dense_(other.dense_),
      is_dense_(other.is_dense_),
      points_used_(other.points_used_),
      points_outside_(other.points_outside_),
      points_nan_(other.points_nan_)
{
    for (std::size_t t = 0; t < tiles_.size(); ++t) {
        if (other.tiles_[t]) tiles_[t] = copy_tile(other.tiles_[t].get());
    }
}
inline raster_accumulator& raster_accumulator::operator=(const raster_accumulator& other)
{
    if (this != &other) *this = raster_accumulator(other);
    return *this;
}
template <point_cloud C>
void raster_accumulator::add(const C& cloud)
{
    add(cloud, 0, static_cast<std::size_t>(cloud.size()));
}

template <point_cloud C>
void raster_accumulator::add(const C& cloud, std::size_t first, std::size_t last)
{
    const auto n = static_cast<std::size_t>(cloud.size());
    detail::require(first <= last && last <= n, "raster_accumulator::add", [&] {
        return detail::concat("range [first, last) must lie in [0, ", n, "] (got [", first, ", ", last, "))");
    });
    // Sparse: in steps, so that the switch to the dense layout comes soon after it is due.
    constexpr std::size_t sparse_step = std::size_t{1} << 12;
    for (std::size_t base = first; base < last;) {
        if (!is_dense_ && dense_is_due()) make_dense();
        if (is_dense_) {
            add_dense(cloud, base, last);
            return;
        }
        const std::size_t end = base + std::min(sparse_step, last - base);
        add_sparse(cloud, base, end);
        base = end;
    }
}

inline void raster_accumulator::merge(const raster_accumulator& other)
{
    require_same_grid(other, "raster_accumulator::merge");
    if (other.is_dense_ && !is_dense_) make_dense();
    if (other.is_dense_)
        merge_dense_rows(other, 0, g_.rows);
    else
        held_tiles_ += merge_tiles(other, 0, tile_rows_);
    merge_counters(other);
    if (!is_dense_ && dense_is_due()) make_dense();
}

inline rasterize_result raster_accumulator::finish() const
{
    rasterize_result out = unfinished();
    finish_rows(out, 0, g_.rows);
    return out;
}

inline std::size_t raster_accumulator::allocated_cells() const noexcept
{
    return is_dense_ ? dense_.size() : held_tiles_ * tile_cells();
}

inline void raster_accumulator::fold(detail::cell_stats& s, const detail::cell_stats& o) noexcept
{
    s.min_z = std::min(s.min_z, o.min_z);
    s.max_z = std::max(s.max_z, o.max_z);
    s.count += o.count;
    s.multiple += o.multiple;
    s.intensity_sum += o.intensity_sum;
}

inline bool raster_accumulator::dense_is_due() const noexcept
{
    // Points scattered over the grid (fewer than 4 per tile held, an eighth of the tiles held: points in random
    // order, not the local order of a flight line or a tiled file) would soon hold every tile, one point at a time.
    const bool scattered = 8 * held_tiles_ >= tiles_.size() && points_used_ < 4 * held_tiles_;
    return points_used_ >= static_cast<std::size_t>(g_.size()) || 2 * held_tiles_ >= tiles_.size() || scattered;
}

inline raster_accumulator::tile_ptr raster_accumulator::copy_tile(const detail::cell_stats* from) const
{
    tile_ptr t(new detail::cell_stats[tile_cells()]);
    std::copy(from, from + tile_cells(), t.get());
    return t;
}

/// Allocates tile t (empty statistics) on the first point that falls in it.
#if defined(__GNUC__) || defined(__clang__)
__attribute__((noinline))
#endif
inline detail::cell_stats*
raster_accumulator::new_tile(std::size_t t)
{
    tiles_[t] = std::make_unique<detail::cell_stats[]>(tile_cells());
    ++held_tiles_;
    return tiles_[t].get();
}

/// Folds tile t (of this grid's tile layout) into the dense array.
inline void raster_accumulator::fold_tile_into_dense(std::size_t t, const detail::cell_stats* tile) noexcept
{
    const std::ptrdiff_t r0 = static_cast<std::ptrdiff_t>(t) / tile_cols_ << row_bits_;
    const std::ptrdiff_t c0 = static_cast<std::ptrdiff_t>(t) % tile_cols_ << col_bits_;
    const std::ptrdiff_t nr = std::min(tile_height(), g_.rows - r0);
    const std::ptrdiff_t nc = std::min(std::ptrdiff_t{1} << col_bits_, g_.cols - c0);
    for (std::ptrdiff_t i = 0; i < nr; ++i) {
        detail::cell_stats* to = dense_.data() + (r0 + i) * g_.cols + c0;
        const detail::cell_stats* from = tile + (i << col_bits_);
        for (std::ptrdiff_t j = 0; j < nc; ++j) fold(to[j], from[j]);
    }
}

/// Moves every tile into one row-major array of all cells and drops the tiles. O(cells).
inline void raster_accumulator::make_dense()
{
    dense_.resize(static_cast<std::size_t>(g_.size()));
    for (std::size_t t = 0; t < tiles_.size(); ++t) {
        if (tiles_[t]) fold_tile_into_dense(t, tiles_[t].get());
    }
    std::vector<tile_ptr>().swap(tiles_);
    held_tiles_ = 0;
    is_dense_ = true;
}

template <point_cloud C>
void raster_accumulator::add_dense(const C& cloud, std::size_t first, std::size_t last)
{
    constexpr std::ptrdiff_t outside_cell = -1, nan_point = -2;
    std::ptrdiff_t at[block];
    float zs[block];
    const grid g = g_;
    detail::cell_stats* cells = dense_.data();
    std::size_t used = 0, outside = 0, nan = 0;
    for (std::size_t base = first; base < last; base += block) {
        const std::size_t m = std::min(block, last - base);
        for (std::size_t j = 0; j < m; ++j) {
            const double x = cloud.x(base + j), y = cloud.y(base + j), z = cloud.z(base + j);
            if (!(std::isfinite(x) && std::isfinite(y) && std::isfinite(z))) {
                at[j] = nan_point;
                continue;
            }
            zs[j] = detail::stored_z(z);
            const auto cell = g.cell_of(x, y);
            at[j] = cell ? cell->row * g.cols + cell->col : outside_cell;
            if (cell) detail::prefetch_write(cells + at[j]);
        }
        for (std::size_t j = 0; j < m; ++j) {
            if (at[j] < 0) {
                ++(at[j] == nan_point ? nan : outside);
                continue;
            }
            update(cells[at[j]], zs[j], cloud, base + j);
            ++used;
        }
    }
    points_used_ += used;
    points_outside_ += outside;
    points_nan_ += nan;
}

template <point_cloud C>
void raster_accumulator::add_sparse(const C& cloud, std::size_t first, std::size_t last)
{
    detail::cell_stats* at[block];
    float zs[block];
    const grid g = g_;
    const int row_bits = row_bits_, col_bits = col_bits_;
    const std::ptrdiff_t tile_cols = tile_cols_, mask_r = (std::ptrdiff_t{1} << row_bits) - 1,
                         mask_c = (std::ptrdiff_t{1} << col_bits) - 1;
    std::size_t used = 0, outside = 0, nan = 0;
    for (std::size_t base = first; base < last; base += block) {
        const std::size_t m = std::min(block, last - base);
        for (std::size_t j = 0; j < m; ++j) {
            at[j] = nullptr;
            const double x = cloud.x(base + j), y = cloud.y(base + j), z = cloud.z(base + j);
            if (!(std::isfinite(x) && std::isfinite(y) && std::isfinite(z))) {
                ++nan;
                continue;
            }
            zs[j] = detail::stored_z(z);
            const auto cell = g.cell_of(x, y);
            if (!cell) {
                ++outside;
                continue;
            }
            const std::ptrdiff_t r = cell->row, c = cell->col;
            const auto t = static_cast<std::size_t>((r >> row_bits) * tile_cols + (c >> col_bits));
            detail::cell_stats* tile = tiles_[t].get();
            if (!tile) [[unlikely]]
                tile = new_tile(t);
            at[j] = tile + (((r & mask_r) << col_bits) | (c & mask_c));
            detail::prefetch_write(at[j]);
        }
        for (std::size_t j = 0; j < m; ++j) {
            if (!at[j]) continue;
            update(*at[j], zs[j], cloud, base + j);
            ++used;
        }
    }
    points_used_ += used;
    points_outside_ += outside;
    points_nan_ += nan;
}

template <point_cloud C>
void raster_accumulator::update(detail::cell_stats& s, float z, const C& cloud, std::size_t i)
{
    s.min_z = std::min(s.min_z, z);
    s.max_z = std::max(s.max_z, z);
    ++s.count;
    s.intensity_sum += detail::intensity_fixed(intensity_of(cloud, i));
    s.multiple += static_cast<std::uint32_t>(number_of_returns_of(cloud, i) > 1);
}

inline void raster_accumulator::require_same_grid(const raster_accumulator& other, const char* function) const
{
    detail::require(other.g_ == g_, function, "other accumulator must be on the same grid");
}

inline void raster_accumulator::merge_counters(const raster_accumulator& other) noexcept
{
    points_used_ += other.points_used_;
    points_outside_ += other.points_outside_;
    points_nan_ += other.points_nan_;
}

/// Folds rows [r0, r1) of the dense `other` into this dense accumulator.
inline void raster_accumulator::merge_dense_rows(const raster_accumulator& other, std::ptrdiff_t r0,
                                                 std::ptrdiff_t r1) noexcept
{
    const auto begin = static_cast<std::size_t>(r0 * g_.cols), end = static_cast<std::size_t>(r1 * g_.cols);
    for (std::size_t i = begin; i < end; ++i) fold(dense_[i], other.dense_[i]);
}

/// Folds the tiles of tile rows [tr0, tr1) of the sparse `other` into this accumulator: into the dense
/// array, onto a tile both hold, or as a copy (taken, when `other` is not const) of a tile only other
/// holds. Returns the number of tiles this accumulator newly holds (held_tiles_ is left to the caller).
template <class Other>
std::size_t raster_accumulator::merge_tiles(Other& other, std::ptrdiff_t tr0, std::ptrdiff_t tr1)
{
    constexpr bool take = !std::is_const_v<Other>;
    const std::size_t n = tile_cells();
    std::size_t added = 0;
    for (auto t = static_cast<std::size_t>(tr0 * tile_cols_); t < static_cast<std::size_t>(tr1 * tile_cols_); ++t) {
        auto& theirs = other.tiles_[t];
        if (!theirs) continue;
        if (is_dense_) {
            fold_tile_into_dense(t, theirs.get());
            continue;
        }
        tile_ptr& mine = tiles_[t];
        if (!mine) {
            if constexpr (take)
                mine = std::move(theirs);
            else
                mine = copy_tile(theirs.get());
            ++added;
            continue;
        }
        for (std::size_t i = 0; i < n; ++i) fold(mine[i], theirs[i]);
    }
    return added;
}

/// The result with its counters set and rasters allocated (not initialized); finish_rows fills them.
inline rasterize_result raster_accumulator::unfinished() const
{
    const auto rows = g_.rows, cols = g_.cols;
    return {g_,
            raster<float>(rows, cols, uninitialized),
            raster<float>(rows, cols, uninitialized),
            raster<float>(rows, cols, uninitialized),
            raster<std::uint32_t>(rows, cols, uninitialized),
            raster<std::uint8_t>(rows, cols, uninitialized),
            raster<std::uint8_t>(rows, cols, uninitialized),
            raster<std::uint32_t>(rows, cols, uninitialized),
            points_used_,
            points_outside_,
            points_nan_};
}

/// Writes cells [i0, i0 + n) of `out` from `cells` (branch-free: empty cells get NaN, 0 and dropout 1).
inline void raster_accumulator::finish_cells(rasterize_result& out, std::size_t i0, std::size_t n,
                                             const detail::cell_stats* cells) noexcept
{
    constexpr float nan = std::numeric_limits<float>::quiet_NaN();
    for (std::size_t j = 0; j < n; ++j) {
        const detail::cell_stats& s = cells[j];
        const std::size_t i = i0 + j;
        const bool any = s.count != 0;
        const double sum =
            static_cast<double>(static_cast<std::int64_t>(s.intensity_sum)) / detail::intensity_units_per_1;
        out.min_z.data()[i] = any ? s.min_z : nan;
        out.max_z.data()[i] = any ? s.max_z : nan;
        out.mean_intensity.data()[i] = any ? static_cast<float>(sum / static_cast<double>(s.count)) : 0.0f;
        out.count.data()[i] = s.count;
        out.dropout.data()[i] = static_cast<std::uint8_t>(!any);
        out.multiple_returns.data()[i] = static_cast<std::uint8_t>(s.multiple != 0);
        out.multiple_return_count.data()[i] = s.multiple;
    }
}

/// Writes every cell of rows [r0, r1) of `out`.
inline void raster_accumulator::finish_rows(rasterize_result& out, std::ptrdiff_t r0, std::ptrdiff_t r1) const
{
    const std::ptrdiff_t cols = g_.cols;
    if (is_dense_) {
        const auto begin = static_cast<std::size_t>(r0 * cols);
        finish_cells(out, begin, static_cast<std::size_t>((r1 - r0) * cols), dense_.data() + begin);
        return;
    }
    constexpr float nan = std::numeric_limits<float>::quiet_NaN();
    for (std::ptrdiff_t r = r0; r < r1; ++r) {
        const std::ptrdiff_t tr = r >> row_bits_, in_tile = (r & (tile_height() - 1)) << col_bits_;
        const tile_ptr* row_tiles = tiles_.data() + tr * tile_cols_;
        for (std::ptrdiff_t tc = 0; tc < tile_cols_;) {
            // A tile, or the run of tiles nobody touched up to the next held one.
            std::ptrdiff_t end = tc + 1;
            if (!row_tiles[tc]) {
                while (end < tile_cols_ && !row_tiles[end]) ++end;
            }
            const std::ptrdiff_t c0 = tc << col_bits_, c1 = std::min(cols, end << col_bits_);
            const auto i0 = static_cast<std::size_t>(r * cols + c0);
            const auto k = static_cast<std::size_t>(c1 - c0);
            if (row_tiles[tc]) {
                finish_cells(out, i0, k, row_tiles[tc].get() + in_tile);
            } else {
                std::fill_n(out.min_z.data() + i0, k, nan);
                std::fill_n(out.max_z.data() + i0, k, nan);
                std::fill_n(out.mean_intensity.data() + i0, k, 0.0f);
                std::fill_n(out.count.data() + i0, k, 0u);
                std::fill_n(out.dropout.data() + i0, k, std::uint8_t{1});
                std::fill_n(out.multiple_returns.data() + i0, k, std::uint8_t{0});
                std::fill_n(out.multiple_return_count.data() + i0, k, 0u);
            }
            tc = end;
        }
    }
}

namespace detail {

/// What rasterize needs beyond the public interface: start dense when the points outnumber the cells,
/// and merge per-thread accumulators by bands of whole tile rows in parallel.
struct accumulator_access {
    static void make_dense(raster_accumulator& acc)
    {
        if (!acc.is_dense_) acc.make_dense();
    }
    static bool is_dense(const raster_accumulator& acc) noexcept { return acc.is_dense_; }
    static std::ptrdiff_t tile_height(const raster_accumulator& acc) noexcept { return acc.tile_height(); }
    /// Folds rows [r0, r1) of `from` into `into` (dense unless both are sparse), taking the tiles only
    /// `from` holds; r0 and r1 start tile rows (or r1 ends the grid). Returns the tiles `into` newly holds,
    /// to be added with add_held once the parallel bands are done.
    static std::size_t take_rows(raster_accumulator& into, raster_accumulator& from, std::ptrdiff_t r0,
                                 std::ptrdiff_t r1)
    {
        if (from.is_dense_) {
            into.merge_dense_rows(from, r0, r1);
            return 0;
        }
        const std::ptrdiff_t h = into.tile_height();
        return into.merge_tiles(from, r0 / h, (r1 + h - 1) / h);
    }
    static void add_held(raster_accumulator& acc, std::size_t tiles) noexcept { acc.held_tiles_ += tiles; }
    static void merge_counters(raster_accumulator& into, const raster_accumulator& from) { into.merge_counters(from); }
    static rasterize_result unfinished(const raster_accumulator& acc) { return acc.unfinished(); }
    static void finish_rows(const raster_accumulator& acc, rasterize_result& out, std::ptrdiff_t r0, std::ptrdiff_t r1)
    {
        acc.finish_rows(out, r0, r1);
    }
};

}  // namespace detail

namespace detail {

/// The points rasterize_options selects, as a point cloud of their indices into `cloud` (x, y, z and the
/// optional attributes read through). Built in one O(points) pass; 8 bytes per selected point.
template <point_cloud C>
class selected_points {
public:
    selected_points(const C& cloud, std::vector<std::size_t> index) : cloud_(cloud), index_(std::move(index)) {}
    std::size_t size() const noexcept { return index_.size(); }
    double x(std::size_t i) const { return static_cast<double>(cloud_.x(index_[i])); }
    double y(std::size_t i) const { return static_cast<double>(cloud_.y(index_[i])); }
    double z(std::size_t i) const { return static_cast<double>(cloud_.z(index_[i])); }
    double intensity(std::size_t i) const requires has_intensity<C>
    {
        return static_cast<double>(cloud_.intensity(index_[i]));
    }
    int return_number(std::size_t i) const requires has_return_number<C>
    {
        return static_cast<int>(cloud_.return_number(index_[i]));
    }
    int number_of_returns(std::size_t i) const requires has_number_of_returns<C>
    {
        return static_cast<int>(cloud_.number_of_returns(index_[i]));
    }

private:
    const C& cloud_;
    std::vector<std::size_t> index_;
};

/// Indices of the points of `cloud` that opt.returns and opt.classes keep, in order.
/// @throws invalid_input if a selection needs an attribute the cloud type lacks, or a class code is
/// outside [0, 255].
template <point_cloud C>
std::vector<std::size_t> select_points(const C& cloud, const rasterize_options& opt, const char* function)
{
    const bool by_return = opt.returns != return_selection::all, by_class = !opt.classes.selects_all();
    if constexpr (!has_return_number<C>) {
        require(!by_return, function,
                "returns = first or last needs return numbers, and this point cloud type has none (no "
                "return_number(i)): pass returns = all or a cloud with return numbers");
    }
    if constexpr (!has_number_of_returns<C>) {
        require(opt.returns != return_selection::last, function,
                "returns = last needs number_of_returns(i), and this point cloud type has none: pass returns = "
                "all or first, or a cloud with the number of returns");
    }
    if constexpr (!has_classification<C>) {
        require(!by_class, function,
                "classes needs classification codes, and this point cloud type has none "
                "(no classification(i)): leave classes empty or pass a classified cloud");
    }
    std::array<std::uint8_t, 256> keep{};
    keep.fill(opt.classes.include.empty() ? 1 : 0);
    for (const int k : opt.classes.include) {
        require(k >= 0 && k <= 255, function, "classes.include code", "in [0, 255]", k);
        keep[static_cast<std::size_t>(k)] = 1;
    }
    for (const int k : opt.classes.exclude) {
        require(k >= 0 && k <= 255, function, "classes.exclude code", "in [0, 255]", k);
        keep[static_cast<std::size_t>(k)] = 0;
    }
    std::vector<std::size_t> index;
    const auto n = static_cast<std::size_t>(cloud.size());
    for (std::size_t i = 0; i < n; ++i) {
        if constexpr (has_classification<C>) {
            const int k = static_cast<int>(cloud.classification(i));
            if (by_class && (k < 0 || k > 255 || !keep[static_cast<std::size_t>(k)])) continue;
        }
        if constexpr (has_return_number<C>) {
            if (opt.returns == return_selection::first && static_cast<int>(cloud.return_number(i)) != 1) continue;
            if constexpr (has_number_of_returns<C>) {
                if (opt.returns == return_selection::last &&
                    static_cast<int>(cloud.return_number(i)) != static_cast<int>(cloud.number_of_returns(i)))
                    continue;
            }
        }
        index.push_back(i);
    }
    return index;
}

}  // namespace detail

namespace detail {

/// rasterize of every point of `cloud` (the selection is already applied).
template <point_cloud C>
rasterize_result rasterize_selected(const C& cloud, const grid& g, const rasterize_options& opt)
{
    constexpr const char* function = "rasterize";
    g.validate(function);
    detail::require(opt.chunk_points >= 1, function, "chunk_points", ">= 1", opt.chunk_points);
    const int threads = detail::resolve_threads(opt.run.threads, function, "run.threads");
    const auto n = static_cast<std::size_t>(cloud.size());
    const std::size_t chunks = std::max<std::size_t>(1, (n + opt.chunk_points - 1) / opt.chunk_points);
    const auto chunk_range = [&](std::size_t k) {
        return std::pair{std::min(n, k * opt.chunk_points), std::min(n, (k + 1) * opt.chunk_points)};
    };
    const auto workers = static_cast<std::size_t>(std::min<std::size_t>(static_cast<std::size_t>(threads), chunks));

    using access = detail::accumulator_access;
    raster_accumulator total(g);
    if (n >= static_cast<std::size_t>(g.size())) access::make_dense(total);  // dense data: the dense layout at once
    if (workers == 1) {
        for (std::size_t k = 0; k < chunks; ++k) {
            const auto [first, last] = chunk_range(k);
            total.add(cloud, first, last);
            detail::report(opt.run.progress, static_cast<double>(k + 1) / static_cast<double>(chunks), function);
        }
        return total.finish();
    }

    // One block per worker, each with its own accumulator; the workers pull chunks in turn, so a thread
    // that the system slows down takes fewer (which accumulator got which chunk never matters). The
    // caller's thread reports progress (and may cancel) after each of its chunks.
    std::vector<raster_accumulator> parts(workers - 1, total);  // empty, in total's layout
    std::atomic<std::size_t> next{0}, done{0};
    std::atomic<bool> stop{false};
    const auto caller = std::this_thread::get_id();
    parallel_for_rows(
        static_cast<std::ptrdiff_t>(workers), 1, threads,
        [&](std::ptrdiff_t w, std::ptrdiff_t) {
            raster_accumulator& acc = w == 0 ? total : parts[static_cast<std::size_t>(w - 1)];
            for (std::size_t k = next.fetch_add(1); k < chunks; k = next.fetch_add(1)) {
                if (stop.load(std::memory_order_relaxed)) return;
                const auto [first, last] = chunk_range(k);
                acc.add(cloud, first, last);
                const auto finished = done.fetch_add(1) + 1;
                if (std::this_thread::get_id() == caller) {
                    try {
                        detail::report(opt.run.progress,
                                       static_cast<double>(finished) / static_cast<double>(chunks + 1), function);
                    } catch (...) {
                        stop = true;
                        throw;
                    }
                }
            }
        },
        {}, function);

    // Merge and finish by bands of whole tile rows in parallel: each band folds every part in worker order,
    // taking the tiles that only a part holds. Dense parts make the total dense first.
    for (const auto& part : parts) {
        access::merge_counters(total, part);
        if (access::is_dense(part)) access::make_dense(total);
    }
    rasterize_result out = access::unfinished(total);
    const std::ptrdiff_t h = access::tile_height(total);
    const std::ptrdiff_t rows_wanted =
        std::max<std::ptrdiff_t>(1, (std::ptrdiff_t{1} << 16) / std::max<std::ptrdiff_t>(1, g.cols));
    const std::ptrdiff_t band = (rows_wanted + h - 1) / h * h;
    std::vector<std::size_t> taken(static_cast<std::size_t>((g.rows + band - 1) / band), 0);
    parallel_for_rows(
        g.rows, band, threads,
        [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
            for (auto& part : parts)
                taken[static_cast<std::size_t>(r0 / band)] += access::take_rows(total, part, r0, r1);
            access::finish_rows(total, out, r0, r1);
        },
        {}, function);
    for (const std::size_t t : taken) access::add_held(total, t);
    detail::report(opt.run.progress, 1.0, function);
    return out;
}

}  // namespace detail

template <point_cloud C>
rasterize_result rasterize(const C& cloud, const grid& g, const rasterize_options& opt)
{
    constexpr const char* function = "rasterize";
    if (opt.returns == return_selection::all && opt.classes.selects_all())
        return detail::rasterize_selected(cloud, g, opt);
    g.validate(function);
    detail::selected_points<C> kept(cloud, detail::select_points(cloud, opt, function));
    rasterize_result out = detail::rasterize_selected(kept, g, opt);
    out.points_unselected = static_cast<std::size_t>(cloud.size()) - kept.size();
    return out;
}

template <point_cloud C>
bounds bounds_of(const C& cloud)
{
    constexpr double inf = std::numeric_limits<double>::infinity();
    bounds b{inf, inf, -inf, -inf};
    const auto n = static_cast<std::size_t>(cloud.size());
    for (std::size_t i = 0; i < n; ++i) {
        const double x = cloud.x(i), y = cloud.y(i), z = cloud.z(i);
        if (!(std::isfinite(x) && std::isfinite(y) && std::isfinite(z))) continue;
        b.xmin = std::min(b.xmin, x);
        b.xmax = std::max(b.xmax, x);
        b.ymin = std::min(b.ymin, y);
        b.ymax = std::max(b.ymax, y);
    }
    detail::require(b.xmin <= b.xmax, "bounds_of", "cloud has no point with finite x, y and z");
    return b;
}

}  // namespace lidarfx
