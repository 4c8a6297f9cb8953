// SPDX-License-Identifier: Apache-2.0
// Implementation of roof_suitability (pipelines/pv/roof_suitability.hpp): the suitability rule, buildings
// grouped by id, the planes mode (roof_planes per building) and the paper mode (appendix steps 3-12).
#pragma once
// Included at the end of its public header, which declares what is defined here.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/grid.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/kernels/filter/morphology.hpp"
#include "lidarfx/kernels/filter/slope_aspect.hpp"
#include "lidarfx/kernels/label/connected_components.hpp"
#include "lidarfx/pipelines/pv/azimuth_mode_select.hpp"
#include "lidarfx/pipelines/pv/roof_planes.hpp"

namespace lidarfx {

namespace detail {

/// The argument checks of roof_suitability.
template <class Dsm, class Dtm, class Ids>
void check_roof_suitability(const Dsm& dsm, const Dtm& dtm, const Ids& building_id, const grid& g,
                            const roof_suitability_options& opt, const char* fn)
{
    g.validate(fn);
    require(dsm.rows() == g.rows && dsm.cols() == g.cols, fn, "dsm must have the grid's shape");
    require_same_shape(dsm, dtm, fn, "dsm", "dtm");
    require_same_shape(dsm, building_id, fn, "dsm", "building_id");
    require(std::isfinite(opt.min_height_m), fn, "min_height_m", "finite", opt.min_height_m);
    require(opt.min_patch_m2 >= 0, fn, "min_patch_m2", ">= 0", opt.min_patch_m2);
    require_positive(opt.m2_per_kwp, fn, "m2_per_kwp");
    require(opt.min_tilt_deg <= opt.max_tilt_deg && opt.max_tilt_deg < 90, fn, "min_tilt_deg", "<= max_tilt_deg < 90",
            opt.min_tilt_deg);
    require(opt.min_azimuth_deg <= opt.max_azimuth_deg, fn, "min_azimuth_deg", "<= max_azimuth_deg",
            opt.min_azimuth_deg);
    require(opt.flat_below_deg >= 0 && opt.flat_below_deg < 90, fn, "flat_below_deg", "in [0, 90)", opt.flat_below_deg);
    require(opt.paper_min_patch_cells >= 1, fn, "paper_min_patch_cells", ">= 1", opt.paper_min_patch_cells);
    require(opt.paper_boundary_cleans >= 0, fn, "paper_boundary_cleans", ">= 0", opt.paper_boundary_cleans);
    require(opt.planes.min_seed_cells >= 3, fn, "planes.min_seed_cells", ">= 3", opt.planes.min_seed_cells);
    require(opt.planes.min_angle_deg > 0 && opt.planes.min_angle_deg <= opt.planes.max_angle_deg, fn,
            "planes.min_angle_deg", "in (0, planes.max_angle_deg]", opt.planes.min_angle_deg);
    require(opt.planes.min_distance_m >= 0, fn, "planes.min_distance_m", ">= 0", opt.planes.min_distance_m);
    require(opt.planes.min_plane_m2 >= 0, fn, "planes.min_plane_m2", ">= 0", opt.planes.min_plane_m2);
    require(opt.planes.max_plane_rms_m > 0, fn, "planes.max_plane_rms_m", "> 0", opt.planes.max_plane_rms_m);
    require(opt.planes.reassign_rounds >= 1, fn, "planes.reassign_rounds", ">= 1", opt.planes.reassign_rounds);
    check_execution(opt.run, fn);
}

/// Footprint cells grouped by building id (raster order inside a group).
struct building_groups {
    std::vector<std::int32_t> ids;
    std::vector<std::size_t> start;     ///< group k = cells[start[k] .. start[k + 1])
    std::vector<std::ptrdiff_t> cells;  ///< r * cols + c
};

template <class Ids>
building_groups group_buildings(const Ids& ids, const char* fn)
{
    std::vector<std::pair<std::int32_t, std::ptrdiff_t>> all;
    for (std::ptrdiff_t r = 0; r < ids.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < ids.cols(); ++c) {
            const auto v = static_cast<std::int64_t>(ids(r, c));
            require(v >= 0 && v <= std::int64_t{2147483647}, fn, "building_id", "in [0, 2^31)", v);
            if (v > 0) all.emplace_back(static_cast<std::int32_t>(v), r * ids.cols() + c);
        }
    std::stable_sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    building_groups g;
    for (std::size_t k = 0; k < all.size(); ++k) {
        if (k == 0 || all[k].first != all[k - 1].first) {
            g.ids.push_back(all[k].first);
            g.start.push_back(k);
        }
        g.cells.push_back(all[k].second);
    }
    g.start.push_back(all.size());
    return g;
}

/// The cells' bounding box as (r0, c0, h, w).
inline std::array<std::ptrdiff_t, 4> cells_box(const std::ptrdiff_t* first, const std::ptrdiff_t* last,
                                               std::ptrdiff_t cols)
{
    std::ptrdiff_t r0 = first[0] / cols, r1 = r0, c0 = first[0] % cols, c1 = c0;
    for (const std::ptrdiff_t* p = first; p != last; ++p) {
        r0 = std::min(r0, *p / cols);
        r1 = std::max(r1, *p / cols);
        c0 = std::min(c0, *p % cols);
        c1 = std::max(c1, *p % cols);
    }
    return {r0, c0, r1 - r0 + 1, c1 - c0 + 1};
}

/// A building's patches before numbering: per patch its cells (grid indices).
struct building_outcome {
    roof_building building;
    std::vector<roof_patch> patches;
    std::vector<std::vector<std::ptrdiff_t>> cells;
};

/// Fills the measured fields of a patch from its cells and tilt/azimuth, and judges it.
inline void measure_patch(roof_patch& p, const std::vector<std::ptrdiff_t>& cells, const grid& g,
                          const roof_suitability_options& o)
{
    double sx = 0, sy = 0;
    for (const auto i : cells) {
        const auto ctr = g.center(i / g.cols, i % g.cols);
        sx += ctr[0];
        sy += ctr[1];
    }
    const double n = static_cast<double>(cells.size());
    p.centroid_x = n > 0 ? sx / n : 0.0;
    p.centroid_y = n > 0 ? sy / n : 0.0;
    p.area_m2 = n * g.cell * g.cell;
    p.sloped_area_m2 = p.area_m2 / std::cos(p.tilt_deg * std::numbers::pi / 180.0);
    p.kwp = p.sloped_area_m2 / o.m2_per_kwp;
    judge_patch(p, o);
}

/// planes mode for one building: roof_planes on its roof cells, one patch per plane.
inline building_outcome building_planes(const raster<float>& roof_z, const std::ptrdiff_t* first,
                                        const std::ptrdiff_t* last, const grid& g, const roof_suitability_options& o)
{
    building_outcome out;
    const auto [r0, c0, h, w] = cells_box(first, last, g.cols);
    roof_box_surface s;
    s.h = h;
    s.w = w;
    s.cell_m = g.cell;
    s.z.assign(static_cast<std::size_t>(h * w), std::numeric_limits<double>::quiet_NaN());
    double zref = std::numeric_limits<double>::quiet_NaN();
    for (const std::ptrdiff_t* p = first; p != last; ++p) {
        const float z = roof_z(*p / g.cols, *p % g.cols);
        if (std::isnan(z)) continue;
        if (std::isnan(zref)) zref = z;
        s.z[static_cast<std::size_t>((*p / g.cols - r0) * w + (*p % g.cols - c0))] = static_cast<double>(z) - zref;
        ++out.building.cells;
    }
    if (out.building.cells == 0) {
        out.building.note = "no roof cells (all below min_height_m or no data)";
        return out;
    }
    const roof_planes_result planes = roof_planes(s, o.planes);
    out.cells.resize(planes.fits.size());
    for (std::ptrdiff_t i = 0; i < h * w; ++i) {
        const std::int32_t k = planes.label[static_cast<std::size_t>(i)];
        if (k > 0) out.cells[static_cast<std::size_t>(k - 1)].push_back((r0 + i / w) * g.cols + c0 + i % w);
    }
    std::size_t in_planes = 0;
    for (std::size_t k = 0; k < planes.fits.size(); ++k) {
        roof_patch p;
        p.tilt_deg = planes.fits[k].tilt_deg();
        p.azimuth_deg = planes.fits[k].azimuth_deg();
        p.rms_m = planes.fits[k].rms;
        measure_patch(p, out.cells[k], g, o);
        in_planes += out.cells[k].size();
        out.patches.push_back(std::move(p));
    }
    out.building.note = std::to_string(planes.fits.size()) + " planes; " +
                        std::to_string(out.building.cells - in_planes) + " cells of clutter or edges";
    return out;
}

/// One boundary clean of a small mask (h x w): a 3x3 closing then a 3x3 opening (ArcGIS Boundary Clean expands
/// and shrinks the zones by one cell).
inline void boundary_clean(std::vector<std::uint8_t>& m, std::ptrdiff_t h, std::ptrdiff_t w)
{
    raster<std::uint8_t> r(h, w);
    for (std::ptrdiff_t i = 0; i < h * w; ++i) r(i / w, i % w) = m[static_cast<std::size_t>(i)];
    const auto cleaned = morph_open(morph_close(r, {.size_cells = 3}), {.size_cells = 3});
    for (std::ptrdiff_t i = 0; i < h * w; ++i) m[static_cast<std::size_t>(i)] = cleaned(i / w, i % w) ? 1 : 0;
}

/// paper mode for one building (appendix steps 3-12).
inline building_outcome building_paper(const slope_aspect_result& sa, const std::ptrdiff_t* first,
                                       const std::ptrdiff_t* last, const grid& g, const roof_suitability_options& o)
{
    building_outcome out;
    std::vector<std::uint32_t> hist(360, 0);
    double slope_sum = 0, a_sum = 0, a_sq = 0;
    std::size_t slopes = 0, aspects = 0;
    for (const std::ptrdiff_t* p = first; p != last; ++p) {
        const float s = sa.slope_deg(*p / g.cols, *p % g.cols);
        if (std::isnan(s)) continue;
        ++out.building.cells;
        slope_sum += s;
        ++slopes;
        const float a = sa.aspect_deg(*p / g.cols, *p % g.cols);
        if (std::isnan(a)) continue;
        const auto k = static_cast<std::size_t>(std::floor(a)) % 360;  // step 3: integer aspect (truncated)
        ++hist[k];
        a_sum += static_cast<double>(k);
        a_sq += static_cast<double>(k) * static_cast<double>(k);
        ++aspects;
    }
    out.patches.emplace_back();
    out.cells.emplace_back();
    roof_patch& pv = out.patches.back();
    if (slopes == 0) {
        out.building.note = "no roof cells (all below min_height_m or no data)";
        pv.reason = out.building.note;
        return out;
    }
    pv.tilt_deg = slope_sum / static_cast<double>(slopes);  // step 4: mean slope = tilt
    const bool flat = pv.tilt_deg < o.flat_below_deg;
    std::vector<std::ptrdiff_t> chosen;
    // Plain variables, not a structured binding: drop_small below captures h and w (Clang 14 cannot).
    const auto box = cells_box(first, last, g.cols);
    const std::ptrdiff_t r0 = box[0], c0 = box[1], h = box[2], w = box[3];
    std::vector<std::uint8_t> mask(static_cast<std::size_t>(h * w), 0);
    if (flat) {
        // Flat roofs are treated separately (paper section 3): every roof cell is a candidate.
        for (const std::ptrdiff_t* p = first; p != last; ++p)
            if (!std::isnan(sa.slope_deg(*p / g.cols, *p % g.cols)))
                mask[static_cast<std::size_t>((*p / g.cols - r0) * w + (*p % g.cols - c0))] = 1;
        pv.azimuth_deg = 180.0;
        out.building.note = "flat roof (mean slope under flat_below_deg)";
    } else {
        const azimuth_selection sel = azimuth_mode_select(hist, o.azimuth);  // step 5
        out.building.selection = sel;
        if (!sel.suitable) {
            out.building.note = sel.reason == azimuth_reason::too_many_planes ? "more than four planes" : "no aspect";
            pv.azimuth_deg = std::isnan(sel.mode_deg) ? 0.0 : sel.mode_deg;
            measure_patch(pv, {}, g, o);
            pv.suitable = false;
            pv.reason = out.building.note;
            return out;
        }
        pv.azimuth_deg = sel.azimuth_deg;
        // Step 7: cells within +-1/2 standard deviation of the PV mode (linear statistics of the integer
        // aspects, as the GIS zonal std computes them).
        const double mean = a_sum / static_cast<double>(aspects);
        const double sd = std::sqrt(std::max(0.0, a_sq / static_cast<double>(aspects) - mean * mean));
        for (const std::ptrdiff_t* p = first; p != last; ++p) {
            const float a = sa.aspect_deg(*p / g.cols, *p % g.cols);
            if (std::isnan(a)) continue;
            const double k = static_cast<double>(static_cast<std::size_t>(std::floor(a)) % 360);
            if (std::fabs(k - sel.azimuth_deg) <= 0.5 * sd)
                mask[static_cast<std::size_t>((*p / g.cols - r0) * w + (*p % g.cols - c0))] = 1;
        }
        out.building.note = "paper: planes " + std::to_string(sel.planes);
    }
    // Steps 8-10: 4-connected patches, small ones dropped, boundary clean; the rest is the PV plane.
    const auto drop_small = [&] {
        raster<std::uint8_t> r(h, w);
        for (std::ptrdiff_t i = 0; i < h * w; ++i) r(i / w, i % w) = mask[static_cast<std::size_t>(i)];
        const components comp = connected_components(r, connectivity::four);
        for (std::ptrdiff_t i = 0; i < h * w; ++i) {
            const auto l = comp.labels(i / w, i % w);
            if (l > 0 && comp.sizes[static_cast<std::size_t>(l)] < static_cast<std::size_t>(o.paper_min_patch_cells))
                mask[static_cast<std::size_t>(i)] = 0;
        }
    };
    drop_small();
    for (int k = 0; k < o.paper_boundary_cleans; ++k) boundary_clean(mask, h, w);
    // The clean may add cells outside the roof: keep roof cells only.
    for (std::ptrdiff_t i = 0; i < h * w; ++i) {
        if (!mask[static_cast<std::size_t>(i)]) continue;
        const std::ptrdiff_t r = r0 + i / w, c = c0 + i % w;
        if (std::isnan(sa.slope_deg(r, c))) continue;
        chosen.push_back(r * g.cols + c);
    }
    // The building's cells only (a clean may reach a neighbour's roof in the box).
    std::vector<std::ptrdiff_t> own(first, last);
    std::sort(own.begin(), own.end());
    std::erase_if(chosen, [&](std::ptrdiff_t i) { return !std::binary_search(own.begin(), own.end(), i); });
    measure_patch(pv, chosen, g, o);
    if (!flat && (pv.azimuth_deg < o.min_azimuth_deg || pv.azimuth_deg > o.max_azimuth_deg)) {
        pv.suitable = false;  // step 6: east-south-west only
        pv.reason = "faces north";
    } else if (chosen.empty()) {
        pv.suitable = false;
        pv.reason = "no patch of the minimum size";
    }
    out.cells.back() = std::move(chosen);
    return out;
}

}  // namespace detail

inline void judge_patch(roof_patch& p, const roof_suitability_options& o)
{
    p.flat = p.tilt_deg < o.flat_below_deg;
    const bool big = p.sloped_area_m2 >= o.min_patch_m2;
    if (p.flat) {
        p.suitable = big;
        p.reason = big ? "flat roof: panels on racks" : "flat roof under the minimum area";
        return;
    }
    const bool tilt_ok = p.tilt_deg >= o.min_tilt_deg && p.tilt_deg <= o.max_tilt_deg;
    const bool facing_ok = p.azimuth_deg >= o.min_azimuth_deg && p.azimuth_deg <= o.max_azimuth_deg;
    p.suitable = big && tilt_ok && facing_ok;
    p.reason = p.suitable                    ? "suitable"
               : !facing_ok                  ? "faces north"
               : p.tilt_deg > o.max_tilt_deg ? "too steep"
               : !tilt_ok                    ? "too shallow"
                                             : "under the minimum area";
}

template <raster_input Dsm, raster_input Dtm, raster_input Ids>
roof_suitability_result roof_suitability(const Dsm& dsm, const Dtm& dtm, const Ids& building_id, const grid& g,
                                         const roof_suitability_options& opt)
{
    constexpr const char* fn = "roof_suitability";
    detail::check_roof_suitability(dsm, dtm, building_id, g, opt, fn);

    const detail::building_groups groups = detail::group_buildings(building_id, fn);
    // Roof surface: the DSM (planes mode) or the nDSM (paper mode) on roof cells, NaN elsewhere.
    raster<float> roof_z(g.rows, g.cols, std::numeric_limits<float>::quiet_NaN());
    for (const auto i : groups.cells) {
        const std::ptrdiff_t r = i / g.cols, c = i % g.cols;
        const double top = static_cast<double>(dsm(r, c)), ground = static_cast<double>(dtm(r, c));
        if (std::isfinite(top) && std::isfinite(ground) && top - ground >= opt.min_height_m)
            roof_z(r, c) = static_cast<float>(opt.mode == roof_mode::paper ? top - ground : top);
    }
    slope_aspect_result sa;
    if (opt.mode == roof_mode::paper) sa = slope_aspect(roof_z, g.cell);
    const std::size_t count = groups.ids.size();
    std::vector<detail::building_outcome> outcomes(count);
    parallel_for_rows(
        static_cast<std::ptrdiff_t>(count), 64, opt.run.threads,
        [&](std::ptrdiff_t k0, std::ptrdiff_t k1) {
            for (std::ptrdiff_t k = k0; k < k1; ++k) {
                const auto ku = static_cast<std::size_t>(k);
                const std::ptrdiff_t* first = groups.cells.data() + groups.start[ku];
                const std::ptrdiff_t* last = groups.cells.data() + groups.start[ku + 1];
                outcomes[ku] = opt.mode == roof_mode::paper ? detail::building_paper(sa, first, last, g, opt)
                                                            : detail::building_planes(roof_z, first, last, g, opt);
                outcomes[ku].building.building_id = groups.ids[ku];
            }
        },
        opt.run.progress, fn);
    roof_suitability_result result{raster<std::int32_t>(g.rows, g.cols, 0), {}, {}};
    std::int32_t next = 1;
    for (auto& o : outcomes) {
        for (std::size_t p = 0; p < o.patches.size(); ++p) {
            o.patches[p].building_id = o.building.building_id;
            o.patches[p].patch_id = next;
            for (const auto i : o.cells[p]) result.patch_id(i / g.cols, i % g.cols) = next;
            result.patches.push_back(std::move(o.patches[p]));
            ++next;
        }
        result.buildings.push_back(std::move(o.building));
    }
    return result;
}

}  // namespace lidarfx
