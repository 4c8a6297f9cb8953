// SPDX-License-Identifier: Apache-2.0
// join_shore_cells and trim_raised_edge_cells: the cells on a waterbody's edge, by their count and their height.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// Options of join_shore_cells.
struct join_shore_cells_options {
    int window_cells = 3;          ///< the water and land a shore cell is compared with lie within this Chebyshev
                                   ///< distance of it, cells, >= 1. Default 3 (a 7 × 7 window)
    double min_contrast = 0.3;     ///< the land's mean returns per cell exceed the water's by at least this share
                                   ///< of the land's, (n_land − n_water) / n_land (without that contrast the
                                   ///< count says nothing of the mix), in (0, 1]. Default 0.3
    double min_water_share = 0.5;  ///< the cell's estimated water share f = (n_land − count) / (n_land −
                                   ///< n_water) is at least this (a cell is water when its centre is: half its
                                   ///< area), in (0, 1]. Default 0.5
    int min_body_neighbours = 3;   ///< the cell has at least this many body cells among its 8 neighbours (a
                                   ///< whole side on the water, not a corner touching it), in [1, 8]. Default 3
};

namespace detail {

inline void validate(const join_shore_cells_options& o, const char* fn)
{
    require(o.window_cells >= 1, fn, "window_cells", ">= 1", o.window_cells);
    require(o.min_contrast > 0 && o.min_contrast <= 1, fn, "min_contrast", "in (0, 1]", o.min_contrast);
    require(o.min_water_share > 0 && o.min_water_share <= 1, fn, "min_water_share", "in (0, 1]", o.min_water_share);
    require(o.min_body_neighbours >= 1 && o.min_body_neighbours <= 8, fn, "min_body_neighbours", "in [1, 8]",
            o.min_body_neighbours);
}

/// The upper median of v[0, n) (n >= 1, no NaN), the value nth_element puts at n / 2 (or the other zero when
/// -0 and +0 are both there: equal, so a height compares alike against either). A window holds a few dozen
/// heights: the first value with at most n / 2 below it and more at or below is found by counts, branch-free
/// (they vectorize), where nth_element mispredicts at most of its steps.
inline float upper_median(float* v, std::size_t n)
{
    constexpr std::size_t small = 64;
    if (n > small) {
        std::nth_element(v, v + n / 2, v + n);
        return v[n / 2];
    }
    const std::size_t half = n / 2;
    for (std::size_t i = 0;; ++i) {
        const float x = v[i];
        std::size_t below = 0, at_or_below = 0;
        for (std::size_t j = 0; j < n; ++j) {
            below += v[j] < x;
            at_or_below += v[j] <= x;
        }
        if (below <= half && at_or_below > half) return x;
    }
}

/// Cell classes of the shore steps, per cell of labels: 2 body (label > 0); else 1 when a body cell lies among
/// its 8 neighbours, 0 otherwise. With `edges`, body cells are split instead: 2 when a land cell lies among
/// their 8 neighbours (an edge), 1 when none does (interior); land is 0. Cells outside the raster count as
/// neither. The steps read them in windows of rows r - k .. r + k as r moves down, so the rows are built as
/// they come into reach, in a ring of 2k + 1 rows that stays in cache (a class raster of the whole labels
/// cost more to write, page by page, than the windows cost to read). Each row by branch-free passes over
/// three rows of body bytes (they vectorize).
class shore_class_rows {
public:
    shore_class_rows(raster_view<const std::int32_t> labels, std::ptrdiff_t k, bool edges)
        : labels_(labels),
          rows_(labels.rows()),
          cols_(labels.cols()),
          k_(k),
          edges_(edges),
          slots_(std::min(rows_, 2 * k + 1)),
          ring_(static_cast<std::size_t>(slots_ * cols_)),
          zero_(static_cast<std::size_t>(cols_), 0),
          any_(static_cast<std::size_t>(cols_) + 2, 0),
          all_(any_.size(), 1),
          has_body_(static_cast<std::size_t>(rows_)),
          row_of_slot_(static_cast<std::size_t>(slots_))
    {
    }

