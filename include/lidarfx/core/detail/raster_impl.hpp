// SPDX-License-Identifier: Apache-2.0
// Implementation of core/raster.hpp: the cells' allocator, and the helpers every kernel uses to read any raster_input
// in place (readable, with_float_view) and to write any output (write_through, overlaps, ensure_shape). Included at
// the end of raster.hpp; not a public header.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
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
