// SPDX-License-Identifier: Apache-2.0
// Implementation of join_across_bridges (included at the end of pipelines/water/join_across_bridges.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <numeric>
#include <span>
#include <vector>
#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/parallel_bands.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/pipelines/water/water_rasters.hpp"

namespace lidarfx {

namespace detail {

inline void validate(const join_across_bridges_options& o, const char* fn)
{
    require(o.max_span_m >= 0, fn, "max_span_m", ">= 0", o.max_span_m);
    require(o.level_tolerance_m >= 0, fn, "level_tolerance_m", ">= 0", o.level_tolerance_m);
    require(o.min_clearance_m >= 0, fn, "min_clearance_m", ">= 0", o.min_clearance_m);
    require(o.water_tolerance_m >= 0, fn, "water_tolerance_m", ">= 0", o.water_tolerance_m);
}

/// water_levels, with errors naming `fn`, on `threads` threads.
inline std::vector<double> water_levels(raster_view<const std::int32_t> labels, raster_view<const float> min_z,
                                        const char* fn, int threads = 1)
{
    detail::require_same_shape(labels, min_z, fn, "labels", "min_z");
    // One pass over the labels in bands of rows (on `threads` threads), each band's heights in a buffer of its
    // own: per row the labels' range by a vectorized min / max (the row then stays in cache), then on a row that
    // holds bodies its runs, land passed over 64 cells at a time. Each run's finite heights are appended to the
    // band's `found` in raster order (branch-free: water cells without a return are scattered, a branch on them
    // mispredicts) and the run is noted as (label, heights appended). The bands in order give every label's
    // heights in raster order, whatever the thread count.
    const std::ptrdiff_t rows = labels.rows(), cols = labels.cols();
    struct run_heights {
        std::int32_t label;
        std::size_t count;
    };
    struct band_heights {
        std::vector<run_heights> runs;
        std::unique_ptr<float[]> found;  // room for every cell of the band, touched only where written
        std::int32_t lowest = 0, highest = 0;
    };
    const auto bands = parallel_bands(rows, 256, threads, [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
        band_heights band;
        std::size_t used = 0;
        for (std::ptrdiff_t r = r0; r < r1; ++r) {
            const std::int32_t* row = labels.row(r);
            const auto [low, high] = detail::row_label_range(row, cols);
            band.lowest = std::min(band.lowest, low);
            band.highest = std::max(band.highest, high);
            if (high <= 0) continue;
            if (!band.found) band.found.reset(new float[static_cast<std::size_t>((r1 - r) * cols)]);
            const float* z = min_z.row(r);
            float* out = band.found.get();
            for_each_run(row, cols, [&](std::int32_t l, std::ptrdiff_t from, std::ptrdiff_t to) {
                std::size_t n = used;
                for (std::ptrdiff_t c = from; c < to; ++c) {
                    out[n] = z[c];
                    n += std::isfinite(z[c]);
                }
                band.runs.push_back({l, n - used});
                used = n;
            });
        }
        return band;
    });
    std::int32_t lowest = 0, highest = 0;
    for (const auto& band : bands) lowest = std::min(lowest, band.lowest), highest = std::max(highest, band.highest);
    detail::require(lowest >= 0, fn, "labels", ">= 0", lowest);
    // The heights of each label in one buffer, label l's at [offset[l], offset[l + 1]), in raster order.
    std::vector<std::size_t> offset(static_cast<std::size_t>(highest) + 2, 0);
    for (const auto& band : bands)
        for (const auto& run : band.runs) offset[static_cast<std::size_t>(run.label) + 1] += run.count;
    for (std::size_t l = 1; l < offset.size(); ++l) offset[l] += offset[l - 1];
    std::vector<float> heights(offset.back());
    std::vector<std::size_t> next(offset.begin(), offset.end() - 1);
    for (const auto& band : bands) {
        const float* from = band.found.get();
        for (const auto& run : band.runs) {
            std::copy(from, from + run.count,
                      heights.begin() + static_cast<std::ptrdiff_t>(next[static_cast<std::size_t>(run.label)]));
            next[static_cast<std::size_t>(run.label)] += run.count;
            from += run.count;
        }
    }
    // The medians, label by label on `threads` threads (each reorders its own heights only).
    std::vector<double> level(static_cast<std::size_t>(highest) + 1, NAN);
    parallel_for_rows(highest, 16, threads, [&](std::ptrdiff_t l0, std::ptrdiff_t l1) {
        for (auto l = static_cast<std::size_t>(l0) + 1; l <= static_cast<std::size_t>(l1); ++l)
            level[l] = detail::median(std::span<float>(heights).subspan(offset[l], offset[l + 1] - offset[l]));
    });
    return level;
}

}  // namespace detail

inline std::vector<double> water_levels(raster_view<const std::int32_t> labels, raster_view<const float> min_z,
                                        const execution& run)
{
    detail::check_execution(run, "water_levels");
    return detail::water_levels(labels, min_z, "water_levels", run.threads);
}

namespace detail {

/// join_across_bridges' test of a run of land cells between bodies a and b: a bridge when the levels agree
/// and its water and deck cells lie in the order water seen (between the lower level − water_tolerance_m and the
/// higher level + water_tolerance_m), one stretch of deck, water seen; and it holds a deck cell or a cell without
/// a return (those fit anywhere). The other cells (banks) are left out of the order and stay land. Ground
/// between two decks (a street between roofs) or land at a water level without a deck is no bridge.
struct bridge_rule {
    /// What a land cell of a run is to the two bodies' levels.
    enum class cell { gap, deck, water, bank };  // no return; clearance above both; water seen; anything else

