// SPDX-License-Identifier: Apache-2.0
// Implementation of kernels/filter/survey_footprint.hpp: the sealing of gaps along the grid edges, the disc centres
// reachable from beyond the grid (a flood fill) and the cells they sweep. Included at the end of survey_footprint.hpp,
// after the declarations it defines; not a public header.
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
#include "lidarfx/kernels/filter/distance_transform.hpp"

namespace lidarfx {

namespace detail {

/// Along each of the four edges of `m`, sets the cells between two nonzero cells at most `gap` cells
/// apart (that many zero cells or fewer between them) to 1. O(rows + cols).
inline void seal_edge_gaps(raster_view<std::uint8_t> m, double gap)
{
    const auto seal_line = [gap](std::ptrdiff_t n, auto&& at) {
        std::ptrdiff_t last = -1;  // the previous nonzero cell of the line
        for (std::ptrdiff_t i = 0; i < n; ++i) {
            if (!at(i)) continue;
            if (last >= 0 && static_cast<double>(i - last - 1) <= gap)
                for (std::ptrdiff_t j = last + 1; j < i; ++j) at(j) = 1;
            last = i;
        }
    };
    const std::ptrdiff_t rows = m.rows(), cols = m.cols();
    seal_line(cols, [&](std::ptrdiff_t i) -> std::uint8_t& { return m(0, i); });
    seal_line(cols, [&](std::ptrdiff_t i) -> std::uint8_t& { return m(rows - 1, i); });
    seal_line(rows, [&](std::ptrdiff_t i) -> std::uint8_t& { return m(i, 0); });
    seal_line(rows, [&](std::ptrdiff_t i) -> std::uint8_t& { return m(i, cols - 1); });
}

}  // namespace detail

inline raster<std::uint8_t> survey_footprint(raster_view<const std::uint8_t> covered, double cell_m,
                                             const survey_footprint_options& opt)
{
    constexpr const char* function = "survey_footprint";
    detail::require_positive(cell_m, function, "cell_m");
    detail::require_positive(opt.hull_radius_m, function, "hull_radius_m");
    detail::check_execution(opt.run, function);
    const std::ptrdiff_t rows = covered.rows(), cols = covered.cols();
    raster<std::uint8_t> inside(rows, cols, 0);
    if (rows == 0 || cols == 0) {
        detail::report(opt.run.progress, 1.0, function);
        return inside;
    }
    const double radius = opt.hull_radius_m / cell_m;  // cells
    const double radius2 = radius * radius;
    // Beyond the grid is open: pad by more than the disc's diameter so it can roll all round the grid.
    detail::require(radius < 1.0e6, function, "hull_radius_m / cell_m", "< 10^6 cells", radius);
    const auto pad = static_cast<std::ptrdiff_t>(std::ceil(radius)) + 1;
    const std::ptrdiff_t prow = rows + 2 * pad, pcol = cols + 2 * pad;
    detail::require_raster_cells(prow, pcol, function, "the grid padded by the disc's radius");
    const auto phase = [&](double from, double to) {
        return execution{.threads = opt.run.threads, .progress = detail::progress_phase(opt.run.progress, from, to)};
    };

    raster<std::uint8_t> mask(prow, pcol, 0);
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        const std::uint8_t* in = covered.row(r);
        std::uint8_t* m = mask.view().row(r + pad) + pad;
        for (std::ptrdiff_t c = 0; c < cols; ++c) m[c] = in[c] != 0;
    }
    detail::seal_edge_gaps(mask.view().window(pad, pad, rows, cols), 2.0 * radius);
    raster<float> to_covered = squared_distance_transform(mask, {.run = phase(0.0, 0.45)});

    // Disc centres the disc can take (no covered cell within R), flood-filled from the padded border.
    std::vector<std::ptrdiff_t> stack;
    const auto free_centre = [&](std::ptrdiff_t r, std::ptrdiff_t c) {
        return static_cast<double>(to_covered.view()(r, c)) > radius2;
    };
    std::fill(mask.data(), mask.data() + mask.size(), std::uint8_t{0});  // now: reachable centres
    const auto push = [&](std::ptrdiff_t r, std::ptrdiff_t c) {
        if (r < 0 || c < 0 || r >= prow || c >= pcol) return;
        std::uint8_t& m = mask.view()(r, c);
        if (m || !free_centre(r, c)) return;
        m = 1;
        stack.push_back(r * pcol + c);
    };
    for (std::ptrdiff_t c = 0; c < pcol; ++c) {
        push(0, c);
        push(prow - 1, c);
    }
    for (std::ptrdiff_t r = 0; r < prow; ++r) {
        push(r, 0);
        push(r, pcol - 1);
    }
    while (!stack.empty()) {
        const std::ptrdiff_t i = stack.back();
        stack.pop_back();
        const std::ptrdiff_t r = i / pcol, c = i % pcol;
        push(r - 1, c);
        push(r + 1, c);
        push(r, c - 1);
        push(r, c + 1);
    }
    detail::report(opt.run.progress, 0.55, function);
    to_covered = raster<float>();  // free before the second transform

    // Outside: within R of a reachable centre (swept by the disc).
    const raster<float> to_disc = squared_distance_transform(mask, {.run = phase(0.55, 1.0)});
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        const float* d = to_disc.view().row(r + pad) + pad;
        const std::uint8_t* in = covered.row(r);
        std::uint8_t* o = inside.view().row(r);
        for (std::ptrdiff_t c = 0; c < cols; ++c) o[c] = in[c] != 0 || static_cast<double>(d[c]) > radius2;
    }
    return inside;
}

}  // namespace lidarfx