    /// Whether row r holds a body cell. Found as the rows are asked for, in order, a few rows before they are
    /// built: the part of a row read to find its first body cell is still in cache when the row is built.
    bool has_body(std::ptrdiff_t r)
    {
        if (r < 0 || r >= rows_) return false;
        for (; scanned_ <= r; ++scanned_)
            has_body_[static_cast<std::size_t>(scanned_)] = next_positive(labels_.row(scanned_), 0, cols_) < cols_;
        return has_body_[static_cast<std::size_t>(r)];
    }

    /// Builds the rows r - k .. r + k not built yet; r only grows from call to call.
    void reach(std::ptrdiff_t r)
    {
        for (std::ptrdiff_t rr = std::max(built_, r - k_), last = std::min(rows_ - 1, r + k_); rr <= last; ++rr)
            build(rr);
        built_ = std::max(built_, std::min(rows_, r + k_ + 1));
    }

    /// The classes of row r, within k of the row last reached; nullptr when all are 0.
    const std::uint8_t* row(std::ptrdiff_t r) const { return row_of_slot_[static_cast<std::size_t>(r % slots_)]; }

    /// A row of 0s, cols long, for rows whose classes are all 0.
    const std::uint8_t* zero_row() const { return zero_.data(); }

private:
    void build(std::ptrdiff_t r)
    {
        const std::size_t slot = static_cast<std::size_t>(r % slots_);
        // Rows without a body cell near them are all 0: they are passed over (most rows of a survey hold no water).
        if (!has_body(r) && (edges_ || (!has_body(r - 1) && !has_body(r + 1)))) {
            row_of_slot_[slot] = nullptr;
            return;
        }
        const std::ptrdiff_t cols = cols_;
        const std::uint8_t* m = body_mask(r);
        const std::uint8_t* u = r > 0 ? body_mask(r - 1) : m;  // the row itself changes neither test
        const std::uint8_t* d = r + 1 < rows_ ? body_mask(r + 1) : m;
        // Per column, whether any / all of the rows r - 1 .. r + 1 (inside) are body cells, padded by a column
        // that changes neither test at each end.
        std::uint8_t* a = any_.data() + 1;
        std::uint8_t* b = all_.data() + 1;
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            a[c] = static_cast<std::uint8_t>(u[c] | m[c] | d[c]);
            b[c] = static_cast<std::uint8_t>(u[c] & m[c] & d[c]);
        }
        std::uint8_t* out = ring_.data() + slot * static_cast<std::size_t>(cols);
        // In 0 / 1 bytes: a body cell is 2 less 1 when interior; a cell near a body is 1 plus 1 when a body
        // cell itself (it is then near one).
        if (edges_) {
            for (std::ptrdiff_t c = 0; c < cols; ++c)
                out[c] = static_cast<std::uint8_t>(2 * m[c] - (b[c - 1] & b[c] & b[c + 1]));
        } else {
            for (std::ptrdiff_t c = 0; c < cols; ++c)
                out[c] = static_cast<std::uint8_t>(m[c] + (a[c - 1] | a[c] | a[c + 1]));
        }
        row_of_slot_[slot] = out;
    }

    /// Row r of labels as 0 / 1 bytes (body or not), from a ring of three: each row is read as labels once
    /// (bytes pass 64 columns a vector, labels 16).
    const std::uint8_t* body_mask(std::ptrdiff_t r)
    {
        const std::size_t slot = static_cast<std::size_t>(r % 3);
        std::uint8_t* mask = masks_.data() + slot * static_cast<std::size_t>(cols_);
        if (mask_row_[slot] != r) {
            const std::int32_t* l = labels_.row(r);
            const std::ptrdiff_t cols = cols_;
            for (std::ptrdiff_t c = 0; c < cols; ++c) mask[c] = l[c] > 0;
            mask_row_[slot] = r;
        }
        return mask;
    }

    raster_view<const std::int32_t> labels_;
    std::ptrdiff_t rows_, cols_, k_;
    bool edges_;
    std::ptrdiff_t slots_, built_ = 0, scanned_ = 0;
    std::vector<std::uint8_t> ring_, zero_, any_, all_, has_body_;
    std::vector<const std::uint8_t*> row_of_slot_;
    std::vector<std::uint8_t> masks_ = std::vector<std::uint8_t>(3 * static_cast<std::size_t>(cols_));
    std::ptrdiff_t mask_row_[3] = {-1, -1, -1};
};

}  // namespace detail

