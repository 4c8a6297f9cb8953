// SPDX-License-Identifier: Apache-2.0
// Reference squared distance transform and survey footprint: brute force over every pair of cells.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include <lidarfx/core/raster.hpp>
#include <lidarfx/core/raster_view.hpp>

namespace reference {

/// min over feature cells f of (r - f.r)^2 + (c - f.c)^2, +infinity without features. O(cells^2).
inline lidarfx::raster<double> squared_distance(lidarfx::raster_view<const std::uint8_t> features)
{
    lidarfx::raster<double> out(features.rows(), features.cols(), std::numeric_limits<double>::infinity());
    for (std::ptrdiff_t fr = 0; fr < features.rows(); ++fr)
        for (std::ptrdiff_t fc = 0; fc < features.cols(); ++fc) {
            if (!features(fr, fc)) continue;
            for (std::ptrdiff_t r = 0; r < features.rows(); ++r)
                for (std::ptrdiff_t c = 0; c < features.cols(); ++c) {
                    const double d = double(r - fr) * double(r - fr) + double(c - fc) * double(c - fc);
                    if (d < out(r, c)) out(r, c) = d;
                }
        }
    return out;
}

/// The survey footprint by its definition: disc centres are the cells of the grid padded by `pad` cells
/// (pad > radius) with no covered cell within `radius` (squared distance > radius^2); those reachable
/// from the padded border by 4-steps through such centres sweep every cell within radius of them; the
/// footprint is every other cell, and every covered cell. Before that, cells of the grid's edge lying
/// between two covered edge cells at most 2 radius cells apart count as covered.
inline lidarfx::raster<std::uint8_t> footprint(lidarfx::raster_view<const std::uint8_t> covered, double radius)
{
    const auto pad = static_cast<std::ptrdiff_t>(std::ceil(radius)) + 1;
    const std::ptrdiff_t rows = covered.rows() + 2 * pad, cols = covered.cols() + 2 * pad;
    lidarfx::raster<std::uint8_t> padded(rows, cols, 0);
    for (std::ptrdiff_t r = 0; r < covered.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < covered.cols(); ++c) padded(r + pad, c + pad) = covered(r, c) != 0;
    // Edge gaps of at most 2 radius cells between covered edge cells are sealed.
    const auto seal = [&](std::ptrdiff_t n, auto cell) {
        for (std::ptrdiff_t a = 0; a < n; ++a)
            for (std::ptrdiff_t b = a + 1; b < n; ++b)
                if (covered(cell(a)[0], cell(a)[1]) && covered(cell(b)[0], cell(b)[1]) &&
                    static_cast<double>(b - a - 1) <= 2 * radius)
                    for (std::ptrdiff_t j = a + 1; j < b; ++j) padded(cell(j)[0] + pad, cell(j)[1] + pad) = 1;
    };
    const std::ptrdiff_t last_row = covered.rows() - 1, last_col = covered.cols() - 1;
    using rc = std::array<std::ptrdiff_t, 2>;
    seal(covered.cols(), [&](std::ptrdiff_t i) { return rc{0, i}; });
    seal(covered.cols(), [&](std::ptrdiff_t i) { return rc{last_row, i}; });
    seal(covered.rows(), [&](std::ptrdiff_t i) { return rc{i, 0}; });
    seal(covered.rows(), [&](std::ptrdiff_t i) { return rc{i, last_col}; });
    const auto to_covered = squared_distance(padded);
    lidarfx::raster<std::uint8_t> reached(rows, cols, 0);
    std::vector<std::pair<std::ptrdiff_t, std::ptrdiff_t>> todo;
    const auto visit = [&](std::ptrdiff_t r, std::ptrdiff_t c) {
        if (r < 0 || c < 0 || r >= rows || c >= cols || reached(r, c) || !(to_covered(r, c) > radius * radius)) return;
        reached(r, c) = 1;
        todo.emplace_back(r, c);
    };
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c)
            if (r == 0 || c == 0 || r == rows - 1 || c == cols - 1) visit(r, c);
    while (!todo.empty()) {
        const auto [r, c] = todo.back();
        todo.pop_back();
        visit(r - 1, c), visit(r + 1, c), visit(r, c - 1), visit(r, c + 1);
    }
    const auto to_disc = squared_distance(reached);
    lidarfx::raster<std::uint8_t> inside(covered.rows(), covered.cols(), 0);
    for (std::ptrdiff_t r = 0; r < covered.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < covered.cols(); ++c)
            inside(r, c) = covered(r, c) != 0 || to_disc(r + pad, c + pad) > radius * radius;
    return inside;
}

}  // namespace reference
