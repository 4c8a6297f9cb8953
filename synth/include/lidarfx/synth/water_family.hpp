// SPDX-License-Identifier: Apache-2.0
// water_family: randomized lake and river surveys from one seed (density, scan geometry, water returns,
// shore types, distractors, bridges, islands), with truth rasters, for testing waterbody extraction on
// surveys it was not tuned on.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/fast_math.hpp"
#include "lidarfx/core/grid.hpp"
#include "lidarfx/core/las_class.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/synth/noise.hpp"
#include "lidarfx/synth/point_set.hpp"
#include "lidarfx/synth/random.hpp"
#include "lidarfx/synth/water.hpp"

namespace lidarfx::synth {

/// The two kinds of family scene.
enum class water_family_kind { lake, river };

/// What the land next to the water looks like.
enum class shore_kind {
    beach,         ///< sand rising 2-6 % from the waterline, intensity 90-140
    steep_bank,    ///< 1.5-4 m bank within 3 m of the waterline
    reeds,         ///< a 3-12 m belt of reeds 1-2.5 m tall (some pulses with two returns) on low ground
    flat_field,    ///< grass (intensity ~86) on a plain 0.5-1 m above the water, no dropouts
    wet_ground,    ///< dark wet ground (intensity 15-35) 0.15 m above the water, rising 2 %
    level_meadow,  ///< mown grass (land intensity) on a level plain 0.2-1 m above the water, out to 60-250 m
    terrace,       ///< a level step 0.2-0.5 m above the water, a second one 0.3-0.6 m higher 15-40 m out
    parking_lot,   ///< a level lot of concrete or pale asphalt (land intensity) 0.2-0.6 m above the water
};

/// Which scenes a family draws.
enum class water_family_variant {
    classic,       ///< lakes of 30-150 m radius and rivers 15-60 m wide with the five classic shores
    level_land,    ///< ponds of 15-60 m radius and rivers 8-40 m wide beside level meadows, terraces and lots of
                   ///< land intensity 0.2-1 m above the water, smooth land, dropouts on the water 0-15 %
    narrow_river,  ///< rivers 5-15 m wide (lakes as classic)
    hydro,         ///< scenes for hydro-flattening (USGS Lidar Base Specification), meant to be drawn at 2-8
                   ///< pulses/m² (set min_density, max_density): lakes of 55-150 m mean radius keeping >= 9,000 m²
                   ///< of water inside the survey, with islands in 60 % of them (4,200-12,000 m² or 100-3,800 m²);
                   ///< rivers 30.5-60 m wide everywhere with 0-2 bridges and 0-2 weirs (drops 0.3-1.5 m, see
                   ///< water_family_scene::weir_along); shores, returns and distractors as classic
};

/// Settings of a family scene; everything else follows from the seed.
struct water_family_options {
    unsigned seed = 1;
    water_family_kind kind = water_family_kind::lake;
    double min_density = 0.5, max_density = 8.0;  ///< pulses per m², drawn log-uniformly in this range, > 0
    double min_size_m = 400, max_size_m = 700;    ///< side of the square survey, drawn uniformly, metres, > 0
    double points_per_cell = 4.0;                 ///< cell_m = max(2, ⌈2·sqrt(points_per_cell / density)⌉ / 2)
    double cell_m = 0;                            ///< truth cell size in metres; 0 = from points_per_cell as above
    water_family_variant variant = water_family_variant::classic;
};

/// How the water of a scene returns pulses.
struct water_family_returns {
    double drop_nadir = 0.3, drop_edge = 0.6;  ///< pulse dropout probability at nadir and at the swath edge
    double patch_share = 0.3;                  ///< approximate share of the water inside dropout patches
    double glint = 0.0;                        ///< share of near-nadir pulses returning a bright specular echo
    double glint_width_deg = 3.0;              ///< scan angle where the glint share falls to 1/e
    double glint_intensity = 55;               ///< mean intensity of specular echoes
    double low_min = 3, low_max = 25;          ///< range of ordinary water intensities (turbid: 25-55)
    double wave_m = 0.02;                      ///< amplitude of the surface's height noise, metres
    bool turbid = false;
    double wind = 0;  ///< 0 calm .. 1 windy
};

/// Scan geometry of a family scene: parallel north-south strips.
struct water_family_scan {
    double flying_height_m = 1000;
    double max_scan_angle_deg = 20;
    double overlap = 0.2;  ///< share of a swath overlapped by the next strip
};

/// An axis-aligned flat-roofed building: also casts a scan shadow (no ground returns behind it).
struct flat_building {
    double x0, y0, x1, y1;  ///< footprint, metres
    double z;               ///< roof, metres
    double intensity;
};

/// A lake or river family scene: points, truth and what was drawn.
struct water_family_scene {
    water_family_kind kind = water_family_kind::lake;
    point_set points;
    grid g;                             ///< truth grid, cell = cell_m, covering [0, size_m]²
    raster<std::uint8_t> water;         ///< 1 = water surface (water under a bridge deck is 1)
    raster<std::uint8_t> water_filled;  ///< water plus islands smaller than 200 m²
    raster<std::int32_t> body_id;       ///< 0 land, 1.. waterbody (river = 1)
    raster<float> water_z;              ///< water level on water cells, NaN elsewhere
    std::vector<double> body_level;     ///< per body id - 1: level at its centre (river: at along = size_m / 2)
    double size_m = 0, density_per_m2 = 0, cell_m = 2;
    water_family_scan scan;
    water_family_returns returns;
    std::vector<shore_kind> shores;  ///< per lake, or river south and north bank
    int bridges = 0, islands = 0;
    std::vector<std::array<double, 2>> bridge_along;  ///< river: (along-river position, half width) of each bridge
    /// River: (along-river position, drop in metres) of each weir, in increasing along; only the hydro variant
    /// has weirs. The level steps down by the drop where the river crosses along = position downstream.
    std::vector<std::array<double, 2>> weir_along;
    /// River: direction of flow. The along-river position of (x, y) is along = (x - c) cos + (y - c) sin + c
    /// with c = size_m / 2; the water flows toward increasing along (the upstream end is at the smallest
    /// along) and its level falls monotonically downstream: linearly by 0.1-1.5 m per size_m, and by each
    /// weir's drop past its weir.
    double river_angle_rad = 0;
    bool touches_edge = false;
};

namespace internal {

/// Height of the land above the water at `d` metres from the waterline, per shore kind; p in [0, 1)
/// varies the kind (slope, bank height).
inline double family_shore_rise(shore_kind k, double d, double p) noexcept
{
    switch (k) {
        case shore_kind::beach:
            return 0.05 + (0.02 + 0.04 * p) * d;
        case shore_kind::steep_bank:
            return (1.5 + 2.5 * p) * smoothstep(0.0, 3.0, d) + 0.02 * d;
        case shore_kind::reeds:
            return 0.2 + 0.03 * d;
        case shore_kind::flat_field:
            return (0.5 + 0.5 * p) * smoothstep(0.0, 1.5, d) + 0.002 * d;
        case shore_kind::wet_ground:
            return 0.15 + 0.02 * d;
        case shore_kind::level_meadow: {
            const double reach = 60 + 190 * p;  // level out to here, then rising 3 %
            return (0.2 + 0.8 * p) * smoothstep(0.0, 1.0, d) + 0.001 * d + 0.03 * std::max(0.0, d - reach);
        }
        case shore_kind::terrace: {
            const double step = 15 + 25 * p;
            return (0.2 + 0.3 * p) * smoothstep(0.0, 1.0, d) + (0.3 + 0.3 * p) * smoothstep(step, step + 2, d) +
                   0.001 * d + 0.03 * std::max(0.0, d - 150);
        }
        case shore_kind::parking_lot:
            return (0.2 + 0.4 * p) * smoothstep(0.0, 0.6, d) + 0.03 * std::max(0.0, d - 40);
    }
    return 0.5;
}

/// One lake of a family scene.
struct family_lake {
    lake_outline outline;
    double level = 0;
    shore_kind shore = shore_kind::beach;
    double shore_p = 0.5;
};

/// One tree: a round crown of radius r, top at z.
struct family_tree {
    double x, y, r, z;
};

/// What lies at a point of a family scene beneath trees and buildings.
struct family_sample {
    double z = 0;
    std::int32_t body = -1;  ///< water body index, -1 on land
    double intensity = 90;   ///< land cover intensity
    double island_area = 0;  ///< area of the island holding the point, m²; 0 if none
    double reeds_m = 0;      ///< height of reeds above the ground, 0 if none
    std::uint8_t cls = las_class::ground;
};

/// The world of a family scene.
struct family_world {
    water_family_kind kind = water_family_kind::lake;
    double S = 500;
    noise_field relief, cover, patch;

