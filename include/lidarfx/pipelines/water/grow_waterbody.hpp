// SPDX-License-Identifier: Apache-2.0
// grow_waterbody: KS-stopped region growing of one seed as a single bucket-queue flood.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/kernels/stats/ks_one_sided.hpp"
#include "lidarfx/pipelines/water/seed_water_level.hpp"
#include "lidarfx/pipelines/water/water_surface_slope.hpp"

namespace lidarfx {

/// Per-cell inputs of the growing step, all of one shape: rasters owned (contiguous), min z and the surface
/// slope shown (keep what they show alive while growing).
struct water_field {
    raster<float> angle_deg;                  ///< angular filter value, degrees; NaN = may join at any threshold
    raster<std::uint8_t> eligible;            ///< 1 = may join a waterbody (not vegetation, not already taken)
    raster<std::int32_t> intensity_bin;       ///< intensity sample of the cell as a bin in [0, bins); -1 = none
    int bins = 1;                             ///< number of intensity bins, >= 1
    raster_view<const float> min_z = {};      ///< optional: lowest return per cell, metres, NaN = none; the level
                                              ///< gate reads it (empty = no gate). A view: keep it alive while growing
    surface_slope_source surface_slope = {};  ///< optional: water_surface_slope of min z (a raster or a
                                              ///< lazy_water_surface_slope), m/m, NaN = unknown; read with
                                              ///< grow_waterbody_options::level_follow_max_slope
    raster_view<const float> mean_intensity = {};  ///< optional: mean intensity per cell (NaN = none); read with
                                                   ///< grow_waterbody_options::level_follow_max_intensity
};

/// Which sample a growth step is compared with the previous region's sample.
enum class ks_sample_mode {
    cumulative,  ///< the whole new region (the dissertation): a small leak into land hides in a large body
    increment,   ///< only the cells the step added: a leak is tested on its own and caught while small
};

/// Threshold schedule and stopping rule of the growing step (dissertation §2.3.3, docs/waterbodies.md).
struct grow_waterbody_options {
    double theta_start_deg = 2.0;     ///< first angular threshold θ_0, degrees, >= 0
    double theta_step_deg = 1.0;      ///< increment of θ per step, degrees, > 0
    double theta_max_deg = 30.0;      ///< last threshold, degrees, >= theta_start_deg, <= 90
    ks_one_sided_options ks = {};     ///< one-sided KS test between consecutive regions (α, critical value)
    std::size_t min_ks_samples = 30;  ///< steps are accepted untested until the reference sample has this
                                      ///< many intensity values (a seed of dropouts has none)
    ks_sample_mode sample = ks_sample_mode::increment;  ///< what each step's sample holds (cumulative =
                                                        ///< the dissertation's literal test)
    double level_gate_m = 0.15;       ///< level gate (needs field.min_z): a cell with a return joins only when
                                      ///< |min z − L| <= level_gate_m, L the level it is reached from (the
                                      ///< seed's: seed_water_level); metres; 0 disables. Default 0.15 m
    double level_drift_m = 0.005;     ///< the level a joining cell passes on follows its min z by at most this
                                      ///< (L' = L + clamp(min z − L, ±drift)): rivers fall, beaches rise
                                      ///< faster; metres per cell, >= 0. Default 0.005 m
    double level_rise_m = -1;         ///< upward drift: the level a joining cell passes on rises by at most this
                                      ///< per cell (L' = L + clamp(min z − L, −level_drift_m, level_rise_m));
                                      ///< metres per cell; < 0 = level_drift_m. Default -1
    double level_ks_exempt_m = 0.05;  ///< with the gate: cells with min z <= L + this are water by level and
                                      ///< stay out of the KS increment sample (bright specular water near
                                      ///< nadir); metres; < 0 disables. Default 0.05 m
    double level_any_angle_m = -1;    ///< with the gate: a cell with a return whose min z lies within this of
                                      ///< the level it is reached at joins at the step it is reached, whatever
                                      ///< its angle: in a channel narrower than the angular window every cell
                                      ///< sees a bank, and its angles exceed θ max; metres; < 0 disables.
                                      ///< Default -1
    seed_water_level_options seed_level = {};  ///< how the seed's level L is read from the returns around it
    double level_follow_max_slope = -1;        ///< with the gate and field.surface_slope: a joining cell passes on a
                                               ///< level that follows its min z (the drift) only where the surface
                                               ///< around it is level, slope <= this (m/m; NaN, unknown, follows);
                                               ///< elsewhere it passes its level on unchanged, as a dropout does (a
                                               ///< flood no longer ratchets up a beach or down a falling bank); < 0
                                               ///< disables. Default -1 (0.008 with flat seeds: docs/waterbodies.md)
    double level_follow_max_intensity = NAN;   ///< with the gate and field.mean_intensity: a joining cell whose mean
                                               ///< intensity is at least this passes its level on unchanged, as a
                                               ///< dropout does: a level lawn or lot of land intensity beside the
                                               ///< water does not lead the level up to its own height; NaN disables.
                                               ///< Default NaN (extract_waterbodies sets the survey's land intensity
                                               ///< for the floods of flat seeds: flat_water_seeds_workspace)
    bool test_first_step = true;  ///< with the gate and level_ks_exempt_m >= 0: the first step, which has no
                                  ///< previous region to be tested against, is tested within itself. Its
                                  ///< cells with returns off the level they are reached at (|min z − L| >
                                  ///< level_ks_exempt_m) wait until the cells at the level are in; then
                                  ///< their intensity sample is tested (ks_one_sided) against the region's
                                  ///< so far, when that has min_ks_samples values: accepted, they join and
                                  ///< the step goes on (what they reach is tested the same way); rejected,
                                  ///< they never join, and the step ends without what only they reach (a
                                  ///< flat meadow or terrace next to the water, within the gate, was
                                  ///< flooded at θ_0 without any test). The seed's own cells never wait.
                                  ///< Default true (on the water family: river specificity 99.40
                                  ///< -> 99.76 %, worst lake's 88 -> 99 %; river sensitivity 66 -> 64 %;
                                  ///< docs/waterbodies.md)
};

/// Result of growing one seed.
struct grow_waterbody_result {
    std::vector<std::ptrdiff_t> cells;  ///< linear cell indices r * cols + c, in the order they joined
    int steps_accepted = -1;            ///< last accepted step k (θ_k = θ_0 + k·Δθ); -1 when nothing joined
    double theta_deg = NAN;             ///< θ of the last accepted step
    bool stopped_by_ks = false;         ///< true when the KS test rejected step steps_accepted + 1
};

/// Scratch of grow_waterbody for a caller that grows many seeds on one field: each flood marks the cells it
/// visits with a stamp of its own, so nothing is cleared between floods. Default-constructed, it allocates a
/// mark raster of the field's shape at the first flood (and again if the shape changes). Constructed over a
/// caller's label raster (`marks`: contiguous rows, the field's shape, labels >= 0), it allocates nothing: each flood
/// writes a new negative stamp into the eligible cells it visits and only reads the others, so labels > 0 of cells that
/// are not eligible stay as they are; clear_marks() sets the stamped cells back to 0. One workspace per thread; it
/// holds no result.
class grow_waterbody_workspace {
public:
    grow_waterbody_workspace() = default;
    explicit grow_waterbody_workspace(raster_view<std::int32_t> marks) noexcept : marks_(marks), borrowed_(true) {}

