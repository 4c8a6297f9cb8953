// SPDX-License-Identifier: Apache-2.0
// sky_options: how the sky enters a solar computation (sky view factor sweep, diffuse sky model, ground albedo),
// one struct shared by irradiance_maps, roof_yield and surface_energy.
#pragma once

#include "lidarfx/core/error.hpp"
#include "lidarfx/kernels/solar/perez_diffuse.hpp"
#include "lidarfx/kernels/solar/sky_view_factor.hpp"

namespace lidarfx {

/// Sky model of the diffuse irradiance.
enum class diffuse_model {
    isotropic,  ///< DHI * SVF * (1 + cos b) / 2: a uniform sky (the dissertation's)
    perez,      ///< Perez et al. (1990) anisotropic sky: circumsolar part times lit, the rest times SVF
};

/// The sky of a solar computation. Fields in this order (designated initializers follow it).
struct sky_options {
    /// Sky view factor for the diffuse part: source_share (the dissertation's 1,081 sources, default) or
    /// cosine_weighted (sky_view_factor_method).
    sky_view_factor_method svf_method = sky_view_factor_method::source_share;
    int svf_directions = 72;  ///< azimuths of the sky view factor sweeps, >= 4 (72 = 5 degree steps)
    /// Sky model of the diffuse part: isotropic (the default, the dissertation's) or perez (perez_diffuse).
    diffuse_model diffuse = diffuse_model::isotropic;
    perez_diffuse_options perez = {};  ///< settings of the Perez sky (used with diffuse_model::perez)
    /// Ground reflectance (albedo) in [0, 1] for ground-reflected irradiance GHI * albedo * (1 - cos b) / 2 on
    /// tilted surfaces; 0 (the default, the dissertation's) leaves it out.
    double albedo = 0.0;
};

/// Refuses svf_directions < 4, an unknown diffuse model, albedo outside [0, 1] or a Perez solar constant outside
/// (0, 1e6] W/m^2, naming `fn` and the field ("irradiance_maps: sky.svf_directions must be >= 4 (got 2)").
/// With isotropic_only (pipelines that model neither the Perez sky nor reflected light) it also refuses
/// diffuse = perez and albedo != 0. @throws invalid_input.
inline void require_sky_options(const sky_options& sky, const char* fn, bool isotropic_only = false)
{
    detail::require(sky.svf_directions >= 4, fn, "sky.svf_directions", ">= 4", sky.svf_directions);
    detail::require(sky.diffuse == diffuse_model::isotropic || sky.diffuse == diffuse_model::perez, fn, "sky.diffuse",
                    "isotropic or perez", static_cast<int>(sky.diffuse));
    detail::require(sky.albedo >= 0.0 && sky.albedo <= 1.0, fn, "sky.albedo", "in [0, 1]", sky.albedo);
    detail::require(sky.perez.solar_constant_w_m2 > 0.0 && sky.perez.solar_constant_w_m2 <= 1.0e6, fn,
                    "sky.perez.solar_constant_w_m2", "in (0, 1e6] W/m^2", sky.perez.solar_constant_w_m2);
    if (isotropic_only) {
        detail::require(sky.diffuse == diffuse_model::isotropic, fn,
                        "sky.diffuse must be isotropic (the Perez sky is not modelled here)");
        detail::require(sky.albedo == 0.0, fn, "sky.albedo", "0 (reflected light is not modelled here)", sky.albedo);
    }
}

}  // namespace lidarfx
