// SPDX-License-Identifier: Apache-2.0
// Bucket grid over a square: which objects (trees, buildings) may cover a point, in O(1).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace lidarfx::synth {

/// Uniform grid of square buckets over [0, size_m]^2; each object is listed in every bucket its bounding
/// box overlaps, so at(x, y) returns every object that may cover (x, y) (and possibly a few that do not).
/// Objects are identified by the int index the caller gives them. Boxes outside the square are clipped.
class bucket_index {
public:
    bucket_index() = default;

    /// Buckets of about `bucket_m` metres over [0, size_m]^2 (size_m, bucket_m > 0).
    bucket_index(double size_m, double bucket_m)
        : n_(static_cast<std::ptrdiff_t>(std::max(1.0, std::ceil(size_m / bucket_m)))),
          inv_(static_cast<double>(n_) / size_m),
          buckets_(static_cast<std::size_t>(n_ * n_))
    {
    }

    /// Lists object `id` in every bucket overlapping the box [xmin, xmax] x [ymin, ymax].
    void insert(std::int32_t id, double xmin, double ymin, double xmax, double ymax)
    {
        const auto [c0, r0] = clamp_bucket(xmin, ymin);
        const auto [c1, r1] = clamp_bucket(xmax, ymax);
        for (auto r = r0; r <= r1; ++r) {
            for (auto c = c0; c <= c1; ++c) buckets_[static_cast<std::size_t>(r * n_ + c)].push_back(id);
        }
    }

    /// Objects whose boxes overlap the bucket holding (x, y); empty outside the square. O(1).
    std::span<const std::int32_t> at(double x, double y) const noexcept
    {
        const double fc = x * inv_, fr = y * inv_;
        if (!(fc >= 0 && fr >= 0 && fc < static_cast<double>(n_) && fr < static_cast<double>(n_))) return {};
        return buckets_[static_cast<std::size_t>(static_cast<std::ptrdiff_t>(fr) * n_ +
                                                 static_cast<std::ptrdiff_t>(fc))];
    }

private:
    std::array<std::ptrdiff_t, 2> clamp_bucket(double x, double y) const noexcept
    {
        const auto clamp = [this](double f) {
            return static_cast<std::ptrdiff_t>(std::clamp(std::floor(f), 0.0, static_cast<double>(n_ - 1)));
        };
        return {clamp(x * inv_), clamp(y * inv_)};
    }

    std::ptrdiff_t n_ = 1;
    double inv_ = 0;
    std::vector<std::vector<std::int32_t>> buckets_ = std::vector<std::vector<std::int32_t>>(1);
};

}  // namespace lidarfx::synth
