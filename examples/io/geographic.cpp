// SPDX-License-Identifier: Apache-2.0
#include "io/geographic.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>

#ifdef LIDARFX_HAVE_PROJ
#include <proj.h>
#endif

namespace lidarfx::io {

namespace {

/// The CRS for messages: its text when short, else its first 60 characters.
std::string shown(const std::string& crs)
{
    return crs.size() <= 60 ? "'" + crs + "'" : "'" + crs.substr(0, 60) + "...'";
}

}  // namespace

#ifdef LIDARFX_HAVE_PROJ

namespace {

struct context_deleter {
    void operator()(PJ_CONTEXT* c) const { proj_context_destroy(c); }
};
struct pj_deleter {
    void operator()(PJ* p) const { proj_destroy(p); }
};
using pj = std::unique_ptr<PJ, pj_deleter>;

/// The projected part of a CRS: bound CRSs (WKT1 with TOWGS84) give their source, compound CRSs their first part.
pj horizontal_of(PJ_CONTEXT* ctx, pj crs)
{
    for (int step = 0; step < 3 && crs; ++step) {
        const PJ_TYPE type = proj_get_type(crs.get());
        if (type == PJ_TYPE_BOUND_CRS)
            crs.reset(proj_get_source_crs(ctx, crs.get()));
        else if (type == PJ_TYPE_COMPOUND_CRS)
            crs.reset(proj_crs_get_sub_crs(ctx, crs.get(), 0));
        else
            break;
    }
    return crs;
}

}  // namespace

bool proj_available() noexcept
{
    return true;
}

geographic_place place_of(const std::string& crs, double x, double y)
{
    const std::unique_ptr<PJ_CONTEXT, context_deleter> owner(proj_context_create());
    PJ_CONTEXT* ctx = owner.get();
    proj_log_level(ctx, PJ_LOG_NONE);
    const auto failure = [&](const std::string& what) {
        const char* why = proj_context_errno_string(ctx, proj_context_errno(ctx));
        return std::runtime_error("the coordinate system " + shown(crs) + " " + what +
                                  (why != nullptr && *why != '\0' ? std::string(" (PROJ: ") + why + ")" : ""));
    };
    pj projected = horizontal_of(ctx, pj(proj_create(ctx, crs.c_str())));
    if (!projected) throw failure("is not understood by PROJ");
    if (proj_get_type(projected.get()) != PJ_TYPE_PROJECTED_CRS) {
        throw failure("is not a projected coordinate system (no grid whose north could be turned)");
    }
    // WGS 84 in degrees from Greenwich (a CRS's own geodetic CRS may count grads from Paris).
    const pj wgs84(proj_create(ctx, "EPSG:4326"));
    const pj raw(wgs84 ? proj_create_crs_to_crs_from_pj(ctx, wgs84.get(), projected.get(), nullptr, nullptr) : nullptr);
    const pj to_grid(raw ? proj_normalize_for_visualization(ctx, raw.get()) : nullptr);  // lon, lat -> x, y
    if (!to_grid) throw failure("has no transformation from WGS 84 in PROJ (is proj.db installed?)");
    const PJ_COORD lonlat = proj_trans(to_grid.get(), PJ_INV, proj_coord(x, y, 0, 0));
    geographic_place p;
    p.longitude_deg = lonlat.v[0];
    p.latitude_deg = lonlat.v[1];
    if (!std::isfinite(p.longitude_deg) || !std::isfinite(p.latitude_deg) || std::abs(p.latitude_deg) > 90.0) {
        throw failure("cannot place the point (" + std::to_string(x) + ", " + std::to_string(y) + ")");
    }
    // The meridian through the point, in grid coordinates: its bearing from grid north is -convergence.
    constexpr double step_deg = 1e-5;
    const double south = std::max(-90.0, p.latitude_deg - step_deg), north = std::min(90.0, p.latitude_deg + step_deg);
    const PJ_COORD a = proj_trans(to_grid.get(), PJ_FWD, proj_coord(p.longitude_deg, south, 0, 0));
    const PJ_COORD b = proj_trans(to_grid.get(), PJ_FWD, proj_coord(p.longitude_deg, north, 0, 0));
    const double dx = b.v[0] - a.v[0], dy = b.v[1] - a.v[1];
    if (!std::isfinite(dx) || !std::isfinite(dy) || (dx == 0.0 && dy == 0.0)) {
        throw failure("gives no meridian direction at (" + std::to_string(x) + ", " + std::to_string(y) + ")");
    }
    p.convergence_deg = -std::atan2(dx, dy) * (180.0 / std::numbers::pi);
    return p;
}

#else

bool proj_available() noexcept
{
    return false;
}

geographic_place place_of(const std::string& crs, double, double)
{
    throw std::runtime_error("placing a point of the coordinate system " + shown(crs) +
                             " needs PROJ, and lidarfx_io "
                             "was built without it (install libproj-dev and reconfigure, or give --lat and --lon)");
}

#endif

}  // namespace lidarfx::io
