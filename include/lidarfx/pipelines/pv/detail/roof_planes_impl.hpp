// SPDX-License-Identifier: Apache-2.0
// Implementation of roof_planes (pipelines/pv/roof_planes.hpp): local 3x3 planes and the noise estimate,
// region growing, robust refits, merging of coplanar neighbours, competitive reassignment, final planes.
#pragma once
// Included at the end of its public header, which declares what is defined here.

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
namespace detail {

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

/// Step 1: per roof cell the 3x3 least-squares plane (a, b) and its rms residual (corrected for the 3 fitted
/// parameters; +inf where no fit), the fitted cells by increasing rms (ties by index), and sigma.
struct roof_local_fits {
    std::vector<double> a, b, rms;
    std::vector<std::ptrdiff_t> order;
    double sigma_m = 0;
};

inline roof_local_fits fit_roof_local_planes(const roof_box_surface& s)
{
    const auto n = static_cast<std::ptrdiff_t>(s.z.size());
    roof_local_fits out;
    out.a.assign(static_cast<std::size_t>(n), 0);
    out.b.assign(static_cast<std::size_t>(n), 0);
    out.rms.assign(static_cast<std::size_t>(n), std::numeric_limits<double>::infinity());
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
        out.a[static_cast<std::size_t>(i)] = f.a;
        out.b[static_cast<std::size_t>(i)] = f.b;
        out.rms[static_cast<std::size_t>(i)] = f.rms * std::sqrt(sums.n / std::max(1.0, sums.n - 3));
        out.order.push_back(i);
        rms_values.push_back(out.rms[static_cast<std::size_t>(i)]);
    }
    if (out.order.empty()) return out;
    std::nth_element(rms_values.begin(), rms_values.begin() + static_cast<std::ptrdiff_t>(rms_values.size() / 2),
                     rms_values.end());
    out.sigma_m = std::max(0.02, rms_values[rms_values.size() / 2]);
    std::stable_sort(out.order.begin(), out.order.end(), [&](std::ptrdiff_t p, std::ptrdiff_t q) {
        return out.rms[static_cast<std::size_t>(p)] < out.rms[static_cast<std::size_t>(q)];
    });
    return out;
}

