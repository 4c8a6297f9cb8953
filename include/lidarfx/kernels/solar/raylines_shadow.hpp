// SPDX-License-Identifier: Apache-2.0
// raylines_shadow: cast shadows of a surface model for one sun position in O(cells), by walking parallel
// lines away from the sun and carrying a shadow-height limit (dissertation 3.2.3).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/kernels/solar/ray_lines.hpp"

namespace lidarfx {

/// Settings of raylines_shadow.
struct raylines_shadow_options {
    std::uint8_t nan_cell = 255;  ///< output of a NaN (no-data) cell: neither lit (1) nor shadow (0) by default
    /// Families of parallel ray lines, each offset across the sun direction by 1 / line_phases cell, in [1, 64].
    /// Every cell takes its shadow from the family whose line passes nearest its centre: at most
    /// 1 / (2 line_phases) cells off the cell's own straight ray. 1 is the dissertation's single family (up to
    /// half a cell off, so the lateral edges of shadows can be one cell away from a per-cell ray march); each
    /// family costs one more sweep, except along the grid axes and diagonals, where one family is exact.
    int line_phases = 4;
    execution run = {};  ///< threads, progress and cancellation (core/parallel.hpp); never changes the result
};

/// The per-row and per-column parts of a shadow key along ray lines: key(r, c) = z + t(r, c) * tan(elevation)
/// (see raylines_shadow) is evaluated as z + (col_lift[c] + row_lift[r]), so that it is bit-identical wherever it
/// is computed (the cast shadows of the cells and the shadows at any other point of a cell, e.g. a facade).
/// col_lift[c] = (c + 0.5) dcol cell_m tan e, row_lift[r] = (r + 0.5) drow cell_m tan e, metres.
struct shadow_lifts {
    std::vector<double> col_lift, row_lift;
};

/// The shadow lifts of ray lines `l` for cells of cell_m metres and a sun of tan(elevation) = tan_elevation.
/// O(rows + cols), no checks. A point of height h at cell (r, c) is in the shadow of the non-NaN cells q before it
/// on its line iff max over q of key(q) > h + (col_lift[c] + row_lift[r]).
inline shadow_lifts make_shadow_lifts(const ray_lines& l, double cell_m, double tan_elevation)
{
    shadow_lifts s{std::vector<double>(static_cast<std::size_t>(l.cols)),
                   std::vector<double>(static_cast<std::size_t>(l.rows))};
    const double a = l.dcol * cell_m * tan_elevation, b = l.drow * cell_m * tan_elevation;
    for (std::ptrdiff_t c = 0; c < l.cols; ++c)
        s.col_lift[static_cast<std::size_t>(c)] = (static_cast<double>(c) + 0.5) * a;
    for (std::ptrdiff_t r = 0; r < l.rows; ++r)
        s.row_lift[static_cast<std::size_t>(r)] = (static_cast<double>(r) + 0.5) * b;
    return s;
}

/// Cast shadows for one sun position (into form): 1 = lit, 0 = shadow, `opt.nan_cell` (default 255) for NaN
/// cells. Ray lines (dissertation 3.2.3): parallel digital lines along the sun azimuth cover every cell once
/// (kernels/solar/ray_lines.hpp); walking each away from the sun, cell p is in shadow iff an earlier non-NaN
/// cell q on its line has z_q - (t_p - t_q) tan(e) > z_p, with t the projection of the cell centre on the walk
/// direction in metres. Computed as key = z + t tan(e) (evaluated as z + (col_lift[c] + row_lift[r])) against
/// the running maximum key of the line. With opt.line_phases = P families of lines (phases 0.5 + j / P), cell p
/// takes its line from family line_phase_of(slope, major index of p, P), the one nearest its centre:
/// O(P * rows * cols) at most, O(rows * cols) along the axes and diagonals. Azimuth clockwise from north (row 0 north,
/// columns east); elevation above the horizon, degrees: e <= 0 -> all shadow, e >= 90 -> all lit. NaN cells cast no
/// shadow. @throws invalid_input if shapes differ, cell_m is not finite and > 0, an angle is not finite,
/// elevation is outside [-90, 90], line_phases is outside [1, 64], run.threads < 0 or out overlaps dsm; cancelled if
/// run.progress says stop.
template <raster_input In, class Out>
requires raster_output_of<Out, std::uint8_t>
void raylines_shadow(const In& dsm, Out&& lit, double cell_m, double sun_azimuth_deg, double sun_elevation_deg,
                     const raylines_shadow_options& opt = {});

/// Cast shadows for one sun position (returning form): see the into form. dsm heights and cell_m in metres,
/// angles in degrees (azimuth clockwise from north, elevation above the horizon). O(rows * cols).
template <raster_input In>
raster<std::uint8_t> raylines_shadow(const In& dsm, double cell_m, double sun_azimuth_deg, double sun_elevation_deg,
                                     const raylines_shadow_options& opt = {});

}  // namespace lidarfx

#include "lidarfx/kernels/solar/detail/raylines_shadow_impl.hpp"
