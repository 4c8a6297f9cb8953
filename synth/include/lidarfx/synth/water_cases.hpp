// SPDX-License-Identifier: Apache-2.0
// water_cases: fixed family scenes of the hard cases (a dropout-dominated pond in a
// field just above its level; a river with bright specular stretches near nadir and a bridge; a turbid
// lake without dropouts next to a meadow and a dark asphalt lot).
#pragma once

#include <cstdint>

#include "lidarfx/synth/water_family.hpp"

namespace lidarfx::synth {

namespace internal {

/// The world of the lake cases: a plain of 0.2 m relief whose flat fields are the ground everywhere (the
/// base, 99 m, lies below them), its noise fields drawn from `ws`; the caller adds the lake.
inline family_world flat_plain_lake_world(std::uint64_t ws, double size_m)
{
    family_world w{water_family_kind::lake, size_m, noise_field{hash64(ws, 1), 400.0, 4, 0.45},
                   noise_field{hash64(ws, 2), 70.0, 3, 0.5}, noise_field{hash64(ws, 3), 60.0, 3, 0.5}};
    w.base_z = 99;
    w.relief_m = 0.2;
    return w;
}

}  // namespace internal

/// A pond of mean radius 55 m (level 100 m) in the middle of a flat grass field 0.7 m above the water
/// (shore_kind::flat_field; grass intensity 86 ± 8, no dropouts, 10 returns per 2 m cell at 2.5
/// pulses/m²); the pond's surface is mostly dropouts (60 % in patches, 70-90 % of other pulses lost) and
/// its returns have intensity 6-27 (mean 13). 300 m square, 2 m truth cells. Deterministic from `seed`.
inline water_family_scene dropout_pond_scene(unsigned seed = 1)
{
    water_family_scene out;
    out.kind = water_family_kind::lake;
    out.size_m = 300, out.density_per_m2 = 2.5, out.cell_m = 2;
    out.scan = {1000, 15, 0.2};
    out.returns = {.drop_nadir = 0.9, .drop_edge = 0.97, .patch_share = 0.8, .low_min = 6, .low_max = 27};
    const std::uint64_t ws = hash64(seed, 0x90D);
    auto w = internal::flat_plain_lake_world(ws, out.size_m);
    rng pick(ws, 1);
    w.lakes.push_back({lake_outline::random(pick, 150, 150, 55, 0.2), 100.0, shore_kind::flat_field, 0.4});
    out.shores = {shore_kind::flat_field};
    out.body_level = {100.0};
    internal::render_family(w, out, seed);
    return out;
}

/// A river 30 m wide flowing east through a 400 m square (level 100.25 m falling 0.5 m eastwards, steep
/// banks), under one flight line at x = 200 m (1000 m above, ±20°): within about 3° of nadir 95 % of the
/// water's pulses return bright specular echoes (intensity 55 ± 30 %, almost no dropouts); elsewhere 45 %
/// of the water lies in dropout patches and the returns are dark (3-25). One bridge 12 m wide crosses at
/// x = 300 m, its deck 5 m above the water. 2 points/m², 2 m truth cells. Deterministic from `seed`.
inline water_family_scene specular_river_scene(unsigned seed = 1)
{
    water_family_scene out;
    out.kind = water_family_kind::river;
    out.size_m = 400, out.density_per_m2 = 2.0, out.cell_m = 2;
    out.scan = {1000, 20, 0.0};
    out.returns = {.drop_nadir = 0.3,
                   .drop_edge = 0.5,
                   .patch_share = 0.45,
                   .glint = 0.95,
                   .glint_width_deg = 3.0,
                   .glint_intensity = 55};
    const std::uint64_t ws = hash64(seed, 0x5BEC);
    internal::family_world w{water_family_kind::river, out.size_m, noise_field{hash64(ws, 1), 400.0, 4, 0.45},
                             noise_field{hash64(ws, 2), 70.0, 3, 0.5}, noise_field{hash64(ws, 3), 80.0, 3, 0.5}};
    w.base_z = 100;
    w.relief_m = 3;
    auto& ch = w.river;
    ch.y_mid = 200;
    ch.meander_amplitude_m = {25, 5};
    ch.meander_wavelength_m = {350, 120};
    ch.mean_width_m = 30;
    ch.width_swing_m = 5;
    ch.level_drop_per_m = 0.5 / 400;
    ch.level_west_z = 100.25;
    w.river_shore = {shore_kind::steep_bank, shore_kind::steep_bank};
    w.river_shore_p = {0.3, 0.6};
    w.bridges.push_back({300, 6, 40, ch.level(300) + 5, 80});
    out.bridge_along.push_back({300, 6});
    out.bridges = 1;
    out.shores = {shore_kind::steep_bank, shore_kind::steep_bank};
    out.body_level = {ch.level(200)};
    out.touches_edge = true;
    internal::render_family(w, out, seed);
    return out;
}

/// A turbid lake of mean radius 60 m (level 100 m) in a flat meadow 0.5-0.6 m above the water
/// (shore_kind::flat_field, grass intensity 86 ± 8) with a dark asphalt lot (intensity 20, 60 × 40 m,
/// level, at x 20-80 m, y 20-60 m) on the plain: the lake's returns have ordinary intensities (25-55) and
/// it loses 20-30 % of its pulses but has no dropout cells (16 pulses per 2 m cell at 4 pulses/m², no
/// dropout patches). 300 m square, 2 m truth cells. Deterministic from `seed`.
inline water_family_scene turbid_lake_scene(unsigned seed = 1)
{
    water_family_scene out;
    out.kind = water_family_kind::lake;
    out.size_m = 300, out.density_per_m2 = 4.0, out.cell_m = 2;
    out.scan = {1000, 15, 0.2};
    out.returns = {
        .drop_nadir = 0.2, .drop_edge = 0.3, .patch_share = 0.0, .low_min = 25, .low_max = 55, .turbid = true};
    const std::uint64_t ws = hash64(seed, 0x7B1D);
    auto w = internal::flat_plain_lake_world(ws, out.size_m);
    rng pick(ws, 1);
    w.lakes.push_back({lake_outline::random(pick, 170, 170, 60, 0.2), 100.0, shore_kind::flat_field, 0.2});
    w.lots.push_back({20, 20, 80, 60, 20});
    out.shores = {shore_kind::flat_field};
    out.body_level = {100.0};
    internal::render_family(w, out, seed);
    return out;
}

}  // namespace lidarfx::synth
