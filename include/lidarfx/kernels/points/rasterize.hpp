// SPDX-License-Identifier: Apache-2.0
// rasterize: per-cell min/max elevation, mean intensity, point count and return statistics of a point cloud.
#pragma once

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <thread>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/grid.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/point_cloud.hpp"
#include "lidarfx/core/raster.hpp"

namespace lidarfx {

/// Settings of rasterize.
struct rasterize_options {
    std::size_t chunk_points = 1 << 20;   ///< points per work unit (progress step and parallel split); >= 1
    execution run = {};                   ///< threads, progress, cancellation (core/parallel.hpp); same result
};

/// The per-cell rasters of a point cloud, all on the grid `g`, plus what happened to the points.
struct rasterize_result {
    grid g;                                 ///< georeferencing shared by every raster below
    raster<float> min_z, max_z;             ///< lowest / highest z in the cell, metres; NaN where no point
    raster<float> mean_intensity;           ///< mean intensity of the cell's points; 0 where no point (dropout)
    raster<std::uint32_t> count;            ///< points in the cell
    raster<std::uint8_t> dropout;           ///< 1 = no return in the cell
    raster<std::uint8_t> multiple_returns;  ///< 1 = some point of the cell has number_of_returns > 1
    std::size_t points_used = 0;            ///< points written into a cell
    std::size_t points_outside = 0;         ///< finite points outside the grid (ignored)
    std::size_t points_nan = 0;             ///< points with a NaN or infinite x, y or z (ignored)
};

namespace detail {

/// Running statistics of one cell (24 bytes; one cache line holds most cells whole).
struct cell_stats {
    float min_z = std::numeric_limits<float>::infinity();
    float max_z = -std::numeric_limits<float>::infinity();
    std::uint32_t count = 0;
    std::uint32_t multiple = 0;       // 1 once a point with number_of_returns > 1 was seen
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

/// Hints that *p will soon be written (no-op where the compiler has no prefetch builtin).
inline void prefetch([[maybe_unused]] const void* p) noexcept
{
#if defined(__GNUC__) || defined(__clang__)
    __builtin_prefetch(p, 1);
#endif
}

}  // namespace detail

/// Streaming per-cell statistics on a fixed grid. Add points in chunks (any split, any order), merge
/// partial accumulators built elsewhere (other threads, other files of a tile), then finish(): every
/// sequence of add/merge over the same points gives bit-identical rasters, because min/max are
/// order-free and intensities are summed as exact integers (see rasterize for the conventions).
/// Memory: 24 bytes per grid cell.
class raster_accumulator {
public:
    /// Empty statistics on `g`. @throws invalid_input if g is invalid (see grid::validate).
    explicit raster_accumulator(const grid& g) : g_(g)
    {
        g.validate("raster_accumulator");
        cells_.resize(static_cast<std::size_t>(g.size()));
    }

    /// Adds every point of `cloud`.
    template <point_cloud C>
    void add(const C& cloud)
    {
        add(cloud, 0, static_cast<std::size_t>(cloud.size()));
    }

    /// Adds points [first, last) of `cloud`. O(last - first).
    /// @throws invalid_input unless first <= last <= cloud.size().
    template <point_cloud C>
    void add(const C& cloud, std::size_t first, std::size_t last)
    {
        const auto n = static_cast<std::size_t>(cloud.size());
        detail::require(first <= last && last <= n, "raster_accumulator::add",
                        detail::concat("range [first, last) must lie in [0, ", n, "] (got [", first, ", ", last, "))"));
        // Two passes per block of points: locate the cells (and prefetch them), then update them, so that
        // the cache misses of randomly ordered points overlap instead of stalling one by one.
        constexpr std::size_t block = 256;
        constexpr std::ptrdiff_t outside_cell = -1, nan_point = -2;
        constexpr auto float_max = static_cast<double>(std::numeric_limits<float>::max());
        std::ptrdiff_t at[block];
        float zs[block];
        const grid g = g_;
        detail::cell_stats* cells = cells_.data();
        std::size_t used = 0, outside = 0, nan = 0;
        for (std::size_t base = first; base < last; base += block) {
            const std::size_t m = std::min(block, last - base);
            for (std::size_t j = 0; j < m; ++j) {
                const double x = cloud.x(base + j), y = cloud.y(base + j), z = cloud.z(base + j);
                if (!(std::isfinite(x) && std::isfinite(y) && std::isfinite(z))) {
                    at[j] = nan_point;
                    continue;
                }
                // float(min(z)) == min(float(z)): saturating and rounding are monotonic, so storing floats
                // loses no order.
                zs[j] = static_cast<float>(std::clamp(z, -float_max, float_max));
                const auto cell = g.cell_of(x, y);
                at[j] = cell ? cell->row * g.cols + cell->col : outside_cell;
                if (cell) detail::prefetch(cells + at[j]);
            }
            for (std::size_t j = 0; j < m; ++j) {
                if (at[j] < 0) {
                    ++(at[j] == nan_point ? nan : outside);
                    continue;
                }
                detail::cell_stats& s = cells[at[j]];
                s.min_z = std::min(s.min_z, zs[j]);
                s.max_z = std::max(s.max_z, zs[j]);
                ++s.count;
                s.intensity_sum += detail::intensity_fixed(intensity_of(cloud, base + j));
                s.multiple |= static_cast<std::uint32_t>(number_of_returns_of(cloud, base + j) > 1);
                ++used;
            }
        }
        points_used_ += used;
        points_outside_ += outside;
        points_nan_ += nan;
    }

