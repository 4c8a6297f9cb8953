// SPDX-License-Identifier: Apache-2.0
// The rooftop PV paper's validation metrics, scored against a synthetic roof town's truth: planes found, tilt
// and azimuth errors, per-building suitability recall and precision, sloped-area RMSE (tests, the benchmark
// bench/pv_accuracy and `lidarfx demo` share them).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "lidarfx/pipelines/pv/roof_suitability.hpp"
#include "lidarfx/synth/render.hpp"
#include "lidarfx/synth/roof_towns.hpp"

namespace lidarfx::synth {

/// One matched true plane (for worst-case listings).
struct roof_match {
    std::int32_t building_id = 0, plane_id = 0;
    roof_town_kind kind = roof_town_kind::flat;
    double true_tilt = 0, tilt = 0, true_azimuth = 0, azimuth = 0, true_area = 0, area = 0;
    double tilt_error() const { return std::fabs(tilt - true_tilt); }
    double azimuth_error() const
    {
        const double d = std::fabs(std::fmod(azimuth - true_azimuth + 720.0, 360.0));
        return d > 180 ? 360 - d : d;
    }
};

/// Scores over one or more towns.
struct roof_scores {
    std::size_t true_planes = 0, found = 0;
    std::size_t tilt_within_5 = 0, tilt_within_10 = 0, azimuth_scored = 0, azimuth_within_15 = 0, azimuth_within_45 = 0;
    double area_sq = 0;
    std::size_t tp = 0, fp = 0, fn = 0, tn = 0;
    std::vector<roof_match> matches;

