// SPDX-License-Identifier: Apache-2.0
// confusion: agreement of a binary prediction with a truth mask, counted by area.
#pragma once

#include <cstddef>
#include <cstdint>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// Confusion counts (cells) and the scores derived from them; areas in m² from the cell size.
struct confusion {
    std::size_t true_positive = 0, false_positive = 0, true_negative = 0, false_negative = 0;
    std::size_t ignored = 0;    ///< cells excluded by the `valid` mask
    double cell_area_m2 = 1.0;  ///< area of one cell, m² (cell_m² in confusion_counts)

    std::size_t total() const noexcept { return true_positive + false_positive + true_negative + false_negative; }
    /// (TP + TN) / all; 0 when there is no cell.
    double accuracy() const noexcept { return ratio(true_positive + true_negative, total()); }
    /// TP / (TP + FN), the share of truth found (recall); 1 when the truth is empty.
    double sensitivity() const noexcept { return ratio(true_positive, true_positive + false_negative, 1.0); }
    /// TN / (TN + FP); 1 when there is no negative.
    double specificity() const noexcept { return ratio(true_negative, true_negative + false_positive, 1.0); }
    /// TP / (TP + FP); 1 when nothing was predicted.
    double precision() const noexcept { return ratio(true_positive, true_positive + false_positive, 1.0); }
    /// TP / (TP + FP + FN), intersection over union; 1 when both are empty.
    double iou() const noexcept { return ratio(true_positive, true_positive + false_positive + false_negative, 1.0); }
    double area_m2(std::size_t cells) const noexcept { return static_cast<double>(cells) * cell_area_m2; }

private:
    static double ratio(std::size_t num, std::size_t den, double if_empty = 0.0) noexcept
    {
        return den == 0 ? if_empty : static_cast<double>(num) / static_cast<double>(den);
    }
};

/// Counts predicted vs truth cell by cell (nonzero = positive). Cells where `valid` is 0 are skipped and
/// counted in `ignored` (pass an empty view, the default, to use every cell). cell_m, the cell size in
/// metres, sets cell_area_m2 = cell_m². O(cells). @throws invalid_input on shape mismatch or cell_m <= 0.
template <raster_input Pred, raster_input Truth>
confusion confusion_counts(const Pred& predicted, const Truth& truth, double cell_m,
                           raster_view<const std::uint8_t> valid = {})
{
    detail::require_same_shape(predicted, truth, "confusion_counts", "predicted", "truth");
    if (!valid.empty()) detail::require_same_shape(predicted, valid, "confusion_counts", "predicted", "valid");
    detail::require_positive(cell_m, "confusion_counts", "cell_m");
    confusion c;
    c.cell_area_m2 = cell_m * cell_m;
    for (std::ptrdiff_t r = 0; r < truth.rows(); ++r) {
        for (std::ptrdiff_t col = 0; col < truth.cols(); ++col) {
            if (!valid.empty() && !valid(r, col)) {
                ++c.ignored;
                continue;
            }
            const bool p = predicted(r, col) != 0, t = truth(r, col) != 0;
            if (p && t)
                ++c.true_positive;
            else if (p)
                ++c.false_positive;
            else if (t)
                ++c.false_negative;
            else
                ++c.true_negative;
        }
    }
    return c;
}

}  // namespace lidarfx
