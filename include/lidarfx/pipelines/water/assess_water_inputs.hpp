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

namespace detail {

inline std::string fixed(double v, int digits = 2)
{
    std::ostringstream os;
    os.setf(std::ios::fixed);
    os.precision(digits);
    os << v;
    return os.str();
}

inline void validate(const assess_water_inputs_options& o, const char* fn)
{
    require(o.min_points_per_cell >= 0, fn, "min_points_per_cell", ">= 0", o.min_points_per_cell);
}

}  // namespace detail

inline std::string water_issue::message() const
{
    using detail::fixed;
    switch (kind) {
        case water_issue_kind::no_returns:
            return "no cell has a return: nothing to analyse";
        case water_issue_kind::intensity_constant:
            return "intensity is the same (" + fixed(intensity, 0) +
                   ") in every cell with returns: the KS test that stops region growing compares intensity "
                   "distributions and cannot work";
        case water_issue_kind::density_too_low:
            return "point density " + fixed(points_per_m2) + " points/m² gives " + fixed(points_per_cell) +
                   " points per " + fixed(cell_m, 1) + " m cell (below " + fixed(min_points_per_cell, 1) +
                   "): " + fixed(100 * dropout_fraction, 0) +
                   " % of cells are empty by sparse sampling, so dropouts no longer mark water; use a cell of at "
                   "least " +
                   fixed(suggested_cell_m, 1) + " m";
        case water_issue_kind::density_unchecked:
            return "no count raster: point density was not checked";
        case water_issue_kind::no_multiple_returns:
            return "no pulse has multiple returns: vegetation comes from max z - min z alone";
    }
    return "unknown issue";
}

/// Checks whether the rasters can support the waterbody method: intensity that varies between cells with
/// returns (the KS stop compares intensity distributions), point density (needs `count`): mean points per
/// cell p = points / cells (cells inside the footprint when one is given) against min_points_per_cell, with
/// suggested cell ceil(2·sqrt(min / (points per m²))) / 2 m (at least cell_m), and multiple returns
/// (vegetation). Blocking findings are problems, the others warnings. O(cells), one vectorized pass.
/// @throws invalid_input on rasters of different shapes or empty, cell_m <= 0, min_points_per_cell < 0.
inline water_diagnostics assess_water_inputs(const water_rasters& in, double cell_m,
                                             const assess_water_inputs_options& opt = {})
{
    constexpr const char* fn = "assess_water_inputs";
    detail::validate(in, fn);
    detail::require_positive(cell_m, fn, "cell_m");
    detail::validate(opt, fn);
    water_diagnostics d;
    const std::ptrdiff_t rows = in.min_z.rows(), cols = in.min_z.cols();
    std::uint64_t points = 0, dropouts = 0, inside = 0;
    // The intensity range over cells with a return, as integer keys that order floats as numbers
    // (key = bits ^ ((bits >> 31) & 0x7fffffff), its own inverse) and integer masks: the loop vectorizes,
    // which float min / max reductions with selects do not. NaN changes neither bound.
    constexpr std::int32_t most = std::numeric_limits<std::int32_t>::max();
    constexpr std::int32_t least = std::numeric_limits<std::int32_t>::min();
    const auto key = [](std::int32_t bits) { return bits ^ ((bits >> 31) & 0x7fffffff); };
    std::int32_t lo_key = most, hi_key = least;
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        const std::uint8_t* dropout = in.dropout.row(r);
        const float* mean = in.mean_intensity.row(r);
        if (!in.count.empty()) {
            const std::uint32_t* count = in.count.row(r);
            for (std::ptrdiff_t c = 0; c < cols; ++c) points += count[c];
        }
        // Outside the footprint: no data, neither a dropout nor a cell of the survey.
        const std::uint8_t* footprint = in.footprint.empty() ? nullptr : in.footprint.row(r);
        const auto scan = [&](auto with_footprint) {
            for (std::ptrdiff_t c = 0; c < cols; ++c) {
                const std::int32_t flown = with_footprint ? footprint[c] != 0 : 1;
                inside += static_cast<std::uint32_t>(flown);
                dropouts += static_cast<std::uint32_t>(flown & (dropout[c] != 0));
                const auto bits = std::bit_cast<std::int32_t>(mean[c]);
                const std::int32_t number = (bits & 0x7fffffff) <= 0x7f800000;  // not NaN
                const std::int32_t mask = -(flown & (dropout[c] == 0) & number);
                const std::int32_t k = key(bits);
                lo_key = std::min(lo_key, (k & mask) | (most & ~mask));
                hi_key = std::max(hi_key, (k & mask) | (least & ~mask));
            }
        };
        if (footprint)
            scan(std::true_type{});
        else
            scan(std::false_type{});
        if (!in.multiple_returns.empty() && !d.has_multiple_returns) {
            const std::uint8_t* multiple = in.multiple_returns.row(r);
            for (std::ptrdiff_t c = 0; c < cols; ++c) d.has_multiple_returns |= multiple[c] && !dropout[c];
        }
    }
    const bool any_return = hi_key != least;
    const float lo = any_return ? std::bit_cast<float>(key(lo_key)) : std::numeric_limits<float>::infinity();
    const float hi = any_return ? std::bit_cast<float>(key(hi_key)) : -std::numeric_limits<float>::infinity();
    const double cells = static_cast<double>(std::max<std::uint64_t>(inside, 1));
    d.dropout_fraction = static_cast<double>(dropouts) / cells;
    d.has_intensity = hi > lo;
    if (!d.has_intensity) {
        water_issue i{.kind = lo <= hi ? water_issue_kind::intensity_constant : water_issue_kind::no_returns};
        if (lo <= hi) i.intensity = lo;
        d.issues.push_back(i);
    }
    if (!in.count.empty()) {
        d.points_per_cell = static_cast<double>(points) / cells;
        const double density = static_cast<double>(points) / (cells * cell_m * cell_m);
        if (density > 0) {
            d.suggested_cell_m = std::max(cell_m, std::ceil(2.0 * std::sqrt(opt.min_points_per_cell / density)) / 2.0);
        }
        if (d.points_per_cell < opt.min_points_per_cell) {
            d.issues.push_back({.kind = water_issue_kind::density_too_low,
                                .points_per_m2 = density,
                                .points_per_cell = d.points_per_cell,
                                .cell_m = cell_m,
                                .min_points_per_cell = opt.min_points_per_cell,
                                .dropout_fraction = d.dropout_fraction,
                                .suggested_cell_m = d.suggested_cell_m});
        }
    } else {
        d.issues.push_back({.kind = water_issue_kind::density_unchecked, .severity = water_severity::warning});
    }
    if (!in.multiple_returns.empty() && !d.has_multiple_returns) {
        d.issues.push_back({.kind = water_issue_kind::no_multiple_returns, .severity = water_severity::warning});
    }
    return d;
}

/// assess_water_inputs on the output of rasterize(), at its grid's cell size.
inline water_diagnostics assess_water_inputs(const rasterize_result& pr, const assess_water_inputs_options& opt = {})
{
    return assess_water_inputs(to_water_rasters(pr), pr.g.cell, opt);
}

}  // namespace lidarfx
