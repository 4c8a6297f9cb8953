// SPDX-License-Identifier: Apache-2.0
// Implementation of pipelines/water/select_flat_seeds.hpp (included at its end; not meant to be included alone).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/pipelines/water/flat_seed_components.hpp"
#include "lidarfx/pipelines/water/flat_seed_rings.hpp"
#include "lidarfx/pipelines/water/flat_water_seeds_options.hpp"
#include "lidarfx/pipelines/water/water_rasters.hpp"
#include "lidarfx/pipelines/water/water_surface_slope.hpp"

namespace lidarfx {

namespace detail {

/// The slope test of the components: keep[l] = 0 for each kept component l (labels > 0 of `labels`,
/// sizes[l] cells) whose median surface slope over its cells (NaN counted as 0, level) exceeds max_slope
/// (m/m). Only the kept components' slopes are gathered (into one buffer, each in row order): most
/// components are land. O(cells + kept cells).
inline void drop_sloping(raster_view<const std::int32_t> labels, const surface_slope_source& slope,
                         const std::vector<std::size_t>& sizes, double max_slope, std::vector<std::uint8_t>& keep)
{
    const std::ptrdiff_t rows = labels.rows(), cols = labels.cols();
    std::vector<std::size_t> offset(keep.size() + 1, 0);  // the slopes of label l: [offset[l], offset[l + 1])
    for (std::size_t l = 1; l < keep.size(); ++l) offset[l + 1] = offset[l] + (keep[l] ? sizes[l] : 0);
    if (offset.back() == 0) return;
    std::vector<float> all(offset.back());
    std::vector<std::size_t> next(offset.begin(), offset.end() - 1);
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for_each_run(labels.row(r), cols, [&](std::int32_t l, std::ptrdiff_t from, std::ptrdiff_t to) {
            if (!keep[static_cast<std::size_t>(l)]) return;
            float* out = all.data() + next[static_cast<std::size_t>(l)];
            for (std::ptrdiff_t i = from; i < to; ++i) {
                const float s = slope(r, i);
                *out++ = std::isnan(s) ? 0.0f : s;
            }
            next[static_cast<std::size_t>(l)] += static_cast<std::size_t>(to - from);
        });
    }
    for (std::size_t l = 1; l < keep.size(); ++l) {
        if (offset[l + 1] == offset[l]) continue;
        if (median(std::span<float>(all).subspan(offset[l], offset[l + 1] - offset[l])) > max_slope) keep[l] = 0;
    }
}

/// The typical roughness of the level cells (median of comps.level_roughness), found when first needed.
class typical_roughness {
public:
    explicit typical_roughness(const flat_seed_components& comps) : comps_(comps) {}
    double get()
    {
        if (!known_) {
            // median reorders its values: a copy, so that comps stays as it was.
            std::vector<float> values(comps_.level_roughness);
            value_ = median(values);
            known_ = true;
        }
        return value_;
    }

private:
    const flat_seed_components& comps_;
    double value_ = NAN;
    bool known_ = false;
};

/// Whether component l is sparse enough to be water (see select_flat_seeds), lowest aside.
inline bool sparse_enough(const flat_seed_components& comps, const flat_seed_rings& rings, std::size_t l,
                          const flat_water_seeds_options& opt, typical_roughness& typical)
{
    const double size = static_cast<double>(comps.sizes[l]);
    const double density = comps.count_sum[l] / size / (rings.count_sum[l] / rings.cells[l]);
    const double intensity = comps.intensity_sum[l] / size / (rings.intensity_sum[l] / rings.cells[l]);
    // Sparse counts only when not brighter than the ring: a bright (specular) echo is one that arrived.
    if (density <= opt.bright_density_ratio) return true;
    // Land-like: as bright as the survey's land; then only the lost pulses above say water.
    const double mean_intensity = comps.intensity_sum[l] / size;
    if (mean_intensity >= rings.land_intensity) return false;
    const bool dark_for_survey = mean_intensity <= opt.max_land_intensity_ratio * rings.land_intensity;
    if (dark_for_survey && rings.raised[l] >= opt.min_raised_share * rings.cells[l]) return true;  // and sunken
    const bool sparse = density <= opt.max_density_ratio && intensity <= 1;
    if (sparse) return true;
    if (!(density <= opt.dark_density_ratio)) return false;
    // Dark against its ring or against the survey's land.
    if (intensity <= opt.max_intensity_ratio) return true;
    if (dark_for_survey) return true;
    // On perfectly smooth data (typical 0) a smooth component is 0, not 0 / 0.
    const double mean_rough = comps.roughness_sum[l] / size;
    const double roughness = mean_rough <= 0 ? 0.0 : mean_rough / typical.get();
    const bool smooth = roughness <= opt.max_roughness_ratio;
    const bool joint = comps.sizes[l] >= opt.joint_min_cells && density * intensity * roughness <= opt.max_joint_ratio;
    return smooth || joint;
}

}  // namespace detail

