// SPDX-License-Identifier: Apache-2.0
// plane_fit: least-squares planes z = a x + b y + c from additive sums, their tilt and facing, and the angle
// between two planes' normals (roof surfaces of buildings and PV planes share them).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace lidarfx {

/// Sums of points (x, y, z) for the least-squares plane z = a x + b y + c. Additive: the sums of two sets
/// added give the sums of their union, so merged segments add their sums. Use coordinates relative to a
/// nearby reference (metres from a box corner) to keep the sums well conditioned.
struct plane_sums {
    double n = 0, sx = 0, sy = 0, sz = 0, sxx = 0, sxy = 0, syy = 0, sxz = 0, syz = 0, szz = 0;
    void add(double x, double y, double z) noexcept
    {
        n += 1;
        sx += x;
        sy += y;
        sz += z;
        sxx += x * x;
        sxy += x * y;
        syy += y * y;
        sxz += x * z;
        syz += y * z;
        szz += z * z;
    }
    void add(const plane_sums& o) noexcept
    {
        n += o.n;
        sx += o.sx;
        sy += o.sy;
        sz += o.sz;
        sxx += o.sxx;
        sxy += o.sxy;
        syy += o.syy;
        sxz += o.sxz;
        syz += o.syz;
        szz += o.szz;
    }
    /// Takes out the sums of a subset added before (the sums of the rest remain).
    void remove(const plane_sums& o) noexcept
    {
        n -= o.n;
        sx -= o.sx;
        sy -= o.sy;
        sz -= o.sz;
        sxx -= o.sxx;
        sxy -= o.sxy;
        syy -= o.syy;
        sxz -= o.sxz;
        syz -= o.syz;
        szz -= o.szz;
    }
};

/// A fitted plane z = a x + b y + c (x east, y north) with its rms residual (metres when z is).
struct plane_fit {
    double a = 0, b = 0, c = 0;                            ///< slope east, slope north, height at the reference
    double rms = std::numeric_limits<double>::infinity();  ///< sqrt(mean squared residual)
    bool ok = false;  ///< false for fewer than 3 points or collinear ones (then a = b = 0, c = mean z)
    double at(double x, double y) const noexcept { return a * x + b * y + c; }
    /// Angle from horizontal, degrees: atan(|grad z|).
    double tilt_deg() const noexcept { return std::atan(std::hypot(a, b)) * 180.0 / std::numbers::pi; }
    /// Facing (down-slope) azimuth clockwise from north, [0, 360): the direction of (-a, -b); 0 when flat.
    double azimuth_deg() const noexcept
    {
        double az = std::atan2(-a, -b) * 180.0 / std::numbers::pi;
        return az < 0 ? az + 360.0 : az >= 360.0 ? 0.0 : az + 0.0;  // + 0.0: -0 becomes 0
    }
};

/// The least-squares plane of `s` from the centred normal equations:
///   [cxx cxy; cxy cyy] [a; b] = [cxz; cyz],  c = mean z - a mean x - b mean y,
///   rms = sqrt(max(0, czz - a cxz - b cyz)), with c.. the (co)variances (sums / n minus products of means).
/// Degenerate sets (n < 3, or det <= 1e-12 (cxx + cyy)^2: collinear points) give ok = false, a = b = 0,
/// c = mean z and rms = the standard deviation of z; an empty set gives c = 0, rms = 0. O(1).
inline plane_fit fit_plane(const plane_sums& s) noexcept
{
    plane_fit f;
    if (s.n <= 0) {
        f.rms = 0;
        return f;
    }
    const double mx = s.sx / s.n, my = s.sy / s.n, mz = s.sz / s.n;
    const double cxx = s.sxx / s.n - mx * mx, cxy = s.sxy / s.n - mx * my, cyy = s.syy / s.n - my * my;
    const double cxz = s.sxz / s.n - mx * mz, cyz = s.syz / s.n - my * mz, czz = s.szz / s.n - mz * mz;
    const double det = cxx * cyy - cxy * cxy;
    if (s.n >= 3 && det > 1e-12 * (cxx + cyy) * (cxx + cyy) && det > 0) {
        f.a = (cxz * cyy - cyz * cxy) / det;
        f.b = (cyz * cxx - cxz * cxy) / det;
        f.ok = true;
    }
    f.c = mz - f.a * mx - f.b * my;
    f.rms = std::sqrt(std::max(0.0, czz - f.a * cxz - f.b * cyz));
    return f;
}

/// Angle between the upward normals (-a1, -b1, 1) and (-a2, -b2, 1) of two planes, degrees in [0, 90).
inline double normal_angle_deg(double a1, double b1, double a2, double b2) noexcept
{
    const double dot = a1 * a2 + b1 * b2 + 1.0;
    const double n1 = std::sqrt(a1 * a1 + b1 * b1 + 1.0), n2 = std::sqrt(a2 * a2 + b2 * b2 + 1.0);
    return std::acos(std::clamp(dot / (n1 * n2), -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

}  // namespace lidarfx