    /// Sets the cells stamped so far (< 0) back to 0 and starts the stamps again. O(cells).
    void clear_marks() noexcept
    {
        for (std::ptrdiff_t r = 0; r < marks_.rows(); ++r) {
            std::int32_t* m = marks_.row(r);
            for (std::ptrdiff_t c = 0, n = marks_.cols(); c < n; ++c) m[c] = m[c] < 0 ? 0 : m[c];
        }
        stamp_ = 0;
    }

    /// The marks of the next flood over a field of rows x cols cells and its stamp (no cell holds it yet).
    /// @throws invalid_input if the workspace is over marks of another shape.
    std::pair<raster_view<std::int32_t>, std::int32_t> next_flood(std::ptrdiff_t rows, std::ptrdiff_t cols)
    {
        if (!borrowed_ && (own_.rows() != rows || own_.cols() != cols)) {
            own_ = raster<std::int32_t>(rows, cols, 0);
            marks_ = own_.view();
            stamp_ = 0;
        }
        detail::require(marks_.rows() == rows && marks_.cols() == cols && marks_.row_stride() == cols, "grow_waterbody",
                        "workspace.marks", "contiguous and of the field's shape", marks_.rows());
        if (stamp_ == std::numeric_limits<std::int32_t>::min()) clear_marks();
        return {marks_, --stamp_};
    }

private:
    raster<std::int32_t> own_;
    raster_view<std::int32_t> marks_ = {};
    std::int32_t stamp_ = 0;
    bool borrowed_ = false;
};

/// Grows one seed into a waterbody. The region at step k is the set of eligible cells 8-connected to the
/// seed through eligible cells whose angle is <= θ_k = θ_0 + k·Δθ (NaN angles join at any step). After
/// each step the intensity sample of the previous region is compared with the new one by ks_one_sided
/// (samples: cells with intensity_bin >= 0); on rejection the previous region is kept and growth stops.
/// All steps run as ONE flood: a bucket queue keyed by the step at which a cell can first join (the
/// minimax of steps along its best path), so each cell enters the queue once, with a cumulative intensity
/// histogram per step. O(cells reached + steps * bins). The cells visited are marked in `workspace` (a caller that
/// grows many seeds on one field keeps one workspace: nothing is allocated or cleared between floods).
/// @throws invalid_input on a field of mismatched shapes (or a workspace over marks of another shape), bins < 1,
/// options out of range, or an intensity bin outside [-1, bins) in a cell the flood reaches.
inline grow_waterbody_result grow_waterbody(const water_field& field, std::span<const std::ptrdiff_t> seed_cells,
                                            const grow_waterbody_options& opt, grow_waterbody_workspace& workspace);

/// grow_waterbody with a workspace of its own (allocated for this call).
inline grow_waterbody_result grow_waterbody(const water_field& field, std::span<const std::ptrdiff_t> seed_cells,
                                            const grow_waterbody_options& opt = {});

}  // namespace lidarfx

#include "lidarfx/pipelines/water/detail/grow_waterbody_impl.hpp"
