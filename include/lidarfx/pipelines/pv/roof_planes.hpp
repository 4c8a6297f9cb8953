// SPDX-License-Identifier: Apache-2.0
// roof_planes: every roof plane of one building from its surface cells, by normal-guided region growing,
// robust least-squares plane fits, merging of adjacent coplanar segments and a competitive reassignment of
// each cell to the plane that fits it best (the `planes` mode of roof_suitability).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <numbers>
#include <queue>
#include <tuple>
#include <utility>
#include <vector>

#include "lidarfx/core/plane_fit.hpp"

namespace lidarfx {

/// Settings of the plane segmentation (roof_suitability's planes mode). Distances in metres, angles in
/// degrees. Noise-dependent tolerances are set per building from sigma, the building's elevation noise
/// estimated as sqrt(1.5) x the median rms residual of the 3x3 plane fits around its cells.
struct roof_planes_options {
    double min_angle_deg = 5.0;    ///< smallest normal tolerance of region growing and merging
    double max_angle_deg = 20.0;   ///< largest normal tolerance (tolerance = 2.5 x the normal noise of a 3x3 fit)
    double min_distance_m = 0.15;  ///< smallest distance of a cell from its plane (tolerance = max(this, 3 sigma))
    int min_seed_cells = 6;        ///< a grown region smaller than this is released (clutter, ridges)
    double min_plane_m2 = 3.0;     ///< final planes of a smaller horizontal area are clutter (cells left out)
    double max_plane_rms_m = 0.6;  ///< final planes with a larger rms residual are clutter (tree crowns)
    int reassign_rounds = 3;       ///< rounds of cell reassignment and refit
};

namespace detail {

/// One building's surface on its bounding box (h x w cells, row-major): z in metres (NaN = not a roof cell),
/// cell size in metres; cell (r, c) of the box lies at x = c cell, y = -r cell.
struct roof_box_surface {
    std::ptrdiff_t h = 0, w = 0;
    double cell_m = 1;
    std::vector<double> z;
    double x(std::ptrdiff_t i) const noexcept { return static_cast<double>(i % w) * cell_m; }
    double y(std::ptrdiff_t i) const noexcept { return -static_cast<double>(i / w) * cell_m; }
    bool in(std::ptrdiff_t i) const noexcept { return !std::isnan(z[static_cast<std::size_t>(i)]); }
    /// Calls f(j) for the 4-neighbours j of cell i that are roof cells.
    template <class F>
    void for_neighbours(std::ptrdiff_t i, F&& f) const
    {
        const std::ptrdiff_t r = i / w, c = i % w;
        if (r > 0 && in(i - w)) f(i - w);
        if (r + 1 < h && in(i + w)) f(i + w);
        if (c > 0 && in(i - 1)) f(i - 1);
        if (c + 1 < w && in(i + 1)) f(i + 1);
    }
};

/// The planes found on one building: per box cell the plane index + 1 (0 = none), and each plane's fit and cells.
struct roof_planes_result {
    std::vector<std::int32_t> label;
    std::vector<plane_fit> fits;
    std::vector<std::size_t> cells;
    double sigma_m = 0;  ///< the building's noise estimate
};

/// Robust refit of a plane to `members`: least squares, then twice without the cells farther than
/// max(2.5 x 1.4826 MAD, 0.05 m) from the fit. Returns the fit and the inliers' sums.
inline std::pair<plane_fit, plane_sums> robust_plane(const roof_box_surface& s,
                                                     const std::vector<std::ptrdiff_t>& members)
{
    plane_sums sums;
    for (const auto i : members) sums.add(s.x(i), s.y(i), s.z[static_cast<std::size_t>(i)]);
    plane_fit f = fit_plane(sums);
    std::vector<double> res(members.size());
    for (int round = 0; round < 2 && f.ok; ++round) {
        for (std::size_t k = 0; k < members.size(); ++k) {
            const auto i = members[k];
            res[k] = std::fabs(s.z[static_cast<std::size_t>(i)] - f.at(s.x(i), s.y(i)));
        }
        std::vector<double> sorted = res;
        std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
        const double cut = std::max(2.5 * 1.4826 * sorted[sorted.size() / 2], 0.05);
        plane_sums in;
        for (std::size_t k = 0; k < members.size(); ++k)
            if (res[k] <= cut) in.add(s.x(members[k]), s.y(members[k]), s.z[static_cast<std::size_t>(members[k])]);
        const plane_fit g = fit_plane(in);
        if (!g.ok) break;
        f = g;
        sums = in;
    }
    return {f, sums};
}

/// Merges adjacent planes (4-neighbour cells labelled p + 1 and q + 1 in `label`) whose normals agree within
/// 2 x angle_tol and whose joint least-squares fit is hardly worse than theirs (rms <= 1.3 x the larger + 0.02 m):
/// the joint-fit test tells a plane cut in two from two faces that meet at a shallow angle. Planes are
/// refitted robustly; planes without a fit are dropped.
inline void merge_coplanar(const roof_box_surface& s, std::vector<std::vector<std::ptrdiff_t>>& planes,
                           std::vector<plane_fit>& fits, const std::vector<std::int32_t>& label, double angle_tol)
{
    const std::size_t count = planes.size();
    const auto n = static_cast<std::ptrdiff_t>(label.size());
    std::vector<plane_fit> fit(count);
    std::vector<plane_sums> sums(count);
    for (std::size_t k = 0; k < count; ++k) std::tie(fit[k], sums[k]) = robust_plane(s, planes[k]);
    std::vector<std::pair<std::int32_t, std::int32_t>> pairs;
    for (std::ptrdiff_t i = 0; i < n; ++i) {
        const std::int32_t a = label[static_cast<std::size_t>(i)];
        if (a <= 0) continue;
        const auto link = [&](std::ptrdiff_t j) {
            const std::int32_t b = label[static_cast<std::size_t>(j)];
            if (b > 0 && b != a) pairs.emplace_back(std::min(a, b), std::max(a, b));
        };
        if (i % s.w + 1 < s.w) link(i + 1);
        if (i + s.w < n) link(i + s.w);
    }
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    std::vector<std::size_t> parent(count);
    for (std::size_t k = 0; k < count; ++k) parent[k] = k;
    const auto root = [&](std::size_t k) {
        while (parent[k] != k) k = parent[k] = parent[parent[k]];
        return k;
    };
    for (bool merged = true; merged;) {
        merged = false;
        for (const auto& [p, q] : pairs) {
            const std::size_t a = root(static_cast<std::size_t>(p - 1)), b = root(static_cast<std::size_t>(q - 1));
            if (a == b || !fit[a].ok || !fit[b].ok) continue;
            if (normal_angle_deg(fit[a].a, fit[a].b, fit[b].a, fit[b].b) > 2 * angle_tol) continue;
            plane_sums joint = sums[a];
            joint.add(sums[b]);
            const plane_fit g = fit_plane(joint);
            if (!g.ok || g.rms > 1.3 * std::max(fit[a].rms, fit[b].rms) + 0.02) continue;
            const std::size_t keep = std::min(a, b), gone = std::max(a, b);
            parent[gone] = keep;
            sums[keep] = joint;
            fit[keep] = g;
            merged = true;
        }
    }
    std::vector<std::vector<std::ptrdiff_t>> out;
    std::vector<std::ptrdiff_t> index_of(count, -1);
    for (std::size_t k = 0; k < count; ++k)
        if (root(k) == k && fit[k].ok) {
            index_of[k] = static_cast<std::ptrdiff_t>(out.size());
            out.emplace_back();
        }
    for (std::size_t k = 0; k < count; ++k) {
        const auto p = index_of[root(k)];
        if (p >= 0)
            out[static_cast<std::size_t>(p)].insert(out[static_cast<std::size_t>(p)].end(), planes[k].begin(),
                                                    planes[k].end());
    }
    planes = std::move(out);
    fits.assign(planes.size(), plane_fit{});
    for (std::size_t p = 0; p < planes.size(); ++p) fits[p] = robust_plane(s, planes[p]).first;
}

/// Competitive reassignment: starting from each plane's cells within dist_tol of it, cells are taken in order
/// of their residual, each by the first plane that reaches it over 4-neighbours with a residual <= dist_tol;
/// `assign` gets plane + 1 (0 = no plane), `planes` the new members, `fits` robust refits.
inline void reassign_cells(const roof_box_surface& s, std::vector<std::vector<std::ptrdiff_t>>& planes,
                           std::vector<plane_fit>& fits, std::vector<std::int32_t>& assign, double dist_tol)
{
    std::fill(assign.begin(), assign.end(), 0);
    using item = std::tuple<double, std::ptrdiff_t, std::int32_t>;
    std::priority_queue<item, std::vector<item>, std::greater<>> queue;
    const auto residual = [&](std::ptrdiff_t i, std::size_t p) {
        return std::fabs(s.z[static_cast<std::size_t>(i)] - fits[p].at(s.x(i), s.y(i)));
    };
    for (std::size_t p = 0; p < planes.size(); ++p)
        for (const auto i : planes[p]) {
            const double r = residual(i, p);
            if (r <= dist_tol) queue.emplace(r, i, static_cast<std::int32_t>(p + 1));
        }
    // A (cell, plane) entry has one residual, so pushing it again changes nothing: skip repeats by one plane.
    std::vector<std::int32_t> last_pushed(assign.size(), 0);
    while (!queue.empty()) {
        // Plain variables, not a structured binding: the lambda below captures them (C++20 allows capturing a
        // binding, Clang 14 does not).
        const std::ptrdiff_t i = std::get<1>(queue.top());
        const std::int32_t p = std::get<2>(queue.top());
        queue.pop();
        if (assign[static_cast<std::size_t>(i)] != 0) continue;
        assign[static_cast<std::size_t>(i)] = p;
        s.for_neighbours(i, [&](std::ptrdiff_t j) {
            const auto ju = static_cast<std::size_t>(j);
            if (assign[ju] != 0 || last_pushed[ju] == p) return;
            last_pushed[ju] = p;
            const double rj = residual(j, static_cast<std::size_t>(p - 1));
            if (rj <= dist_tol) queue.emplace(rj, j, p);
        });
    }
    for (auto& m : planes) m.clear();
    const auto n = static_cast<std::ptrdiff_t>(assign.size());
    for (std::ptrdiff_t i = 0; i < n; ++i)
        if (assign[static_cast<std::size_t>(i)] > 0)
            planes[static_cast<std::size_t>(assign[static_cast<std::size_t>(i)] - 1)].push_back(i);
    for (std::size_t p = 0; p < planes.size(); ++p)
        if (planes[p].size() >= 3) {
            const plane_fit g = robust_plane(s, planes[p]).first;
            if (g.ok) fits[p] = g;
        }
}

/// Segments the roof planes of one building (see roof_planes_options):
/// 1. a 3x3 least-squares plane around each cell (roof neighbours only) gives its normal and rms residual, and
///    the building's noise sigma (sqrt(1.5) x their median rms) sets the tolerances;
/// 2. regions grow from the most planar free cell over 4-neighbours whose normal lies within the angle
///    tolerance of the region's plane and whose elevation lies within the distance tolerance of it (the plane
///    refitted as the region doubles); regions under min_seed_cells are released;
/// 3. adjacent planes merge when their joint least-squares fit is hardly worse than theirs (merge_coplanar);
/// 4. reassign_rounds times: every cell goes to the plane that reaches it with the smallest residual
///    (reassign_cells), planes are refitted, and merged again between rounds;
/// 5. final fits on each plane's interior cells; planes under min_plane_m2 or rougher than max_plane_rms_m
///    (tree crowns, chimneys) are dropped, their cells left without a plane.
/// Tilt, facing and areas follow from the fits (plane_fit). O(cells log cells) per building.
inline roof_planes_result roof_planes(const roof_box_surface& s, const roof_planes_options& o)
{
    const auto n = static_cast<std::ptrdiff_t>(s.z.size());
    roof_planes_result out;
    out.label.assign(static_cast<std::size_t>(n), 0);
    // 1. Local planes.
    std::vector<double> la(static_cast<std::size_t>(n), 0), lb(static_cast<std::size_t>(n), 0),
        lrms(static_cast<std::size_t>(n), std::numeric_limits<double>::infinity());
    std::vector<std::ptrdiff_t> order;
    std::vector<double> rms_values;
    for (std::ptrdiff_t i = 0; i < n; ++i) {
        if (!s.in(i)) continue;
        const std::ptrdiff_t r = i / s.w, c = i % s.w;
        plane_sums sums;
        for (std::ptrdiff_t dr = -1; dr <= 1; ++dr)
            for (std::ptrdiff_t dc = -1; dc <= 1; ++dc) {
                const std::ptrdiff_t rr = r + dr, cc = c + dc;
                if (rr < 0 || rr >= s.h || cc < 0 || cc >= s.w) continue;
                const std::ptrdiff_t j = rr * s.w + cc;
                if (s.in(j))
                    sums.add(static_cast<double>(dc) * s.cell_m, -static_cast<double>(dr) * s.cell_m,
                             s.z[static_cast<std::size_t>(j)]);
            }
        if (sums.n < 4) continue;
        const plane_fit f = fit_plane(sums);
        if (!f.ok) continue;
        la[static_cast<std::size_t>(i)] = f.a;
        lb[static_cast<std::size_t>(i)] = f.b;
        lrms[static_cast<std::size_t>(i)] = f.rms * std::sqrt(sums.n / std::max(1.0, sums.n - 3));
        order.push_back(i);
        rms_values.push_back(lrms[static_cast<std::size_t>(i)]);
    }
    if (order.empty()) return out;
    std::nth_element(rms_values.begin(), rms_values.begin() + static_cast<std::ptrdiff_t>(rms_values.size() / 2),
                     rms_values.end());
    const double sigma = std::max(0.02, rms_values[rms_values.size() / 2]);
    out.sigma_m = sigma;
    const double slope_noise_deg = std::atan(sigma / (s.cell_m * std::sqrt(6.0))) * 180.0 / std::numbers::pi;
    const double angle_tol = std::clamp(2.5 * slope_noise_deg, o.min_angle_deg, o.max_angle_deg);
    const double dist_tol = std::max(o.min_distance_m, 3.0 * sigma);
    std::stable_sort(order.begin(), order.end(), [&](std::ptrdiff_t p, std::ptrdiff_t q) {
        return lrms[static_cast<std::size_t>(p)] < lrms[static_cast<std::size_t>(q)];
    });

    // 2. Region growing. lab: 0 free, > 0 region, -1 released.
    std::vector<std::int32_t> lab(static_cast<std::size_t>(n), 0);
    std::vector<std::vector<std::ptrdiff_t>> regions;
    std::vector<std::ptrdiff_t> members;
    for (const auto seed : order) {
        if (lab[static_cast<std::size_t>(seed)] != 0) continue;
        const auto k = static_cast<std::int32_t>(regions.size() + 1);
        members.assign(1, seed);
        lab[static_cast<std::size_t>(seed)] = k;
        plane_sums sums;
        sums.add(s.x(seed), s.y(seed), s.z[static_cast<std::size_t>(seed)]);
        plane_fit f;
        f.a = la[static_cast<std::size_t>(seed)];
        f.b = lb[static_cast<std::size_t>(seed)];
        f.c = s.z[static_cast<std::size_t>(seed)] - f.a * s.x(seed) - f.b * s.y(seed);
        std::size_t next_refit = 4;
        for (std::size_t head = 0; head < members.size(); ++head) {
            s.for_neighbours(members[head], [&](std::ptrdiff_t j) {
                const auto ju = static_cast<std::size_t>(j);
                if (lab[ju] > 0 || !std::isfinite(lrms[ju])) return;
                if (normal_angle_deg(la[ju], lb[ju], f.a, f.b) > angle_tol) return;
                if (std::fabs(s.z[ju] - f.at(s.x(j), s.y(j))) > dist_tol) return;
                lab[ju] = k;
                members.push_back(j);
                sums.add(s.x(j), s.y(j), s.z[ju]);
                if (members.size() >= next_refit) {
                    const plane_fit g = fit_plane(sums);
                    if (g.ok) f = g;
                    next_refit = next_refit < 64 ? 2 * next_refit : next_refit + 64;
                }
            });
        }
        if (static_cast<int>(members.size()) < o.min_seed_cells) {
            for (const auto m : members) lab[static_cast<std::size_t>(m)] = -1;
            continue;
        }
        regions.push_back(members);
    }
    // 3-4. Merging of adjacent coplanar planes, then competitive reassignment of the cells, in rounds.
    std::vector<std::vector<std::ptrdiff_t>> planes = std::move(regions);
    std::vector<plane_fit> plane_fits;
    std::vector<std::int32_t> assign(static_cast<std::size_t>(n), 0);
    for (std::size_t p = 0; p < planes.size(); ++p)
        for (const auto i : planes[p]) assign[static_cast<std::size_t>(i)] = static_cast<std::int32_t>(p + 1);
    merge_coplanar(s, planes, plane_fits, assign, angle_tol);
    for (int round = 0; round < o.reassign_rounds; ++round) {
        reassign_cells(s, planes, plane_fits, assign, dist_tol);
        if (round + 1 < o.reassign_rounds) {
            merge_coplanar(s, planes, plane_fits, assign, angle_tol);
            for (std::size_t p = 0; p < planes.size(); ++p)
                for (const auto i : planes[p]) assign[static_cast<std::size_t>(i)] = static_cast<std::int32_t>(p + 1);
        }
    }
    // Final fits on the planes' interior cells (all four neighbours on the same plane) when there are enough:
    // cells on ridges, hips and eaves mix two surfaces in the DSM and bias a small plane's tilt.
    for (std::size_t p = 0; p < planes.size(); ++p) {
        std::vector<std::ptrdiff_t> interior;
        for (const auto i : planes[p]) {
            int same = 0;
            s.for_neighbours(i, [&](std::ptrdiff_t j) {
                same += assign[static_cast<std::size_t>(j)] == assign[static_cast<std::size_t>(i)];
            });
            if (same == 4) interior.push_back(i);
        }
        if (interior.size() >= 8) {
            const plane_fit g = robust_plane(s, interior).first;
            if (g.ok) plane_fits[p] = g;
        }
    }
    // Final planes: large and smooth enough; numbered in the order of their first cell.
    const double min_cells = o.min_plane_m2 / (s.cell_m * s.cell_m);
    std::vector<std::int32_t> final_index(planes.size(), 0);
    for (std::ptrdiff_t i = 0; i < n; ++i) {
        const std::int32_t p = assign[static_cast<std::size_t>(i)];
        if (p <= 0) continue;
        const auto pu = static_cast<std::size_t>(p - 1);
        if (final_index[pu] == 0) {
            const plane_fit& f = plane_fits[pu];
            // Residual rms over the plane's cells (all of them: a tree crown is rough everywhere).
            double sq = 0;
            for (const auto j : planes[pu]) {
                const double d = s.z[static_cast<std::size_t>(j)] - f.at(s.x(j), s.y(j));
                sq += d * d;
            }
            const double rms = std::sqrt(sq / static_cast<double>(planes[pu].size()));
            if (static_cast<double>(planes[pu].size()) < min_cells || rms > o.max_plane_rms_m || !f.ok) {
                final_index[pu] = -1;
            } else {
                out.fits.push_back(f);
                out.fits.back().rms = rms;
                out.cells.push_back(planes[pu].size());
                final_index[pu] = static_cast<std::int32_t>(out.fits.size());
            }
        }
        out.label[static_cast<std::size_t>(i)] = std::max(0, final_index[pu]);
    }
    return out;
}

}  // namespace detail
}  // namespace lidarfx
