// SPDX-License-Identifier: Apache-2.0
// flat_water_seeds_options: the settings of flat_water_seeds, shared by its steps.
#pragma once

#include <cstddef>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"

namespace lidarfx {

/// Options of flat_water_seeds. The defaults follow from the physics of the returns, not from one survey:
/// a water surface is level to the range noise of the scanner (2-3 cm per return), returns fewer pulses
/// than the land around it (specular reflection away from the sensor, absorption), and lies below its banks.
struct flat_water_seeds_options {
    int level_radius_cells = 1;            ///< the level test reads the (2 r + 1)² window around a cell (3 × 3: a
                                           ///< river a few cells wide still has level cells), >= 1. Default 1
    double level_tolerance_m = 0.10;       ///< the window's min z spans at most this, metres (≈ 4 σ of 2-3 cm range
                                           ///< noise on the lowest return), >= 0. Default 0.10
    double max_roughness_m = 0.2;          ///< a cell's max z − min z is at most this (several σ of range noise plus
                                           ///< waves; low vegetation and edges are rougher), metres, >= 0. Default 0.2
    std::size_t min_cells = 50;            ///< a seed keeps components of at least this many cells, >= 1. Default 50
    int ring_cells = 4;                    ///< the land a component is compared with lies within this Chebyshev
                                           ///< distance of it, cells, >= 1. Default 4
    double max_density_ratio = 0.85;       ///< sparse: a component's mean returns per cell is at most this share of its
                                           ///< ring's (water loses pulses; flat land, asphalt and roofs do not), in
                                           ///< (0, 1]. Default 0.85
    double dark_density_ratio = 0.97;      ///< dark and sparse: ... or at most this share when it is also dark (then
                                           ///< a few % fewer returns suffice: asphalt is dark but returns every
                                           ///< pulse), in (0, 1]. Default 0.97
    double max_intensity_ratio = 0.6;      ///< dark: its mean intensity is at most this share of its ring's (water
                                           ///< absorbs the near infrared), >= 0; 0 disables the dark path. Default 0.6
    double max_roughness_ratio = 0.6;      ///< smooth and sparse: ... or at most dark_density_ratio of it when its mean
                                           ///< max z − min z is at most this share of the median over all level cells
                                           ///< (calm water is smoother than grass, soil and asphalt with their
                                           ///< micro-relief), >= 0; 0 disables the smooth path. Default 0.6
    double max_lower_share = 0.1;          ///< lowest: at most this share of its ring lies more than level_tolerance_m
                                           ///< below the component's lowest cell within ring_cells of it (water fills
                                           ///< the lowest ground around it; roofs and lots on sloping ground have
                                           ///< lower ground next to them), in [0, 1].
                                           ///< Default 0.1
    double bright_density_ratio = 0.72;    ///< sparse and bright: at most this share of the ring's returns makes a
                                           ///< component sparse whatever its intensity (specular echoes near nadir
                                           ///< are brighter than a dark ring while the pulses around them are lost;
                                           ///< no flat land loses a quarter of its pulses), in [0, 1]; 0 disables.
                                           ///< Default 0.72
    double max_joint_ratio = 0.6;          ///< weak cues together: ... or at most dark_density_ratio of the ring's
                                           ///< returns when density ratio × intensity ratio × roughness ratio (as
                                           ///< above; roughness against the median of level cells) is at most this,
                                           ///< for a component of at least joint_min_cells (each cue a little
                                           ///< water-like; land fragments of a few dozen cells scatter too much to be
                                           ///< judged so), >= 0; 0 disables. Default 0.6
    std::size_t joint_min_cells = 150;     ///< see max_joint_ratio, cells. Default 150
    double land_intensity_quantile = 0.1;  ///< land-like: a component whose mean intensity is at least this
                                           ///< quantile of the survey's land intensities (the cells with a
                                           ///< return outside the lowest components: all that could not be water)
                                           ///< is a seed only when it is sparse and bright
                                           ///< (bright_density_ratio): a level field, lawn or lot of land
                                           ///< intensity that returns its pulses is land however level and
                                           ///< smooth it is; in [0, 1], < 0 disables. Default 0.1
    double max_land_intensity_ratio = 0.8;  ///< dark against the survey: a component whose mean intensity is at
                                            ///< most this share of that land quantile is dark (as with
                                            ///< max_intensity_ratio against its ring: turbid water beside a
                                            ///< dim shore), >= 0; 0 disables. Default 0.8
    double min_raised_share = 0.5;          ///< dark and sunken: a component dark against the survey with at least this
                                            ///< share of its ring more than level_tolerance_m above its lowest cell
                                            ///< nearby (water below its banks) is a seed with no pulse lost (clear or
                                            ///< turbid water that returns every pulse; a dark lot lies flush with the
                                            ///< ground around it), in [0, 1]; > 1 disables. Default 0.5
    double max_surface_slope = 0.008;       ///< level: given a surface slope (water_surface_slope or its lazy form), a
                                            ///< component is a seed only when the median over its cells of the slope
                                            ///< of the plane fitted around them is at most this, and its cells where
                                            ///< the slope exceeds it are no seed cells, m/m (a water surface is level;
                                            ///< a river falls a few mm per metre; a beach rising 1-6 % has level 3 × 3
                                            ///< windows too, and joins the water's level cells); < 0 disables.
                                            ///< Default 0.008
};

namespace detail {

inline void validate(const flat_water_seeds_options& o, const char* fn)
{
    require(o.level_radius_cells >= 1, fn, "level_radius_cells", ">= 1", o.level_radius_cells);
    require(o.level_tolerance_m >= 0, fn, "level_tolerance_m", ">= 0", o.level_tolerance_m);
    require(o.max_roughness_m >= 0, fn, "max_roughness_m", ">= 0", o.max_roughness_m);
    require(o.min_cells >= 1, fn, "min_cells", ">= 1", o.min_cells);
    require(o.ring_cells >= 1, fn, "ring_cells", ">= 1", o.ring_cells);
    require(o.max_density_ratio > 0 && o.max_density_ratio <= 1, fn, "max_density_ratio", "in (0, 1]",
            o.max_density_ratio);
    require(o.dark_density_ratio > 0 && o.dark_density_ratio <= 1, fn, "dark_density_ratio", "in (0, 1]",
            o.dark_density_ratio);
    require(o.max_intensity_ratio >= 0, fn, "max_intensity_ratio", ">= 0", o.max_intensity_ratio);
    require(o.max_roughness_ratio >= 0, fn, "max_roughness_ratio", ">= 0", o.max_roughness_ratio);
    require(o.max_lower_share >= 0 && o.max_lower_share <= 1, fn, "max_lower_share", "in [0, 1]", o.max_lower_share);
    require(o.bright_density_ratio >= 0 && o.bright_density_ratio <= 1, fn, "bright_density_ratio", "in [0, 1]",
            o.bright_density_ratio);
    require(o.max_joint_ratio >= 0, fn, "max_joint_ratio", ">= 0", o.max_joint_ratio);
    require(o.min_raised_share >= 0, fn, "min_raised_share", ">= 0 (> 1 disables)", o.min_raised_share);
    require(o.max_land_intensity_ratio >= 0, fn, "max_land_intensity_ratio", ">= 0", o.max_land_intensity_ratio);
    require(o.land_intensity_quantile <= 1, fn, "land_intensity_quantile", "<= 1 (< 0 disables)",
            o.land_intensity_quantile);
}

}  // namespace detail

}  // namespace lidarfx
