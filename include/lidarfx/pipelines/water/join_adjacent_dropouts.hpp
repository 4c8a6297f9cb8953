// SPDX-License-Identifier: Apache-2.0
// join_adjacent_dropouts: a seed mask gains the eligible dropout cells next to it.
#pragma once

#include <cstdint>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/mask_ops.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/kernels/filter/morphology.hpp"

namespace lidarfx {

/// The dropouts next to a seed mask join it: out = seed | (dilate(seed) & dropout & eligible), dilate = the
/// 3 × 3 dilation (8-neighbours), all masks 0/1 of one shape (nonzero = on). Water with scattered dropouts has
/// level cells between them that a later opening of the seed mask would otherwise break apart; the dropouts
/// joined carry no return, so a seed's water level ignores them. `eligible`: cells that may join a body (e.g.
/// not vegetation, in no body yet). run: threads of the dilation (same result for any count). O(cells).
/// @throws invalid_input on masks of different shapes.
inline raster<std::uint8_t> join_adjacent_dropouts(raster_view<const std::uint8_t> seed,
                                                   raster_view<const std::uint8_t> dropout,
                                                   raster_view<const std::uint8_t> eligible, const execution& run = {});

// ---- implementation ----

inline raster<std::uint8_t> join_adjacent_dropouts(raster_view<const std::uint8_t> seed,
                                                   raster_view<const std::uint8_t> dropout,
                                                   raster_view<const std::uint8_t> eligible, const execution& run)
{
    constexpr const char* fn = "join_adjacent_dropouts";
    detail::require_same_shape(seed, dropout, fn, "seed", "dropout");
    detail::require_same_shape(seed, eligible, fn, "seed", "eligible");
    auto out = morph_dilate(seed, morphology_options{.size_cells = 3, .run = {.threads = run.threads}});
    mask_and(out, dropout, out);
    mask_and(out, eligible, out);
    mask_or(out, seed, out);
    return out;
}

}  // namespace lidarfx
