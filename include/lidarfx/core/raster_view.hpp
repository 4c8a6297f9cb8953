// SPDX-License-Identifier: Apache-2.0
// raster_view: a non-owning, row-strided 2-D view of cells in caller memory, and the raster concepts.
#pragma once

#include <algorithm>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string_view>
#include <type_traits>
#include <utility>

#include "lidarfx/core/error.hpp"

namespace lidarfx {

/// The most cells a raster, a raster_view or a grid may have: 2^40 (1.1e12 cells, 4 TiB of floats). Their
/// constructors (and grid::validate) refuse more with invalid_input, and each extent alone is bounded by it
/// too (an empty 0 x 2^41 raster is refused), so `rows * cols`, every cell offset and every byte count fit
/// in 64-bit integers with room to spare.
inline constexpr std::int64_t max_raster_cells = std::int64_t{1} << 40;

namespace detail {

/// True if rows, cols >= 0 and max(rows, 1) * max(cols, 1) <= max_raster_cells (and <= PTRDIFF_MAX on
/// 32-bit targets), computed without overflow.
constexpr bool fits_raster_cells(std::ptrdiff_t rows, std::ptrdiff_t cols) noexcept
{
    constexpr auto most = static_cast<std::uint64_t>(
        std::min<std::int64_t>(max_raster_cells, std::numeric_limits<std::ptrdiff_t>::max()));
    if (rows < 0 || cols < 0) return false;
    const auto r = std::max<std::uint64_t>(static_cast<std::uint64_t>(rows), 1);
    const auto c = std::max<std::uint64_t>(static_cast<std::uint64_t>(cols), 1);
    return r <= most && c <= most / r;
}

/// Throws invalid_input "<function>: <what> must be <= 2^40 cells (got <rows> x <cols>)" unless
/// fits_raster_cells(rows, cols); `what` names the extents, e.g. "rows x cols".
constexpr void require_raster_cells(std::ptrdiff_t rows, std::ptrdiff_t cols, std::string_view function,
                                    std::string_view what)
{
    if (!fits_raster_cells(rows, cols)) {
        throw invalid_input(concat(function, ": ", what, " must be <= 2^40 cells (got ", rows, " x ", cols, ")"));
    }
}

/// Splits linear cell indices i = r * cols + c (0 <= i < max_raster_cells) into row and column without an
/// integer division: r = ⌊i · (1 / cols)⌋ in double, which below 2^40 is off by at most one (the product's
/// error is < 2^-11), then corrected. For the hot loops of floods, where a division per cell costs more
/// than the cell's work.
struct cell_splitter {
    std::ptrdiff_t cols = 1;
    double inverse = 1.0;

    explicit cell_splitter(std::ptrdiff_t columns) noexcept
        : cols(columns), inverse(columns > 0 ? 1.0 / static_cast<double>(columns) : 0.0)
    {
    }

    std::pair<std::ptrdiff_t, std::ptrdiff_t> operator()(std::ptrdiff_t i) const noexcept
    {
        auto r = static_cast<std::ptrdiff_t>(static_cast<double>(i) * inverse);
        std::ptrdiff_t c = i - r * cols;
        if (c < 0) {
            --r;
            c += cols;
        } else if (c >= cols) {
            ++r;
            c -= cols;
        }
        return {r, c};
    }
};

}  // namespace detail

/// Anything with rows(), cols() and (r, c) indexing yielding its value_type: algorithms accept it.
template <class V>
concept raster_input = requires(const V& v, std::ptrdiff_t i)
{
    typename V::value_type;
    {
        v.rows()
        } -> std::convertible_to<std::ptrdiff_t>;
    {
        v.cols()
        } -> std::convertible_to<std::ptrdiff_t>;
    {
        v(i, i)
        } -> std::convertible_to<typename V::value_type>;
};

/// A raster_input whose cells can be assigned a T through an lvalue: algorithms write results into it.
/// (raster_view<T> and raster<T>& both qualify; pass outputs as `Out&&`.)
template <class V, class T>
concept raster_output_of = raster_input<std::remove_cvref_t<V>> && requires(V& v, T x)
{
    v(0, 0) = x;
};

/// A raster whose cells sit in memory as rows of contiguous cells `row_stride()` apart: it can be viewed
/// without copying (raster, raster_view, or a host type such as a wrapped cv::Mat or GDAL buffer).
template <class V>
concept strided_raster = raster_input<V> && requires(const V& v)
{
    {
        v.data()
        } -> std::convertible_to<const typename V::value_type*>;
    {
        v.row_stride()
        } -> std::convertible_to<std::ptrdiff_t>;
};

/// Non-owning view of `rows` x `cols` cells; cell (r, c) is at data[r * row_stride + c] (row 0 = north).
/// Cheap to copy; constness lives in T (raster_view<const float> reads, raster_view<float> writes).
template <class T>
class raster_view {
public:
    using value_type = std::remove_cv_t<T>;
    using element_type = T;