    family_world(water_family_kind k, double size_m, noise_field relief_field, noise_field cover_field,
                 noise_field patch_field)
        : kind(k), S(size_m), relief(relief_field), cover(cover_field), patch(patch_field)
    {
    }
    double base_z = 100, relief_m = 5;
    std::vector<family_lake> lakes;
    std::vector<island_truth> islands;  ///< each in body island_body[i]
    std::vector<std::int32_t> island_body;
    river_channel river;
    std::vector<std::array<double, 2>> weirs;  ///< river: (along, drop) of each weir
    double angle = 0, ca = 1, sa = 0;          ///< river direction
    std::array<shore_kind, 2> river_shore{};
    std::array<double, 2> river_shore_p{};
    struct bridge {
        double along, half_width, half_reach, z, intensity;
    };
    std::vector<bridge> bridges;
    struct asphalt {
        double x0, y0, x1, y1, intensity;
    };
    std::vector<asphalt> lots;
    std::vector<flat_building> buildings;
    std::vector<family_tree> trees;
    double reed_belt_m = 8, reed_height_m = 1.5;
    double wet_belt_m = 10;
    double meadow_intensity = 86, lot_intensity = 80;  ///< level meadows (mown grass) and lots beside the water
    double land_noise_m = 0.05;                        ///< amplitude of the land returns' height noise, metres

    /// (along, across) river coordinates: along the flow from the scene centre, across to the left.
    std::array<double, 2> river_frame(double x, double y) const noexcept
    {
        const double dx = x - 0.5 * S, dy = y - 0.5 * S;
        return {dx * ca + dy * sa + 0.5 * S, -dx * sa + dy * ca + 0.5 * S};
    }

    /// Water level of the river at along-river position u: the channel's linear fall, stepped down by the
    /// drop of each weir upstream of u.
    double river_level(double u) const noexcept
    {
        double z = river.level(u);
        for (const auto& weir : weirs)
            if (u > weir[0]) z -= weir[1];
        return z;
    }

