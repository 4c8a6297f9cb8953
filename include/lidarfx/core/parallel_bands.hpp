// SPDX-License-Identifier: Apache-2.0
// A deterministic parallel map over bands of rows: each band's result in a slot of its own, in band order.
#pragma once

#include <algorithm>
#include <concepts>
#include <cstddef>
#include <type_traits>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"

namespace lidarfx {

/// Runs body(r0, r1) over [0, rows) split into bands of `band_rows` rows on `threads` threads (0 = all cores),
/// as parallel_for_rows does, and returns what each band's call returned, one slot per band in band order:
/// ceil(rows / band_rows) slots, the last band short when band_rows does not divide rows, none for rows = 0.
/// Bands are fixed by `rows` and `band_rows` alone, so slots merged in order give the same result for every
/// thread count, bit for bit. The result type must be default-constructible and move-assignable.
/// @throws invalid_input if band_rows < 1 or threads < 0; rethrows the first exception a body throws.
template <class Body>
requires std::invocable<Body&, std::ptrdiff_t, std::ptrdiff_t>
auto parallel_bands(std::ptrdiff_t rows, std::ptrdiff_t band_rows, int threads, Body&& body)
{
    using result = std::remove_cvref_t<std::invoke_result_t<Body&, std::ptrdiff_t, std::ptrdiff_t>>;
    constexpr const char* fn = "parallel_bands";
    detail::require(band_rows >= 1, fn, "band_rows", ">= 1", band_rows);
    std::vector<result> slots(
        static_cast<std::size_t>((std::max<std::ptrdiff_t>(rows, 0) + band_rows - 1) / band_rows));
    parallel_for_rows(
        rows, band_rows, threads,
        [&](std::ptrdiff_t r0, std::ptrdiff_t r1) { slots[static_cast<std::size_t>(r0 / band_rows)] = body(r0, r1); },
        {}, fn);
    return slots;
}

}  // namespace lidarfx
