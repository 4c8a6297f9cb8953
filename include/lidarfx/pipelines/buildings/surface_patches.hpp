// SPDX-License-Identifier: Apache-2.0
// surface_patches: the roof and ground patches of a surface model, one per 2 x 2 quad of cell centres, with
// normal, tilt, azimuth and area (dissertation 3.2.4, the patch-based representation).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/kernels/solar/incidence.hpp"

namespace lidarfx {

/// What a quad patch lies on.
enum class patch_kind : std::uint8_t {
    ground,  ///< all four cells are not building (building id 0)
    roof,    ///< all four cells belong to one building
};

/// One quad patch: the surface through the centres of cells (row, col), (row, col + 1), (row + 1, col + 1)
/// and (row + 1, col), split along the diagonal (row, col) - (row + 1, col + 1) into two triangles.
struct surface_patch {
    std::ptrdiff_t row = 0, col = 0;  ///< the quad's top-left (north-west) cell
    std::int32_t building_id = 0;     ///< the building of all four cells (roof), 0 for ground
    patch_kind kind = patch_kind::ground;
    enu_vector normal{};     ///< area-weighted unit normal of the two triangles, pointing up (up > 0)
    double tilt_deg = 0;     ///< angle of the normal from the vertical: 0 flat, < 90 for any quad
    double azimuth_deg = 0;  ///< direction the surface faces (down-slope), clockwise from north; 0 if flat
    double area_m2 = 0;      ///< 3D area of the two triangles, m^2 (cell_m^2 when flat)
    double height_m = 0;     ///< mean height of the four corners, m
};

/// Settings of surface_patches.
struct surface_patches_options {
    bool ground = true;  ///< also return the ground patches (false: roofs only)
};

/// Roof and ground quad patches of a DSM (dissertation 3.2.4): one patch per 2 x 2 quad of cell centres whose
/// four cells are all ground (building id 0) or all one building, in raster order of their top-left cell. Quads
/// that straddle a roof edge, or touch a NaN cell, give no patch: the vertical facade patches
/// (facade_patches.hpp) stand for the first. Corners in metres: x = col * cell_m east, y = -row * cell_m north,
/// z = dsm. Normal n = sum of the triangles' cross products (area-weighted), made unit, so
///   tilt = acos(n_up), azimuth = atan2(n_east, n_north) (clockwise from north), area = sum of |cross| / 2.
/// A flat quad has tilt 0, azimuth 0 and area cell_m^2. O(rows * cols).
/// @throws invalid_input if shapes differ or cell_m is not finite and > 0.
template <raster_input Dsm, raster_input Ids>
std::vector<surface_patch> surface_patches(const Dsm& dsm, const Ids& building_id, double cell_m,
                                           const surface_patches_options& opt = {});

// ---- implementation ----

template <raster_input Dsm, raster_input Ids>
std::vector<surface_patch> surface_patches(const Dsm& dsm, const Ids& building_id, double cell_m,
                                           const surface_patches_options& opt)
{
    constexpr const char* fn = "surface_patches";
    detail::require_positive(cell_m, fn, "cell_m");
    detail::require_same_shape(dsm, building_id, fn, "dsm", "building_id");
    std::vector<surface_patch> out;
    const std::ptrdiff_t rows = dsm.rows(), cols = dsm.cols();
    const double d = cell_m;
    for (std::ptrdiff_t r = 0; r + 1 < rows; ++r) {
        for (std::ptrdiff_t c = 0; c + 1 < cols; ++c) {
            const auto id = static_cast<std::int32_t>(building_id(r, c));
            if (static_cast<std::int32_t>(building_id(r, c + 1)) != id ||
                static_cast<std::int32_t>(building_id(r + 1, c)) != id ||
                static_cast<std::int32_t>(building_id(r + 1, c + 1)) != id || (id == 0 && !opt.ground)) {
                continue;
            }
            const double z00 = dsm(r, c), z01 = dsm(r, c + 1), z10 = dsm(r + 1, c), z11 = dsm(r + 1, c + 1);
            if (std::isnan(z00) || std::isnan(z01) || std::isnan(z10) || std::isnan(z11)) continue;
            // Corners (east, north, up): p00 = (0, 0, z00), p01 = (d, 0, z01), p10 = (0, -d, z10), p11 = (d, -d, z11).
            // Triangle A = p00, p10, p11 and B = p00, p11, p01, both counter-clockwise seen from above.
            const auto cross = [](double ax, double ay, double az, double bx, double by, double bz) {
                return enu_vector{ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx};
            };
            const enu_vector a = cross(0.0, -d, z10 - z00, d, -d, z11 - z00);
            const enu_vector b = cross(d, -d, z11 - z00, d, 0.0, z01 - z00);
            const auto norm = [](const enu_vector& v) {
                return std::sqrt(v.east * v.east + v.north * v.north + v.up * v.up);
            };
            const enu_vector sum{a.east + b.east, a.north + b.north, a.up + b.up};
            const double len = norm(sum);
            surface_patch p;
            p.row = r;
            p.col = c;
            p.building_id = id;
            p.kind = id == 0 ? patch_kind::ground : patch_kind::roof;
            p.normal = {sum.east / len, sum.north / len, sum.up / len};
            p.tilt_deg = std::acos(std::fmin(1.0, p.normal.up)) * (180.0 / std::numbers::pi);
            const bool flat = p.normal.east == 0.0 && p.normal.north == 0.0;
            double az = flat ? 0.0 : std::atan2(p.normal.east, p.normal.north) * (180.0 / std::numbers::pi);
            p.azimuth_deg = az < 0.0 ? az + 360.0 : az;
            p.area_m2 = 0.5 * (norm(a) + norm(b));
            p.height_m = 0.25 * (z00 + z01 + z10 + z11);
            out.push_back(p);
        }
    }
    return out;
}

}  // namespace lidarfx
