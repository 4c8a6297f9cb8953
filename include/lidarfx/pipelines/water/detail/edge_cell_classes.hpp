// SPDX-License-Identifier: Apache-2.0
// Internals shared by join_shore_cells and trim_raised_edge_cells: the upper median of a window and the cell
// classes (body, edge, near a body) of a label raster, row by row.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx::detail {

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
/// three rows of body bytes (they vectorize). A band of rows from `first_row` on asks only for rows from
/// first_row - k - 1 on (the rows above are never looked at).
class shore_class_rows {
public:
    shore_class_rows(raster_view<const std::int32_t> labels, std::ptrdiff_t k, bool edges, std::ptrdiff_t first_row = 0)
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
        scanned_ = built_ = std::clamp<std::ptrdiff_t>(first_row - k - 1, 0, rows_);
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

}  // namespace lidarfx::detail
