// SPDX-License-Identifier: Apache-2.0
// raster: an owning, contiguous, row-major 2-D array of cells (no georeferencing, no metadata).
#pragma once

#include <algorithm>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

namespace detail {
template <class T>
struct raster_allocator;  // the cells' allocator: large blocks aligned for huge pages (detail/raster_impl.hpp)
}  // namespace detail

/// Tag for rasters whose cells an algorithm is about to overwrite: raster(rows, cols, uninitialized).
struct uninitialized_t {
    explicit uninitialized_t() = default;
};
inline constexpr uninitialized_t uninitialized{};

/// Owning rows x cols raster of T, stored row-major and contiguous (row_stride() == cols()).
/// Converts implicitly to raster_view<T> / raster_view<const T>; copying a raster copies its cells.
template <class T>
class raster {
public:
    using value_type = T;

    raster() = default;
    raster(const raster&) = default;
    raster& operator=(const raster&) = default;
    /// A moved-from raster is empty (0 x 0), never a shape without cells.
    raster(raster&& other) noexcept
        : rows_(std::exchange(other.rows_, 0)), cols_(std::exchange(other.cols_, 0)), cells_(std::move(other.cells_))
    {
        other.cells_.clear();
    }
    raster& operator=(raster&& other) noexcept
    {
        if (this != &other) {
            rows_ = std::exchange(other.rows_, 0);
            cols_ = std::exchange(other.cols_, 0);
            cells_ = std::move(other.cells_);
            other.cells_.clear();
        }
        return *this;
    }

    /// rows x cols cells, each set to `fill`. @throws invalid_input if rows or cols < 0 or rows x cols exceeds
    /// max_raster_cells (core/raster_view.hpp); std::bad_alloc if the memory is not there.
    raster(std::ptrdiff_t rows, std::ptrdiff_t cols, T fill = T{})
        : rows_(checked(rows, "rows")), cols_(checked(cols, "cols")), cells_(cell_count(rows, cols), fill)
    {
    }

    /// rows x cols cells left default-initialized (indeterminate for arithmetic T): for outputs that are
    /// written in full before being read, which saves zeroing a large block. @throws as the filling form.
    raster(std::ptrdiff_t rows, std::ptrdiff_t cols, uninitialized_t)
        : rows_(checked(rows, "rows")), cols_(checked(cols, "cols"))
    {
        cells_.resize(cell_count(rows, cols));
    }

    /// Deep copy of any raster-like input.
    template <raster_input V>
    requires std::convertible_to<typename V::value_type, T>
    explicit raster(const V& source) : raster(source.rows(), source.cols())
    {
        for (std::ptrdiff_t r = 0; r < rows_; ++r) {
            for (std::ptrdiff_t c = 0; c < cols_; ++c) (*this)(r, c) = static_cast<T>(source(r, c));
        }
    }

    std::ptrdiff_t rows() const noexcept { return rows_; }
    std::ptrdiff_t cols() const noexcept { return cols_; }
    std::ptrdiff_t row_stride() const noexcept { return cols_; }
    std::ptrdiff_t size() const noexcept { return rows_ * cols_; }
    bool empty() const noexcept { return size() == 0; }

    T& operator()(std::ptrdiff_t r, std::ptrdiff_t c) noexcept
    {
        LIDARFX_ASSERT(r >= 0 && r < rows_ && c >= 0 && c < cols_);
        return cells_[static_cast<std::size_t>(r * cols_ + c)];
    }
    const T& operator()(std::ptrdiff_t r, std::ptrdiff_t c) const noexcept
    {
        LIDARFX_ASSERT(r >= 0 && r < rows_ && c >= 0 && c < cols_);
        return cells_[static_cast<std::size_t>(r * cols_ + c)];
    }

    T* data() noexcept { return cells_.data(); }
    const T* data() const noexcept { return cells_.data(); }
    T* row(std::ptrdiff_t r) noexcept { return data() + r * cols_; }
    const T* row(std::ptrdiff_t r) const noexcept { return data() + r * cols_; }
    auto begin() noexcept { return cells_.begin(); }
    auto end() noexcept { return cells_.end(); }
    auto begin() const noexcept { return cells_.begin(); }
    auto end() const noexcept { return cells_.end(); }

    void fill(const T& value) { std::fill(cells_.begin(), cells_.end(), value); }

    raster_view<T> view() noexcept { return {data(), rows_, cols_, cols_}; }
    raster_view<const T> view() const noexcept { return {data(), rows_, cols_, cols_}; }
    operator raster_view<T>() noexcept { return view(); }
    operator raster_view<const T>() const noexcept { return view(); }

    friend bool operator==(const raster& a, const raster& b)
    {
        return a.rows_ == b.rows_ && a.cols_ == b.cols_ && a.cells_ == b.cells_;
    }

private:
    static std::ptrdiff_t checked(std::ptrdiff_t n, const char* name)
    {
        detail::require(n >= 0, "raster", name, ">= 0", n);
        return n;
    }
    static std::size_t cell_count(std::ptrdiff_t rows, std::ptrdiff_t cols)
    {
        detail::require_raster_cells(rows, cols, "raster", "rows x cols");
        return static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols);
    }

    std::ptrdiff_t rows_ = 0, cols_ = 0;
    std::vector<T, detail::raster_allocator<T>> cells_;
};

}  // namespace lidarfx

#include "lidarfx/core/detail/raster_impl.hpp"
