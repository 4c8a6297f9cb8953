// SPDX-License-Identifier: Apache-2.0
// point_set: an owning struct-of-arrays point cloud (the points of a synthetic scene).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "lidarfx/core/las_class.hpp"
#include "lidarfx/core/point_cloud.hpp"

namespace lidarfx::synth {

/// Owning struct-of-arrays point cloud: coordinates in metres, LAS-style attributes. All vectors have
/// size() elements; point i is (x[i], y[i], z[i]) with intensity[i], return_number[i] (1-based) of
/// number_of_returns[i], and classification[i] (lidarfx::las_class codes).
struct point_set {
    std::vector<double> x, y, z;
    std::vector<std::uint16_t> intensity;
    std::vector<std::uint8_t> return_number, number_of_returns, classification;
    std::vector<double> gps_time;  ///< seconds since the survey began: the time of the pulse (scan order)
    double pulse_time_s = 0;       ///< the time push() stamps on the points it appends

    /// Number of points.
    std::size_t size() const noexcept { return x.size(); }

    /// Zero-copy view for the algorithms (a point_cloud with intensity, returns and classification).
    /// The view reads this set's vectors: keep the set alive and unchanged while using it.
    soa_cloud<> cloud() const
    {
        return soa_cloud<>(x, y, z, intensity, return_number, number_of_returns, classification);
    }

    /// Reserves room for n points in every attribute.
    void reserve(std::size_t n)
    {
        x.reserve(n), y.reserve(n), z.reserve(n), intensity.reserve(n);
        return_number.reserve(n), number_of_returns.reserve(n), classification.reserve(n), gps_time.reserve(n);
    }

    /// Appends a point with GPS time pulse_time_s; the intensity is rounded and clamped to [1, 65535].
    void push(double px, double py, double pz, double point_intensity, int return_no, int returns,
              std::uint8_t point_class)
    {
        x.push_back(px);
        y.push_back(py);
        z.push_back(pz);
        intensity.push_back(static_cast<std::uint16_t>(std::clamp(std::round(point_intensity), 1.0, 65535.0)));
        return_number.push_back(static_cast<std::uint8_t>(return_no));
        number_of_returns.push_back(static_cast<std::uint8_t>(returns));
        classification.push_back(point_class);
        gps_time.push_back(pulse_time_s);
    }

    friend bool operator==(const point_set&, const point_set&) = default;
};

}  // namespace lidarfx::synth
