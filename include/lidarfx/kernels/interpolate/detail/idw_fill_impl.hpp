// SPDX-License-Identifier: Apache-2.0
// Implementation of kernels/interpolate/idw_fill.hpp: the search index, the ring search for the k nearest data
// cells and the weighted mean. Included at the end of idw_fill.hpp, after the declarations it defines; not a
// public header.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

namespace detail {

/// A data cell offered to a hole: squared distance in cells, position, value.
struct idw_neighbour {
    std::int64_t d2;
    std::ptrdiff_t r, c;
    double z;
};

/// The neighbour order: nearer first, ties by row, then column (what a sorted brute-force search takes).
constexpr bool idw_before(const idw_neighbour& a, const idw_neighbour& b) noexcept
{
    if (a.d2 != b.d2) return a.d2 < b.d2;
    return a.r != b.r ? a.r < b.r : a.c < b.c;
}

/// floor(sqrt(v)) for v >= 0, exact.
inline std::int64_t isqrt(std::int64_t v) noexcept
{
    auto s = static_cast<std::int64_t>(std::sqrt(static_cast<double>(v)));
    while (s > 0 && s * s > v) --s;
    while ((s + 1) * (s + 1) <= v) ++s;
    return s;
}

/// Largest squared distance in cells d2 within the radius: sqrt(d2) <= radius_m / cell_m + 1e-9 (the
/// tolerance keeps a radius of exactly n cells inclusive despite rounding, e.g. 0.3 m at 0.1 m cells), or a
/// value beyond any distance in the raster when the radius is unlimited (0).
inline std::int64_t idw_reach_d2(double radius_m, double cell_m, std::ptrdiff_t rows, std::ptrdiff_t cols)
{
    const auto span = static_cast<double>(std::max(rows, cols));
    const auto unlimited = static_cast<std::int64_t>(2.0 * span * span) + 2;
    const double reach = radius_m / cell_m + 1e-9;
    if (radius_m == 0 || !(reach * reach < static_cast<double>(unlimited))) return unlimited;
    const auto within = [&](std::int64_t d2) { return std::sqrt(static_cast<double>(d2)) <= reach; };
    auto d2 = static_cast<std::int64_t>(reach * reach);
    while (d2 > 0 && !within(d2)) --d2;
    while (within(d2 + 1)) ++d2;
    return d2;
}

/// Keeps the k first neighbours in idw_before order, sorted.
class idw_best {
public:
    explicit idw_best(std::size_t k) : k_(k) { items_.reserve(k + 1); }
    void clear() noexcept { items_.clear(); }
    bool full() const noexcept { return items_.size() == k_; }
    bool empty() const noexcept { return items_.empty(); }
    std::int64_t worst_d2() const noexcept { return items_.back().d2; }
    /// False when a neighbour at squared distance d2 cannot enter (cheap test before reading its value).
    bool may_take(std::int64_t d2) const noexcept { return !full() || d2 <= items_.back().d2; }
    const std::vector<idw_neighbour>& items() const noexcept { return items_; }

    void offer(const idw_neighbour& n)
    {
        if (full()) {
            if (!idw_before(n, items_.back())) return;
            items_.pop_back();
        }
        auto at = items_.end();
        while (at != items_.begin() && idw_before(n, *(at - 1))) --at;
        items_.insert(at, n);
    }

private:
    std::size_t k_;
    std::vector<idw_neighbour> items_;
};

/// Sum of w*z over sum of w, w = 1 / (cell_m * sqrt(d2))^power, accumulated in neighbour order.
inline float idw_mean(const std::vector<idw_neighbour>& nb, double cell_m, double power)
{
    double sw = 0, swz = 0;
    for (const idw_neighbour& n : nb) {
        const double d = cell_m * std::sqrt(static_cast<double>(n.d2));
        const double w = power == 1.0 ? 1.0 / d : 1.0 / std::pow(d, power);
        sw += w;
        swz += w * n.z;
    }
    return static_cast<float>(swz / sw);
}

/// Search aids built once per raster, so that ring searches skip what holds no data: next_in_row(r, c)
/// is the first column >= c of row r holding data (finite), cols if none; next_in_col(r, c) the first
/// row >= r of column c, rows if none; first_ring(r, c) the Chebyshev distance to the nearest data cell
/// (rings closer than that are empty). 12 bytes per cell.
struct idw_index {
    raster<std::int32_t> next_in_row, next_in_col, first_ring;

