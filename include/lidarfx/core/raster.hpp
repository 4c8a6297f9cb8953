// SPDX-License-Identifier: Apache-2.0
// raster: an owning, contiguous, row-major 2-D array of cells (no georeferencing, no metadata).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

namespace detail {

/// Allocator of raster cells: blocks of 4 MiB and more are aligned to 2 MiB and, on Linux, marked for
/// transparent huge pages (as NumPy does), which saves most of the page faults of a large new raster. They
/// come from malloc, over-allocated by 2 MiB and aligned inside, with the block's start kept just before the
/// cells: glibc keeps a freed block of that size for the next one (aligned_alloc's blocks were unmapped on
/// every free), so a returning form called again finds warm pages instead of the kernel's zero fill.
template <class T>
struct raster_allocator {
    using value_type = T;
    static constexpr std::size_t huge = std::size_t{2} << 20;

    raster_allocator() noexcept = default;
    template <class U>
    raster_allocator(const raster_allocator<U>&) noexcept
    {
    }

    T* allocate(std::size_t n)
    {
        if (n > (static_cast<std::size_t>(-1) - 2 * huge) / sizeof(T)) throw std::bad_array_new_length();
        const std::size_t bytes = n * sizeof(T);
        if (bytes < 2 * huge) return std::allocator<T>().allocate(n);
        void* block = std::malloc(bytes + huge + sizeof(void*));
        if (!block) throw std::bad_alloc();
        const std::uintptr_t start = reinterpret_cast<std::uintptr_t>(block) + sizeof(void*);
        void* cells = reinterpret_cast<void*>((start + huge - 1) / huge * huge);
        std::memcpy(block_slot(cells), &block, sizeof block);
#if defined(__linux__) && defined(MADV_HUGEPAGE)
        ::madvise(cells, bytes / huge * huge, MADV_HUGEPAGE);  // a hint: failure only costs speed
#endif
        return static_cast<T*>(cells);
    }
    void deallocate(T* p, std::size_t n) noexcept
    {
        if (n * sizeof(T) < 2 * huge)
            std::allocator<T>().deallocate(p, n);
        else {
            void* block = nullptr;
            std::memcpy(&block, block_slot(p), sizeof block);
            std::free(block);
        }
    }
    /// Where a large block's start is kept: the bytes just before its cells. Reached through the address as
    /// an integer, since the cells' own type says nothing of the bytes before them (and GCC would warn).
    static void* block_slot(void* cells) noexcept
    {
        return reinterpret_cast<void*>(reinterpret_cast<std::uintptr_t>(cells) - sizeof(void*));
    }
    /// Value-less construction default-initializes (no zeroing of trivial cells; see raster(.., uninitialized)).
    template <class U>
    void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>)
    {
        ::new (static_cast<void*>(p)) U;
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args)
    {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
    friend bool operator==(const raster_allocator&, const raster_allocator&) noexcept
    {
        return true;
    }
};

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

namespace detail {

/// Makes `r` a rows x cols raster, keeping its memory when it already has that shape (its cells are then
/// unspecified, as a new one's would be): for buffers that a caller passes to several steps in turn, since a
/// new large raster's pages cost their first touch.
template <class T>
void ensure_shape(raster<T>& r, std::ptrdiff_t rows, std::ptrdiff_t cols)
{
    if (r.rows() != rows || r.cols() != cols) r = raster<T>(rows, cols, uninitialized);
}

/// Read access to any raster_input through a raster_view: strided rasters are viewed in place, other
/// types are copied once into an owned raster. Lets kernels run on plain pointers whatever the caller's type.
template <raster_input In>
class readable {
public:
    using T = typename In::value_type;
    explicit readable(const In& in)
    {
        if constexpr (strided_raster<In>) {
            view_ = view_of(in);
        } else {
            copy_ = raster<T>(in);
            view_ = copy_.view();
        }
    }
    raster_view<const T> view() const noexcept { return view_; }

private:
    raster<T> copy_;
    raster_view<const T> view_;
};

/// True if the memory spans of two views (first to last cell) intersect: an into form must not write its input.
/// Conservative: interleaved windows of one buffer (side by side, sharing rows) count as overlapping.
template <class A, class B>
bool overlaps(raster_view<A> a, raster_view<B> b) noexcept
{
    if (a.empty() || b.empty()) return false;
    const auto bytes = [](auto v) {
        const auto* first = reinterpret_cast<const unsigned char*>(v.data());
        const auto* last = reinterpret_cast<const unsigned char*>(&v(v.rows() - 1, v.cols() - 1) + 1);
        return std::pair{reinterpret_cast<std::uintptr_t>(first), reinterpret_cast<std::uintptr_t>(last)};
    };
    const auto [a0, a1] = bytes(a);
    const auto [b0, b1] = bytes(b);
    return a0 < b1 && b0 < a1;
}

/// Calls f(raster_view<const float>) on z's cells: through detail::readable (in place for strided rasters)
/// when z holds floats, else on one converted float copy.
template <raster_input In, class F>
decltype(auto) with_float_view(const In& z, F&& f)
{
    if constexpr (std::is_same_v<typename In::value_type, float>) {
        return f(readable<In>(z).view());
    } else {
        return f(raster<float>(z).view());
    }
}

/// Calls `compute(raster_view<T>)` on `out` directly when it is a strided raster of T, otherwise on a
/// scratch raster that is then copied into `out` cell by cell.
template <class T, class Out, class Compute>
void write_through(Out&& out, Compute&& compute)
{
    using O = std::remove_cvref_t<Out>;
    if constexpr (std::is_same_v<O, raster_view<T>>) {
        compute(out);
    } else if constexpr (std::is_same_v<O, raster<T>>) {
        compute(out.view());
    } else {
        raster<T> scratch(out.rows(), out.cols());
        compute(scratch.view());
        for (std::ptrdiff_t r = 0; r < scratch.rows(); ++r) {
            for (std::ptrdiff_t c = 0; c < scratch.cols(); ++c)
                out(r, c) = static_cast<typename O::value_type>(scratch(r, c));
        }
    }
}

}  // namespace detail
}  // namespace lidarfx