    /// Adds the statistics of `other` (same grid), as if its points had been added here.
    /// O(cells). @throws invalid_input if other.grid differs from this grid.
    void merge(const raster_accumulator& other)
    {
        require_same_grid(other, "raster_accumulator::merge");
        merge_rows(other, 0, g_.rows);
        merge_counters(other);
    }

    /// The rasters of every point added so far (the accumulator is unchanged). O(cells).
    rasterize_result finish() const
    {
        rasterize_result out = unfinished();
        finish_rows(out, 0, g_.rows);
        return out;
    }

    const grid& target_grid() const noexcept { return g_; }   ///< the grid the points are binned on
    std::size_t points_used() const noexcept { return points_used_; }
    std::size_t points_outside() const noexcept { return points_outside_; }
    std::size_t points_nan() const noexcept { return points_nan_; }

private:
    friend struct detail::accumulator_access;

    void require_same_grid(const raster_accumulator& other, const char* function) const
    {
        detail::require(other.g_ == g_, function, "other accumulator must be on the same grid");
    }

    void merge_counters(const raster_accumulator& other) noexcept
    {
        points_used_ += other.points_used_;
        points_outside_ += other.points_outside_;
        points_nan_ += other.points_nan_;
    }

    /// The result with its counters set and rasters allocated; finish_rows fills them.
    rasterize_result unfinished() const
    {
        const auto rows = g_.rows, cols = g_.cols;
        return {g_,
                raster<float>(rows, cols),
                raster<float>(rows, cols),
                raster<float>(rows, cols),
                raster<std::uint32_t>(rows, cols),
                raster<std::uint8_t>(rows, cols),
                raster<std::uint8_t>(rows, cols),
                points_used_,
                points_outside_,
                points_nan_};
    }

    /// Writes every cell of rows [r0, r1) of `out` (branch-free: empty cells get NaN, 0 and dropout 1).
    void finish_rows(rasterize_result& out, std::ptrdiff_t r0, std::ptrdiff_t r1) const
    {
        constexpr float nan = std::numeric_limits<float>::quiet_NaN();
        const auto begin = static_cast<std::size_t>(r0 * g_.cols), end = static_cast<std::size_t>(r1 * g_.cols);
        for (std::size_t i = begin; i < end; ++i) {
            const detail::cell_stats& s = cells_[i];
            const bool any = s.count != 0;
            const double sum = static_cast<double>(static_cast<std::int64_t>(s.intensity_sum)) / detail::intensity_units_per_1;
            out.min_z.data()[i] = any ? s.min_z : nan;
            out.max_z.data()[i] = any ? s.max_z : nan;
            out.mean_intensity.data()[i] = any ? static_cast<float>(sum / static_cast<double>(s.count)) : 0.0f;
            out.count.data()[i] = s.count;
            out.dropout.data()[i] = static_cast<std::uint8_t>(!any);
            out.multiple_returns.data()[i] = static_cast<std::uint8_t>(s.multiple);
        }
    }