    double land_intensity(double x, double y) const noexcept
    {
        return std::clamp(95.0 + 60.0 * cover(x, y), 60.0, 140.0);
    }

    family_sample at(double x, double y) const noexcept
    {
        family_sample s;
        const double terrain = base_z + relief_m * relief(x, y);
        double ground = terrain;
        double nearest = std::numeric_limits<double>::infinity();
        shore_kind near_kind = shore_kind::beach;
        if (kind == water_family_kind::lake) {
            for (std::size_t k = 0; k < lakes.size(); ++k) {
                const auto& lake = lakes[k];
                const double d = lake.outline.shore_distance(x, y);
                if (d < 0) {
                    s.z = lake.level;
                    s.body = static_cast<std::int32_t>(k);
                    break;
                }
                ground = std::max(ground, lake.level + family_shore_rise(lake.shore, d, lake.shore_p));
                if (d < nearest) nearest = d, near_kind = lake.shore;
            }
        } else {
            const auto [u, v] = river_frame(x, y);
            const double off = river.offset(u, v), half = 0.5 * river.width(u), level = river_level(u);
            const double d = std::abs(off) - half;
            if (d < 0) {
                s.z = level;
                s.body = 0;
            } else {
                const int side = off > 0 ? 1 : 0;
                ground = std::max(ground, level + family_shore_rise(river_shore[side], d, river_shore_p[side]));
                nearest = d, near_kind = river_shore[side];
            }
        }
        if (s.body >= 0) {
            for (std::size_t i = 0; i < islands.size(); ++i) {
                if (island_body[i] != s.body) continue;
                const double h = islands[i].height_above_water(x, y);
                if (h > 0) {
                    s.z += h;
                    s.body = -1;
                    s.island_area = islands[i].area_m2();
                    s.intensity = land_intensity(x, y);
                    return s;
                }
            }
            return s;
        }
        s.z = ground;
        s.intensity = land_intensity(x, y);
        if (near_kind == shore_kind::flat_field && nearest < 200) s.intensity = 86 + 8 * cover(y, x);
        if (near_kind == shore_kind::beach && nearest < 15) s.intensity = 115 + 20 * cover(y, x);
        if (near_kind == shore_kind::wet_ground && nearest < wet_belt_m) s.intensity = 25 + 10 * cover(y, x);
        if (near_kind == shore_kind::level_meadow && nearest < 250) s.intensity = meadow_intensity + 12 * cover(y, x);
        if (near_kind == shore_kind::parking_lot && nearest < 40) {
            s.intensity = lot_intensity + 6 * cover(y, x);
            s.cls = las_class::road_surface;
        }
        if (near_kind == shore_kind::reeds && nearest < reed_belt_m) s.reeds_m = reed_height_m;
        for (const auto& a : lots) {
            if (x >= a.x0 && x <= a.x1 && y >= a.y0 && y <= a.y1) {
                s.intensity = a.intensity;
                s.cls = las_class::road_surface;
                s.z = base_z + relief_m * relief(0.5 * (a.x0 + a.x1), 0.5 * (a.y0 + a.y1));
                s.z = std::max(s.z, ground);
            }
        }
        return s;
    }

    /// Index of the bridge over (x, y), or -1.
    int bridge_at(double x, double y) const noexcept
    {
        if (bridges.empty()) return -1;
        const auto [u, v] = river_frame(x, y);
        for (std::size_t i = 0; i < bridges.size(); ++i) {
            const auto& b = bridges[i];
            if (std::abs(u - b.along) <= b.half_width && std::abs(river.offset(u, v)) <= b.half_reach)
                return static_cast<int>(i);
        }
        return -1;
    }

    int building_at(double x, double y) const noexcept
    {
        for (std::size_t i = 0; i < buildings.size(); ++i) {
            const auto& b = buildings[i];
            if (x >= b.x0 && x <= b.x1 && y >= b.y0 && y <= b.y1) return static_cast<int>(i);
        }
        return -1;
    }

    /// True when a building hides ground point (x, y, z) from a sensor at easting x_sensor, height H.
    bool shadowed(double x, double y, double z, double x_sensor, double H) const noexcept
    {
        for (const auto& b : buildings) {
            if (y < b.y0 || y > b.y1 || b.z <= z) continue;
            const double reach = (b.z - z) * std::abs(x_sensor - x) / H;  // horizontal run of the ray below the roof
            const double lo = x_sensor > x ? x : x - reach, hi = x_sensor > x ? x + reach : x;
            if (hi >= b.x0 && lo <= b.x1) return true;
        }
        return false;
    }

