// SPDX-License-Identifier: Apache-2.0
// Reference shadows and horizons by brute force: a straight ray march from every cell centre towards the sun
// (cell by cell, Amanatides-Woo), and direct searches over every earlier cell of a cell's ray line.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>

#include <lidarfx/core/raster.hpp>
#include <lidarfx/core/raster_view.hpp>

namespace reference {

/// (sin, cos) in degrees, exact at multiples of 90.
inline void sincos_deg(double deg, double& s, double& c)
{
    double a = std::fmod(deg, 360.0);
    if (a < 0) a += 360.0;
    if (a == 0.0 || a == 90.0 || a == 180.0 || a == 270.0) {
        s = a == 90.0 ? 1.0 : a == 270.0 ? -1.0 : 0.0;
        c = a == 0.0 ? 1.0 : a == 180.0 ? -1.0 : 0.0;
        return;
    }
    s = std::sin(a * std::numbers::pi / 180.0);
    c = std::cos(a * std::numbers::pi / 180.0);
}

/// The documented shadow key of a cell: z + t tan(e), t = ((double(c) + 0.5) dcol + (double(r) + 0.5) drow) cell_m with
/// the walk direction (dcol, drow) = (-sin A, cos A), evaluated in the kernel's order so that ties round alike.
struct shadow_key {
    double a, b;  // dcol * cell_m * tan e, drow * cell_m * tan e
    shadow_key(double azimuth_deg, double elevation_deg, double cell_m)
    {
        double s, c;
        sincos_deg(azimuth_deg, s, c);
        const double t = std::tan(elevation_deg * (std::numbers::pi / 180.0));
        a = -s * cell_m * t;
        b = c * cell_m * t;
    }
    double operator()(double z, std::ptrdiff_t r, std::ptrdiff_t c) const
    {
        return z + ((static_cast<double>(c) + 0.5) * a + (static_cast<double>(r) + 0.5) * b);
    }
};

/// The per-cell frame both brute-force shadows share: NaN cells get nan_cell, a sun at or below the horizon
/// shades every other cell, a sun at the zenith lights it, and otherwise the cell is shadow when
/// shaded(r, col, kp) finds a blocker (kp = the cell's own shadow_key value). 1 lit, 0 shadow.
template <class Shaded>
lidarfx::raster<std::uint8_t> shadow_per_cell(lidarfx::raster_view<const float> z, double elevation_deg,
                                              const shadow_key& key, std::uint8_t nan_cell, Shaded&& shaded)
{
    lidarfx::raster<std::uint8_t> out(z.rows(), z.cols(), 1);
    for (std::ptrdiff_t r = 0; r < z.rows(); ++r) {
        for (std::ptrdiff_t col = 0; col < z.cols(); ++col) {
            const float zp = z(r, col);
            if (std::isnan(zp))
                out(r, col) = nan_cell;
            else if (elevation_deg <= 0)
                out(r, col) = 0;
            else if (elevation_deg < 90 && shaded(r, col, key(zp, r, col)))
                out(r, col) = 0;
        }
    }
    return out;
}

/// Whether a straight line from the centre of cell (r, col) towards the sun is blocked: every cell it passes
/// through (Amanatides-Woo traversal) whose centre projects nearer the sun is tested, z_q + t_q tan e > kp (kp =
/// the shadow key of the point, key(h, r, col)) blocks. NaN cells block nothing; the line leaves at the border.
inline bool straight_march_blocked(lidarfx::raster_view<const float> z, const shadow_key& key, double azimuth_deg,
                                   std::ptrdiff_t r, std::ptrdiff_t col, double kp)
{
    double s, c;
    sincos_deg(azimuth_deg, s, c);
    const double vx = s, vy = -c;  // towards the sun, in (column, row) units
    const double inf = std::numeric_limits<double>::infinity();
    const double tp = (double(col) + 0.5) * -vx + (double(r) + 0.5) * -vy;  // along the walk direction
    std::ptrdiff_t ix = col, iy = r;
    const std::ptrdiff_t step_x = vx > 0 ? 1 : -1, step_y = vy > 0 ? 1 : -1;
    double tmax_x = vx != 0 ? 0.5 / std::fabs(vx) : inf, tmax_y = vy != 0 ? 0.5 / std::fabs(vy) : inf;
    const double dx = vx != 0 ? 1 / std::fabs(vx) : inf, dy = vy != 0 ? 1 / std::fabs(vy) : inf;
    while (true) {
        if (tmax_x < tmax_y) {
            ix += step_x;
            tmax_x += dx;
        } else {
            iy += step_y;
            tmax_y += dy;
        }
        if (ix < 0 || ix >= z.cols() || iy < 0 || iy >= z.rows()) return false;
        const float zq = z(iy, ix);
        const double tq = (double(ix) + 0.5) * -vx + (double(iy) + 0.5) * -vy;
        if (!std::isnan(zq) && tq < tp && key(zq, iy, ix) > kp) return true;
    }
}

/// Shadow by a straight march: from each cell centre towards the sun (straight_march_blocked). 1 lit, 0 shadow,
/// nan_cell for NaN cells; NaN cells cast nothing. O(cells * length).
inline lidarfx::raster<std::uint8_t> shadow_ray_march(lidarfx::raster_view<const float> z, double cell_m,
                                                      double azimuth_deg, double elevation_deg,
                                                      std::uint8_t nan_cell = 255)
{
    const shadow_key key(azimuth_deg, elevation_deg, cell_m);
    return shadow_per_cell(z, elevation_deg, key, nan_cell, [&](std::ptrdiff_t r, std::ptrdiff_t col, double kp) {
        return straight_march_blocked(z, key, azimuth_deg, r, col, kp);
    });
}

/// Shadow by a straight march sampled once per row (steep sun azimuths, |cos A| >= |sin A|) or per column:
/// from each cell centre towards the sun, at every row (column) the line crosses, the cell nearest the line
/// at that row's (column's) centre is tested: z_q + t_q tan e > z_p + t_p tan e means shadow. The classic
/// per-cell ray march of the dissertation; 1 lit, 0 shadow, nan_cell for NaN cells. O(cells * length).
inline lidarfx::raster<std::uint8_t> shadow_sampled_march(lidarfx::raster_view<const float> z, double cell_m,
                                                          double azimuth_deg, double elevation_deg,
                                                          std::uint8_t nan_cell = 255)
{
    const std::ptrdiff_t rows = z.rows(), cols = z.cols();
    double s, c;
    sincos_deg(azimuth_deg, s, c);
    const double vx = s, vy = -c;  // towards the sun, in (column, row) units
    const bool steep = std::fabs(vy) >= std::fabs(vx);
    const shadow_key key(azimuth_deg, elevation_deg, cell_m);
    return shadow_per_cell(z, elevation_deg, key, nan_cell, [&](std::ptrdiff_t r, std::ptrdiff_t col, double kp) {
        for (std::ptrdiff_t j = 1;; ++j) {
            std::ptrdiff_t iy, ix;
            if (steep) {
                iy = r + (vy > 0 ? j : -j);
                ix = static_cast<std::ptrdiff_t>(
                    std::floor(double(col) + 0.5 + double(j) * std::fabs(vx / vy) * (vx > 0 ? 1 : -1)));
            } else {
                ix = col + (vx > 0 ? j : -j);
                iy = static_cast<std::ptrdiff_t>(
                    std::floor(double(r) + 0.5 + double(j) * std::fabs(vy / vx) * (vy > 0 ? 1 : -1)));
            }
            if (ix < 0 || ix >= cols || iy < 0 || iy >= rows) return false;
            const float zq = z(iy, ix);
            if (!std::isnan(zq) && key(zq, iy, ix) > kp) return true;
        }
    });
}

/// The cells of the ray line through (r, c) that come before it when walking away from `azimuth_deg`, by the
/// definition of kernels/solar/ray_lines.hpp: steep lines hold (i, k + round(i * dcol / drow)), shallow ones
/// (k + round(i * drow / dcol), i), round(x) = floor(x + 0.5). Calls f(r', c') for each, nearest first.
/// With phases = P > 1 the line through (r, c) is that of the family j nearest the cell's centre, rendered with
/// floor(0.5 + j / P + i * slope): j = round(P (1 - frac(major * slope))) mod P.
template <class F>
void for_each_earlier_on_line(std::ptrdiff_t rows, std::ptrdiff_t cols, double azimuth_deg, std::ptrdiff_t r,
                              std::ptrdiff_t c, F&& f, int phases = 1)
{
    double s, co;
    sincos_deg(azimuth_deg, s, co);
    const double dcol = -s, drow = co;
    const bool steep = std::fabs(drow) >= std::fabs(dcol);
    const double slope = steep ? dcol / drow : drow / dcol;
    const std::ptrdiff_t major = steep ? r : c;
    const double frac = double(major) * slope - std::floor(double(major) * slope);
    const int family = static_cast<int>(std::floor(0.5 + phases * (1.0 - frac))) % phases;
    const double phase = 0.5 + double(family) / phases;
    const auto rnd = [&](std::ptrdiff_t i) {
        return static_cast<std::ptrdiff_t>(std::floor(phase + double(i) * slope));
    };
    const std::ptrdiff_t k = (steep ? c : r) - rnd(major);
    const std::ptrdiff_t back = (steep ? drow : dcol) > 0 ? -1 : 1;  // towards the azimuth
    for (std::ptrdiff_t i = major + back; i >= 0 && i < (steep ? rows : cols); i += back) {
        const std::ptrdiff_t m = k + rnd(i);
        if (m < 0 || m >= (steep ? cols : rows)) continue;
        if (steep)
            f(i, m);
        else
            f(m, i);
    }
}

/// Shadow on the kernel's own ray lines, by a direct search over every earlier cell of each cell's line.
inline lidarfx::raster<std::uint8_t> shadow_on_lines(lidarfx::raster_view<const float> z, double cell_m,
                                                     double azimuth_deg, double elevation_deg,
                                                     std::uint8_t nan_cell = 255, int phases = 4)
{
    lidarfx::raster<std::uint8_t> out(z.rows(), z.cols(), 1);
    const shadow_key key(azimuth_deg, elevation_deg, cell_m);
    for (std::ptrdiff_t r = 0; r < z.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < z.cols(); ++c) {
            if (std::isnan(z(r, c))) {
                out(r, c) = nan_cell;
                continue;
            }
            const double kp = key(z(r, c), r, c);
            for_each_earlier_on_line(
                z.rows(), z.cols(), azimuth_deg, r, c,
                [&](std::ptrdiff_t rq, std::ptrdiff_t cq) {
                    if (!std::isnan(z(rq, cq)) && key(z(rq, cq), rq, cq) > kp) out(r, c) = 0;
                },
                phases);
        }
    }
    return out;
}

