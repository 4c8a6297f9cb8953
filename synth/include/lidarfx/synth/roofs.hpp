// SPDX-License-Identifier: Apache-2.0
// Buildings for synthetic scenes: rotated rectangular footprints with flat, shed, gable and hip roofs.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "lidarfx/core/fast_math.hpp"

namespace lidarfx::synth {

/// One planar roof face of a building, as recorded in the scene truth.
struct roof_plane_truth {
    std::int32_t building_id = 0;  ///< id of the building (1-based, as in the building_id raster)
    double tilt_deg = 0;           ///< 0 horizontal .. 90 vertical
    double azimuth_deg = 0;        ///< down-slope direction, clockwise from north, [0, 360); 0 when tilt is 0
    double area_m2 = 0;            ///< sloped (true) area = horizontal area / cos(tilt), m^2
};

/// Roof shapes of the synthetic buildings. Gable ridges and hip ridges run along the footprint's long
/// axis; a hip roof has the same tilt on its four faces, so its ridge is length - width long (a pyramid
/// on a square).
enum class roof_kind_truth { flat, shed, gable, hip };

/// A dormer: a box standing on face 0 (v0 > 0) or face 1 (v0 < 0) of a gable or hip roof, in the building's local
/// frame (building_truth::local). Its back (the side towards the ridge, |v| = |v0| - hv) meets the roof where
/// top_z is the roof's height there; its front (towards the eave, |v| = |v0| + hv) stands above the roof as a step.
/// The top is flat, or a shed falling front_drop_m from back to front. building_truth::roof_at gives the higher of
/// roof and top where the dormer stands.
struct dormer_truth {
    double u0 = 0;            ///< centre along u (the long axis) from the footprint centre, metres
    double v0 = 0;            ///< centre along v (across) from the footprint centre, metres; its sign picks the face
    double hu = 1;            ///< half the dormer's width along u, metres, > 0
    double hv = 1;            ///< half the dormer's depth along v, metres, > 0
    double top_z = 0;         ///< elevation of the top at the dormer's back, metres
    double front_drop_m = 0;  ///< how far a shed top falls from the back to the front, metres; 0 = flat top

    /// True when local point (pu, pv) lies on the dormer (edges included).
    bool covers(double pu, double pv) const noexcept { return std::abs(pu - u0) <= hu && std::abs(pv - v0) <= hv; }

    /// Elevation of the top at local across-coordinate pv (on the dormer), metres.
    double top_at(double pv) const noexcept
    {
        if (front_drop_m == 0) return top_z;
        const double to_front = v0 >= 0 ? pv - (v0 - hv) : (v0 + hv) - pv;  // 0 at the back, 2 hv at the front
        return top_z - front_drop_m * to_front / (2 * hv);
    }
};

/// A synthetic building, as built and as stated in the truth: a length x width rectangle (length >=
/// width) centred at (x, y) whose long axis points to `axis_azimuth_deg` (clockwise from north), walls up
/// to `eave_z` (absolute elevation), and a roof.
/// Local axes: u along the long axis, v = u turned 90 degrees clockwise; faces are numbered in the order
/// of planes(): gable 0 faces +v and 1 faces -v; hip adds 2 facing +u and 3 facing -u; a shed faces
/// `shed_facing` (0 +v, 1 -v, 2 +u, 3 -u).
/// Dormers (gable and hip roofs, on faces 0 and 1) raise the roof where they stand; roof_at marks them with face
/// -1, and planes() takes their horizontal area off the face they stand on (their tops and walls are no plane).
struct building_truth {
    std::int32_t id = 1;  ///< 1-based id
    double x = 0, y = 0;  ///< footprint centre, metres
    double length_m = 12, width_m = 8;
    double axis_azimuth_deg = 0;  ///< direction of the long axis, clockwise from north
    roof_kind_truth kind = roof_kind_truth::gable;
    double tilt_deg = 30;   ///< roof tilt of every face (ignored for flat roofs)
    int shed_facing = 0;    ///< facing of a shed roof, 0..3 (see above)
    double eave_z = 10;     ///< elevation of the eaves (top of the walls), metres
    double intensity = 70;  ///< mean intensity of the roof material
    /// Dormers on the roof (dormer_truth); empty = none. Each lies inside the footprint, on one face (gable, hip).
    std::vector<dormer_truth> dormers;

    /// Local coordinates (along u, along v) of world point (px, py).
    std::array<double, 2> local(double px, double py) const noexcept
    {
        const double a = deg_to_rad(axis_azimuth_deg);
        const double su = std::sin(a), cu = std::cos(a), dx = px - x, dy = py - y;
        return {dx * su + dy * cu, dx * cu - dy * su};
    }

    /// Half the horizontal radius that encloses the footprint (centre to corner), metres.
    double bounding_radius() const noexcept { return 0.5 * std::hypot(length_m, width_m); }

    /// True when (px, py) lies inside the footprint (edges included).
    bool contains(double px, double py) const noexcept
    {
        const auto [pu, pv] = local(px, py);
        return std::abs(pu) <= 0.5 * length_m && std::abs(pv) <= 0.5 * width_m;
    }