/// Shore refinement: a cell on a body's edge whose centre lies on the water holds more water than land, and
/// water loses pulses (specular reflection, absorption) that land returns. So where the water around it
/// returns clearly fewer points than the land around it, the cell's count tells its water share. For every
/// land cell (label <= 0, inside the footprint; excluded or not) with at least min_body_neighbours body cells
/// among its 8 neighbours ("shore cell"): n_water = mean count over the body cells of its (2 window_cells +
/// 1)² window (dropouts count 0), n_land = mean count over the window's land cells with a return that are
/// neither next to a body (a body cell among their 8 neighbours) nor excluded; the cell joins when n_land
/// > 0, (n_land − n_water) / n_land >= min_contrast and (n_land − count) / (n_land − n_water) >=
/// min_water_share. It takes the label most frequent among its body neighbours (ties: the smallest). All
/// decisions read the labels as given (one pass; joined cells do not feed each other). `excluded` (optional;
/// e.g. vegetation, whose several returns per pulse would lift n_land) only keeps cells out of n_land; a
/// shore cell may be excluded itself (a bank's edge reads as vegetation). `footprint` is optional (empty =
/// all inside). Returns the number of cells joined.
/// O(cells + shore cells · (2 window_cells + 1)²).
/// @throws invalid_input on rasters of different shapes or options out of range.
inline std::size_t join_shore_cells(raster_view<std::int32_t> labels, raster_view<const std::uint32_t> count,
                                    raster_view<const std::uint8_t> excluded = {},
                                    raster_view<const std::uint8_t> footprint = {},
                                    const join_shore_cells_options& opt = {})
{
    constexpr const char* fn = "join_shore_cells";
    detail::validate(opt, fn);
    detail::require_same_shape(labels, count, fn, "labels", "count");
    if (!excluded.empty()) detail::require_same_shape(labels, excluded, fn, "labels", "excluded");
    if (!footprint.empty()) detail::require_same_shape(labels, footprint, fn, "labels", "footprint");
    const std::ptrdiff_t rows = labels.rows(), cols = labels.cols();
    if (rows == 0 || cols == 0) return 0;
    enum : std::uint8_t { far_land = 0, next_to_body = 1, body = 2 };
    const std::ptrdiff_t k = opt.window_cells;
    detail::shore_class_rows cls(labels, k, false);
    struct joining {
        std::ptrdiff_t r, c;
        std::int32_t label;
    };
    std::vector<joining> joined;
    std::vector<std::uint8_t> candidate(static_cast<std::size_t>(cols));  // next to a body, inside
    struct window_row {
        const std::uint8_t* cls;
        const std::uint32_t* count;
        const std::uint8_t* excluded;  // nullptr: none
    };
    std::vector<window_row> window;
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        if (!cls.has_body(r - 1) && !cls.has_body(r) && !cls.has_body(r + 1)) continue;  // no body near this row
        cls.reach(r);
        const std::uint8_t* cl = cls.row(r);
        const std::uint8_t* inside = footprint.empty() ? nullptr : footprint.row(r);
        for (std::ptrdiff_t c = 0; c < cols; ++c)
            candidate[static_cast<std::size_t>(c)] =
                static_cast<std::uint8_t>((cl[c] == next_to_body) & (!inside || inside[c] != 0));
        // The window rows, the same for every candidate of the row: found once.
        window.clear();
        for (std::ptrdiff_t rr = std::max<std::ptrdiff_t>(0, r - k), last = std::min(rows - 1, r + k); rr <= last; ++rr)
            window.push_back({cls.row(rr) ? cls.row(rr) : cls.zero_row(), count.row(rr),
                              excluded.empty() ? nullptr : excluded.row(rr)});
        for (std::ptrdiff_t c = detail::next_positive(candidate.data(), 0, cols); c < cols;
             c = detail::next_positive(candidate.data(), c + 1, cols)) {
            // Body neighbours and their most frequent label.
            std::int32_t nb[8];
            int n_nb = 0;
            for (std::ptrdiff_t dr = -1; dr <= 1; ++dr) {
                for (std::ptrdiff_t dc = -1; dc <= 1; ++dc) {
                    const std::ptrdiff_t rr = r + dr, cc = c + dc;
                    if ((dr | dc) == 0 || rr < 0 || cc < 0 || rr >= rows || cc >= cols) continue;
                    if (labels(rr, cc) > 0) nb[n_nb++] = labels(rr, cc);
                }
            }
            if (n_nb < opt.min_body_neighbours) continue;
            const std::ptrdiff_t c0 = std::max<std::ptrdiff_t>(0, c - k), c1 = std::min(cols - 1, c + k);
            double water_sum = 0, water_cells = 0, land_sum = 0, land_cells = 0;
            for (const auto& w : window) {
                for (std::ptrdiff_t cc = c0; cc <= c1; ++cc) {
                    if (w.cls[cc] == body) {
                        water_sum += w.count[cc];
                        water_cells += 1;
                    } else if (w.cls[cc] == far_land && w.count[cc] > 0 && !(w.excluded && w.excluded[cc])) {
                        land_sum += w.count[cc];
                        land_cells += 1;
                    }
                }
            }
            if (land_cells == 0 || water_cells == 0) continue;
            const double n_land = land_sum / land_cells, n_water = water_sum / water_cells;
            if (!(n_land - n_water >= opt.min_contrast * n_land)) continue;
            if (!((n_land - count(r, c)) >= opt.min_water_share * (n_land - n_water))) continue;
            std::int32_t best = 0;  // the most frequent neighbour label, the smallest among equals
            int best_votes = 0;
            for (int i = 0; i < n_nb; ++i) {
                const int votes = static_cast<int>(std::count(nb, nb + n_nb, nb[i]));
                if (votes > best_votes || (votes == best_votes && nb[i] < best)) best = nb[i], best_votes = votes;
            }
            joined.push_back({r, c, best});
        }
    }
    for (const auto& j : joined) labels(j.r, j.c) = j.label;
    return joined.size();
}