/// Horizon angle towards `azimuth_deg` by a direct search: max(0, max over earlier non-NaN cells q of the
/// cell's ray line of atan((z_q - z_p) / (t_p - t_q))) in degrees, NaN for NaN cells.
inline lidarfx::raster<float> horizon_on_lines(lidarfx::raster_view<const float> z, double cell_m, double azimuth_deg)
{
    lidarfx::raster<float> out(z.rows(), z.cols(), 0.0f);
    double s, co;
    sincos_deg(azimuth_deg, s, co);
    const auto t = [&](std::ptrdiff_t r, std::ptrdiff_t c) {
        return ((double(c) + 0.5) * -s + (double(r) + 0.5) * co) * cell_m;
    };
    for (std::ptrdiff_t r = 0; r < z.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < z.cols(); ++c) {
            if (std::isnan(z(r, c))) {
                out(r, c) = std::numeric_limits<float>::quiet_NaN();
                continue;
            }
            double best = 0;
            for_each_earlier_on_line(z.rows(), z.cols(), azimuth_deg, r, c, [&](std::ptrdiff_t rq, std::ptrdiff_t cq) {
                if (std::isnan(z(rq, cq))) return;
                const double a =
                    std::atan2(double(z(rq, cq)) - z(r, c), t(r, c) - t(rq, cq)) * 180.0 / std::numbers::pi;
                best = std::max(best, a);
            });
            out(r, c) = static_cast<float>(best);
        }
    }
    return out;
}

