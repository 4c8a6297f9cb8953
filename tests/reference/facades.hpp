// SPDX-License-Identifier: Apache-2.0
// Reference facade shading and sky view by brute force: for one sub-patch (seen from the centre of its front cell
// at its height), a straight ray march towards the sun, a direct search over every earlier cell of its ray line,
// and the dissertation's count of visible sky sources, one shadow test per source.
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

#include "solar.hpp"

namespace reference {

/// True if a sun at (azimuth, elevation) is in front of a wall facing facing_deg: cos e cos(A - facing) > 0.
inline bool in_front_of_wall(double azimuth_deg, double elevation_deg, double facing_deg)
{
    double s, c;
    sincos_deg(azimuth_deg - facing_deg, s, c);
    return elevation_deg < 90.0 && std::cos(elevation_deg * std::numbers::pi / 180.0) * c > 1e-12;
}

/// Lit state (1 lit, 0 shadow) of the point (front cell (r, c) centre, height h) by a straight march towards the
/// sun from the cell centre, Amanatides-Woo cell by cell: a cell q the line passes whose centre projects nearer
/// the sun with shadow key z_q + t_q tan e above h + t_p tan e shades it; the sun must be in front of the wall.
inline std::uint8_t facade_lit_ray_march(lidarfx::raster_view<const float> z, double cell_m, std::ptrdiff_t r,
                                         std::ptrdiff_t col, double h, double facing_deg, double azimuth_deg,
                                         double elevation_deg)
{
    if (elevation_deg <= 0 || !in_front_of_wall(azimuth_deg, elevation_deg, facing_deg)) return 0;
    const shadow_key key(azimuth_deg, elevation_deg, cell_m);
    return straight_march_blocked(z, key, azimuth_deg, r, col, key(h, r, col)) ? 0 : 1;
}

/// Lit state of the same point on the kernel's ray lines: a direct search over every earlier cell of the front
/// cell's line towards the sun (for_each_earlier_on_line); the sun must be in front of the wall.
inline std::uint8_t facade_lit_on_line(lidarfx::raster_view<const float> z, double cell_m, std::ptrdiff_t r,
                                       std::ptrdiff_t c, double h, double facing_deg, double azimuth_deg,
                                       double elevation_deg)
{
    if (elevation_deg <= 0 || !in_front_of_wall(azimuth_deg, elevation_deg, facing_deg)) return 0;
    const shadow_key key(azimuth_deg, elevation_deg, cell_m);
    const double kp = key(h, r, c);
    std::uint8_t lit = 1;
    for_each_earlier_on_line(z.rows(), z.cols(), azimuth_deg, r, c, [&](std::ptrdiff_t rq, std::ptrdiff_t cq) {
        if (!std::isnan(z(rq, cq)) && key(z(rq, cq), rq, cq) > kp) lit = 0;
    });
    return lit;
}

/// Horizon tangent of the point towards azimuth_deg by a direct search: max(0, max over earlier non-NaN cells q of
/// the front cell's line of (z_q - h) / (t_p - t_q)).
inline double facade_horizon_on_line(lidarfx::raster_view<const float> z, double cell_m, std::ptrdiff_t r,
                                     std::ptrdiff_t c, double h, double azimuth_deg)
{
    double s, co;
    sincos_deg(azimuth_deg, s, co);
    const double a = -s * cell_m, b = co * cell_m;
    const auto t = [&](std::ptrdiff_t rr, std::ptrdiff_t cc) {
        return (double(cc) + 0.5) * a + (double(rr) + 0.5) * b;
    };
    double best = 0.0;
    for_each_earlier_on_line(z.rows(), z.cols(), azimuth_deg, r, c, [&](std::ptrdiff_t rq, std::ptrdiff_t cq) {
        if (std::isnan(z(rq, cq))) return;
        best = std::max(best, (double(z(rq, cq)) - h) / (t(r, c) - t(rq, cq)));
    });
    return best;
}

/// The dissertation's sky sources seen by the point: one shadow test (facade_lit_on_line) per source at each
/// elevation 15, 20, ..., 85 degrees of each azimuth i * 360 / directions, plus the zenith (never in front of a
/// vertical wall). Returns the count of visible sources; the share is count / (15 directions + 1).
inline int facade_visible_sources(lidarfx::raster_view<const float> z, double cell_m, std::ptrdiff_t r,
                                  std::ptrdiff_t c, double h, double facing_deg, int directions = 72)
{
    int count = 0;
    for (int i = 0; i < directions; ++i) {
        for (int j = 0; j < 15; ++j) {
            count += facade_lit_on_line(z, cell_m, r, c, h, facing_deg, 360.0 * i / directions, 15.0 + 5.0 * j);
        }
    }
    return count + facade_lit_on_line(z, cell_m, r, c, h, facing_deg, 0.0, 90.0);
}

/// A flat DSM of `ground` metres with one rows_b x cols_b box of height `top` at (r0, c0), and its id raster (1).
struct box_scene {
    lidarfx::raster<float> dsm;
    lidarfx::raster<std::int32_t> ids;
};

inline box_scene one_box(std::ptrdiff_t rows, std::ptrdiff_t cols, std::ptrdiff_t r0, std::ptrdiff_t c0,
                         std::ptrdiff_t rows_b, std::ptrdiff_t cols_b, float ground, float top)
{
    box_scene s{lidarfx::raster<float>(rows, cols, ground), lidarfx::raster<std::int32_t>(rows, cols, 0)};
    for (std::ptrdiff_t r = r0; r < r0 + rows_b; ++r) {
        for (std::ptrdiff_t c = c0; c < c0 + cols_b; ++c) {
            s.dsm(r, c) = top;
            s.ids(r, c) = 1;
        }
    }
    return s;
}

/// A town of `buildings` box buildings (ids 1, 2, ...; a later box overwrites an earlier one) 3..max_side cells a
/// side and 4..30 m tall on flat ground of 10 m with up to noise_m of noise.
inline box_scene box_town_ids(std::mt19937& rng, std::ptrdiff_t rows, std::ptrdiff_t cols, int buildings,
                              std::ptrdiff_t max_side = 12, double noise_m = 0.2)
{
    box_scene s{lidarfx::raster<float>(rows, cols), lidarfx::raster<std::int32_t>(rows, cols, 0)};
    std::uniform_real_distribution<double> noise(0.0, noise_m), height(4.0, 30.0);
    for (std::ptrdiff_t r = 0; r < rows; ++r)
        for (std::ptrdiff_t c = 0; c < cols; ++c) s.dsm(r, c) = static_cast<float>(10.0 + noise(rng));
    std::uniform_int_distribution<std::ptrdiff_t> size(3, max_side), row(0, rows - 1), col(0, cols - 1);
    for (int b = 1; b <= buildings; ++b) {
        const std::ptrdiff_t r0 = row(rng), c0 = col(rng), h = size(rng), w = size(rng);
        const double top = 10.0 + height(rng);
        for (std::ptrdiff_t r = r0; r < std::min(rows, r0 + h); ++r) {
            for (std::ptrdiff_t c = c0; c < std::min(cols, c0 + w); ++c) {
                s.dsm(r, c) = static_cast<float>(top);
                s.ids(r, c) = b;
            }
        }
    }
    return s;
}

}  // namespace reference