    template <class T>
    idw_index(raster_view<const T> z, int threads, const progress_callback& progress = {})
        : next_in_row(z.rows(), z.cols()), next_in_col(z.rows(), z.cols()), first_ring(z.rows(), z.cols())
    {
        const std::ptrdiff_t rows = z.rows(), cols = z.cols();
        parallel_for_rows(
            rows, 64, threads,
            [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
                for (std::ptrdiff_t r = r0; r < r1; ++r) {
                    const T* in = z.row(r);
                    std::int32_t* next = next_in_row.row(r);
                    auto at = static_cast<std::int32_t>(cols);
                    for (std::ptrdiff_t c = cols - 1; c >= 0; --c) {
                        if (std::isfinite(in[c])) at = static_cast<std::int32_t>(c);
                        next[c] = at;
                    }
                }
            },
            progress, "idw_fill");
        for (std::ptrdiff_t r = rows - 1; r >= 0; --r) {
            const T* in = z.row(r);
            std::int32_t* next = next_in_col.row(r);
            const std::int32_t* below = r + 1 < rows ? next_in_col.row(r + 1) : nullptr;
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                next[c] = std::isfinite(in[c]) ? static_cast<std::int32_t>(r)
                                               : (below ? below[c] : static_cast<std::int32_t>(rows));
            }
        }
        chessboard_distance(z);
    }

private:
    /// Two-pass 3x3 chamfer with unit weights: exact for the Chebyshev (chessboard) metric.
    template <class T>
    void chessboard_distance(raster_view<const T> z)
    {
        const std::ptrdiff_t rows = z.rows(), cols = z.cols();
        constexpr std::int32_t far = std::numeric_limits<std::int32_t>::max() / 2;
        raster<std::int32_t>& d = first_ring;
        for (std::ptrdiff_t r = 0; r < rows; ++r) {
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                std::int32_t v = std::isfinite(z(r, c)) ? 0 : far;
                if (v != 0) {
                    if (c > 0) v = std::min(v, d(r, c - 1) + 1);
                    if (r > 0) {
                        for (std::ptrdiff_t cc = std::max<std::ptrdiff_t>(0, c - 1); cc <= std::min(cols - 1, c + 1);
                             ++cc)
                            v = std::min(v, d(r - 1, cc) + 1);
                    }
                }
                d(r, c) = v;
            }
        }
        for (std::ptrdiff_t r = rows - 1; r >= 0; --r) {
            for (std::ptrdiff_t c = cols - 1; c >= 0; --c) {
                std::int32_t v = d(r, c);
                if (v == 0) continue;
                if (c + 1 < cols) v = std::min(v, d(r, c + 1) + 1);
                if (r + 1 < rows) {
                    for (std::ptrdiff_t cc = std::max<std::ptrdiff_t>(0, c - 1); cc <= std::min(cols - 1, c + 1); ++cc)
                        v = std::min(v, d(r + 1, cc) + 1);
                }
                d(r, c) = v;
            }
        }
    }
};