/// A town: gently sloping ground with noise_m of noise and box buildings 3..25 m tall, each side
/// min_side..max_side cells.
inline lidarfx::raster<float> box_town(std::mt19937& rng, std::ptrdiff_t rows, std::ptrdiff_t cols, int buildings,
                                       double noise_m = 0.3, std::ptrdiff_t min_side = 3, std::ptrdiff_t max_side = 14)
{
    std::uniform_real_distribution<double> noise(0.0, noise_m), height(3.0, 25.0), tilt(-0.05, 0.05);
    const double gx = tilt(rng), gy = tilt(rng);
    lidarfx::raster<float> z(rows, cols);
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c)
            z(r, c) = static_cast<float>(100 + gx * double(c) + gy * double(r) + noise(rng));
    std::uniform_int_distribution<std::ptrdiff_t> size(min_side, max_side), row(0, rows - 1), col(0, cols - 1);
    for (int b = 0; b < buildings; ++b) {
        const std::ptrdiff_t r0 = row(rng), c0 = col(rng), h = size(rng), w = size(rng);
        const double top = 100 + height(rng);
        for (std::ptrdiff_t r = r0; r < std::min(rows, r0 + h); ++r)
            for (std::ptrdiff_t c = c0; c < std::min(cols, c0 + w); ++c) z(r, c) = static_cast<float>(top);
    }
    return z;
}

}  // namespace reference
