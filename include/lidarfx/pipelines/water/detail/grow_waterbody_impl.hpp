// SPDX-License-Identifier: Apache-2.0
// Implementation of grow_waterbody (included at the end of pipelines/water/grow_waterbody.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/kernels/stats/ks_one_sided.hpp"
#include "lidarfx/pipelines/water/seed_water_level.hpp"

namespace lidarfx {

namespace detail {

inline void validate(const grow_waterbody_options& o, const char* function)
{
    require(o.theta_start_deg >= 0 && o.theta_start_deg <= 90, function, "theta_start_deg", "in [0, 90]",
            o.theta_start_deg);
    require(o.theta_step_deg > 0 && o.theta_step_deg <= 90, function, "theta_step_deg", "in (0, 90]", o.theta_step_deg);
    require(o.theta_max_deg >= o.theta_start_deg && o.theta_max_deg <= 90, function, "theta_max_deg",
            ">= theta_start_deg and <= 90", o.theta_max_deg);
    require(o.ks.alpha > 0 && o.ks.alpha < 1, function, "ks.alpha", "in (0, 1)", o.ks.alpha);
    require(o.level_gate_m >= 0, function, "level_gate_m", ">= 0", o.level_gate_m);
    require(o.level_drift_m >= 0, function, "level_drift_m", ">= 0", o.level_drift_m);
    require(!std::isnan(o.level_any_angle_m), function, "level_any_angle_m", "a number (< 0 disables)",
            o.level_any_angle_m);
}

/// θ_k, computed the same way everywhere so that step membership is exact.
inline double theta_of_step(const grow_waterbody_options& o, int k) noexcept
{
    return o.theta_start_deg + static_cast<double>(k) * o.theta_step_deg;
}

inline int last_step(const grow_waterbody_options& o) noexcept
{
    int k = static_cast<int>(std::floor((o.theta_max_deg - o.theta_start_deg) / o.theta_step_deg));
    while (k > 0 && theta_of_step(o, k) > o.theta_max_deg) --k;
    while (theta_of_step(o, k + 1) <= o.theta_max_deg) ++k;
    return k;
}

/// Smallest step k with angle <= θ_k (NaN: 0); last + 1 when the angle exceeds θ_max.
inline int step_of_angle(const grow_waterbody_options& o, float angle, int last) noexcept
{
    if (std::isnan(angle)) return 0;
    const double a = angle;
    if (a <= o.theta_start_deg) return 0;
    int k = static_cast<int>(std::ceil((a - o.theta_start_deg) / o.theta_step_deg));
    if (k > last + 1) return last + 1;
    while (k > 0 && a <= theta_of_step(o, k - 1)) --k;
    while (k <= last && a > theta_of_step(o, k)) ++k;
    return k;
}

/// Where a joining cell passes on a level that follows its min z (with the gate): not where the surface
/// slope exceeds level_follow_max_slope, nor where the mean intensity reaches level_follow_max_intensity.
/// Each test is on only when its option is set and the field holds its raster (else that view is empty).
struct level_follow_rule {
    surface_slope_source slope = {};
    float max_slope = 0;
    raster_view<const float> intensity = {};
    float max_intensity = 0;

