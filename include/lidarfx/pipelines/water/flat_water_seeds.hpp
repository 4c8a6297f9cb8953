// SPDX-License-Identifier: Apache-2.0
// flat_water_seeds: seeds of waterbodies from cells with returns: level, smooth, low, and sparser than the land around.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/kernels/filter/morphology.hpp"
#include "lidarfx/kernels/label/connected_components.hpp"
#include "lidarfx/pipelines/water/water_rasters.hpp"

namespace lidarfx {

/// Options of flat_water_seeds. The defaults follow from the physics of the returns, not from one survey:
/// a water surface is level to the range noise of the scanner (2-3 cm per return), returns fewer pulses
/// than the land around it (specular reflection away from the sensor, absorption), and lies below its banks.
struct flat_water_seeds_options {
    int level_radius_cells = 1;       ///< the level test reads the (2 r + 1)² window around a cell (3 × 3: a
                                      ///< river a few cells wide still has level cells), >= 1. Default 1
    double level_tolerance_m = 0.10;  ///< the window's min z spans at most this, metres (≈ 4 σ of 2-3 cm range
                                      ///< noise on the lowest return), >= 0. Default 0.10
    double max_roughness_m = 0.2;     ///< a cell's max z − min z is at most this (several σ of range noise plus
                                      ///< waves; low vegetation and edges are rougher), metres, >= 0. Default 0.2
    std::size_t min_cells = 50;       ///< a seed keeps components of at least this many cells, >= 1. Default 50
    int ring_cells = 4;               ///< the land a component is compared with lies within this Chebyshev
                                      ///< distance of it, cells, >= 1. Default 4
    double max_density_ratio = 0.85;  ///< sparse: a component's mean returns per cell is at most this share of its
                                      ///< ring's (water loses pulses; flat land, asphalt and roofs do not), in
                                      ///< (0, 1]. Default 0.85
    double dark_density_ratio = 0.97; ///< dark and sparse: ... or at most this share when it is also dark (then
                                      ///< a few % fewer returns suffice: asphalt is dark but returns every
                                      ///< pulse), in (0, 1]. Default 0.97
    double max_intensity_ratio = 0.6; ///< dark: its mean intensity is at most this share of its ring's (water
                                      ///< absorbs the near infrared), >= 0; 0 disables the dark path. Default 0.6
    double max_roughness_ratio = 0.6; ///< smooth and sparse: ... or at most dark_density_ratio of it when its mean
                                      ///< max z − min z is at most this share of the median over all level cells
                                      ///< (calm water is smoother than grass, soil and asphalt with their
                                      ///< micro-relief), >= 0; 0 disables the smooth path. Default 0.6
    double max_lower_share = 0.1;     ///< lowest: at most this share of its ring lies more than level_tolerance_m
                                      ///< below the component's lowest cell within ring_cells of it (water fills
                                      ///< the lowest ground around it; roofs and lots on sloping ground have
                                      ///< lower ground next to them), in [0, 1].
                                      ///< Default 0.1
    double bright_density_ratio = 0.72; ///< sparse and bright: at most this share of the ring's returns makes a
                                      ///< component sparse whatever its intensity (specular echoes near nadir
                                      ///< are brighter than a dark ring while the pulses around them are lost;
                                      ///< no flat land loses a quarter of its pulses), in [0, 1]; 0 disables.
                                      ///< Default 0.72
    double max_joint_ratio = 0.6;     ///< weak cues together: ... or at most dark_density_ratio of the ring's
                                      ///< returns when density ratio × intensity ratio × roughness ratio (as
                                      ///< above; roughness against the median of level cells) is at most this,
                                      ///< for a component of at least joint_min_cells (each cue a little
                                      ///< water-like; land fragments of a few dozen cells scatter too much to be
                                      ///< judged so), >= 0; 0 disables. Default 0.6
    std::size_t joint_min_cells = 150; ///< see max_joint_ratio, cells. Default 150
    execution run = {};               ///< threads of the labelling kernel (same result for any count)
};

namespace detail {

inline void validate(const flat_water_seeds_options& o, const char* fn)
{
    require(o.level_radius_cells >= 1, fn, "level_radius_cells", ">= 1", o.level_radius_cells);
    require(o.level_tolerance_m >= 0, fn, "level_tolerance_m", ">= 0", o.level_tolerance_m);
    require(o.max_roughness_m >= 0, fn, "max_roughness_m", ">= 0", o.max_roughness_m);
    require(o.min_cells >= 1, fn, "min_cells", ">= 1", o.min_cells);
    require(o.ring_cells >= 1, fn, "ring_cells", ">= 1", o.ring_cells);
    require(o.max_density_ratio > 0 && o.max_density_ratio <= 1, fn, "max_density_ratio", "in (0, 1]",
            o.max_density_ratio);
    require(o.dark_density_ratio > 0 && o.dark_density_ratio <= 1, fn, "dark_density_ratio", "in (0, 1]",
            o.dark_density_ratio);
    require(o.max_intensity_ratio >= 0, fn, "max_intensity_ratio", ">= 0", o.max_intensity_ratio);
    require(o.max_roughness_ratio >= 0, fn, "max_roughness_ratio", ">= 0", o.max_roughness_ratio);
    require(o.max_lower_share >= 0 && o.max_lower_share <= 1, fn, "max_lower_share", "in [0, 1]", o.max_lower_share);
    require(o.bright_density_ratio >= 0 && o.bright_density_ratio <= 1, fn, "bright_density_ratio", "in [0, 1]",
            o.bright_density_ratio);
    require(o.max_joint_ratio >= 0, fn, "max_joint_ratio", ">= 0", o.max_joint_ratio);
    check_execution(o.run, fn);
}

}  // namespace detail

/// Seed mask of waterbodies that need no dropouts: seed = components (8-connected, >= min_cells) of the
/// level cells {return, not excluded, max z − min z <= max_roughness_m, max − min of min z over the
/// (2 level_radius_cells + 1)² window <= level_tolerance_m} that are sparse (mean count <=
/// max_density_ratio · their ring's and not brighter, or <= bright_density_ratio · whatever the intensity),
/// or, on >= joint_min_cells, <= dark_density_ratio · with count ratio × intensity ratio × roughness ratio
/// <= max_joint_ratio, or dark and sparse (<= dark_density_ratio · and mean intensity <=
/// max_intensity_ratio · their ring's), or smooth and sparse (<= dark_density_ratio · and mean max z −
/// min z <= max_roughness_ratio · median over level cells) and lowest (<= max_lower_share of the ring more than
/// level_tolerance_m below the component's lowest min z within ring_cells of the ring cell); the ring:
/// cells with returns within ring_cells of the component, not in a component.
/// Needs in.count (without it the mask is empty). `excluded` (optional, same shape; nonzero = never a
/// seed, e.g. vegetation) and in.footprint keep cells out. Returns 1 = seed cell.
/// O(cells · ((2 level_radius_cells + 1)² + (2 ring_cells + 1)²)).
/// @throws invalid_input on rasters of different shapes or options out of range.
inline raster<std::uint8_t> flat_water_seeds(const water_rasters& in, raster_view<const std::uint8_t> excluded = {},
                                             const flat_water_seeds_options& opt = {})
{
    constexpr const char* fn = "flat_water_seeds";
    detail::validate(in, fn);
    detail::validate(opt, fn);
    if (!excluded.empty()) detail::require_same_shape(in.min_z, excluded, fn, "min_z", "excluded");
    const std::ptrdiff_t rows = in.min_z.rows(), cols = in.min_z.cols();
    raster<std::uint8_t> out(rows, cols, 0);
    if (in.count.empty()) return out;
    const auto has_return = [&](std::ptrdiff_t r, std::ptrdiff_t c) {
        return !in.dropout(r, c) && std::isfinite(in.min_z(r, c)) && detail::inside_footprint(in, r, c);
    };
    // Level cells: smooth, not excluded, and the lowest returns of the window around them within the tolerance.
    raster<std::uint8_t> level(rows, cols, 0);
    const std::ptrdiff_t k = opt.level_radius_cells;
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            if (!has_return(r, c) || (!excluded.empty() && excluded(r, c))) continue;
            if (!(in.max_z(r, c) - in.min_z(r, c) <= opt.max_roughness_m)) continue;
            float lo = in.min_z(r, c), hi = lo;
            for (std::ptrdiff_t rr = std::max<std::ptrdiff_t>(0, r - k); rr <= std::min(rows - 1, r + k); ++rr) {
                for (std::ptrdiff_t cc = std::max<std::ptrdiff_t>(0, c - k); cc <= std::min(cols - 1, c + k); ++cc) {
                    const float z = in.min_z(rr, cc);
                    if (!std::isfinite(z)) continue;
                    lo = std::min(lo, z);
                    hi = std::max(hi, z);
                }
            }
            level.view()(r, c) = hi - lo <= opt.level_tolerance_m;
        }
    }
    auto comps = connected_components(level, connected_components_options{.conn = connectivity::eight,
                                                                          .run = {.threads = opt.run.threads}});
    const std::size_t n = comps.count();
    if (n == 0) return out;
    const auto& labels = comps.labels;
    // Per component: its count and min z, and those of its ring (cells with returns near it, not level).
    std::vector<double> count_sum(n + 1, 0), ring_count(n + 1, 0), ring_cells(n + 1, 0), light(n + 1, 0), ring_light(n + 1, 0),
        rough(n + 1, 0);
    std::vector<float> level_rough;  // max z − min z of every level cell: the survey's typical roughness
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c)
            if (level(r, c)) level_rough.push_back(in.max_z(r, c) - in.min_z(r, c));
    const double typical_rough = detail::median(level_rough);
    std::vector<double> lower(n + 1, 0);
    const std::ptrdiff_t q = opt.ring_cells;
    struct near_level {
        std::int32_t label;
        float z;  // lowest min z of the component's cells in the window
    };
    std::vector<near_level> near;
    // Only cells within ring_cells of a component large enough are in a ring: find them in O(cells).
    raster<std::int32_t> big_label(rows, cols, uninitialized);  // the label of a component large enough, else 0
    for (std::ptrdiff_t i = 0; i < big_label.size(); ++i) {
        const std::int32_t l = labels.data()[i];
        big_label.data()[i] = l > 0 && comps.sizes[static_cast<std::size_t>(l)] >= opt.min_cells ? l : 0;
    }
    const auto in_reach = morph_dilate(big_label, morphology_options{.size_cells = static_cast<int>(2 * q + 1),
                                                                .run = {.threads = opt.run.threads}});
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const std::int32_t l = labels.view()(r, c);
            if (l > 0) {
                if (comps.sizes[static_cast<std::size_t>(l)] < opt.min_cells) continue;
                count_sum[static_cast<std::size_t>(l)] += in.count(r, c);
                light[static_cast<std::size_t>(l)] += in.mean_intensity(r, c);
                rough[static_cast<std::size_t>(l)] += in.max_z(r, c) - in.min_z(r, c);
                continue;
            }
            if (!in_reach(r, c) || !has_return(r, c)) continue;
            near.clear();
            for (std::ptrdiff_t rr = std::max<std::ptrdiff_t>(0, r - q); rr <= std::min(rows - 1, r + q); ++rr) {
                const std::int32_t* row = big_label.view().row(rr);
                for (std::ptrdiff_t cc = std::max<std::ptrdiff_t>(0, c - q); cc <= std::min(cols - 1, c + q); ++cc) {
                    const std::int32_t m = row[cc];
                    if (m == 0) continue;
                    const auto it = std::find_if(near.begin(), near.end(), [&](const near_level& e) { return e.label == m; });
                    if (it == near.end()) near.push_back({m, in.min_z(rr, cc)});
                    else it->z = std::min(it->z, in.min_z(rr, cc));
                }
            }
            for (const auto& e : near) {
                const auto m = static_cast<std::size_t>(e.label);
                ring_count[m] += in.count(r, c);
                ring_cells[m] += 1;
                ring_light[m] += in.mean_intensity(r, c);
                lower[m] += in.min_z(r, c) < e.z - opt.level_tolerance_m;
            }
        }
    }
    std::vector<std::uint8_t> keep(n + 1, 0);
    for (std::size_t l = 1; l <= n; ++l) {
        if (comps.sizes[l] < opt.min_cells || ring_cells[l] == 0) continue;
        const double size = static_cast<double>(comps.sizes[l]);
        const double density = count_sum[l] / size / (ring_count[l] / ring_cells[l]);
        const double intensity = light[l] / size / (ring_light[l] / ring_cells[l]);
        // Sparse counts only when not brighter than the ring: a bright (specular) echo is one that arrived.
        const bool sparse = (density <= opt.max_density_ratio && intensity <= 1) || density <= opt.bright_density_ratio;
        const bool dark = intensity <= opt.max_intensity_ratio;
        const double roughness = rough[l] / size / typical_rough;
        const bool smooth = roughness <= opt.max_roughness_ratio;
        const bool joint = comps.sizes[l] >= opt.joint_min_cells && density * intensity * roughness <= opt.max_joint_ratio;
        if (!sparse && !((dark || smooth || joint) && density <= opt.dark_density_ratio)) continue;
        if (!(lower[l] <= opt.max_lower_share * ring_cells[l])) continue;
        keep[l] = 1;
    }
    for (std::ptrdiff_t i = 0; i < out.size(); ++i) out.data()[i] = keep[static_cast<std::size_t>(labels.data()[i])];
    return out;
}

}  // namespace lidarfx
