// SPDX-License-Identifier: Apache-2.0
// remove_surface_outliers: isolated spikes (birds, noise) and pits (returns through canopy gaps) of a surface
// model, found by how few neighbours stand near them, replaced by the median of their neighbourhood.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// Settings of remove_surface_outliers.
struct surface_outliers_options {
    int radius_cells = 2;          ///< the neighbourhood: the (2 r + 1)^2 window around a cell, itself left out; >= 1
    double spike_height_m = 10.0;  ///< a spike stands more than this above all but a few neighbours, metres, > 0
    double pit_depth_m = 10.0;     ///< a pit lies more than this below all but a few neighbours, metres, > 0
    /// "A few": a cell is an outlier when fewer than this many of its finite neighbours lie within the height
    /// (depth) of it or beyond; >= 1. 3 keeps a roof's corner (8 roof cells around it in a 5 x 5 window), a
    /// 2 x 2 chimney and a one-cell alley, and finds one or two cells alone.
    int min_support_cells = 3;
    execution run = {};  ///< threads, progress and cancellation (core/parallel.hpp); never changes the result
};

/// What an outlier cell was.
enum class surface_outlier : std::uint8_t { none = 0, spike = 1, pit = 2 };

/// The surface with its outliers replaced, where they were, and how many.
struct surface_outliers_result {
    raster<float> surface;         ///< the input with each outlier cell set to the median of its finite neighbours
    raster<std::uint8_t> outlier;  ///< surface_outlier of each cell (0 none, 1 spike, 2 pit)
    std::size_t spikes = 0, pits = 0;
};

/// Finds the isolated spikes and pits of a surface model and replaces them. Let k be min_support_cells scaled
/// to the part of p's window inside the raster: k = max(1, ceil(min_support_cells * m / ((2 r + 1)^2 - 1))), m the
/// window's cells inside the raster other than p (so a border cell, with half a window, needs half the support).
/// A finite cell p with finite neighbours q in its window is a spike when fewer than k of them have z_q >= z_p -
/// spike_height_m, a pit when fewer than k have z_q <= z_p + pit_depth_m (a cell with fewer finite neighbours
/// than k is neither: too little is known around it). Every outlier takes the
/// median of its window's finite neighbours as they were in the input (the lower middle of an even count), so
/// the result does not depend on the order cells are visited. NaN cells stay NaN. z in metres.
/// O(rows * cols * (2 r + 1)^2); progress between blocks of rows.
/// @throws invalid_input for radius_cells < 1, a height or depth not finite and > 0, min_support_cells < 1 or
/// run.threads < 0; cancelled if run.progress returns false.
inline surface_outliers_result remove_surface_outliers(raster_view<const float> z,
                                                       const surface_outliers_options& opt = {});

// ---------------------------------------------------------------- implementation

inline surface_outliers_result remove_surface_outliers(raster_view<const float> z, const surface_outliers_options& opt)
{
    constexpr const char* fn = "remove_surface_outliers";
    detail::require(opt.radius_cells >= 1, fn, "radius_cells", ">= 1", opt.radius_cells);
    detail::require_positive(opt.spike_height_m, fn, "spike_height_m");
    detail::require_positive(opt.pit_depth_m, fn, "pit_depth_m");
    detail::require(opt.min_support_cells >= 1, fn, "min_support_cells", ">= 1", opt.min_support_cells);
    detail::check_execution(opt.run, fn);
    const std::ptrdiff_t rows = z.rows(), cols = z.cols(), r0 = opt.radius_cells;
    surface_outliers_result out{raster<float>(rows, cols), raster<std::uint8_t>(rows, cols, 0), 0, 0};
    for (std::ptrdiff_t r = 0; r < rows; ++r) std::copy(z.row(r), z.row(r) + cols, out.surface.row(r));
    const auto full = static_cast<std::size_t>((2 * r0 + 1) * (2 * r0 + 1) - 1);
    const auto needed = [&](std::ptrdiff_t inside) {  // k of the doc comment, for `inside` cells of the window
        const std::size_t scaled =
            (static_cast<std::size_t>(opt.min_support_cells) * static_cast<std::size_t>(inside) + full - 1) / full;
        return std::max<std::size_t>(1, scaled);
    };
    parallel_for_rows(
        rows, 32, opt.run.threads,
        [&](std::ptrdiff_t row0, std::ptrdiff_t row1) {
            std::vector<float> around;
            for (std::ptrdiff_t r = row0; r < row1; ++r) {
                for (std::ptrdiff_t c = 0; c < cols; ++c) {
                    const float zp = z(r, c);
                    if (std::isnan(zp)) continue;
                    around.clear();
                    std::size_t above = 0, below = 0;  // neighbours supporting the cell's height from above / below
                    const std::ptrdiff_t ra = std::max<std::ptrdiff_t>(0, r - r0), rb = std::min(rows - 1, r + r0);
                    const std::ptrdiff_t ca = std::max<std::ptrdiff_t>(0, c - r0), cb = std::min(cols - 1, c + r0);
                    const std::size_t support = needed((rb - ra + 1) * (cb - ca + 1) - 1);
                    for (std::ptrdiff_t rr = ra; rr <= rb; ++rr) {
                        for (std::ptrdiff_t cc = ca; cc <= cb; ++cc) {
                            const float zq = z(rr, cc);
                            if ((rr == r && cc == c) || std::isnan(zq)) continue;
                            around.push_back(zq);
                            above += zq >= zp - opt.spike_height_m;
                            below += zq <= zp + opt.pit_depth_m;
                        }
                    }
                    if (around.size() < support || (above >= support && below >= support)) continue;
                    const auto middle = around.begin() + static_cast<std::ptrdiff_t>((around.size() - 1) / 2);
                    std::nth_element(around.begin(), middle, around.end());
                    out.surface(r, c) = *middle;
                    out.outlier(r, c) =
                        static_cast<std::uint8_t>(above < support ? surface_outlier::spike : surface_outlier::pit);
                }
            }
        },
        opt.run.progress, fn);
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            out.spikes += out.outlier(r, c) == static_cast<std::uint8_t>(surface_outlier::spike);
            out.pits += out.outlier(r, c) == static_cast<std::uint8_t>(surface_outlier::pit);
        }
    }
    return out;
}

}  // namespace lidarfx