    /// The heights that sort the cells of a run between bodies a and b.
    struct heights {
        double water_from, water_to, deck_from;
        cell of(float z) const noexcept
        {
            if (!std::isfinite(z)) return cell::gap;
            const double h = z;
            return h >= deck_from ? cell::deck : h >= water_from && h <= water_to ? cell::water : cell::bank;
        }
    };

    raster_view<const float> min_z;
    std::span<const double> level;
    const join_across_bridges_options& opt;

    heights between(std::int32_t a, std::int32_t b) const noexcept
    {
        const double la = level[static_cast<std::size_t>(a)], lb = level[static_cast<std::size_t>(b)];
        return {std::min(la, lb) - opt.water_tolerance_m, std::max(la, lb) + opt.water_tolerance_m,
                std::max(la, lb) + opt.min_clearance_m};
    }
    /// The run of `gap` cells walked back from (r, c) by (dr, dc), between bodies a and b, is a bridge.
    bool bridges(std::ptrdiff_t r, std::ptrdiff_t c, int dr, int dc, std::ptrdiff_t gap, std::int32_t a,
                 std::int32_t b) const
    {
        if (!(std::abs(level[static_cast<std::size_t>(a)] - level[static_cast<std::size_t>(b)]) <=
              opt.level_tolerance_m))
            return false;
        const heights h = between(a, b);
        int part = 0;  // 0: water before the deck, 1: the deck, 2: water after it
        bool gap_or_deck = false;
        for (std::ptrdiff_t k = 1; k <= gap; ++k) {
            switch (h.of(min_z(r - k * dr, c - k * dc))) {
                case cell::gap:
                    gap_or_deck = true;
                    break;
                case cell::deck:
                    if (part == 2) return false;  // a second deck
                    part = 1;
                    gap_or_deck = true;
                    break;
                case cell::water:
                    part = part == 1 ? 2 : part;
                    break;
                case cell::bank:
                    break;
            }
        }
        return gap_or_deck;
    }
};

/// The bridge sweep of join_across_bridges on validated arguments (labels in [0, level.size())).
inline std::size_t bridge_sweep(raster_view<std::int32_t> labels, raster_view<const float> min_z,
                                std::span<const double> level, double cell_m, const join_across_bridges_options& opt)
{
    const std::ptrdiff_t rows = labels.rows(), cols = labels.cols();
    // No straight run of cells is longer than rows + cols: clamping there keeps huge or infinite spans exact.
    const int span_cells = static_cast<int>(std::min(
        std::floor(opt.max_span_m / cell_m), static_cast<double>(std::min<std::ptrdiff_t>(rows + cols, 1 << 30))));
    if (span_cells <= 0 && !opt.join_touching) return 0;
    std::vector<std::int32_t> parent(level.size());
    std::iota(parent.begin(), parent.end(), 0);
    const auto find = [&](std::int32_t x) {
        while (parent[static_cast<std::size_t>(x)] != x) x = parent[static_cast<std::size_t>(x)];
        return x;
    };
    const bridge_rule rule{min_z, level, opt};
    // Last water cell on each line: its row (for rows: its column) and label; -1 = none yet. The lines of
    // the columns, diagonals and anti-diagonals each in two arrays (rows and labels), so that a run of
    // cells moves its stretch of lines on in a loop that vectorizes (below).
    const auto n_lines = static_cast<std::size_t>(cols + 2 * (rows + cols));
    std::vector<std::ptrdiff_t> last_at(n_lines, -1);
    std::vector<std::int32_t> last_label(n_lines, 0);
    // Bridged cells are recorded and written after the pass, so every decision reads the original labels.
    struct bridged_cell {
        std::ptrdiff_t cell;
        int direction;
        std::int32_t label;
    };
    std::vector<bridged_cell> bridged;
    const auto close_run = [&](std::ptrdiff_t& lw_at, std::int32_t& lw_label, std::ptrdiff_t at, std::int32_t l,
                               std::ptrdiff_t r, std::ptrdiff_t c, int dr, int dc, int direction) {
        const std::ptrdiff_t gap = at - lw_at - 1;
        if (opt.join_touching && lw_at >= 0 && lw_label != l && gap == 0 &&
            std::abs(level[static_cast<std::size_t>(lw_label)] - level[static_cast<std::size_t>(l)]) <=
                opt.level_tolerance_m) {
            const auto ra = find(lw_label), rb = find(l);
            if (ra != rb) parent[static_cast<std::size_t>(std::max(ra, rb))] = std::min(ra, rb);
        }
        if (lw_at >= 0 && lw_label != l && gap >= 1 && gap <= span_cells &&
            rule.bridges(r, c, dr, dc, gap, lw_label, l)) {
            const auto heights = rule.between(lw_label, l);
            for (std::ptrdiff_t k = 1; k <= gap; ++k) {  // walk back from (r, c) over the land run: banks stay land
                const std::ptrdiff_t rr = r - k * dr, cc = c - k * dc;
                if (heights.of(min_z(rr, cc)) != bridge_rule::cell::bank)
                    bridged.push_back({rr * cols + cc, direction, std::min(lw_label, l)});
            }
            const auto ra = find(lw_label), rb = find(l);
            if (ra != rb) parent[static_cast<std::size_t>(std::max(ra, rb))] = std::min(ra, rb);
        }
        lw_at = at;
        lw_label = l;
    };
    // The columns that hold water (or a bridged cell) in each row, [first, last): the merge below reads
    // only them.
    std::vector<std::ptrdiff_t> first_water(static_cast<std::size_t>(rows), cols),
        last_water(static_cast<std::size_t>(rows), 0);
    std::vector<std::uint8_t> other_body(static_cast<std::size_t>(cols));
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        std::ptrdiff_t across_at = -1;
        std::int32_t across_label = 0;
        const std::int32_t* row = labels.row(r);
        // Run by run of one label, land passed over in blocks: along the row only a run's first cell can
        // close a land run.
        for_each_run(row, cols, [&](std::int32_t l, std::ptrdiff_t from, std::ptrdiff_t to) {
            close_run(across_at, across_label, from, l, r, from, 0, 1, 0);
            across_at = to - 1;
            first_water[static_cast<std::size_t>(r)] = std::min(first_water[static_cast<std::size_t>(r)], from);
            last_water[static_cast<std::size_t>(r)] = to;
            // Down the columns, diagonals and anti-diagonals (the lines of cell (r, c) are c, cols + rows +
            // c − r and cols + (rows + cols) + c + r: a run meets a stretch of to − from lines of each): a
            // line whose last water cell is of this body closes nothing and only moves on, a select over
            // the stretch that vectorizes; the others close a run, cell by cell (the order of closings does
            // not matter: bridged cells are sorted, and a merged group's root is its smallest label). The
            // loop's bounds are block-locals: captured ones might change under a store, as far as the
            // compiler knows, and keep it scalar.
            const auto advance = [&](std::ptrdiff_t first_line, int dc, int direction) {
                std::ptrdiff_t* at = last_at.data() + first_line;
                std::int32_t* label = last_label.data() + first_line;
                const std::ptrdiff_t n = to - from, row_at = r;
                const std::int32_t body = l;
                std::uint8_t* other = other_body.data();  // 1: the line's last water cell is of another body
                std::ptrdiff_t others = 0;
                for (std::ptrdiff_t k = 0; k < n; ++k) {
                    const bool same = label[k] == body;
                    others += !same;
                    other[k] = !same;
                    at[k] = same ? row_at : at[k];
                }
                if (others == 0) return;
                for (std::ptrdiff_t k = next_positive(other, 0, n); k < n; k = next_positive(other, k + 1, n))
                    close_run(at[k], label[k], r, l, r, from + k, 1, dc, direction);
            };
            advance(from, 0, 1);
            advance(cols + from - r + rows, 1, 2);
            advance(cols + (rows + cols) + from + r, -1, 3);
        });
    }
    std::sort(bridged.begin(), bridged.end(), [](const bridged_cell& a, const bridged_cell& b) {
        return a.cell != b.cell ? a.cell < b.cell : a.direction < b.direction;
    });
    std::size_t count = 0;
    for (std::size_t k = 0; k < bridged.size(); ++k) {
        if (k > 0 && bridged[k].cell == bridged[k - 1].cell) continue;
        const std::ptrdiff_t r = bridged[k].cell / cols, c = bridged[k].cell % cols;
        labels(r, c) = bridged[k].label;
        first_water[static_cast<std::size_t>(r)] = std::min(first_water[static_cast<std::size_t>(r)], c);
        last_water[static_cast<std::size_t>(r)] = std::max(last_water[static_cast<std::size_t>(r)], c + 1);
        ++count;
    }
    bool merged = false;
    for (std::size_t b = 0; b < parent.size(); ++b) merged |= parent[b] != static_cast<std::int32_t>(b);
    if (merged) {
        // Every label's group once, then only the water cells: the runs of the rows' water columns, those of
        // a label that keeps its number passed over.
        std::vector<std::int32_t> root(parent.size());
        for (std::size_t b = 0; b < parent.size(); ++b) root[b] = find(static_cast<std::int32_t>(b));
        for (std::ptrdiff_t r = 0; r < rows; ++r) {
            const std::ptrdiff_t first = first_water[static_cast<std::size_t>(r)],
                                 last = last_water[static_cast<std::size_t>(r)];
            if (first >= last) continue;
            std::int32_t* row = labels.row(r) + first;
            for_each_run(row, last - first, [&](std::int32_t l, std::ptrdiff_t from, std::ptrdiff_t to) {
                const std::int32_t to_label = root[static_cast<std::size_t>(l)];
                if (to_label != l) std::fill(row + from, row + to, to_label);
            });
        }
    }
    return count;
}

}  // namespace detail

