// SPDX-License-Identifier: Apache-2.0
// Plain reference for region growing: one BFS per threshold step and a KS test on explicit samples,
// exactly as the dissertation describes the iteration phase.
#pragma once

#include <cmath>
#include <cstdint>
#include <queue>
#include <vector>

#include <lidarfx/kernels/stats/ks_one_sided.hpp>
#include <lidarfx/pipelines/water/grow_waterbody.hpp>

namespace reference {

/// Region at threshold theta: BFS (8-neighbours) from the seed cells through eligible cells whose angle is
/// NaN or <= theta. Returns a 0/1 membership vector.
inline std::vector<std::uint8_t> region_at(const lidarfx::water_field& f, const std::vector<std::ptrdiff_t>& seed,
                                           double theta)
{
    const std::ptrdiff_t rows = f.angle_deg.rows(), cols = f.angle_deg.cols();
    std::vector<std::uint8_t> in(static_cast<std::size_t>(rows * cols), 0);
    const auto ok = [&](std::ptrdiff_t i) {
        const float a = f.angle_deg.data()[i];
        return f.eligible.data()[i] && (std::isnan(a) || static_cast<double>(a) <= theta);
    };
    std::queue<std::ptrdiff_t> q;
    for (auto i : seed)
        if (ok(i) && !in[i]) {
            in[i] = 1;
            q.push(i);
        }
    while (!q.empty()) {
        const auto i = q.front();
        q.pop();
        const std::ptrdiff_t r = i / cols, c = i % cols;
        for (std::ptrdiff_t dr = -1; dr <= 1; ++dr)
            for (std::ptrdiff_t dc = -1; dc <= 1; ++dc) {
                const std::ptrdiff_t rr = r + dr, cc = c + dc;
                if (rr < 0 || cc < 0 || rr >= rows || cc >= cols) continue;
                const auto j = rr * cols + cc;
                if (!in[j] && ok(j)) {
                    in[j] = 1;
                    q.push(j);
                }
            }
    }
    return in;
}

/// Grows like the dissertation: θ from theta_start by theta_step up to theta_max, a BFS at every step, the
/// one-sided KS test between the intensity samples of consecutive regions (cells with a bin >= 0), stop at
/// the first rejection and keep the previous region. Returns the membership of the final region.
inline std::vector<std::uint8_t> grow(const lidarfx::water_field& f, const std::vector<std::ptrdiff_t>& seed,
                                      const lidarfx::grow_waterbody_options& o)
{
    std::vector<std::uint8_t> previous(static_cast<std::size_t>(f.angle_deg.size()), 0);
    std::vector<double> previous_sample;
    std::size_t previous_cells = 0;
    for (int k = 0;; ++k) {
        const double theta = o.theta_start_deg + static_cast<double>(k) * o.theta_step_deg;
        if (theta > o.theta_max_deg) break;
        auto current = region_at(f, seed, theta);
        std::vector<double> sample;
        std::size_t cells = 0;
        for (std::size_t i = 0; i < current.size(); ++i)
            if (current[i]) {
                ++cells;
                if (f.intensity_bin.data()[i] >= 0) sample.push_back(f.intensity_bin.data()[i]);
            }
        // The increment: values of the cells that joined at this step.
        std::vector<double> added;
        for (std::size_t i = 0; i < current.size(); ++i)
            if (current[i] && !previous[i] && f.intensity_bin.data()[i] >= 0)
                added.push_back(f.intensity_bin.data()[i]);
        const auto& tested = o.sample == lidarfx::ks_sample_mode::increment ? added : sample;
        if (k > 0 && cells > previous_cells && previous_sample.size() >= o.min_ks_samples && !previous_sample.empty() &&
            !tested.empty() && lidarfx::ks_one_sided(previous_sample, tested, o.ks).reject) {
            return previous;
        }
        previous = std::move(current);
        previous_sample = std::move(sample);
        previous_cells = cells;
    }
    return previous;
}

}  // namespace reference
