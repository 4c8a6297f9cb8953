// SPDX-License-Identifier: Apache-2.0
// assess_water_inputs: what a survey's rasters can support, as coded issues with their values.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/pipelines/water/water_rasters.hpp"

namespace lidarfx {

/// What is wrong with (or missing from) the inputs of the waterbody method.
enum class water_issue_kind {
    no_returns,           ///< problem: no cell has a return
    intensity_constant,   ///< problem: every cell with returns has the same intensity (value: intensity)
    density_too_low,      ///< problem: fewer points per cell than min_points_per_cell (values: points_per_m2,
                          ///< points_per_cell, cell_m, min_points_per_cell, dropout_fraction, suggested_cell_m)
    density_unchecked,    ///< warning: no count raster, so the density was not checked
    no_multiple_returns,  ///< warning: the multiple_returns raster marks no cell with returns
};

/// Whether an issue blocks the method (problem) or only limits it (warning).
enum class water_severity { problem, warning };

/// One finding of assess_water_inputs: a code, its severity and the values it was found with, so that a
/// host can act on it or word it in its own language. Values that do not belong to `kind` are NaN.
struct water_issue {
    water_issue_kind kind = water_issue_kind::no_returns;
    water_severity severity = water_severity::problem;
    double intensity = NAN;            ///< intensity_constant: the one intensity value
    double points_per_m2 = NAN;        ///< density_too_low: mean points per square metre over the grid
    double points_per_cell = NAN;      ///< density_too_low: mean points per cell over the grid
    double cell_m = NAN;               ///< density_too_low: cell size checked, metres
    double min_points_per_cell = NAN;  ///< density_too_low: the required density, points per cell
    double dropout_fraction = NAN;     ///< density_too_low: share of cells without returns, [0, 1]
    double suggested_cell_m = NAN;     ///< density_too_low: smallest cell (0.5 m steps) reaching the required
                                       ///< density, metres; NaN when the grid holds no point at all

    /// The issue as one English sentence (the text lidarfx water prints).
    std::string message() const;
};

/// What the inputs can support. Issues come in the order they are checked: intensity, density, returns.
struct water_diagnostics {
    double points_per_cell = NAN;       ///< mean points per cell over the grid (needs the count raster)
    double dropout_fraction = NAN;      ///< share of cells without returns
    bool has_intensity = false;         ///< intensity varies between cells with returns
    bool has_multiple_returns = false;  ///< some cell has a multiple-return pulse
    double suggested_cell_m = NAN;      ///< smallest cell (0.5 m steps) reaching min_points_per_cell
    std::vector<water_issue> issues;    ///< problems and warnings found

    /// True when no issue is a problem.
    bool usable() const noexcept
    {
        return std::none_of(issues.begin(), issues.end(),
                            [](const water_issue& i) { return i.severity == water_severity::problem; });
    }
    /// The messages of the issues of one severity, in order.
    std::vector<std::string> messages(water_severity severity) const
    {
        std::vector<std::string> out;
        for (const auto& i : issues)
            if (i.severity == severity) out.push_back(i.message());
        return out;
    }
};

/// Options of assess_water_inputs.
struct assess_water_inputs_options {
    double min_points_per_cell = 2.0;  ///< density below this (points per cell) is a problem; >= 0. Default 2.
};

/// Checks whether the rasters can support the waterbody method: intensity that varies between cells with
/// returns (the KS stop compares intensity distributions), point density (needs `count`): mean points per
/// cell p = points / cells (cells inside the footprint when one is given) against min_points_per_cell, with
/// suggested cell ceil(2·sqrt(min / (points per m²))) / 2 m (at least cell_m), and multiple returns
/// (vegetation). Blocking findings are problems, the others warnings. O(cells), one vectorized pass in bands of
/// rows on `run.threads` threads (integer sums and bounds: the same result for any count).
/// @throws invalid_input on rasters of different shapes or empty, cell_m <= 0, min_points_per_cell < 0,
/// run.threads < 0.
inline water_diagnostics assess_water_inputs(const water_rasters& in, double cell_m,
                                             const assess_water_inputs_options& opt = {}, const execution& run = {});

/// assess_water_inputs on the output of rasterize(), at its grid's cell size.
inline water_diagnostics assess_water_inputs(const rasterize_result& pr, const assess_water_inputs_options& opt = {},
                                             const execution& run = {});

}  // namespace lidarfx

#include "lidarfx/pipelines/water/detail/assess_water_inputs_impl.hpp"
