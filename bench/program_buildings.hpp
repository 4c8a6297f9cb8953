// SPDX-License-Identifier: Apache-2.0
// extract_buildings run as `lidarfx solar --facades` runs it on LAS input, for the plain benchmark programs on
// synthetic towns (bench/small_buildings --program, bench/party_walls): every return binned, the terrain from the
// class-2 points filled by fill_ground, pulse counts, each building's rim decided by the points raised above it, the
// roof under overhanging crowns found by the lowest raised points;
// and the list parser both programs take.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include <lidarfx/core/grid.hpp>
#include <lidarfx/core/las_class.hpp>
#include <lidarfx/core/raster.hpp>
#include <lidarfx/kernels/interpolate/idw_fill.hpp>
#include <lidarfx/kernels/points/count_points_above.hpp>
#include <lidarfx/kernels/points/rasterize.hpp>
#include <lidarfx/pipelines/buildings/extract_buildings.hpp>

namespace bench {

/// What the program's route hands extract_buildings, binned once per survey and grid.
struct program_inputs {
    lidarfx::rasterize_result all;          ///< every return binned on the grid (max_z, count, multiple_return_count)
    lidarfx::raster<float> dsm;             ///< all.max_z with its empty cells filled by idw_fill, metres
    lidarfx::raster<float> ground;          ///< min z of the class-2 points, filled by fill_ground, metres
    lidarfx::raster<std::uint32_t> raised;  ///< points per cell above ground by building_candidates min_height_m
    lidarfx::raster<float> lowest_raised;   ///< the lowest of each cell's raised points, NaN = none
};

/// The program_inputs of a point cloud on grid g.
template <class Cloud>
program_inputs program_inputs_of(const Cloud& cloud, const lidarfx::grid& g)
{
    program_inputs in;
    in.all = lidarfx::rasterize(cloud, g);
    in.dsm = lidarfx::idw_fill(in.all.max_z, g.cell).filled;
    in.ground = lidarfx::fill_ground(
        lidarfx::rasterize(cloud, g, {.classes = {.include = {lidarfx::las_class::ground}}}).min_z, g.cell);
    in.raised = lidarfx::raster<std::uint32_t>(g.rows, g.cols, 0);
    in.lowest_raised = lidarfx::raster<float>(g.rows, g.cols, NAN);
    lidarfx::count_points_above(cloud, g, in.ground.view(), lidarfx::building_candidates_options{}.min_height_m,
                                in.raised.view(), in.lowest_raised.view());
    return in;
}

/// extract_buildings on the program's inputs (grid g, as given to program_inputs_of), with options o; without
/// under_crowns the lowest raised points are not given (the roof under overhanging crowns is not looked for).
inline lidarfx::extract_buildings_result program_buildings(const program_inputs& in, const lidarfx::grid& g,
                                                           const lidarfx::extract_buildings_options& o = {},
                                                           bool under_crowns = true)
{
    return lidarfx::extract_buildings(
        in.dsm, g, in.ground.view(),
        lidarfx::pulse_returns{in.all.count.view(), in.all.multiple_return_count.view(), in.raised.view(),
                               under_crowns ? in.lowest_raised.view() : lidarfx::raster_view<const float>{}},
        o);
}

/// "1.5,2,4" into numbers (the --density lists of the plain programs).
inline std::vector<double> parse_list(const char* text)
{
    std::vector<double> out;
    std::string item;
    for (const char* p = text;; ++p) {
        if (*p == ',' || *p == '\0') {
            if (!item.empty()) out.push_back(std::strtod(item.c_str(), nullptr));
            item.clear();
            if (*p == '\0') break;
        } else {
            item += *p;
        }
    }
    return out;
}

}  // namespace bench