    /// Folds the cell statistics of rows [r0, r1) of `other` into this one (point counters untouched).
    void merge_rows(const raster_accumulator& other, std::ptrdiff_t r0, std::ptrdiff_t r1)
    {
        const auto begin = static_cast<std::size_t>(r0 * g_.cols), end = static_cast<std::size_t>(r1 * g_.cols);
        for (std::size_t i = begin; i < end; ++i) {
            detail::cell_stats& s = cells_[i];
            const detail::cell_stats& o = other.cells_[i];
            s.min_z = std::min(s.min_z, o.min_z);
            s.max_z = std::max(s.max_z, o.max_z);
            s.count += o.count;
            s.multiple |= o.multiple;
            s.intensity_sum += o.intensity_sum;
        }
    }

    grid g_;
    std::vector<detail::cell_stats> cells_;
    std::size_t points_used_ = 0, points_outside_ = 0, points_nan_ = 0;
};

namespace detail {

/// rasterize merges per-thread accumulators by row bands in parallel, then adds their point counters.
struct accumulator_access {
    static void merge_rows(raster_accumulator& into, const raster_accumulator& from, std::ptrdiff_t r0,
                           std::ptrdiff_t r1)
    {
        into.merge_rows(from, r0, r1);
    }
    static void merge_counters(raster_accumulator& into, const raster_accumulator& from)
    {
        into.merge_counters(from);
    }
    static rasterize_result unfinished(const raster_accumulator& acc) { return acc.unfinished(); }
    static void finish_rows(const raster_accumulator& acc, rasterize_result& out, std::ptrdiff_t r0, std::ptrdiff_t r1)
    {
        acc.finish_rows(out, r0, r1);
    }
};

}  // namespace detail

/// Bins a point cloud on `g` (dissertation 2.3.1): per cell min and max z (float, saturating), mean
/// intensity, count, dropout (no return) and multiple returns (a point with number_of_returns > 1). Points
/// go to grid::cell_of (far east/south edge -> last column/row); outside and NaN/infinite points are
/// counted, never written. Intensities are rounded to multiples of 2^-16 (clamped to +-2^24, NaN as 0) and
/// summed as 64-bit integers, exact for LAS intensities: any chunking, order or thread count gives the
/// same bits. O(points + cells); 24 bytes per cell per worker thread. Details in docs/rasters.md.
/// Progress is reported after each chunk of chunk_points points (and once more after merging, with threads).
/// @throws invalid_input on an invalid grid, chunk_points == 0 or run.threads < 0; cancelled if run.progress
/// returns false.
template <point_cloud C>
rasterize_result rasterize(const C& cloud, const grid& g, const rasterize_options& opt = {})
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

    raster_accumulator total(g);
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
    std::vector<raster_accumulator> parts(workers - 1, raster_accumulator(g));
    std::atomic<std::size_t> next{0}, done{0};
    std::atomic<bool> stop{false};
    const auto caller = std::this_thread::get_id();
    parallel_for_rows(static_cast<std::ptrdiff_t>(workers), 1, threads, [&](std::ptrdiff_t w, std::ptrdiff_t) {
        raster_accumulator& acc = w == 0 ? total : parts[static_cast<std::size_t>(w - 1)];
        for (std::size_t k = next.fetch_add(1); k < chunks; k = next.fetch_add(1)) {
            if (stop.load(std::memory_order_relaxed)) return;
            const auto [first, last] = chunk_range(k);
            acc.add(cloud, first, last);
            const auto finished = done.fetch_add(1) + 1;
            if (std::this_thread::get_id() == caller) {
                try {
                    detail::report(opt.run.progress, static_cast<double>(finished) / static_cast<double>(chunks + 1),
                                   function);
                } catch (...) {
                    stop = true;
                    throw;
                }
            }
        }
    }, {}, function);

    // Merge and finish by row bands in parallel: each band folds every part in worker order.
    using access = detail::accumulator_access;
    for (const auto& part : parts) access::merge_counters(total, part);
    rasterize_result out = access::unfinished(total);
    const std::ptrdiff_t band = std::max<std::ptrdiff_t>(1, (std::ptrdiff_t{1} << 16) / std::max<std::ptrdiff_t>(1, g.cols));
    parallel_for_rows(g.rows, band, threads, [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
        for (const auto& part : parts) access::merge_rows(total, part, r0, r1);
        access::finish_rows(total, out, r0, r1);
    }, {}, function);
    detail::report(opt.run.progress, 1.0, function);
    return out;
}

/// Bounding box of the points of `cloud` whose x, y and z are all finite (others are ignored); pass it to
/// snapped_grid(bounds, cell_m) for the usual survey grid. O(points).
/// @throws invalid_input if no point has finite x, y and z (an empty cloud included).
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