    constexpr raster_view() noexcept = default;

    /// View of contiguous rows (row_stride = cols).
    constexpr raster_view(T* data, std::ptrdiff_t rows, std::ptrdiff_t cols) : raster_view(data, rows, cols, cols) {}

    /// View with an explicit row stride in elements. @throws invalid_input unless rows, cols >= 0,
    /// rows x cols <= max_raster_cells, row_stride >= cols, the cells addressed ((rows - 1) * row_stride + cols
    /// elements of T) fit in PTRDIFF_MAX bytes, and data is not null for a non-empty view.
    constexpr raster_view(T* data, std::ptrdiff_t rows, std::ptrdiff_t cols, std::ptrdiff_t row_stride)
        : data_(data), rows_(rows), cols_(cols), stride_(row_stride)
    {
        detail::require(rows >= 0 && cols >= 0, "raster_view", "rows and cols must be >= 0");
        detail::require_raster_cells(rows, cols, "raster_view", "rows x cols");
        detail::require(row_stride >= cols, "raster_view", "row_stride", ">= cols", row_stride);
        if (rows > 0 && cols > 0) {
            constexpr std::ptrdiff_t most =
                std::numeric_limits<std::ptrdiff_t>::max() / static_cast<std::ptrdiff_t>(sizeof(T));
            // The message is made only on failure: views are made in hot loops (per row, per tile).
            detail::require(rows - 1 <= (most - cols) / row_stride, "raster_view", [&] {
                return detail::concat("(rows - 1) * row_stride + cols cells must fit in the address space (got ", rows,
                                      " rows, row_stride ", row_stride, ")");
            });
        }
        detail::require(data != nullptr || rows == 0 || cols == 0, "raster_view",
                        "data must not be null for a non-empty view");
    }

    /// Converts a mutable view to a read-only one.
    template <class U>
    requires(std::is_const_v<T>&& std::is_same_v<std::remove_cv_t<T>, U>) constexpr raster_view(
        const raster_view<U>& other) noexcept
        : data_(other.data()), rows_(other.rows()), cols_(other.cols()), stride_(other.row_stride())
    {
    }

    constexpr T& operator()(std::ptrdiff_t r, std::ptrdiff_t c) const noexcept
    {
        LIDARFX_ASSERT(r >= 0 && r < rows_ && c >= 0 && c < cols_);
        return data_[r * stride_ + c];
    }

    constexpr T* data() const noexcept { return data_; }
    constexpr std::ptrdiff_t rows() const noexcept { return rows_; }
    constexpr std::ptrdiff_t cols() const noexcept { return cols_; }
    constexpr std::ptrdiff_t row_stride() const noexcept { return stride_; }
    constexpr std::ptrdiff_t size() const noexcept { return rows_ * cols_; }
    constexpr bool empty() const noexcept { return rows_ == 0 || cols_ == 0; }
    constexpr bool is_contiguous() const noexcept { return stride_ == cols_ || rows_ <= 1; }

    /// Pointer to the first of cols() contiguous cells of row r.
    constexpr T* row(std::ptrdiff_t r) const noexcept
    {
        LIDARFX_ASSERT(r >= 0 && r < rows_);
        return data_ + r * stride_;
    }

    /// Sub-view of nr x nc cells starting at (r0, c0), sharing this view's stride.
    /// @throws invalid_input if the window does not lie inside the view.
    constexpr raster_view window(std::ptrdiff_t r0, std::ptrdiff_t c0, std::ptrdiff_t nr, std::ptrdiff_t nc) const
    {
        if (r0 < 0 || c0 < 0 || nr < 0 || nc < 0 || r0 > rows_ || c0 > cols_ || nr > rows_ - r0 || nc > cols_ - c0) {
            throw invalid_input(detail::concat("raster_view::window: window (", r0, ", ", c0, ") of ", nr, "x", nc,
                                               " does not fit in a ", rows_, "x", cols_, " view"));
        }
        return raster_view(nr == 0 || nc == 0 ? data_ : data_ + r0 * stride_ + c0, nr, nc, stride_);
    }

    /// Read-only copy of this handle.
    constexpr raster_view<const T> as_const() const noexcept { return *this; }

private:
    T* data_ = nullptr;
    std::ptrdiff_t rows_ = 0, cols_ = 0, stride_ = 0;
};

template <class T>
raster_view(T*, std::ptrdiff_t, std::ptrdiff_t) -> raster_view<T>;
template <class T>
raster_view(T*, std::ptrdiff_t, std::ptrdiff_t, std::ptrdiff_t) -> raster_view<T>;

/// Non-owning read-only view of any strided raster (no copy).
template <strided_raster V>
constexpr auto view_of(const V& v)
{
    using T = typename V::value_type;
    return raster_view<const T>(static_cast<const T*>(v.data()), v.rows(), v.cols(), v.row_stride());
}

}  // namespace lidarfx