inline std::size_t join_across_bridges(raster_view<std::int32_t> labels, raster_view<const float> min_z,
                                       std::span<const double> level, double cell_m,
                                       const join_across_bridges_options& opt)
{
    constexpr const char* fn = "join_across_bridges";
    detail::require_same_shape(labels, min_z, fn, "labels", "min_z");
    detail::require_positive(cell_m, fn, "cell_m");
    detail::validate(opt, fn);
    const auto [bottom, top] = detail::label_range(labels);
    detail::require(bottom >= 0, fn, "labels", ">= 0", bottom);
    detail::require(top == 0 || static_cast<std::size_t>(top) < level.size(), fn, "labels", "< level.size()", top);
    return detail::bridge_sweep(labels, min_z, level, cell_m, opt);
}

inline std::size_t join_across_bridges(raster_view<std::int32_t> labels, raster_view<const float> min_z, double cell_m,
                                       const join_across_bridges_options& opt, const execution& run)
{
    constexpr const char* fn = "join_across_bridges";
    detail::require_same_shape(labels, min_z, fn, "labels", "min_z");
    detail::require_positive(cell_m, fn, "cell_m");
    detail::validate(opt, fn);
    detail::check_execution(run, fn);
    // One level per label up to the largest; negative labels are refused.
    const auto level = detail::water_levels(labels, min_z, fn, run.threads);
    return detail::bridge_sweep(labels, min_z, level, cell_m, opt);
}

}  // namespace lidarfx