    double found_share() const { return true_planes ? double(found) / double(true_planes) : 0; }
    double tilt5() const { return found ? double(tilt_within_5) / double(found) : 0; }
    double tilt10() const { return found ? double(tilt_within_10) / double(found) : 0; }
    double azimuth15() const { return azimuth_scored ? double(azimuth_within_15) / double(azimuth_scored) : 0; }
    double azimuth45() const { return azimuth_scored ? double(azimuth_within_45) / double(azimuth_scored) : 0; }
    double recall() const { return tp + fn ? double(tp) / double(tp + fn) : 1; }
    double precision() const { return tp + fp ? double(tp) / double(tp + fp) : 1; }
    double area_rmse() const { return found ? std::sqrt(area_sq / double(found)) : 0; }
    /// Pools the scores of another town (its matches appended).
    void add(const roof_scores& o)
    {
        true_planes += o.true_planes;
        found += o.found;
        tilt_within_5 += o.tilt_within_5;
        tilt_within_10 += o.tilt_within_10;
        azimuth_scored += o.azimuth_scored;
        azimuth_within_15 += o.azimuth_within_15;
        azimuth_within_45 += o.azimuth_within_45;
        area_sq += o.area_sq;
        tp += o.tp;
        fp += o.fp;
        fn += o.fn;
        tn += o.tn;
        matches.insert(matches.end(), o.matches.begin(), o.matches.end());
    }
};

/// A scene's truth as a roof town without its rasters (the caller sets dsm and dtm): the grid, building and
/// plane ids, every roof face as a plane (id k + 1 for roof_planes[k]; horizontal area = sloped area x
/// cos(tilt)) and one building per id, of kind flat when its faces are flat and gable otherwise (kinds only
/// label listings).
inline roof_town roof_town_from_truth(const scene_truth& truth, double density_per_m2)
{
    roof_town t;
    t.g = truth.g;
    t.building_id = truth.building_id;
    t.plane_id = truth.roof_plane_id;
    t.density_per_m2 = density_per_m2;
    std::int32_t last = 0;
    for (std::size_t k = 0; k < truth.roof_planes.size(); ++k) {
        const auto& p = truth.roof_planes[k];
        const double cos_tilt = std::cos(p.tilt_deg * std::numbers::pi / 180.0);
        t.planes.push_back({p.building_id, static_cast<std::int32_t>(k + 1), p.tilt_deg, p.azimuth_deg,
                            p.area_m2 * cos_tilt, p.area_m2});
        if (p.building_id != last) {
            roof_town_building b;
            b.id = p.building_id;
            b.kind = p.tilt_deg == 0 ? roof_town_kind::flat : roof_town_kind::gable;
            t.buildings.push_back(b);
        }
        last = p.building_id;
    }
    return t;
}

/// True when a true plane meets the suitability rule of `o` (the one judge_patch applies to measured patches).
inline bool truth_suitable(const roof_town_plane& p, const roof_suitability_options& o)
{
    roof_patch q;
    q.tilt_deg = p.tilt_deg;
    q.azimuth_deg = p.azimuth_deg;
    q.sloped_area_m2 = p.sloped_area_m2;
    lidarfx::judge_patch(q, o);
    return q.suitable;
}

/// Adds the scores of `r` on town `t`:
/// - true planes: those with a sloped area >= min_true_m2; a true plane is found when the patch whose cells
///   overlap it most has it as its own majority plane and the patches with that majority cover >= 50 % of
///   its cells (planes mode), or, in
///   paper mode, when it is the majority plane of its building's PV patch;
/// - tilt and azimuth errors of each found plane against that patch (azimuth only for true tilts >= 5 degrees);
///   relative sloped-area error against the patches whose majority plane it is (a plane cut in two by another
///   wing keeps both pieces); in paper mode against the PV patch, as the paper compares it to the installed
///   system;
/// - per building: truly suitable = some true plane meets the rule; found suitable = some patch is suitable.
inline void score_roofs(const roof_town& t, const roof_suitability_result& r, const roof_suitability_options& o,
                        roof_scores& s, double min_true_m2 = 8.0)
{
    // overlap[(plane, patch)] and per-patch majority plane.
    std::map<std::pair<std::int32_t, std::int32_t>, std::size_t> overlap;
    std::map<std::int32_t, std::size_t> plane_cells;
    for (std::ptrdiff_t row = 0; row < t.g.rows; ++row)
        for (std::ptrdiff_t c = 0; c < t.g.cols; ++c) {
            const auto tp = t.plane_id(row, c);
            if (tp > 0) ++plane_cells[tp];
            const auto pp = r.patch_id(row, c);
            if (tp > 0 && pp > 0) ++overlap[{tp, pp}];
        }
    std::map<std::int32_t, std::pair<std::int32_t, std::size_t>> majority_of_patch;  // patch -> (plane, cells)
    std::map<std::int32_t, std::pair<std::int32_t, std::size_t>> best_patch_of_plane;
    for (const auto& [key, n] : overlap) {
        auto& m = majority_of_patch[key.second];
        if (n > m.second) m = {key.first, n};
        auto& b = best_patch_of_plane[key.first];
        if (n > b.second) b = {key.second, n};
    }
    std::map<std::int32_t, const roof_patch*> patch_by_id;
    for (const auto& p : r.patches) patch_by_id[p.patch_id] = &p;
    std::map<std::int32_t, roof_town_kind> kind_of;
    for (const auto& b : t.buildings) kind_of[b.id] = b.kind;
    // Patches per true plane: those whose majority plane it is (a plane cut in pieces keeps all of them).
    std::map<std::int32_t, std::vector<std::int32_t>> pieces;
    for (const auto& [patch, m] : majority_of_patch) pieces[m.first].push_back(patch);
    for (const auto& tp : t.planes) {
        if (tp.sloped_area_m2 < min_true_m2) continue;
        ++s.true_planes;
        const auto best = best_patch_of_plane.find(tp.plane_id);
        if (best == best_patch_of_plane.end()) continue;
        const std::int32_t patch = best->second.first;
        if (majority_of_patch[patch].first != tp.plane_id) continue;
        std::size_t covered = 0;
        double sloped = 0;
        for (const auto q : pieces[tp.plane_id]) {
            covered += overlap[{tp.plane_id, q}];
            sloped += patch_by_id.at(q)->sloped_area_m2;
        }
        if (o.mode == roof_mode::planes && 2 * covered < plane_cells[tp.plane_id]) continue;
        const roof_patch& p = *patch_by_id.at(patch);
        if (o.mode == roof_mode::paper) sloped = p.sloped_area_m2;
        ++s.found;
        roof_match m{tp.building_id, tp.plane_id,   kind_of[tp.building_id], tp.tilt_deg, p.tilt_deg,
                     tp.azimuth_deg, p.azimuth_deg, tp.sloped_area_m2,       sloped};
        s.tilt_within_5 += m.tilt_error() <= 5;
        s.tilt_within_10 += m.tilt_error() <= 10;
        if (tp.tilt_deg >= 5) {
            ++s.azimuth_scored;
            s.azimuth_within_15 += m.azimuth_error() <= 15;
            s.azimuth_within_45 += m.azimuth_error() <= 45;
        }
        const double rel = (sloped - tp.sloped_area_m2) / tp.sloped_area_m2;
        s.area_sq += rel * rel;
        s.matches.push_back(m);
    }
    std::map<std::int32_t, bool> truly, found;
    for (const auto& b : t.buildings) truly[b.id] = found[b.id] = false;
    for (const auto& tp : t.planes) truly[tp.building_id] = truly[tp.building_id] || truth_suitable(tp, o);
    for (const auto& p : r.patches) found[p.building_id] = found[p.building_id] || p.suitable;
    for (const auto& [id, yes] : truly) {
        const bool f = found[id];
        s.tp += yes && f;
        s.fn += yes && !f;
        s.fp += !yes && f;
        s.tn += !yes && !f;
    }
}

inline const char* kind_name(roof_town_kind k)
{
    switch (k) {
        case roof_town_kind::flat:
            return "flat";
        case roof_town_kind::shed:
            return "shed";
        case roof_town_kind::gable:
            return "gable";
        case roof_town_kind::hip:
            return "hip";
        case roof_town_kind::l_shaped:
            return "L";
    }
    return "?";
}

}  // namespace lidarfx::synth
