// SPDX-License-Identifier: Apache-2.0
// scan_coverage: cells a scan line crossed between two consecutive returns (pulses lost on the way).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <utility>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/grid.hpp"
#include "lidarfx/core/raster.hpp"

namespace lidarfx {

/// Settings of scan_coverage.
struct scan_coverage_options {
    /// Two consecutive returns belong to one sweep of the scanner when their GPS times differ by at most
    /// this, seconds; > 0. At 100–500 kHz, 5 ms is 500–2,500 lost pulses: a river 250 m wide at 0.5 m
    /// spacing, but far less than the seconds between two flight lines or the jumps of a sorted file.
    double max_time_gap_s = 0.005;
    /// ... and lie at most this far apart horizontally, metres; > 0 (the longest gap bridged).
    double max_span_m = 250.0;
};

/// Marks the cells of a grid that the scanner swept while its pulses were lost: for every two returns
/// that follow each other in acquisition order (the order a LAS file keeps within a flight line) with
/// GPS times at most max_time_gap_s apart and at most max_span_m apart, every cell the straight segment
/// between them crosses is covered. Together with the cells that hold returns this tells "no pulses
/// reached the ground here" (water, dark roofs) from "nothing was flown here" (see survey_footprint).
/// Feed the points in file order, chunk by chunk; the last point of a chunk links to the first of the
/// next, so the result does not depend on chunking; call end_sweep() between files. A file sorted in
/// space, or without GPS times, simply adds nothing. Coordinates in grid units, times in seconds.
/// O(points + cells crossed).
class scan_coverage {
public:
    /// @throws invalid_input if the grid is invalid or an option is not finite and > 0.
    explicit scan_coverage(const grid& g, const scan_coverage_options& opt = {})
        : scan_coverage(g, cell_box{0, 0, g.rows - 1, g.cols - 1}, opt)
    {
    }

    /// Coverage of the cells `window` of `g` only (a tile of a survey): segments are walked in g's cell
    /// coordinates exactly as on the whole grid and clipped to the window, so the tiles' windows of a
    /// partition of g put together give the whole grid's raster bit for bit. covered() is window-sized.
    /// @throws invalid_input as above, or if the window is empty or not inside g.
    scan_coverage(const grid& g, const cell_box& window, const scan_coverage_options& opt = {})
        : g_(g), opt_(opt), window_(window), covered_(window.rows(), window.cols(), 0)
    {
        constexpr const char* function = "scan_coverage";
        g.validate(function);
        detail::require(g.size() == 0 || (!window.empty() && window.row_min >= 0 && window.col_min >= 0 &&
                                          window.row_max < g.rows && window.col_max < g.cols),
                        function, "window must be a non-empty box of cells inside the grid");
        detail::require_positive(opt.max_time_gap_s, function, "max_time_gap_s");
        detail::require_positive(opt.max_span_m, function, "max_span_m");
    }

    /// Adds points in acquisition order: x, y (grid units) and GPS time (seconds) of equal lengths.
    /// Non-finite values break the sweep. @throws invalid_input if the lengths differ.
    void add(std::span<const double> x, std::span<const double> y, std::span<const double> gps_time)
    {
        detail::require(x.size() == y.size() && x.size() == gps_time.size(), "scan_coverage::add",
                        "x, y and gps_time must have equal lengths");
        const double span2 = opt_.max_span_m * opt_.max_span_m;
        for (std::size_t i = 0; i < x.size(); ++i) {
            const point p{x[i], y[i], gps_time[i]};
            if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.t))) {
                previous_.reset();
                continue;
            }
            if (previous_) {
                const double dx = p.x - previous_->x, dy = p.y - previous_->y;
                if (std::abs(p.t - previous_->t) <= opt_.max_time_gap_s && dx * dx + dy * dy <= span2)
                    mark_segment(*previous_, p);
            }
            previous_ = p;
        }
    }

    /// Ends the current sweep: the next point added starts a new one (call between files).
    void end_sweep() noexcept { previous_.reset(); }

    /// 1 = a scan line crossed the cell between two returns (cells holding the returns themselves are
    /// not marked unless a segment crosses them).
    raster_view<const std::uint8_t> covered() const noexcept { return covered_; }
    /// Moves the coverage raster out (the object is then empty).
    raster<std::uint8_t> take() noexcept { return std::move(covered_); }

private:
    struct point {
        double x, y, t;
    };

    // Walks the segment in steps of at most half a cell (fractional cell coordinates), marking each cell
    // inside the grid; short segments inside one cell cost one step.
    void mark_segment(const point& a, const point& b)
    {
        const cell_coords p = g_.to_cell_coords(a.x, a.y), q = g_.to_cell_coords(b.x, b.y);
        const double length = std::max(std::abs(q.row - p.row), std::abs(q.col - p.col));
        if (length < 1.0) return;  // within a cell or two neighbours: the returns mark them already
        // A segment whose box (one cell wider, for rounding) misses the window marks nothing in it.
        if (std::max(p.row, q.row) < static_cast<double>(window_.row_min - 1) ||
            std::min(p.row, q.row) > static_cast<double>(window_.row_max + 2) ||
            std::max(p.col, q.col) < static_cast<double>(window_.col_min - 1) ||
            std::min(p.col, q.col) > static_cast<double>(window_.col_max + 2))
            return;
        const auto steps = static_cast<std::ptrdiff_t>(std::ceil(2.0 * length));
        const raster_view<std::uint8_t> covered = covered_.view();
        for (std::ptrdiff_t s = 1; s < steps; ++s) {
            const double f = static_cast<double>(s) / static_cast<double>(steps);
            const double row = p.row + f * (q.row - p.row), col = p.col + f * (q.col - p.col);
            if (!(row >= 0 && col >= 0 && row < static_cast<double>(g_.rows) && col < static_cast<double>(g_.cols)))
                continue;
            const auto r = static_cast<std::ptrdiff_t>(row), c = static_cast<std::ptrdiff_t>(col);
            if (r < window_.row_min || r > window_.row_max || c < window_.col_min || c > window_.col_max) continue;
            covered(r - window_.row_min, c - window_.col_min) = 1;
        }
    }

    grid g_;
    scan_coverage_options opt_;
    cell_box window_;  // the cells of g_ that covered_ holds
    raster<std::uint8_t> covered_;
    std::optional<point> previous_;
};

}  // namespace lidarfx
