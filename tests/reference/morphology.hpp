// SPDX-License-Identifier: Apache-2.0
// Reference binary morphology (brute-force window min/max) and the test masks shared by the label tests.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <random>

#include <lidarfx/core/raster.hpp>
#include <lidarfx/core/raster_view.hpp>

namespace reference {

using mask = lidarfx::raster<std::uint8_t>;

/// rows x cols mask whose cells are 1 with probability `density`; nonzero cells get varied values
/// (1..255) so that "nonzero = 1" is exercised too.
inline mask random_mask(std::mt19937& rng, std::ptrdiff_t rows, std::ptrdiff_t cols, double density)
{
    std::bernoulli_distribution one(density);
    std::uniform_int_distribution<int> value(1, 255);
    mask m(rows, cols);
    for (auto& v : m) v = one(rng) ? static_cast<std::uint8_t>(value(rng)) : std::uint8_t{0};
    return m;
}

/// Checkerboard of `cell` x `cell` squares, 1 where (r / cell + c / cell) is even.
inline mask checkerboard(std::ptrdiff_t rows, std::ptrdiff_t cols, std::ptrdiff_t cell = 1)
{
    mask m(rows, cols);
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c) m(r, c) = (r / cell + c / cell) % 2 == 0 ? 1 : 0;
    return m;
}

/// A square spiral path of ones, one cell wide with one-cell gaps: a single long 4-connected component.
inline mask spiral(std::ptrdiff_t rows, std::ptrdiff_t cols)
{
    mask m(rows, cols);
    std::ptrdiff_t top = 0, left = 0, bottom = rows - 1, right = cols - 1;
    while (top <= bottom && left <= right) {
        for (std::ptrdiff_t c = left; c <= right; ++c) m(top, c) = 1;
        for (std::ptrdiff_t r = top; r <= bottom; ++r) m(r, right) = 1;
        if (top + 2 <= bottom)
            for (std::ptrdiff_t c = left; c <= right; ++c) m(bottom, c) = 1;
        if (left + 2 <= right)
            for (std::ptrdiff_t r = top + 2; r <= bottom; ++r) m(r, left) = 1;
        top += 2;
        left += 2;
        bottom -= 2;
        right -= 2;
        if (top <= bottom && left <= right) m(top, left - 1) = 1;  // link to the next turn
    }
    return m;
}

/// A comb: a full top row with teeth on every second column hanging down (merges late in a scan).
inline mask comb(std::ptrdiff_t rows, std::ptrdiff_t cols)
{
    mask m(rows, cols);
    for (std::ptrdiff_t c = 0; c < cols; ++c) m(rows - 1, c) = 1;
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; c += 2) m(r, c) = 1;
    return m;
}

/// Brute force: out(r, c) = max (dilate) or min (erode) of (m != 0) over the width x height rectangle
/// centred on (r, c), clipped at the raster border.
template <class View>
mask window_extreme(const View& m, int width, int height, bool erode)
{
    mask out(m.rows(), m.cols());
    const std::ptrdiff_t kx = width / 2, ky = height / 2;
    for (std::ptrdiff_t r = 0; r < m.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < m.cols(); ++c) {
            bool any = false, all = true;
            for (std::ptrdiff_t rr = std::max<std::ptrdiff_t>(0, r - ky); rr <= std::min(m.rows() - 1, r + ky); ++rr) {
                for (std::ptrdiff_t cc = std::max<std::ptrdiff_t>(0, c - kx); cc <= std::min(m.cols() - 1, c + kx);
                     ++cc) {
                    const bool v = m(rr, cc) != 0;
                    any = any || v;
                    all = all && v;
                }
            }
            out(r, c) = (erode ? all : any) ? 1 : 0;
        }
    }
    return out;
}

template <class View>
mask dilate(const View& m, int width, int height)
{
    return window_extreme(m, width, height, false);
}
template <class View>
mask erode(const View& m, int width, int height)
{
    return window_extreme(m, width, height, true);
}
template <class View>
mask open(const View& m, int width, int height)
{
    return dilate(erode(m, width, height), width, height);
}
template <class View>
mask close(const View& m, int width, int height)
{
    return erode(dilate(m, width, height), width, height);
}

/// 1 - (m != 0).
template <class View>
mask complement(const View& m)
{
    mask out(m.rows(), m.cols());
    for (std::ptrdiff_t r = 0; r < m.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < m.cols(); ++c) out(r, c) = m(r, c) != 0 ? 0 : 1;
    return out;
}

/// Copy of m placed at (r0, c0) inside a larger raster filled with `fill`, returned with a view of the
/// copy: the view has row_stride > cols.
struct embedded {
    mask storage;
    lidarfx::raster_view<const std::uint8_t> view;
};
inline embedded embed(const mask& m, std::ptrdiff_t r0, std::ptrdiff_t c0, std::uint8_t fill)
{
    embedded e{mask(m.rows() + r0 + 2, m.cols() + c0 + 3, fill), {}};
    for (std::ptrdiff_t r = 0; r < m.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < m.cols(); ++c) e.storage(r0 + r, c0 + c) = m(r, c);
    e.view = e.storage.view().as_const().window(r0, c0, m.rows(), m.cols());
    return e;
}

}  // namespace reference