    level_follow_rule(const water_field& field, const grow_waterbody_options& opt, bool gate)
    {
        if (gate && opt.level_follow_max_slope >= 0) slope = field.surface_slope;
        if (gate && !std::isnan(opt.level_follow_max_intensity)) intensity = field.mean_intensity;
        max_slope = static_cast<float>(opt.level_follow_max_slope);
        max_intensity = static_cast<float>(opt.level_follow_max_intensity);
    }
    bool follows(std::ptrdiff_t r, std::ptrdiff_t c) const
    {
        return (slope.empty() || !(slope(r, c) > max_slope)) &&
               (intensity.empty() || !(intensity(r, c) >= max_intensity));
    }
};

/// grow_waterbody's checks of its field and options.
inline void validate(const water_field& field, const grow_waterbody_options& opt, const char* fn)
{
    validate(opt, fn);
    require_same_shape(field.angle_deg, field.eligible, fn, "field.angle_deg", "field.eligible");
    require_same_shape(field.angle_deg, field.intensity_bin, fn, "field.angle_deg", "field.intensity_bin");
    require(field.bins >= 1, fn, "field.bins", ">= 1", field.bins);
    const bool gate = opt.level_gate_m > 0 && !field.min_z.empty();
    if (gate) require_same_shape(field.angle_deg, field.min_z, fn, "field.angle_deg", "field.min_z");
    const level_follow_rule follow(field, opt, gate);
    if (!follow.slope.empty())
        require_same_shape(field.angle_deg, follow.slope, fn, "field.angle_deg", "field.surface_slope");
    if (!follow.intensity.empty())
        require_same_shape(field.angle_deg, follow.intensity, fn, "field.angle_deg", "field.mean_intensity");
}

/// grow_waterbody's flood over the eligible cells `eligible` (the field's shape, contiguous; field.eligible or a
/// copy of it), marking the cells it queues with `stamp` in `seen` (contiguous, the field's shape; no cell holds
/// the stamp before). Each cell it queues (and marks) is passed to on_queued(i) as it is: with the seed cells, these
/// are the only cells whose eligibility the result depends on (a cell never queued has no effect on it). on_queued may
/// throw to end the flood.
template <class Mark, class Queued>
grow_waterbody_result grow_waterbody_flood(const water_field& field, const std::uint8_t* eligible,
                                           std::span<const std::ptrdiff_t> seed_cells,
                                           const grow_waterbody_options& opt, Mark* seen, Mark stamp,
                                           Queued&& on_queued)
{
    constexpr const char* fn = "grow_waterbody";
    const std::ptrdiff_t rows = field.angle_deg.rows(), cols = field.angle_deg.cols(), n = rows * cols;
    const float* angle = field.angle_deg.data();
    const std::int32_t* bin = field.intensity_bin.data();
    const int last = detail::last_step(opt);

    // The level gate: each queued cell carries the water level L it passes on (NaN: unknown yet).
    const bool gate = opt.level_gate_m > 0 && !field.min_z.empty();
    const detail::cell_splitter split(cols);
    const bool exempt = gate && opt.level_ks_exempt_m >= 0;
    const bool any_angle = gate && opt.level_any_angle_m >= 0;
    const auto exempt_m = static_cast<float>(opt.level_ks_exempt_m);
    // A queued cell: its index, the level it passes on (gate; NaN: unknown yet) and its intensity sample
    // (bin, -1 for none) with two bits read when it joins, all found while its row is in cache at the push.
    struct queued {
        std::ptrdiff_t cell;
        float level;
        std::int32_t sample;
    };
    constexpr std::int32_t by_level_bit = 1 << 30;    // min z <= level + exempt: water by its height
    constexpr std::int32_t at_level_bit = 1 << 29;    // |min z − level| <= exempt (test_first_step)
    constexpr std::int32_t bin_bits = (1 << 24) - 1;  // bins <= ks_histogram::largest_max_value + 1
    static_assert(ks_histogram::largest_max_value <= static_cast<std::uint32_t>(bin_bits));
    // Queues on huge pages when large: a big flood grows them by doubling, and fresh small pages are costly.
    using cell_queue = std::vector<queued, detail::raster_allocator<queued>>;
    std::vector<cell_queue> buckets(static_cast<std::size_t>(last + 1));
    const double rise = opt.level_rise_m < 0 ? opt.level_drift_m : std::min(opt.level_rise_m, opt.level_drift_m);
    // The views in locals: the queue stores could alias their members, which would then be reloaded.
    const raster_view<const float> min_z = field.min_z;
    const detail::level_follow_rule follow(field, opt, gate);
    // Cell i = r * cols + c, not seen and eligible, reached at step from_step from a cell passing on
    // from_level. The callers test seen and eligible inline: most neighbours of a joining cell are seen
    // already, and a call per neighbour would cost more than the test.
    const auto push = [&](std::ptrdiff_t i, std::ptrdiff_t r, std::ptrdiff_t c, int from_step, float from_level) {
        int k = std::max(from_step, detail::step_of_angle(opt, angle[i], last));
        if (k > last && !any_angle) return;  // can never join: leave it unvisited (its angle is its own)
        float level = from_level;
        std::int32_t sample = bin[i];
        if (sample > bin_bits) [[unlikely]]
            detail::require(false, fn, "field.intensity_bin", "in [-1, bins)", sample);
        if (gate) {
            const float z = min_z(r, c);
            if (!std::isnan(z)) {
                if (std::isnan(from_level)) {
                    level = z;
                } else {
                    const double d = static_cast<double>(z) - from_level;
                    if (std::abs(d) > opt.level_gate_m) return;  // off the level: another path may pass
                    if (any_angle && std::abs(d) <= opt.level_any_angle_m) k = from_step;  // water by level
                    if (follow.follows(r, c))
                        level = static_cast<float>(from_level + std::clamp(d, -opt.level_drift_m, rise));
                }
            }
            if (exempt && sample >= 0) {
                if (z <= level + exempt_m) sample |= by_level_bit;
                if (std::abs(z - level) <= exempt_m) sample |= at_level_bit;
            }
        }
        if (k > last) return;  // neither its angle nor its level lets it in
        seen[i] = stamp;
        on_queued(i);
        buckets[static_cast<std::size_t>(k)].push_back({i, level, sample});
    };
    const auto fresh = [&](std::ptrdiff_t i) { return seen[i] != stamp && eligible[i]; };
    const float seed_level = gate ? static_cast<float>(seed_water_level(seed_cells, field.min_z, opt.seed_level)) : NAN;
    for (const auto i : seed_cells) {
        if (i < 0 || i >= n) [[unlikely]]
            detail::require(false, fn, "seed cell index", "inside the field", i);
        const auto [r, c] = split(i);
        if (fresh(i)) push(i, r, c, 0, seed_level);
    }
    const std::size_t seed_entries = buckets.front().size();  // the seed's own cells never wait (test_first_step)

    grow_waterbody_result out;
    const auto max_bin = static_cast<std::uint32_t>(field.bins - 1);
    ks_histogram previous(max_bin), current(max_bin), added(max_bin);
    const bool increment = opt.sample == ks_sample_mode::increment;
    // The first step's test within itself (test_first_step): its cells off the level wait here.
    const bool first_test = exempt && opt.test_first_step;
    std::vector<queued> waiting;
    ks_histogram waiting_sample(max_bin);
    for (int k = 0; k <= last; ++k) {
        const std::size_t before = out.cells.size();
        auto& bucket = buckets[static_cast<std::size_t>(k)];
        const auto join = [&](const queued& q) {
            const std::ptrdiff_t i = q.cell;
            out.cells.push_back(i);
            if (q.sample >= 0) {
                current.add(q.sample & bin_bits);
                // A cell at or below the level it joined at is water by its height: no KS evidence needed.
                if (increment && !(q.sample & by_level_bit)) added.add(q.sample & bin_bits);
            }
            const auto [r, c] = split(i);
            for (std::ptrdiff_t dr = -1; dr <= 1; ++dr) {
                const std::ptrdiff_t rr = r + dr;
                if (rr < 0 || rr >= rows) continue;
                for (std::ptrdiff_t dc = -1; dc <= 1; ++dc) {
                    const std::ptrdiff_t cc = c + dc;
                    if ((dr == 0 && dc == 0) || cc < 0 || cc >= cols) continue;
                    if (const std::ptrdiff_t j = rr * cols + cc; fresh(j)) push(j, rr, cc, k, q.level);
                }
            }
        };
        // Cells pushed into this bucket while it is being drained join at this same step.
        for (std::size_t q = 0;;) {
            for (; q < bucket.size(); ++q) {
                const queued entry = bucket[q];
                if (first_test && k == 0 && q >= seed_entries && entry.sample >= 0 && !(entry.sample & at_level_bit)) {
                    waiting.push_back(entry);
                    waiting_sample.add(entry.sample & bin_bits);
                    continue;
                }
                join(entry);
            }
            if (waiting.empty()) break;
            const bool rejected =
                current.size() >= opt.min_ks_samples && ks_one_sided(current, waiting_sample, opt.ks).reject;
            const auto cells = std::exchange(waiting, {});
            waiting_sample.clear();
            if (rejected) break;  // they stay visited: no other path lets them in
            for (const auto& w : cells) join(w);
        }
        cell_queue().swap(bucket);
        const bool grew = out.cells.size() > before;
        if (k > 0 && grew && previous.size() >= opt.min_ks_samples && previous.size() > 0 &&
            current.size() > previous.size() && (!increment || !added.empty())) {
            if (ks_one_sided(previous, increment ? added : current, opt.ks).reject) {
                out.cells.resize(before);
                out.stopped_by_ks = true;
                break;
            }
        }
        if (!out.cells.empty()) {
            out.steps_accepted = k;
            out.theta_deg = detail::theta_of_step(opt, k);
        }
        if (grew) previous = current;
        if (increment && !added.empty()) added.clear();
    }
    return out;
}

}  // namespace detail

inline grow_waterbody_result grow_waterbody(const water_field& field, std::span<const std::ptrdiff_t> seed_cells,
                                            const grow_waterbody_options& opt, grow_waterbody_workspace& workspace)
{
    detail::validate(field, opt, "grow_waterbody");
    const auto [marks, stamp] = workspace.next_flood(field.angle_deg.rows(), field.angle_deg.cols());
    return detail::grow_waterbody_flood(field, field.eligible.data(), seed_cells, opt, marks.data(), stamp,
                                        [](std::ptrdiff_t) {});
}

inline grow_waterbody_result grow_waterbody(const water_field& field, std::span<const std::ptrdiff_t> seed_cells,
                                            const grow_waterbody_options& opt)
{
    grow_waterbody_workspace workspace;
    return grow_waterbody(field, seed_cells, opt, workspace);
}

}  // namespace lidarfx
