// SPDX-License-Identifier: Apache-2.0
// Implementation of lower_to_banks (included at the end of pipelines/water/lower_to_banks.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/pipelines/water/lake_level.hpp"

namespace lidarfx {

inline lower_to_banks_result lower_to_banks(river_profile& p, raster_view<const std::int32_t> labels,
                                            std::int32_t label, raster_view<const float> ground,
                                            const river_profile_options& river, const lower_to_banks_options& opt)
{
    constexpr const char* fn = "lower_to_banks";
    detail::require_same_shape(labels, ground, fn, "labels", "ground");
    detail::check_body_box(labels, p.box, fn);
    detail::require(p.section.rows() == p.box.rows() && p.section.cols() == p.box.cols(), fn,
                    "the profile's section raster must be box-sized");
    detail::require(opt.bank_quantile >= 0 && opt.bank_quantile <= 1, fn, "bank_quantile", "in [0, 1]",
                    opt.bank_quantile);
    const std::size_t n = p.level_m.size();
    detail::require(p.returns.size() == n && p.cells.size() == n, fn,
                    "the profile's vectors must hold a value per section");
    // The ground of the land beside each unmeasured section.
    std::vector<std::vector<float>> bank(n);
    for (std::ptrdiff_t r = 0; r < p.box.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < p.box.cols(); ++c) {
            const std::int32_t k = p.section(r, c);
            if (k < 0 || static_cast<std::size_t>(k) >= n || p.returns[static_cast<std::size_t>(k)] > 0) continue;
            for (std::ptrdiff_t dr = -1; dr <= 1; ++dr)
                for (std::ptrdiff_t dc = -1; dc <= 1; ++dc) {
                    const std::ptrdiff_t rr = p.box.row_min + r + dr, cc = p.box.col_min + c + dc;
                    if (rr < 0 || rr >= labels.rows() || cc < 0 || cc >= labels.cols() || labels(rr, cc) == label)
                        continue;
                    if (const float z = ground(rr, cc); std::isfinite(z))
                        bank[static_cast<std::size_t>(k)].push_back(z);
                }
        }
    lower_to_banks_result out;
    for (std::size_t first = 0; first < n;) {
        if (p.returns[first] > 0) {
            ++first;
            continue;
        }
        std::size_t last = first;  // the stretch [first, last) holds no measured section
        while (last < n && p.returns[last] == 0) ++last;
        const double floor = last < n ? p.level_m[last] : -INFINITY;
        for (std::size_t k = first; k < last; ++k) {
            double level = p.level_m[k];
            if (const double banks = detail::quantile_in_place(bank[k], opt.bank_quantile); banks < level)
                level = std::max(banks, floor);
            if (k > 0) level = std::min(level, p.level_m[k - 1]);
            if (level < p.level_m[k]) {
                ++out.sections_lowered;
                out.largest_drop_m = std::max(out.largest_drop_m, p.level_m[k] - level);
                p.level_m[k] = level;
            }
        }
        first = last;
    }
    detail::count_weirs(p, river.weir_min_drop_m);
    return out;
}

}  // namespace lidarfx
