// SPDX-License-Identifier: Apache-2.0
// Implementation of assess_water_inputs (included at the end of pipelines/water/assess_water_inputs.hpp).
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
#include "lidarfx/core/parallel_bands.hpp"
#include "lidarfx/pipelines/water/water_rasters.hpp"

namespace lidarfx {

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

inline water_diagnostics assess_water_inputs(const water_rasters& in, double cell_m,
                                             const assess_water_inputs_options& opt, const execution& run)
{
    constexpr const char* fn = "assess_water_inputs";
    detail::validate(in, fn);
    detail::require_positive(cell_m, fn, "cell_m");
    detail::validate(opt, fn);
    detail::check_execution(run, fn);
    water_diagnostics d;
    const std::ptrdiff_t rows = in.min_z.rows(), cols = in.min_z.cols();
    // The intensity range over cells with a return, as integer keys that order floats as numbers
    // (key = bits ^ ((bits >> 31) & 0x7fffffff), its own inverse) and integer masks: the loop vectorizes,
    // which float min / max reductions with selects do not. NaN changes neither bound. Integer sums and bounds
    // per band of rows (on run.threads threads), merged after: exact for any thread count.
    constexpr std::int32_t most = std::numeric_limits<std::int32_t>::max();
    constexpr std::int32_t least = std::numeric_limits<std::int32_t>::min();
    const auto key = [](std::int32_t bits) { return bits ^ ((bits >> 31) & 0x7fffffff); };
    struct band_totals {
        std::uint64_t points = 0, dropouts = 0, inside = 0;
        std::int32_t lo_key = most, hi_key = least;
        bool multiple = false;
    };
    const auto bands = parallel_bands(rows, 256, run.threads, [&](std::ptrdiff_t r0, std::ptrdiff_t r1) {
        band_totals t;
        for (std::ptrdiff_t r = r0; r < r1; ++r) {
            const std::uint8_t* dropout = in.dropout.row(r);
            const float* mean = in.mean_intensity.row(r);
            if (!in.count.empty()) {
                const std::uint32_t* count = in.count.row(r);
                for (std::ptrdiff_t c = 0; c < cols; ++c) t.points += count[c];
            }
            // Outside the footprint: no data, neither a dropout nor a cell of the survey.
            const std::uint8_t* footprint = in.footprint.empty() ? nullptr : in.footprint.row(r);
            const auto scan = [&](auto with_footprint) {
                std::uint64_t inside = 0, dropouts = 0;
                std::int32_t lo_key = t.lo_key, hi_key = t.hi_key;
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
                t.inside += inside;
                t.dropouts += dropouts;
                t.lo_key = lo_key;
                t.hi_key = hi_key;
            };
            if (footprint)
                scan(std::true_type{});
            else
                scan(std::false_type{});
            if (!in.multiple_returns.empty() && !t.multiple) {
                const std::uint8_t* multiple = in.multiple_returns.row(r);
                for (std::ptrdiff_t c = 0; c < cols; ++c) t.multiple |= multiple[c] && !dropout[c];
            }
        }
        return t;
    });
    std::uint64_t points = 0, dropouts = 0, inside = 0;
    std::int32_t lo_key = most, hi_key = least;
    for (const auto& t : bands) {
        points += t.points;
        dropouts += t.dropouts;
        inside += t.inside;
        lo_key = std::min(lo_key, t.lo_key);
        hi_key = std::max(hi_key, t.hi_key);
        d.has_multiple_returns |= t.multiple;
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

inline water_diagnostics assess_water_inputs(const rasterize_result& pr, const assess_water_inputs_options& opt,
                                             const execution& run)
{
    return assess_water_inputs(to_water_rasters(pr), pr.g.cell, opt, run);
}

}  // namespace lidarfx