inline std::vector<std::uint8_t> select_flat_seeds(const flat_seed_components& comps, const flat_seed_rings& rings,
                                                   const flat_water_seeds_options& opt,
                                                   surface_slope_source surface_slope)
{
    constexpr const char* fn = "select_flat_seeds";
    detail::validate(opt, fn);
    const std::size_t nb = comps.count();
    detail::require(
        comps.free_cells.size() == nb + 1 && comps.count_sum.size() == nb + 1 && comps.intensity_sum.size() == nb + 1 &&
            comps.roughness_sum.size() == nb + 1 && rings.cells.size() == nb + 1 && rings.count_sum.size() == nb + 1 &&
            rings.intensity_sum.size() == nb + 1 && rings.lower.size() == nb + 1 && rings.raised.size() == nb + 1,
        fn, "comps and rings must hold count() + 1 entries per measure");
    if (!surface_slope.empty()) detail::require_same_shape(comps.labels, surface_slope, fn, "labels", "surface_slope");
    std::vector<std::uint8_t> keep(nb + 1, 0);
    detail::typical_roughness typical(comps);
    for (std::size_t l = 1; l <= nb; ++l) {
        // A component all taken leaves no seed cell. (Every component has >= min_cells cells.)
        if (comps.free_cells[l] == 0 || rings.cells[l] == 0) continue;
        if (!detail::sparse_enough(comps, rings, l, opt, typical)) continue;
        if (!detail::lowest(rings, l, opt)) continue;
        keep[l] = 1;
    }
    if (!surface_slope.empty() && opt.max_surface_slope >= 0)
        detail::drop_sloping(comps.labels, surface_slope, comps.sizes, opt.max_surface_slope, keep);
    return keep;
}

inline void write_flat_seed_mask(const flat_seed_components& comps, const std::vector<std::uint8_t>& keep,
                                 raster_view<std::uint8_t> mask, raster_view<const std::int32_t> taken,
                                 surface_slope_source surface_slope, const flat_water_seeds_options& opt)
{
    constexpr const char* fn = "write_flat_seed_mask";
    detail::require_same_shape(comps.labels, mask, fn, "labels", "mask");
    if (!taken.empty()) detail::require_same_shape(comps.labels, taken, fn, "labels", "taken");
    if (!surface_slope.empty()) detail::require_same_shape(comps.labels, surface_slope, fn, "labels", "surface_slope");
    detail::require(keep.size() == comps.count() + 1, fn, "keep", "of comps.count() + 1 entries", keep.size());
    const std::ptrdiff_t rows = mask.rows(), nc = mask.cols();
    const bool slope_test = !surface_slope.empty() && opt.max_surface_slope >= 0;
    const float max_slope = slope_test ? detail::float_at_most(opt.max_surface_slope) : 0.0f;  // x > it: x > max
    const std::vector<std::int32_t> none_taken(taken.empty() ? static_cast<std::size_t>(nc) : 0, 0);
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        const std::int32_t* lab = comps.labels.view().row(r);
        const std::int32_t* body = taken.empty() ? none_taken.data() : taken.row(r);
        std::uint8_t* d = mask.row(r);
        std::fill(d, d + nc, std::uint8_t{0});
        // Run by run of one label; no taken cell (its slope is not read).
        detail::for_each_run(lab, nc, [&](std::int32_t l, std::ptrdiff_t from, std::ptrdiff_t to) {
            if (!keep[static_cast<std::size_t>(l)]) return;
            if (!slope_test)
                for (std::ptrdiff_t i = from; i < to; ++i) d[i] = static_cast<std::uint8_t>(body[i] <= 0);
            else
                for (std::ptrdiff_t i = from; i < to; ++i)
                    d[i] = static_cast<std::uint8_t>(body[i] <= 0 && !(surface_slope(r, i) > max_slope));
        });
    }
}

}  // namespace lidarfx