/// Ring search for the hole at (r, c): Chebyshev rings rho = 1, 2, ... around it; ring rho holds no
/// cell nearer than rho, so the search stops once rho^2 passes the k-th best squared distance (or the
/// reach). Rings nearer than the nearest data cell are skipped; within a ring only offsets t with
/// rho^2 + t^2 <= the current bound are visited, and runs of holes are jumped over, so a ring costs
/// O(1 + data cells offered).
template <class T>
void idw_search(raster_view<const T> z, const idw_index& index, std::ptrdiff_t r, std::ptrdiff_t c,
                std::int64_t reach_d2, idw_best& best)
{
    best.clear();
    const std::ptrdiff_t rows = z.rows(), cols = z.cols();
    const std::ptrdiff_t last_ring = std::max({r, rows - 1 - r, c, cols - 1 - c});
    const auto offer_row = [&](std::ptrdiff_t rr, std::ptrdiff_t c0, std::ptrdiff_t c1, std::int64_t dr2) {
        const std::int32_t* next = index.next_in_row.row(rr);
        c1 = std::min(c1, cols - 1);
        for (std::ptrdiff_t cc = next[std::max<std::ptrdiff_t>(c0, 0)]; cc <= c1;
             cc = cc + 1 < cols ? next[cc + 1] : cols) {
            const std::int64_t dc = cc - c, d2 = dr2 + dc * dc;
            if (best.may_take(d2)) best.offer({d2, rr, cc, static_cast<double>(z(rr, cc))});
        }
    };
    const auto offer_col = [&](std::ptrdiff_t cc, std::ptrdiff_t r0, std::ptrdiff_t r1, std::int64_t dc2) {
        r1 = std::min(r1, rows - 1);
        for (std::ptrdiff_t rr = index.next_in_col(std::max<std::ptrdiff_t>(r0, 0), cc); rr <= r1;
             rr = rr + 1 < rows ? index.next_in_col(rr + 1, cc) : rows) {
            const std::int64_t dr = rr - r, d2 = dc2 + dr * dr;
            if (best.may_take(d2)) best.offer({d2, rr, cc, static_cast<double>(z(rr, cc))});
        }
    };
    for (std::ptrdiff_t rho = index.first_ring(r, c); rho <= last_ring; ++rho) {
        const std::int64_t rho2 = static_cast<std::int64_t>(rho) * rho;
        const std::int64_t bound = best.full() ? std::min(reach_d2, best.worst_d2()) : reach_d2;
        if (rho2 > bound) break;
        const std::ptrdiff_t t = bound - rho2 >= rho2 ? rho : static_cast<std::ptrdiff_t>(isqrt(bound - rho2));
        if (r - rho >= 0) offer_row(r - rho, c - t, c + t, rho2);
        if (r + rho < rows) offer_row(r + rho, c - t, c + t, rho2);
        const std::ptrdiff_t side = std::min(t, rho - 1);
        if (c - rho >= 0) offer_col(c - rho, r - side, r + side, rho2);
        if (c + rho < cols) offer_col(c + rho, r - side, r + side, rho2);
    }
}

/// Fills `out` from `z`. Progress: the search index is the first 5 %, the holes (blocks of 8 rows) the rest.
template <class T>
idw_fill_counts idw_fill_view(raster_view<const T> z, raster_view<float> out, double cell_m,
                              const idw_fill_options& opt)
{
    const std::ptrdiff_t rows = z.rows(), cols = z.cols();
    const std::int64_t reach_d2 = idw_reach_d2(opt.radius_m, cell_m, rows, cols);
    const idw_index index(z, opt.run.threads, progress_phase(opt.run.progress, 0.0, 0.05));
    constexpr std::ptrdiff_t block = 8;
    std::vector<idw_fill_counts> per_block(static_cast<std::size_t>((rows + block - 1) / block));
    parallel_for_rows(
        rows, block, opt.run.threads,
        [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
            idw_best best(static_cast<std::size_t>(opt.k));
            idw_fill_counts& counts = per_block[static_cast<std::size_t>(r0 / block)];
            for (std::ptrdiff_t r = r0; r < r1; ++r) {
                const T* in = z.row(r);
                float* o = out.row(r);
                for (std::ptrdiff_t c = 0; c < cols; ++c) {
                    if (!std::isnan(in[c])) {
                        o[c] = static_cast<float>(in[c]);
                        continue;
                    }
                    idw_search(z, index, r, c, reach_d2, best);
                    if (best.empty()) {
                        o[c] = std::numeric_limits<float>::quiet_NaN();
                        ++counts.unfilled_cells;
                    } else {
                        o[c] = idw_mean(best.items(), cell_m, opt.power);
                        ++counts.filled_cells;
                    }
                }
            }
        },
        progress_phase(opt.run.progress, 0.05, 1.0), "idw_fill");
    idw_fill_counts total;
    for (const idw_fill_counts& b : per_block) {
        total.filled_cells += b.filled_cells;
        total.unfilled_cells += b.unfilled_cells;
    }
    return total;
}