/// Options of trim_raised_edge_cells.
struct trim_raised_edge_cells_options {
    int window_cells = 3;             ///< the local water level is read within this Chebyshev distance, cells, >= 1.
                                      ///< Default 3 (a 7 × 7 window)
    double min_rise_m = 0.05;         ///< an edge cell whose min z stands more than this above the local level is
                                      ///< dry ground (2 σ of the 2-3 cm range noise of the lowest return), metres,
                                      ///< >= 0. Default 0.05
    double max_rise_m = 0.5;          ///< ... up to this; higher cells are bridge decks or bank cells whose water
                                      ///< returns were lost, left as they are (join_shore_cells, which runs after
                                      ///< this step in extract_waterbodies, judges bank cells by their count),
                                      ///< metres, > min_rise_m. Default 0.5
    std::size_t min_level_cells = 3;  ///< the local level needs at least this many interior body cells with a
                                      ///< return in the window, >= 1. Default 3
};

namespace detail {

inline void validate(const trim_raised_edge_cells_options& o, const char* fn)
{
    require(o.window_cells >= 1, fn, "window_cells", ">= 1", o.window_cells);
    require(o.min_rise_m >= 0, fn, "min_rise_m", ">= 0", o.min_rise_m);
    require(o.max_rise_m > o.min_rise_m, fn, "max_rise_m", "> min_rise_m", o.max_rise_m);
    require(o.min_level_cells >= 1, fn, "min_level_cells", ">= 1", o.min_level_cells);
}

}  // namespace detail