/// Step 2: regions grown from the most planar free cell (see roof_planes); regions under min_seed_cells are
/// released (their cells seed no other region).
inline std::vector<std::vector<std::ptrdiff_t>> grow_roof_plane_regions(const roof_box_surface& s,
                                                                        const roof_local_fits& lf, double angle_tol,
                                                                        double dist_tol, int min_seed_cells)
{
    // lab: 0 free, > 0 region, -1 released.
    std::vector<std::int32_t> lab(s.z.size(), 0);
    std::vector<std::vector<std::ptrdiff_t>> regions;
    std::vector<std::ptrdiff_t> members;
    for (const auto seed : lf.order) {
        if (lab[static_cast<std::size_t>(seed)] != 0) continue;
        const auto k = static_cast<std::int32_t>(regions.size() + 1);
        members.assign(1, seed);
        lab[static_cast<std::size_t>(seed)] = k;
        plane_sums sums;
        sums.add(s.x(seed), s.y(seed), s.z[static_cast<std::size_t>(seed)]);
        plane_fit f;
        f.a = lf.a[static_cast<std::size_t>(seed)];
        f.b = lf.b[static_cast<std::size_t>(seed)];
        f.c = s.z[static_cast<std::size_t>(seed)] - f.a * s.x(seed) - f.b * s.y(seed);
        std::size_t next_refit = 4;
        for (std::size_t head = 0; head < members.size(); ++head) {
            s.for_neighbours(members[head], [&](std::ptrdiff_t j) {
                const auto ju = static_cast<std::size_t>(j);
                if (lab[ju] > 0 || !std::isfinite(lf.rms[ju])) return;
                if (normal_angle_deg(lf.a[ju], lf.b[ju], f.a, f.b) > angle_tol) return;
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
        if (static_cast<int>(members.size()) < min_seed_cells) {
            for (const auto m : members) lab[static_cast<std::size_t>(m)] = -1;
            continue;
        }
        regions.push_back(members);
    }
    return regions;
}

/// Writes plane p + 1 into `assign` at every cell of planes[p] (other cells keep their value).
inline void label_plane_cells(const std::vector<std::vector<std::ptrdiff_t>>& planes, std::vector<std::int32_t>& assign)
{
    for (std::size_t p = 0; p < planes.size(); ++p)
        for (const auto i : planes[p]) assign[static_cast<std::size_t>(i)] = static_cast<std::int32_t>(p + 1);
}

/// A straight cut of a plane's cells into two parts with their least-squares planes.
struct plane_cut {
    std::vector<std::ptrdiff_t> first, second;
    plane_fit fit_first, fit_second;
    double sse = std::numeric_limits<double>::infinity();  ///< summed squared residual of the two fits
    double angle_deg = 0;                                  ///< direction of the cut line's normal
};

/// The best cut of `members` by a straight line into two least-squares planes: lines whose normals point at
/// first_deg + k step_deg (k < angles; degrees counterclockwise from east), each at every place between two
/// cells' projections on its normal that leaves >= min_part cells on either side. Returns false when no cut
/// gives two fits. O(angles n log n).
inline bool best_plane_cut(const roof_box_surface& s, const std::vector<std::ptrdiff_t>& members, int min_part,
                           double first_deg, int angles, double step_deg, plane_cut& out)
{
    const std::size_t n = members.size();
    if (n < static_cast<std::size_t>(2 * min_part)) return false;
    std::vector<std::pair<double, std::ptrdiff_t>> order(n);
    std::vector<plane_sums> prefix(n + 1);
    double best = std::numeric_limits<double>::infinity();
    double best_angle = 0;
    std::size_t best_k = 0;
    for (int k_angle = 0; k_angle < angles; ++k_angle) {
        const double angle = first_deg + k_angle * step_deg;
        const double cx = std::cos(angle * std::numbers::pi / 180.0), cy = std::sin(angle * std::numbers::pi / 180.0);
        for (std::size_t k = 0; k < n; ++k) order[k] = {cx * s.x(members[k]) + cy * s.y(members[k]), members[k]};
        std::sort(order.begin(), order.end());
        prefix[0] = plane_sums{};
        for (std::size_t k = 0; k < n; ++k) {
            prefix[k + 1] = prefix[k];
            const auto i = order[k].second;
            prefix[k + 1].add(s.x(i), s.y(i), s.z[static_cast<std::size_t>(i)]);
        }
        for (auto k = static_cast<std::size_t>(min_part); k + static_cast<std::size_t>(min_part) <= n; ++k) {
            if (order[k].first - order[k - 1].first < 1e-9) continue;
            plane_sums rest = prefix[n];
            rest.remove(prefix[k]);
            const plane_fit below = fit_plane(prefix[k]), above = fit_plane(rest);
            if (!below.ok || !above.ok) continue;
            const double sse = below.rms * below.rms * prefix[k].n + above.rms * above.rms * rest.n;
            if (sse < best) {
                best = sse;
                best_angle = angle;
                best_k = k;
            }
        }
    }
    if (!std::isfinite(best)) return false;
    const double cx = std::cos(best_angle * std::numbers::pi / 180.0),
                 cy = std::sin(best_angle * std::numbers::pi / 180.0);
    for (std::size_t k = 0; k < n; ++k) order[k] = {cx * s.x(members[k]) + cy * s.y(members[k]), members[k]};
    std::sort(order.begin(), order.end());
    out.first.clear();
    out.second.clear();
    plane_sums a, b;
    for (std::size_t k = 0; k < n; ++k) {
        const auto i = order[k].second;
        (k < best_k ? out.first : out.second).push_back(i);
        (k < best_k ? a : b).add(s.x(i), s.y(i), s.z[static_cast<std::size_t>(i)]);
    }
    out.fit_first = fit_plane(a);
    out.fit_second = fit_plane(b);
    out.sse = best;
    out.angle_deg = best_angle;
    return true;
}

/// best_plane_cut coarse to fine: normals every 10 degrees, then every 2 degrees within 8 of the best, at least
/// 4 cells a side.
inline bool best_two_plane_cut(const roof_box_surface& s, const std::vector<std::ptrdiff_t>& members, plane_cut& out)
{
    if (!best_plane_cut(s, members, 4, 0.0, 18, 10.0, out)) return false;
    plane_cut fine;
    if (best_plane_cut(s, members, 4, out.angle_deg - 8.0, 9, 2.0, fine) && fine.sse < out.sse) out = std::move(fine);
    return true;
}

/// Step 4b, first part: 4-connected groups of >= min_seed_cells roof cells that no plane took and that are
/// planar (median rms of their cells' 3x3 fits <= 2 sigma: not a crown, not a strip of ridge cells) become
/// planes with their robust fit.
inline void add_free_cell_groups(const roof_box_surface& s, const roof_local_fits& lf,
                                 std::vector<std::vector<std::ptrdiff_t>>& planes, std::vector<plane_fit>& fits,
                                 const std::vector<std::int32_t>& assign, int min_seed_cells)
{
    std::vector<std::uint8_t> seen(s.z.size(), 0);
    std::vector<std::ptrdiff_t> group;
    std::vector<double> local_rms;
    const auto n = static_cast<std::ptrdiff_t>(s.z.size());
    for (std::ptrdiff_t i = 0; i < n; ++i) {
        if (!s.in(i) || assign[static_cast<std::size_t>(i)] != 0 || seen[static_cast<std::size_t>(i)]) continue;
        group.assign(1, i);
        seen[static_cast<std::size_t>(i)] = 1;
        for (std::size_t head = 0; head < group.size(); ++head)
            s.for_neighbours(group[head], [&](std::ptrdiff_t j) {
                if (assign[static_cast<std::size_t>(j)] != 0 || seen[static_cast<std::size_t>(j)]) return;
                seen[static_cast<std::size_t>(j)] = 1;
                group.push_back(j);
            });
        if (static_cast<int>(group.size()) < min_seed_cells) continue;
        local_rms.clear();
        for (const auto g : group) local_rms.push_back(lf.rms[static_cast<std::size_t>(g)]);  // +inf: no fit
        std::nth_element(local_rms.begin(), local_rms.begin() + static_cast<std::ptrdiff_t>(local_rms.size() / 2),
                         local_rms.end());
        if (!(local_rms[local_rms.size() / 2] <= 2 * lf.sigma_m)) continue;
        const plane_fit f = robust_plane(s, group).first;
        if (!f.ok) continue;
        planes.push_back(group);
        fits.push_back(f);
    }
}

/// Whether a cut into two planes explains far more than noise: F = (the squared residual it removes / 3) /
/// (the squared residual left / (cells - 6)) >= min_f, with one plane's squared residual `one_sse` over `cells`.
inline bool cut_explains_more_than_noise(double one_sse, const plane_cut& cut, double cells, double min_f)
{
    const double dof = cells - 6;
    return dof >= 1 && (one_sse - cut.sse) / 3 >= min_f * cut.sse / dof;
}

/// Step 4b: planes that are two faces. Small roofs (a garage's gable, a hip end) give few cells whose 3x3
/// windows all straddle a ridge, so region growing can take two faces as one plane, or lose one face
/// (add_free_cell_groups first gives its cells a plane). A plane of at most 400 cells whose least-squares rms
/// lies between min_distance / 2 and max_plane_rms_m (rougher is a crown, dropped later) is cut along the best
/// straight line (best_two_plane_cut) when the two parts' normals differ by more than 2 x angle_tol and
/// cut_explains_more_than_noise (F >= 10: many cuts were tried). Parts are cut again in turn; at most one cut
/// per 4 cells, so O(n^2 log n) for a plane of n <= 400 cells. Returns whether planes were added (then
/// reassignment runs again).
inline bool split_two_faced_planes(const roof_box_surface& s, const roof_local_fits& lf,
                                   std::vector<std::vector<std::ptrdiff_t>>& planes, std::vector<plane_fit>& fits,
                                   const std::vector<std::int32_t>& assign, double angle_tol,
                                   const roof_planes_options& o)
{
    const std::size_t count_before = planes.size();
    add_free_cell_groups(s, lf, planes, fits, assign, o.min_seed_cells);
    const double min_cut_rms = 0.5 * o.min_distance_m;
    constexpr std::size_t max_cut_cells = 400;
    constexpr double min_f = 10;
    std::size_t p = 0;
    while (p < planes.size()) {
        plane_sums sums;
        for (const auto i : planes[p]) sums.add(s.x(i), s.y(i), s.z[static_cast<std::size_t>(i)]);
        const plane_fit single = fit_plane(sums);
        plane_cut cut;
        const bool cut_found = single.ok && single.rms > min_cut_rms && single.rms <= o.max_plane_rms_m &&
                               planes[p].size() <= max_cut_cells && best_two_plane_cut(s, planes[p], cut);
        if (!cut_found ||
            normal_angle_deg(cut.fit_first.a, cut.fit_first.b, cut.fit_second.a, cut.fit_second.b) <= 2 * angle_tol ||
            !cut_explains_more_than_noise(single.rms * single.rms * sums.n, cut, sums.n, min_f)) {
            ++p;
            continue;
        }
        planes[p] = std::move(cut.first);  // and p stays: the first part is cut again if it is still two faces
        fits[p] = cut.fit_first;
        planes.push_back(std::move(cut.second));
        fits.push_back(cut.fit_second);
    }
    return planes.size() != count_before;
}

/// Step 5a: final fits on the planes' interior cells (all four neighbours on the same plane) when there are at
/// least 8: cells on ridges, hips and eaves mix two surfaces in the DSM and bias a small plane's tilt.
inline void refit_plane_interiors(const roof_box_surface& s, const std::vector<std::vector<std::ptrdiff_t>>& planes,
                                  std::vector<plane_fit>& fits, const std::vector<std::int32_t>& assign)
{
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
            if (g.ok) fits[p] = g;
        }
    }
}

/// Step 5b: the planes large and smooth enough, numbered in the order of their first cell, into `out`.
inline void keep_final_planes(const roof_box_surface& s, const std::vector<std::vector<std::ptrdiff_t>>& planes,
                              const std::vector<plane_fit>& fits, const std::vector<std::int32_t>& assign,
                              const roof_planes_options& o, roof_planes_result& out)
{
    const auto n = static_cast<std::ptrdiff_t>(assign.size());
    const double min_cells = o.min_plane_m2 / (s.cell_m * s.cell_m);
    std::vector<std::int32_t> final_index(planes.size(), 0);
    for (std::ptrdiff_t i = 0; i < n; ++i) {
        const std::int32_t p = assign[static_cast<std::size_t>(i)];
        if (p <= 0) continue;
        const auto pu = static_cast<std::size_t>(p - 1);
        if (final_index[pu] == 0) {
            const plane_fit& f = fits[pu];
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
}

}  // namespace detail

inline roof_planes_result roof_planes(const roof_box_surface& s, const roof_planes_options& o)
{
    const auto n = static_cast<std::ptrdiff_t>(s.z.size());
    roof_planes_result out;
    out.label.assign(static_cast<std::size_t>(n), 0);
    const detail::roof_local_fits lf = detail::fit_roof_local_planes(s);
    if (lf.order.empty()) return out;
    const double sigma = lf.sigma_m;
    out.sigma_m = sigma;
    const double slope_noise_deg = std::atan(sigma / (s.cell_m * std::sqrt(6.0))) * 180.0 / std::numbers::pi;
    const double angle_tol = std::clamp(2.5 * slope_noise_deg, o.min_angle_deg, o.max_angle_deg);
    const double dist_tol = std::max(o.min_distance_m, 3.0 * sigma);
    std::vector<std::vector<std::ptrdiff_t>> planes =
        detail::grow_roof_plane_regions(s, lf, angle_tol, dist_tol, o.min_seed_cells);
    // Merging of adjacent coplanar planes, then competitive reassignment of the cells, in rounds.
    std::vector<plane_fit> plane_fits;
    std::vector<std::int32_t> assign(static_cast<std::size_t>(n), 0);
    detail::label_plane_cells(planes, assign);
    detail::merge_coplanar(s, planes, plane_fits, assign, angle_tol);
    for (int round = 0; round < o.reassign_rounds; ++round) {
        detail::reassign_cells(s, planes, plane_fits, assign, dist_tol);
        if (round + 1 < o.reassign_rounds) {
            detail::merge_coplanar(s, planes, plane_fits, assign, angle_tol);
            detail::label_plane_cells(planes, assign);
        }
    }
    if (detail::split_two_faced_planes(s, lf, planes, plane_fits, assign, angle_tol, o)) {
        detail::label_plane_cells(planes, assign);
        detail::merge_coplanar(s, planes, plane_fits, assign, angle_tol);
        for (int round = 0; round < o.reassign_rounds; ++round)
            detail::reassign_cells(s, planes, plane_fits, assign, dist_tol);
    }
    detail::refit_plane_interiors(s, planes, plane_fits, assign);
    detail::keep_final_planes(s, planes, plane_fits, assign, o, out);
    return out;
}

}  // namespace lidarfx