template <class T>
bool has_finite_cell(raster_view<const T> z) noexcept
{
    for (std::ptrdiff_t r = 0; r < z.rows(); ++r) {
        const T* row = z.row(r);
        for (std::ptrdiff_t c = 0; c < z.cols(); ++c) {
            if (std::isfinite(row[c])) return true;
        }
    }
    return false;
}

inline void validate_idw(double cell_m, const idw_fill_options& opt)
{
    require(opt.k >= 1, "idw_fill", "k", ">= 1", opt.k);
    require(opt.radius_m >= 0 && opt.radius_m <= 1.0e300, "idw_fill", "radius_m", "finite and >= 0 (0 = unlimited)",
            opt.radius_m);
    require_positive(opt.power, "idw_fill", "power");
    require_positive(cell_m, "idw_fill", "cell_m");
    check_execution(opt.run, "idw_fill");
}

template <class In>
void validate_idw_extent(const In& z)
{
    constexpr auto most = static_cast<std::ptrdiff_t>(std::numeric_limits<std::int32_t>::max());
    require(z.rows() < most && z.cols() < most, "idw_fill", [&] {
        return concat("z must have fewer than 2^31 - 1 rows and columns (got ", z.rows(), "x", z.cols(), ")");
    });
}

}  // namespace detail

template <raster_input In, class Out>
requires raster_output_of<Out, float> && std::is_floating_point_v<typename In::value_type> idw_fill_counts
idw_fill(const In& z, Out&& out, double cell_m, const idw_fill_options& opt)
{
    detail::validate_idw(cell_m, opt);
    detail::require_same_shape(z, out, "idw_fill", "z", "out");
    detail::validate_idw_extent(z);
    const detail::readable<In> in(z);
    detail::require(detail::has_finite_cell(in.view()), "idw_fill", "z has no finite cell to interpolate from");
    idw_fill_counts counts;
    detail::write_through<float>(std::forward<Out>(out), [&](raster_view<float> o) {
        // Filled holes written into z would become data for the holes after them.
        detail::require(!detail::overlaps(in.view(), o), "idw_fill", "out must not overlap z");
        counts = detail::idw_fill_view(in.view(), o, cell_m, opt);
    });
    return counts;
}

template <raster_input In>
requires std::is_floating_point_v<typename In::value_type> idw_fill_result idw_fill(const In& z, double cell_m,
                                                                                    const idw_fill_options& opt)
{
    idw_fill_result result{raster<float>(z.rows(), z.cols()), 0, 0};
    const idw_fill_counts counts = idw_fill(z, result.filled, cell_m, opt);
    result.filled_cells = counts.filled_cells;
    result.unfilled_cells = counts.unfilled_cells;
    return result;
}

inline std::ptrdiff_t idw_fill_reach_cells(const idw_fill_options& opt, double cell_m)
{
    constexpr const char* fn = "idw_fill_reach_cells";
    detail::require_positive(cell_m, fn, "cell_m");
    detail::require(opt.radius_m > 0 && opt.radius_m <= 1.0e300, fn, [&] {
        return detail::concat("radius_m must be finite and > 0 (got ", opt.radius_m,
                              "); with radius_m 0 (unlimited) idw_fill is not local");
    });
    const std::int64_t span = std::int64_t{1} << 30;  // beyond any raster: only the radius limits the reach
    const std::int64_t d2 = detail::idw_reach_d2(opt.radius_m, cell_m, span, span);
    return static_cast<std::ptrdiff_t>(detail::isqrt(d2));
}

}  // namespace lidarfx
