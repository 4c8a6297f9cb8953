// SPDX-License-Identifier: Apache-2.0
// vegetation_by_returns: trees told from roofs by what their pulses did. Leaves and branches split a laser pulse
// into several returns; a roof stops it, but for its edges. Used by extract_buildings when the survey's pulse
// counts are given (rasterize_result::count and multiple_return_count).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"

namespace lidarfx {

/// What the pulses of a survey say of each cell: rasterize_result::count and multiple_return_count of all the
/// returns (first returns alone count a tree's split pulse once instead of twice or more).
struct pulse_returns {
    raster_view<const std::uint32_t> points;    ///< points in the cell
    raster_view<const std::uint32_t> multiple;  ///< of them, points whose pulse had more than one return
    /// Of them, points raised above the terrain (count_points_above against the terrain given to
    /// extract_buildings, by its candidates' min_height_m); empty = not counted. extract_buildings then decides
    /// each building's rim by them (refine_building_rim).
    raster_view<const std::uint32_t> raised;
    /// The lowest of each cell's raised points (metres; NaN = none; count_points_above gives it with raised); empty
    /// = not given. With raised, extract_buildings then finds the roofs hidden under overhanging crowns
    /// (join_roof_under_crowns).
    raster_view<const float> lowest;

    /// Empty counts. Explicit, so that a `{}` argument never reads as pulse counts.
    explicit pulse_returns() = default;
    pulse_returns(raster_view<const std::uint32_t> points_in, raster_view<const std::uint32_t> multiple_in,
                  raster_view<const std::uint32_t> raised_in = {}, raster_view<const float> lowest_in = {})
        : points(points_in), multiple(multiple_in), raised(raised_in), lowest(lowest_in)
    {
    }
};

/// Settings of vegetation_by_returns and drop_vegetation_parts.
struct vegetation_by_returns_options {
    /// A cell is vegetation when at least this share of its points came from pulses with more than one return;
    /// in (0, 1]. Half: a roof cell holds split pulses only along an edge or a ridge.
    double cell_share = 0.5;
    /// A candidate building is vegetation when at least this share of the points on its cells did; in (0, 1].
    /// On the AHN3 survey of Delft (leaf-off, 15 points/m²) building parts hold 9-18 % such points and rows of
    /// trees 24-34 %.
    double part_share = 0.2;
    /// A part whose cells hold fewer points than this share of the survey's mean points per cell (over the
    /// cells with points) was not seen by the laser; in [0, 1]. A roof returns about the mean; a surface
    /// interpolated over a canal between trees returns almost nothing.
    double min_seen_density = 0.25;
};

/// Vegetation cells by returns: 1 where returns.points > 0 and returns.multiple >= cell_share x returns.points.
/// O(cells). @throws invalid_input if the two rasters differ in shape, some multiple exceeds its points, or
/// cell_share is not in (0, 1].
inline raster<std::uint8_t> vegetation_by_returns(const pulse_returns& returns,
                                                  const vegetation_by_returns_options& opt = {});

/// Drops, in place, the candidate parts 1..count of `building_id` that are no roofs by their returns, and
/// renumbers the others 1..kept in their order. A part is dropped when the laser did not see it: its cells hold
/// no point, or fewer than min_seen_density x the survey's mean points per cell with points (a surface
/// interpolated over water or dark gaps between crowns), or when it is vegetation: at least part_share of its
/// points came from split pulses. Returns {kept, dropped}. O(cells). @throws invalid_input if the shapes differ, an
/// option is out of range, or some cell counts more split pulses than points.
inline std::array<std::size_t, 2> drop_vegetation_parts(raster_view<std::int32_t> building_id, std::size_t count,
                                                        const pulse_returns& returns,
                                                        const vegetation_by_returns_options& opt = {});

// ---- implementation ----

namespace detail {

inline void check_vegetation_by_returns(const pulse_returns& returns, const vegetation_by_returns_options& opt,
                                        const char* function)
{
    require(opt.cell_share > 0 && opt.cell_share <= 1, function, "cell_share", "in (0, 1]", opt.cell_share);
    require(opt.part_share > 0 && opt.part_share <= 1, function, "part_share", "in (0, 1]", opt.part_share);
    require(opt.min_seen_density >= 0 && opt.min_seen_density <= 1, function, "min_seen_density", "in [0, 1]",
            opt.min_seen_density);
    require_same_shape(returns.points, returns.multiple, function, "returns.points", "returns.multiple");
    require_counts_within(returns.multiple, returns.points, function,
                          "returns.multiple must not exceed returns.points in any cell");
}

}  // namespace detail

inline raster<std::uint8_t> vegetation_by_returns(const pulse_returns& returns,
                                                  const vegetation_by_returns_options& opt)
{
    detail::check_vegetation_by_returns(returns, opt, "vegetation_by_returns");
    raster<std::uint8_t> out(returns.points.rows(), returns.points.cols());
    for (std::ptrdiff_t r = 0; r < out.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < out.cols(); ++c) {
            const double n = returns.points(r, c), m = returns.multiple(r, c);
            out(r, c) = static_cast<std::uint8_t>(n > 0 && m >= opt.cell_share * n);
        }
    }
    return out;
}

inline std::array<std::size_t, 2> drop_vegetation_parts(raster_view<std::int32_t> building_id, std::size_t count,
                                                        const pulse_returns& returns,
                                                        const vegetation_by_returns_options& opt)
{
    constexpr const char* function = "drop_vegetation_parts";
    detail::check_vegetation_by_returns(returns, opt, function);
    detail::require_same_shape(building_id, returns.points, function, "building_id", "returns.points");
    struct part_counts {
        double cells = 0, points = 0, multiple = 0;
    };
    std::vector<part_counts> parts(count + 1);
    double survey_points = 0, survey_cells = 0;  // over the cells with points
    for (std::ptrdiff_t r = 0; r < building_id.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < building_id.cols(); ++c) {
            survey_points += returns.points(r, c);
            survey_cells += returns.points(r, c) > 0;
            const std::int32_t b = building_id(r, c);
            if (b <= 0 || static_cast<std::size_t>(b) > count) continue;
            part_counts& p = parts[static_cast<std::size_t>(b)];
            p.cells += 1;
            p.points += returns.points(r, c);
            p.multiple += returns.multiple(r, c);
        }
    }
    const double mean_density = survey_cells > 0 ? survey_points / survey_cells : 0.0;
    std::vector<std::int32_t> renumber(count + 1, 0);
    std::size_t kept = 0, dropped = 0;
    for (std::size_t b = 1; b <= count; ++b) {
        const part_counts& p = parts[b];
        const bool seen = p.points > 0 && p.points >= opt.min_seen_density * mean_density * p.cells;
        if (!seen || p.multiple >= opt.part_share * p.points)
            ++dropped;
        else
            renumber[b] = static_cast<std::int32_t>(++kept);
    }
    for (std::ptrdiff_t r = 0; r < building_id.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < building_id.cols(); ++c) {
            const std::int32_t b = building_id(r, c);
            if (b > 0 && static_cast<std::size_t>(b) <= count)
                building_id(r, c) = renumber[static_cast<std::size_t>(b)];
        }
    }
    return {kept, dropped};
}

}  // namespace lidarfx