/// Edge refinement: the level gate and join_level_cells let a body take ground up to their tolerance (0.15 m)
/// above its level, a metre or two of a beach or a field; the water surface next to an edge cell is known far
/// better than that. For every edge cell (a body cell with a land cell among its 8 neighbours) with a return,
/// the local level is the median min z (the upper median of an even count) over the interior cells (no
/// land neighbour) of the same body with a finite min z in its (2 window_cells + 1)² window, given at least
/// min_level_cells of them (a body next to another at a different level reads its own); the cell becomes land (label 0)
/// when min_rise_m < min z − level <= max_rise_m. One pass over the labels as given. Returns the number of cells
/// trimmed. Elevations in metres. O(cells + edge cells · (2 window_cells + 1)²).
/// @throws invalid_input on rasters of different shapes or options out of range.
inline std::size_t trim_raised_edge_cells(raster_view<std::int32_t> labels, raster_view<const float> min_z,
                                          const trim_raised_edge_cells_options& opt = {})
{
    constexpr const char* fn = "trim_raised_edge_cells";
    detail::validate(opt, fn);
    detail::require_same_shape(labels, min_z, fn, "labels", "min_z");
    const std::ptrdiff_t rows = labels.rows(), cols = labels.cols();
    if (rows == 0 || cols == 0) return 0;
    const std::ptrdiff_t k = opt.window_cells;
    detail::shore_class_rows cls(labels, k, true);  // 0 land, 1 interior body cell, 2 edge body cell
    std::vector<std::ptrdiff_t> trimmed;
    std::vector<float> level;
    std::vector<std::uint8_t> edge(static_cast<std::size_t>(cols));  // an edge cell
    struct window_row {
        const std::uint8_t* cls;
        const float* z;
        const std::int32_t* labels;
    };
    std::vector<window_row> window;
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        if (!cls.has_body(r)) continue;
        cls.reach(r);
        const std::uint8_t* cl = cls.row(r);
        for (std::ptrdiff_t c = 0; c < cols; ++c) edge[static_cast<std::size_t>(c)] = cl[c] == 2;
        const float* z = min_z.row(r);  // read at edge cells and in their windows only
        // The window rows holding a body cell, the same for every edge cell of the row: found once.
        window.clear();
        for (std::ptrdiff_t rr = std::max<std::ptrdiff_t>(0, r - k), last = std::min(rows - 1, r + k); rr <= last; ++rr)
            if (const std::uint8_t* cw = cls.row(rr)) window.push_back({cw, min_z.row(rr), labels.row(rr)});
        // Row r + k enters the windows here, its heights not in cache: their loads (at both ends of each
        // window) are all started first, not one window after the other.
        if (r + k < rows) {
            const float* z_new = min_z.row(r + k);
            for (std::ptrdiff_t c = detail::next_positive(edge.data(), 0, cols); c < cols;
                 c = detail::next_positive(edge.data(), c + 1, cols)) {
                detail::prefetch_read(z_new + std::max<std::ptrdiff_t>(0, c - k));
                detail::prefetch_read(z_new + std::min(cols - 1, c + k));
            }
        }
        for (std::ptrdiff_t c = detail::next_positive(edge.data(), 0, cols); c < cols;
             c = detail::next_positive(edge.data(), c + 1, cols)) {
            if (!std::isfinite(z[c])) continue;
            const std::int32_t own = labels(r, c);
            const std::ptrdiff_t c0 = std::max<std::ptrdiff_t>(0, c - k), c1 = std::min(cols - 1, c + k);
            const std::size_t width = static_cast<std::size_t>(c1 - c0 + 1);
            std::size_t n = 0;
            for (const auto& w : window) {
                if (level.size() < n + width) level.resize(n + width);  // grows with the heights kept
                float* out = level.data();
                // Every height is written and kept when it counts (no branch on the mix of cells).
                for (std::ptrdiff_t cc = c0; cc <= c1; ++cc) {
                    out[n] = w.z[cc];
                    n += static_cast<std::size_t>((w.cls[cc] == 1) & (w.labels[cc] == own) & std::isfinite(w.z[cc]));
                }
            }
            if (n < opt.min_level_cells) continue;
            const double rise = static_cast<double>(z[c]) - static_cast<double>(detail::upper_median(level.data(), n));
            if (rise > opt.min_rise_m && rise <= opt.max_rise_m) trimmed.push_back(r * cols + c);
        }
    }
    for (const std::ptrdiff_t i : trimmed) labels(i / cols, i % cols) = 0;
    return trimmed.size();
}

}  // namespace lidarfx
