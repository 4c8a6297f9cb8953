// SPDX-License-Identifier: Apache-2.0
// Implementation of water_under_decks (included at the end of pipelines/water/water_under_decks.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <tuple>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/kernels/filter/distance_transform.hpp"
#include "lidarfx/kernels/label/connected_components.hpp"

namespace lidarfx {

namespace detail {

inline void validate(const water_under_decks_options& o, const char* fn)
{
    require_positive(o.deck_clearance_m, fn, "deck_clearance_m");
    const auto at_least_zero = [fn](double v, const char* name) {
        require(std::isfinite(v) && v >= 0, fn, name, "finite and >= 0", v);
    };
    at_least_zero(o.level_tolerance_m, "level_tolerance_m");
    at_least_zero(o.reach_m, "reach_m");
    at_least_zero(o.max_span_m, "max_span_m");
}

/// The rivers of water_under_decks and the cells they own.
struct deck_rivers {
    raster_view<std::int32_t> body;
    raster_view<float> water;
    raster_view<const float> min_z;
    std::vector<std::uint8_t> is_river;  ///< per id

    bool river(std::int32_t id) const noexcept
    {
        return id > 0 && static_cast<std::size_t>(id) < is_river.size() && is_river[static_cast<std::size_t>(id)];
    }
    bool inside(std::ptrdiff_t r, std::ptrdiff_t c) const noexcept
    {
        return r >= 0 && c >= 0 && r < body.rows() && c < body.cols();
    }
    /// Calls f(river cell row, col) for the 8 neighbours of (r, c) that are river cells, in row-major order, until
    /// f returns true.
    template <class F>
    void each_river_neighbour(std::ptrdiff_t r, std::ptrdiff_t c, F&& f) const
    {
        for (std::ptrdiff_t rr = r - 1; rr <= r + 1; ++rr)
            for (std::ptrdiff_t cc = c - 1; cc <= c + 1; ++cc)
                if ((rr != r || cc != c) && inside(rr, cc) && river(body(rr, cc)) && f(rr, cc)) return;
    }
};

/// Step 1: the land cells within reach of a deck cell, in raster order.
inline std::vector<std::ptrdiff_t> cells_near_decks(const deck_rivers& k, double clearance_m, double reach_cells)
{
    const std::ptrdiff_t rows = k.body.rows(), cols = k.body.cols();
    raster<std::uint8_t> deck(rows, cols, 0);
    bool any = false;
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const float z = k.min_z(r, c);
            if (k.body(r, c) != 0 || !std::isfinite(z)) continue;
            k.each_river_neighbour(r, c, [&](std::ptrdiff_t rr, std::ptrdiff_t cc) {
                deck(r, c) = z >= static_cast<double>(k.water(rr, cc)) + clearance_m ? 1 : 0;
                return deck(r, c) == 1;
            });
            any = any || deck(r, c);
        }
    std::vector<std::ptrdiff_t> near;
    if (!any) return near;
    const raster<float> d2 = squared_distance_transform(deck);
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c)
            if (k.body(r, c) == 0 && std::isfinite(k.min_z(r, c)) && d2(r, c) <= reach_cells * reach_cells)
                near.push_back(r * cols + c);
    return near;
}

/// Step 1: cells at a river's level near a deck join it, round after round.
inline std::size_t join_level_cells_near_decks(const deck_rivers& k, const std::vector<std::ptrdiff_t>& near,
                                               double tolerance_m)
{
    const std::ptrdiff_t cols = k.body.cols();
    std::size_t joined = 0;
    std::vector<std::tuple<std::ptrdiff_t, std::int32_t, float>> round;
    do {
        round.clear();
        for (const std::ptrdiff_t at : near) {
            const std::ptrdiff_t r = at / cols, c = at % cols;
            if (k.body(r, c) != 0) continue;
            const float z = k.min_z(r, c);
            k.each_river_neighbour(r, c, [&](std::ptrdiff_t rr, std::ptrdiff_t cc) {
                const float level = k.water(rr, cc);
                if (!(std::abs(static_cast<double>(z) - level) <= tolerance_m)) return false;
                round.emplace_back(at, k.body(rr, cc), level);
                return true;
            });
        }
        for (const auto& [at, id, level] : round) {
            k.body(at / cols, at % cols) = id;
            k.water(at / cols, at % cols) = level;
        }
        joined += round.size();
    } while (!round.empty());
    return joined;
}