    /// Top of the tallest crown over (x, y), or -inf.
    double tree_top(double x, double y) const noexcept
    {
        double top = -std::numeric_limits<double>::infinity();
        for (const auto& t : trees) {
            const double d2 = (x - t.x) * (x - t.x) + (y - t.y) * (y - t.y);
            if (d2 < t.r * t.r) top = std::max(top, t.z - 0.5 * d2 / t.r);
        }
        return top;
    }
};

}  // namespace internal

namespace internal {

/// Samples the truth of `w` at the cell centres of out.cell_m cells over [0, out.size_m]² and scans it with
/// out.scan and out.returns (see water_family). Deterministic from `seed`.
inline void render_family(const family_world& w, water_family_scene& out, unsigned seed)
{
    const double S = out.size_m;
    const auto cells = static_cast<std::ptrdiff_t>(std::llround(S / out.cell_m));
    const auto& wr = out.returns;
    // Truth at the cell centres.
    out.g = grid{0.0, S, out.cell_m, cells, cells};
    out.water = raster<std::uint8_t>(cells, cells, 0);
    out.water_filled = raster<std::uint8_t>(cells, cells, 0);
    out.body_id = raster<std::int32_t>(cells, cells, 0);
    out.water_z = raster<float>(cells, cells, std::numeric_limits<float>::quiet_NaN());
    for (std::ptrdiff_t r = 0; r < cells; ++r) {
        for (std::ptrdiff_t c = 0; c < cells; ++c) {
            const auto [x, y] = out.g.center(r, c);
            const auto s = w.at(x, y);
            if (s.body >= 0) {
                out.water(r, c) = 1;
                out.body_id(r, c) = s.body + 1;
                out.water_z(r, c) = static_cast<float>(s.z);
            }
            out.water_filled(r, c) = s.body >= 0 || (s.island_area > 0 && s.island_area < 200.0);
        }
    }

    // Scan: strips of swath W = 2 H tan(max angle), spaced W (1 - overlap); each strip at the density that
    // makes the mean density out.density_per_m2.
    const double H = out.scan.flying_height_m, tmax = std::tan(deg_to_rad(out.scan.max_scan_angle_deg));
    const double swath = 2 * H * tmax, spacing_strips = swath * (1 - out.scan.overlap);
    const auto strips = static_cast<int>(std::ceil(S / spacing_strips));
    const double strip_density = out.density_per_m2 * spacing_strips / swath;
    const double step = 1.0 / std::sqrt(strip_density);
    const noise_field& patch = w.patch;
    // Patches: the field above its (1 - patch_share) quantile over the scene's water (truth cells).
    std::vector<double> on_water;
    for (std::ptrdiff_t r = 0; r < cells; ++r)
        for (std::ptrdiff_t c = 0; c < cells; ++c)
            if (out.water(r, c)) on_water.push_back(patch(out.g.center(r, c)[0], out.g.center(r, c)[1]));
    double patch_threshold = std::numeric_limits<double>::infinity();
    if (!on_water.empty()) {
        const auto at = on_water.begin() +
                        static_cast<std::ptrdiff_t>((1.0 - wr.patch_share) * static_cast<double>(on_water.size() - 1));
        std::nth_element(on_water.begin(), at, on_water.end());
        patch_threshold = *at;
    }
    rng random(hash64(seed, 0x5CA95), 2);
    auto& pts = out.points;
    pts.reserve(static_cast<std::size_t>(1.2 * S * S * out.density_per_m2));
    double time = 0;
    for (int k = 0; k < strips; ++k) {
        const double xc = (k + 0.5) * S / strips;
        const double x0 = std::max(0.0, xc - 0.5 * swath), x1 = std::min(S, xc + 0.5 * swath);
        const auto lines = static_cast<long long>(std::ceil(S / step));
        const auto per_line = static_cast<long long>(std::ceil((x1 - x0) / step));
        for (long long i = 0; i < lines; ++i) {
            for (long long j = 0; j < per_line; ++j) {
                const double x =
                    std::clamp(x0 + (static_cast<double>(j) + 0.5 + 0.35 * random.triangular()) * step, 0.0, S - 1e-6);
                const double y =
                    std::clamp((static_cast<double>(i) + 0.5 + 0.15 * random.triangular()) * step, 1e-6, S - 1e-6);
                time += 1e-5;
                pts.pulse_time_s = time;
                const double angle = rad_to_deg(std::atan(std::abs(x - xc) / H));
                const double unit_noise = random.triangular();
                const double noise = 0.05 * unit_noise, land_noise = w.land_noise_m * unit_noise;
                const int bridge = w.bridge_at(x, y);
                if (bridge >= 0) {
                    const auto& b = w.bridges[static_cast<std::size_t>(bridge)];
                    pts.push(x, y, b.z + noise, b.intensity * (1 + 0.15 * random.triangular()), 1, 1,
                             las_class::bridge_deck);
                    continue;
                }
                const int building = w.building_at(x, y);
                if (building >= 0) {
                    const auto& b = w.buildings[static_cast<std::size_t>(building)];
                    pts.push(x, y, b.z + noise, b.intensity * (1 + 0.1 * random.triangular()), 1, 1,
                             las_class::building);
                    continue;
                }
                const auto s = w.at(x, y);
                const double top = w.tree_top(x, y);
                if (top > s.z + 2 && random.chance(0.9)) {
                    const bool ground_too = random.chance(0.5);
                    pts.push(x, y, top - 2 * random.uniform() + noise, 60 + 30 * random.uniform(), 1,
                             ground_too ? 2 : 1, las_class::high_vegetation);
                    if (ground_too) pts.push(x, y, s.z + noise, 0.5 * s.intensity, 2, 2, las_class::ground);
                    continue;
                }
                if (w.shadowed(x, y, s.z, xc, H)) continue;
                if (s.body >= 0) {
                    const double t = angle / out.scan.max_scan_angle_deg;
                    const double g = wr.glint * std::exp(-(angle / wr.glint_width_deg) * (angle / wr.glint_width_deg));
                    if (patch(x, y) + 0.03 * random.triangular() > patch_threshold && !random.chance(g)) continue;
                    double drop = wr.drop_nadir + (wr.drop_edge - wr.drop_nadir) * t * t;
                    drop *= 1 - g;
                    if (random.chance(drop)) continue;
                    double intensity;
                    if (random.chance(g)) {
                        intensity = wr.glint_intensity * (1 + 0.3 * random.triangular());
                    } else {
                        const double u = random.uniform();
                        intensity = wr.low_min + (wr.low_max - wr.low_min) * u * u;
                    }
                    pts.push(x, y, s.z + wr.wave_m * random.triangular() + 0.5 * noise, intensity, 1, 1,
                             las_class::water);
                    continue;
                }
                if (s.reeds_m > 0 && random.chance(0.7)) {
                    const bool ground_too = random.chance(0.4);
                    pts.push(x, y, s.z + s.reeds_m * random.uniform(0.5, 1.0), 40 + 30 * random.uniform(), 1,
                             ground_too ? 2 : 1, las_class::low_vegetation);
                    if (ground_too) pts.push(x, y, s.z + noise, 0.6 * s.intensity, 2, 2, las_class::ground);
                    continue;
                }
                if (random.chance(0.003)) continue;  // an odd lost pulse on land
                pts.push(x, y, s.z + land_noise, s.intensity * (1 + 0.1 * random.triangular()), 1, 1, s.cls);
            }
        }
        time += 60;
    }
}

/// Area of the lake inside the survey [0, S]², m², from 2 m samples.
inline double lake_area_inside(const lake_outline& o, double S) noexcept
{
    constexpr double step = 2.0;
    const double R = o.max_radius();
    double area = 0;
    for (double y = std::max(0.0, o.y - R) + 0.5 * step; y < std::min(S, o.y + R); y += step)
        for (double x = std::max(0.0, o.x - R) + 0.5 * step; x < std::min(S, o.x + R); x += step)
            if (o.shore_distance(x, y) < 0) area += step * step;
    return area;
}

}  // namespace internal

/// A randomized lake or river survey. Drawn from the seed: survey side (min..max_size_m), density
/// (log-uniform), scan geometry (flying height 300-2000 m, half angle 10-30°, strip overlap 0-50 %),
/// water returns (dropouts 5-60 % at nadir rising toward the swath edge, falling with wind; dropout
/// patches 10-60 %; in 40 % of scenes specular echoes near nadir with intensity 40-120 on 30-90 % of
/// pulses; 30 % turbid water with intensities 25-55), shores (beach, steep bank, reeds, flat field
/// 0.5-1 m above the water, wet dark ground), distractors (dark asphalt lots, flat-roofed buildings with
/// their scan shadows, trees). Lakes: 1-3 lakes at different levels, some side by side 10-40 m apart,
/// some cut by the survey edge, islands of 50-2000 m² (at most 8 % of the lake). Rivers: 15-60 m wide meandering in any
/// direction across the survey, level falling 0.1-1.5 m across it, 0-4 bridges (deck 3-8 m above the water, 8-20 m
/// wide), sometimes an island. The variants (water_family_variant) change some of these ranges; rivers of the
/// hydro variant also step down at 0-2 weirs. Deterministic; about 0.3 s per scene at 2 points/m² on 600 m.
/// @throws invalid_input on bad options.
inline water_family_scene water_family(const water_family_options& options = {})
{
    constexpr const char* fn = "water_family";
    lidarfx::detail::require(options.min_density > 0 && options.min_density <= options.max_density, fn,
                             "densities must satisfy 0 < min_density <= max_density");
    lidarfx::detail::require(options.min_size_m > 0 && options.min_size_m <= options.max_size_m, fn,
                             "sizes must satisfy 0 < min_size_m <= max_size_m");
    lidarfx::detail::require_positive(options.points_per_cell, fn, "points_per_cell");
    lidarfx::detail::require(options.cell_m >= 0 && std::isfinite(options.cell_m), fn, "cell_m must be >= 0");
    const bool is_lake = options.kind == water_family_kind::lake;
    rng pick(hash64(options.seed, is_lake ? 0x1A4EFA : 0x71FEFA), 1);
    water_family_scene out;
    out.kind = options.kind;
    out.density_per_m2 = std::exp(pick.uniform(std::log(options.min_density), std::log(options.max_density)));
    out.cell_m = options.cell_m > 0
                     ? options.cell_m
                     : std::max(2.0, std::ceil(2.0 * std::sqrt(options.points_per_cell / out.density_per_m2)) / 2.0);
    const bool level_land = options.variant == water_family_variant::level_land;
    const bool hydro = options.variant == water_family_variant::hydro;
    const auto cells =
        static_cast<std::ptrdiff_t>(std::ceil(pick.uniform(options.min_size_m, options.max_size_m) / out.cell_m));
    out.size_m = static_cast<double>(cells) * out.cell_m;
    const double S = out.size_m;
    out.scan = {pick.uniform(300.0, 2000.0), pick.uniform(10.0, 30.0), pick.uniform(0.0, 0.5)};

    auto& wr = out.returns;
    wr.wind = pick.uniform();
    wr.drop_nadir = pick.uniform(0.05, 0.6) * (1.0 - 0.5 * wr.wind);
    wr.drop_edge = std::min(0.95, wr.drop_nadir + pick.uniform(0.1, 0.4));
    wr.patch_share = pick.uniform(0.1, 0.6);
    if (pick.chance(0.4)) {
        wr.glint = pick.uniform(0.3, 0.9);
        wr.glint_width_deg = pick.uniform(2.0, 6.0);
        wr.glint_intensity = pick.uniform(40.0, 120.0);
    }
    wr.turbid = pick.chance(0.3);
    if (wr.turbid) wr.low_min = 25, wr.low_max = 55;
    wr.wave_m = 0.01 + 0.05 * wr.wind;
    if (level_land) {  // water that returns most pulses: with a few dropout patches or none
        wr.drop_nadir = pick.uniform(0.0, 0.15);
        wr.drop_edge = wr.drop_nadir + pick.uniform(0.0, 0.1);
        wr.patch_share = pick.chance(0.5) ? pick.uniform(0.05, 0.3) : 0.0;
    }

    const std::uint64_t ws = hash64(options.seed, is_lake ? 0xFA1A : 0xFA21);
    internal::family_world w{options.kind, S, noise_field{hash64(ws, 1), pick.uniform(200.0, 500.0), 4, 0.45},
                             noise_field{hash64(ws, 2), 70.0, 3, 0.5}, noise_field{hash64(ws, 3), 80.0, 3, 0.5}};
    w.base_z = 100;
    w.relief_m = pick.uniform(1.0, 15.0);
    w.reed_belt_m = pick.uniform(3.0, 12.0);
    w.reed_height_m = pick.uniform(1.0, 2.5);
    w.wet_belt_m = pick.uniform(5.0, 15.0);
    const double water_base = w.base_z;
    constexpr double hydro_lake_water_m2 = 9000;  // water of each hydro lake inside the survey, at least
    const auto classic_shore = [&] { return static_cast<shore_kind>(pick.between(0, 4)); };
    const auto level_shore = [&] {
        const double u = pick.uniform();
        return u < 0.4    ? shore_kind::level_meadow
               : u < 0.65 ? shore_kind::terrace
               : u < 0.85 ? shore_kind::parking_lot
                          : shore_kind::flat_field;
    };
    const auto any_shore = [&] { return level_land ? level_shore() : classic_shore(); };
    if (level_land) {  // the terrain lies below every water level: the shores' level land is the ground
        w.base_z = water_base - 4 - w.relief_m;
        w.meadow_intensity = pick.uniform(75.0, 120.0);
        w.lot_intensity = pick.uniform(60.0, 110.0);
        w.land_noise_m = pick.uniform(0.015, 0.05);
    }

    if (is_lake) {
        const int n = pick.between(1, 3);
        for (int attempt = 0; attempt < 200 && static_cast<int>(w.lakes.size()) < n; ++attempt) {
            const double r = level_land ? pick.uniform(15.0, 60.0)
                             : hydro    ? pick.uniform(55.0, 150.0)
                                        : pick.uniform(0.08, 0.22) * S;
            // Centres may lie just outside the survey: the lake is then cut by the edge.
            const double x = pick.uniform(-0.05, 1.05) * S, y = pick.uniform(-0.05, 1.05) * S;
            auto outline = lake_outline::random(pick, x, y, r, pick.uniform(0.1, 0.4));
            const double gap = pick.uniform(10.0, 40.0);
            bool clear = true;
            for (const auto& o : w.lakes)
                clear = clear && std::hypot(o.outline.x - x, o.outline.y - y) >
                                     o.outline.max_radius() + outline.max_radius() + gap;
            // At least a third of the lake inside the survey.
            const bool inside =
                x > 0.1 * S - 0.3 * r && x < 0.9 * S + 0.3 * r && y > 0.1 * S - 0.3 * r && y < 0.9 * S + 0.3 * r;
            if (!clear || !inside) continue;
            if (hydro && internal::lake_area_inside(outline, S) < hydro_lake_water_m2) continue;
            const double level = water_base + (level_land ? pick.uniform(-0.5, 0.5) : pick.uniform(-3.0, 3.0));
            w.lakes.push_back({outline, level, any_shore(), pick.uniform()});
        }
        for (std::size_t k = 0; k < w.lakes.size(); ++k) {
            const auto& o = w.lakes[k].outline;
            if (hydro) {
                // Islands on both sides of the specification's 1-acre (4,047 m²) threshold, within a budget that
                // keeps hydro_lake_water_m2 of water inside the survey.
                double budget = internal::lake_area_inside(o, S) - hydro_lake_water_m2;
                const double cap = 0.15 * std::numbers::pi * o.mean_radius_m * o.mean_radius_m;
                const int isl = pick.chance(0.6) ? pick.between(1, 2) : 0;
                for (int i = 0, tries = 0; i < isl && tries < 50; ++tries) {
                    const double large = std::min({12000.0, cap, budget}), small = std::min({3800.0, cap, budget});
                    if (small < 100) break;
                    const double area =
                        large >= 4200 && pick.chance(0.5) ? pick.uniform(4200.0, large) : pick.uniform(100.0, small);
                    const double rr = std::sqrt(area / std::numbers::pi);
                    const double ix = o.x + pick.uniform(-1.0, 1.0) * o.mean_radius_m,
                                 iy = o.y + pick.uniform(-1.0, 1.0) * o.mean_radius_m;
                    if (o.shore_distance(ix, iy) > -(rr + 10)) continue;
                    w.islands.push_back({ix, iy, rr, pick.uniform(0.5, 4.0)});
                    w.island_body.push_back(static_cast<std::int32_t>(k));
                    budget -= area;
                    ++i;
                }
            } else {
                const int isl = pick.between(0, 2);
                for (int i = 0, tries = 0; i < isl && tries < 50; ++tries) {
                    const double rr = std::sqrt(
                        pick.uniform(50.0, std::min(2000.0, 0.08 * o.mean_radius_m * o.mean_radius_m * 3.14)) /
                        std::numbers::pi);
                    const double ix = o.x + pick.uniform(-1.0, 1.0) * o.mean_radius_m,
                                 iy = o.y + pick.uniform(-1.0, 1.0) * o.mean_radius_m;
                    if (o.shore_distance(ix, iy) > -(rr + 10)) continue;
                    w.islands.push_back({ix, iy, rr, pick.uniform(0.5, 4.0)});
                    w.island_body.push_back(static_cast<std::int32_t>(k));
                    ++i;
                }
            }
            out.shores.push_back(w.lakes[k].shore);
            out.body_level.push_back(w.lakes[k].level);
            const double R = o.max_radius();
            out.touches_edge = out.touches_edge || o.x - R < 0 || o.y - R < 0 || o.x + R > S || o.y + R > S;
        }
    } else {
        w.angle = pick.uniform(0.0, 2.0 * std::numbers::pi);
        w.ca = std::cos(w.angle), w.sa = std::sin(w.angle);
        out.river_angle_rad = w.angle;
        auto& ch = w.river;
        ch.y_mid = 0.5 * S + pick.uniform(-0.1, 0.1) * S;
        ch.meander_amplitude_m = {pick.uniform(0.0, 0.12) * S, pick.uniform(0.0, 0.04) * S};
        ch.meander_wavelength_m = {pick.uniform(0.6, 1.2) * S, pick.uniform(0.25, 0.4) * S};
        ch.meander_phase = {pick.uniform(0.0, 6.28), pick.uniform(0.0, 6.28)};
        ch.mean_width_m = options.variant == water_family_variant::narrow_river ? pick.uniform(5.0, 15.0)
                          : level_land                                          ? pick.uniform(8.0, 40.0)
                          : hydro                                               ? pick.uniform(30.5, 60.0)
                                                                                : pick.uniform(15.0, 60.0);
        // hydro: the width stays within 30.5-60 m (the specification's minimum nominal width is 100 ft).
        ch.width_swing_m =
            hydro ? pick.uniform() * std::min({0.35 * ch.mean_width_m, ch.mean_width_m - 30.5, 60.0 - ch.mean_width_m})
                  : pick.uniform(0.0, 0.35) * ch.mean_width_m;
        ch.width_wavelength_m = {pick.uniform(0.4, 0.8) * S, pick.uniform(0.15, 0.3) * S};
        ch.width_phase = {pick.uniform(0.0, 6.28), pick.uniform(0.0, 6.28)};
        const double drop = pick.uniform(0.1, 1.5);
        ch.level_drop_per_m = drop / S;
        ch.level_west_z = water_base + 0.5 * drop;
        w.river_shore = {any_shore(), any_shore()};
        w.river_shore_p = {pick.uniform(), pick.uniform()};
        out.shores = {w.river_shore[0], w.river_shore[1]};
        out.body_level.push_back(ch.level(0.5 * S));
        out.touches_edge = true;
        const int nb = hydro ? pick.between(0, 2) : pick.between(0, 4);
        for (int i = 0; i < nb; ++i) {
            const double along = S * (static_cast<double>(i) + 0.5 + 0.3 * pick.triangular()) / nb;
            const double hw = 0.5 * pick.uniform(8.0, 20.0);
            const double reach = 0.5 * (ch.mean_width_m + ch.width_swing_m) + pick.uniform(8.0, 20.0);
            w.bridges.push_back(
                {along, hw, reach, ch.level(along) + pick.uniform(3.0, 8.0), pick.uniform(40.0, 100.0)});
            out.bridge_along.push_back({along, hw});
        }
        out.bridges = nb;
        double island_u = 0, island_r = -1e9;  // along-river position and radius of the river's island
        if (ch.mean_width_m > 30 && pick.chance(0.5)) {
            const double u = pick.uniform(0.2, 0.8) * S;
            const double rr = std::min(0.3 * ch.mean_width_m, std::sqrt(pick.uniform(50.0, 1500.0) / std::numbers::pi));
            island_u = u, island_r = rr;
            // island centre in world coordinates: the inverse of river_frame.
            const double du = u - 0.5 * S, dv = ch.centre_y(u) - 0.5 * S;
            w.islands.push_back(
                {du * w.ca - dv * w.sa + 0.5 * S, du * w.sa + dv * w.ca + 0.5 * S, rr, pick.uniform(0.5, 3.0)});
            w.island_body.push_back(0);
        }
        if (hydro) {
            // Weirs: the whole crossing at least 80 m inside the survey, 25 m clear of bridges, 20 m of the
            // island and 60 m of each other.
            const auto site_ok = [&](double u) {
                const double s = ch.centre_slope(u), hv = 0.5 * ch.width(u) * std::sqrt(1 + s * s);
                for (const double v : {ch.centre_y(u) - hv, ch.centre_y(u) + hv}) {
                    const double du = u - 0.5 * S, dv = v - 0.5 * S;
                    const double x = du * w.ca - dv * w.sa + 0.5 * S, y = du * w.sa + dv * w.ca + 0.5 * S;
                    if (std::min(x, y) < 80 || std::max(x, y) > S - 80) return false;
                }
                for (const auto& b : w.bridges)
                    if (std::abs(u - b.along) < b.half_width + 25) return false;
                if (std::abs(u - island_u) < island_r + 20) return false;
                for (const auto& weir : w.weirs)
                    if (std::abs(u - weir[0]) < 60) return false;
                return true;
            };
            for (int i = 0, n = pick.between(0, 2), tries = 0; i < n && tries < 100; ++tries) {
                const double u = pick.uniform(-0.2, 1.2) * S, weir_drop = pick.uniform(0.3, 1.5);
                if (!site_ok(u)) continue;
                w.weirs.push_back({u, weir_drop});
                ++i;
            }
            std::sort(w.weirs.begin(), w.weirs.end());
            out.weir_along = w.weirs;
            for (auto& b : w.bridges) b.z += w.river_level(b.along) - ch.level(b.along);
            out.body_level[0] = w.river_level(0.5 * S);
        }
    }
    out.islands = static_cast<int>(w.islands.size());

    // Distractors on land: dark asphalt lots, flat-roofed buildings (with scan shadows), trees.
    const auto dry = [&](double x0, double y0, double x1, double y1) {
        for (int i = 0; i <= 4; ++i)
            for (int j = 0; j <= 4; ++j) {
                const double x = x0 + (x1 - x0) * i / 4.0, y = y0 + (y1 - y0) * j / 4.0;
                if (w.at(x, y).body >= 0 || w.bridge_at(x, y) >= 0) return false;
                if (is_lake) {
                    for (const auto& l : w.lakes)
                        if (l.outline.shore_distance(x, y) < 15) return false;
                } else {
                    const auto [u, v] = w.river_frame(x, y);
                    if (std::abs(w.river.offset(u, v)) < 0.5 * w.river.width(u) + 15) return false;
                }
            }
        return true;
    };
    for (int i = 0, n = pick.between(0, 3), tries = 0; i < n && tries < 60; ++tries) {
        const double a = pick.uniform(20.0, 70.0), b = pick.uniform(15.0, 50.0);
        const double x = pick.uniform(0.0, S - a), y = pick.uniform(0.0, S - b);
        if (!dry(x, y, x + a, y + b)) continue;
        w.lots.push_back({x, y, x + a, y + b, pick.uniform(12.0, 35.0)});
        ++i;
    }
    for (int i = 0, n = pick.between(0, 8), tries = 0; i < n && tries < 100; ++tries) {
        const double a = pick.uniform(10.0, 35.0), b = pick.uniform(10.0, 35.0);
        const double x = pick.uniform(0.0, S - a), y = pick.uniform(0.0, S - b);
        if (!dry(x - 5, y - 5, x + a + 5, y + b + 5)) continue;
        const double z = w.at(x + 0.5 * a, y + 0.5 * b).z + pick.uniform(3.0, 12.0);
        w.buildings.push_back(
            {x, y, x + a, y + b, z, pick.chance(0.5) ? pick.uniform(15.0, 35.0) : pick.uniform(60.0, 140.0)});
        ++i;
    }
    for (int i = 0, n = pick.between(0, 60), tries = 0; i < n && tries < 400; ++tries) {
        const double r = pick.uniform(2.0, 5.0), x = pick.uniform(0.0, S), y = pick.uniform(0.0, S);
        if (!dry(x - r - 1, y - r - 1, x + r + 1, y + r + 1) || w.building_at(x, y) >= 0) continue;
        w.trees.push_back({x, y, r, w.at(x, y).z + pick.uniform(6.0, 18.0)});
        ++i;
    }

    internal::render_family(w, out, options.seed);
    return out;
}

/// True when a river scene's stretches between its bridges (and beyond them; cells within a bridge's half
/// width + 4 cells of it left out) are each found mostly (over half their truth water cells) as one and
/// the same nonzero label of `labels` (a waterbody label raster on the scene's grid). Stretches of fewer
/// than 20 cells (cut by the survey edge) are ignored. O(cells · bridges).
template <class Labels>
bool river_found_as_one_body(const water_family_scene& s, const Labels& labels)
{
    std::vector<std::map<std::int64_t, long>> votes(s.bridge_along.size() + 1);
    const double ca = std::cos(s.river_angle_rad), sa = std::sin(s.river_angle_rad), h = 0.5 * s.size_m;
    for (std::ptrdiff_t r = 0; r < s.g.rows; ++r) {
        for (std::ptrdiff_t c = 0; c < s.g.cols; ++c) {
            if (!s.water(r, c)) continue;
            const auto [x, y] = s.g.center(r, c);
            const double u = (x - h) * ca + (y - h) * sa + h;
            std::size_t stretch = 0;
            bool on_bridge = false;
            for (const auto& b : s.bridge_along) {
                if (std::abs(u - b[0]) <= b[1] + 4 * s.cell_m) on_bridge = true;
                if (u > b[0]) ++stretch;
            }
            if (!on_bridge) votes[stretch][static_cast<std::int64_t>(labels(r, c))] += 1;
        }
    }
    std::int64_t common = -1;
    for (const auto& v : votes) {
        long total = 0, best = 0;
        std::int64_t label = 0;
        for (const auto& [l, n] : v) {
            total += n;
            if (l != 0 && n > best) best = n, label = l;
        }
        if (total < 20) continue;
        if (label == 0 || 2 * best < total || (common >= 0 && label != common)) return false;
        common = label;
    }
    return common > 0;
}

}  // namespace lidarfx::synth