    /// Roof elevation and face index at (px, py) inside the footprint (see the face numbering above); face -1 on
    /// a dormer whose top stands above the roof there.
    struct roof_hit {
        double z;  ///< elevation, metres
        int face;  ///< index into planes(), or -1 on a dormer
    };
    roof_hit roof_at(double px, double py) const noexcept
    {
        const auto [pu, pv] = local(px, py);
        const roof_hit roof = roof_without_dormers(pu, pv);
        if (dormers.empty()) return roof;
        roof_hit top = roof;
        for (const auto& d : dormers) {
            if (!d.covers(pu, pv)) continue;
            const double z = d.top_at(pv);
            if (z > top.z) top = {z, -1};
        }
        return top;
    }

    /// The roof (without dormers) at local point (pu, pv): elevation and face.
    roof_hit roof_without_dormers(double pu, double pv) const noexcept
    {
        const double slope = std::tan(deg_to_rad(tilt_deg));
        const double to_long_edge = 0.5 * width_m - std::abs(pv), to_short_edge = 0.5 * length_m - std::abs(pu);
        switch (kind) {
            case roof_kind_truth::flat:
                return {eave_z, 0};
            case roof_kind_truth::shed: {
                const double along = shed_facing == 0 ? pv : shed_facing == 1 ? -pv : shed_facing == 2 ? pu : -pu;
                const double half = shed_facing < 2 ? 0.5 * width_m : 0.5 * length_m;
                return {eave_z + slope * (half - along), 0};
            }
            case roof_kind_truth::gable:
                return {eave_z + slope * to_long_edge, pv >= 0 ? 0 : 1};
            case roof_kind_truth::hip:
                if (to_long_edge <= to_short_edge) return {eave_z + slope * to_long_edge, pv >= 0 ? 0 : 1};
                return {eave_z + slope * to_short_edge, pu >= 0 ? 2 : 3};
        }
        return {eave_z, 0};
    }

    /// The roof faces with tilt, facing azimuth and sloped area, in face order; a gable's or hip's face 0 (1) without
    /// the sloped area under its dormers with v0 >= 0 (< 0).
    std::vector<roof_plane_truth> planes() const
    {
        auto faces = planes_without_dormers();
        if (dormers.empty() || (kind != roof_kind_truth::gable && kind != roof_kind_truth::hip)) return faces;
        const double cos_tilt = std::cos(deg_to_rad(tilt_deg));
        for (const auto& d : dormers) faces[d.v0 >= 0 ? 0 : 1].area_m2 -= 4 * d.hu * d.hv / cos_tilt;
        return faces;
    }

    /// The roof faces as if there were no dormers.
    std::vector<roof_plane_truth> planes_without_dormers() const
    {
        const double cos_tilt = std::cos(deg_to_rad(tilt_deg));
        const auto facing = [&](double offset) { return std::fmod(axis_azimuth_deg + offset + 720.0, 360.0); };
        const double l = length_m, w = width_m;
        switch (kind) {
            case roof_kind_truth::flat:
                return {{id, 0.0, 0.0, l * w}};
            case roof_kind_truth::shed: {
                static constexpr double offsets[] = {90, 270, 0, 180};
                return {{id, tilt_deg, facing(offsets[shed_facing]), l * w / cos_tilt}};
            }
            case roof_kind_truth::gable:
                return {{id, tilt_deg, facing(90), 0.5 * l * w / cos_tilt},
                        {id, tilt_deg, facing(270), 0.5 * l * w / cos_tilt}};
            case roof_kind_truth::hip: {
                const double side = 0.25 * (2 * l - w) * w / cos_tilt, end = 0.25 * w * w / cos_tilt;
                return {{id, tilt_deg, facing(90), side},
                        {id, tilt_deg, facing(270), side},
                        {id, tilt_deg, facing(0), end},
                        {id, tilt_deg, facing(180), end}};
            }
        }
        return {};
    }

    /// Footprint as a closed counter-clockwise ring of (x, y), x east and y north, first corner repeated
    /// at the end: the exterior ring of a GeoJSON (RFC 7946) polygon, the library's one orientation.
    std::vector<std::array<double, 2>> footprint() const
    {
        const double a = deg_to_rad(axis_azimuth_deg);
        const std::array<double, 2> u{0.5 * length_m * std::sin(a), 0.5 * length_m * std::cos(a)};
        const std::array<double, 2> v{0.5 * width_m * std::cos(a), -0.5 * width_m * std::sin(a)};
        // With the long axis north, +u+v, +u-v, -u-v, -u+v are NE, NW, SW, SE: counter-clockwise, and a
        // rotation keeps the orientation.
        std::vector<std::array<double, 2>> ring{{x + u[0] + v[0], y + u[1] + v[1]},
                                                {x + u[0] - v[0], y + u[1] - v[1]},
                                                {x - u[0] - v[0], y - u[1] - v[1]},
                                                {x - u[0] + v[0], y - u[1] + v[1]}};
        ring.push_back(ring.front());
        return ring;
    }
};

}  // namespace lidarfx::synth