/// Per land cell of `body` (4-connected, the dual of 8-connected water): whether its land reaches the raster's
/// edge. Land that does not is an island of the water around it.
inline raster<std::uint8_t> land_reaching_the_edge(raster_view<const std::int32_t> body)
{
    raster<std::uint8_t> land(body.rows(), body.cols(), 0);
    for (std::ptrdiff_t r = 0; r < body.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < body.cols(); ++c) land(r, c) = body(r, c) == 0 ? 1 : 0;
    const components parts = connected_components(land, connectivity::four);
    std::vector<std::uint8_t> open(parts.count() + 1, 0);
    for (std::ptrdiff_t r = 0; r < body.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < body.cols(); ++c)
            if (r == 0 || c == 0 || r == body.rows() - 1 || c == body.cols() - 1)
                open[static_cast<std::size_t>(parts.labels(r, c))] = 1;
    for (std::ptrdiff_t r = 0; r < body.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < body.cols(); ++c)
            land(r, c) = land(r, c) && open[static_cast<std::size_t>(parts.labels(r, c))];
    return land;
}

/// Step 2: the runs of deck cells between two cells of one river, in the four directions.
inline std::size_t join_deck_runs(const deck_rivers& k, double clearance_m, std::ptrdiff_t max_cells)
{
    const raster<std::int32_t> before(k.body);  // runs are found on the cells as step 1 left them
    const raster<float> level(k.water);
    const raster<std::uint8_t> open_land = land_reaching_the_edge(before);
    constexpr std::ptrdiff_t step[4][2] = {{0, 1}, {1, 0}, {1, 1}, {1, -1}};
    std::size_t joined = 0;
    for (const auto& d : step)
        for (std::ptrdiff_t r = 0; r < before.rows(); ++r)
            for (std::ptrdiff_t c = 0; c < before.cols(); ++c) {
                const std::int32_t id = before(r, c);
                if (!k.river(id)) continue;
                const double from = level(r, c);
                std::ptrdiff_t n = 1;  // cells of the run so far + 1
                bool deck = false;
                for (;; ++n) {
                    const std::ptrdiff_t rr = r + n * d[0], cc = c + n * d[1];
                    if (n - 1 > max_cells || !k.inside(rr, cc)) break;
                    if (before(rr, cc) != 0 || !open_land(rr, cc)) break;  // water, or an island
                    const float z = k.min_z(rr, cc);
                    if (std::isfinite(z) && !(z >= from + clearance_m)) break;  // ground: no deck here
                    deck = deck || std::isfinite(z);
                }
                const std::ptrdiff_t re = r + n * d[0], ce = c + n * d[1];
                if (!deck || n - 1 > max_cells || !k.inside(re, ce) || before(re, ce) != id) continue;
                const double to = level(re, ce);
                for (std::ptrdiff_t j = 1; j < n; ++j) {
                    const std::ptrdiff_t rr = r + j * d[0], cc = c + j * d[1];
                    if (k.body(rr, cc) != 0) continue;  // taken by an earlier run
                    k.body(rr, cc) = id;
                    k.water(rr, cc) =
                        static_cast<float>(from + (to - from) * static_cast<double>(j) / static_cast<double>(n));
                    ++joined;
                }
            }
    return joined;
}

}  // namespace detail

inline water_under_decks_result water_under_decks(raster_view<std::int32_t> body, raster_view<float> water_surface,
                                                  raster_view<const float> min_z, std::span<const std::int32_t> rivers,
                                                  double cell_m, const water_under_decks_options& opt)
{
    constexpr const char* fn = "water_under_decks";
    detail::require_same_shape(body, water_surface, fn, "body", "water_surface");
    detail::require_same_shape(body, min_z, fn, "body", "min_z");
    detail::require_positive(cell_m, fn, "cell_m");
    detail::validate(opt, fn);
    detail::deck_rivers k{body, water_surface, min_z, {}};
    for (const std::int32_t id : rivers) {
        detail::require(id >= 0, fn, "rivers", "ids >= 0", id);
        if (static_cast<std::size_t>(id) >= k.is_river.size()) k.is_river.resize(static_cast<std::size_t>(id) + 1, 0);
        k.is_river[static_cast<std::size_t>(id)] = 1;
    }
    for (std::ptrdiff_t r = 0; r < body.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < body.cols(); ++c)
            detail::require(body(r, c) >= 0, fn, "body", ">= 0", body(r, c));
    water_under_decks_result out;
    if (rivers.empty()) return out;
    const std::vector<std::ptrdiff_t> near = detail::cells_near_decks(k, opt.deck_clearance_m, opt.reach_m / cell_m);
    out.level_cells = detail::join_level_cells_near_decks(k, near, opt.level_tolerance_m);
    const double span = std::floor(opt.max_span_m / cell_m + 1e-9);
    out.deck_cells = detail::join_deck_runs(
        k, opt.deck_clearance_m,
        static_cast<std::ptrdiff_t>(std::min(span, static_cast<double>(body.rows() + body.cols()))));
    return out;
}

}  // namespace lidarfx
