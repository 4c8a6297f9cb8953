// SPDX-License-Identifier: Apache-2.0
// roof_suitability: rooftop PV suitability from a DSM, a DTM and a building-id raster: the paper's method
// (one PV plane per building) or every roof plane with its own tilt, azimuth, area and suitability.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "lidarfx/core/grid.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/pipelines/pv/azimuth_mode_select.hpp"
#include "lidarfx/pipelines/pv/roof_planes.hpp"

namespace lidarfx {

/// How roof_suitability finds PV planes.
enum class roof_mode {
    planes,  ///< every roof plane segmented and judged on its own fitted tilt and azimuth (beyond the paper)
    paper,   ///< the paper's method: one PV plane per building (mean tilt, aspect mode, +-1/2 std band)
};

/// Settings of roof_suitability. Angles in degrees, azimuths clockwise from north; areas in m^2.
struct roof_suitability_options {
    roof_mode mode = roof_mode::planes;
    double min_height_m = 2.0;  ///< nDSM = DSM - DTM cut: lower cells are not roof (paper step 1)
    double min_patch_m2 = 8.0;  ///< a suitable patch has at least this sloped area (1 kWp minimum system)
    double m2_per_kwp = 8.0;    ///< system size: 1 kWp per this many m^2 of (sloped) patch area, > 0
    double min_tilt_deg = 15, max_tilt_deg = 60;         ///< suitable tilts (pitched roofs), inclusive
    double min_azimuth_deg = 90, max_azimuth_deg = 270;  ///< suitable facings (east-south-west), inclusive
    /// Flat roofs: a patch tilted less than this is flat. Its own rule: suitable when its sloped area is at
    /// least min_patch_m2 whatever its facing (panels stand on racks facing south at their own tilt); its kWp
    /// counts that area.
    double flat_below_deg = 15;
    azimuth_mode_select_options azimuth = {};  ///< paper mode: the step-5 rules
    int paper_min_patch_cells = 10;   ///< paper mode: smaller 4-connected patches are dropped (step 9, 1 m cells)
    int paper_boundary_cleans = 2;    ///< paper mode: boundary cleans (3x3 closing then opening; step 10)
    roof_planes_options planes = {};  ///< planes mode: the segmentation
    execution run = {};               ///< threads, progress and cancellation; never changes the result
};

/// One PV patch: a roof plane (planes mode) or a building's PV plane (paper mode).
struct roof_patch {
    std::int32_t building_id = 0, patch_id = 0;  ///< patch ids 1.. over the whole result (patch_id raster)
    double tilt_deg = 0;        ///< 0 horizontal; planes: fitted plane; paper: the building's mean slope
    double azimuth_deg = 0;     ///< facing (down-slope) azimuth clockwise from north, [0, 360)
    double area_m2 = 0;         ///< horizontal area = cells x cell^2
    double sloped_area_m2 = 0;  ///< area_m2 / cos(tilt)
    double kwp = 0;             ///< sloped_area_m2 / m2_per_kwp
    bool suitable = false, flat = false;
    double centroid_x = 0, centroid_y = 0;  ///< mean of the cell centres, world coordinates (grid units)
    double rms_m = 0;                       ///< planes mode: rms residual of the cells about the fitted plane
    std::string reason;                     ///< why (un)suitable
};

/// What happened to one building (every label of building_id, in increasing order).
struct roof_building {
    std::int32_t building_id = 0;
    std::size_t cells = 0;        ///< roof cells: inside the footprint, finite, nDSM >= min_height_m
    azimuth_selection selection;  ///< paper mode: the step-5 decision
    std::string note;
};

/// Result of roof_suitability.
struct roof_suitability_result {
    raster<std::int32_t> patch_id;  ///< patch of each cell (0 = none), the grid's shape
    std::vector<roof_patch> patches;
    std::vector<roof_building> buildings;
};

/// The suitability rule of one measured patch (tilt_deg, azimuth_deg and sloped_area_m2 set): sets flat (tilt
/// under flat_below_deg), suitable and reason. Flat: suitable when sloped_area_m2 >= min_patch_m2, whatever its
/// facing. Else suitable when also tilt in [min_tilt_deg, max_tilt_deg] and azimuth (clockwise from north) in
/// [min_azimuth_deg, max_azimuth_deg]; reason names the first rule failed ("faces north", "too steep", "too
/// shallow", "under the minimum area"). O(1); options are not checked.
inline void judge_patch(roof_patch& p, const roof_suitability_options& o);

/// Rooftop PV suitability of every building of `building_id` (footprints burned on grid g, e.g. by
/// burn_polygons; 0 = no building) from a DSM and a DTM (metres, same shape as g; NaN = no data).
/// Roof cells: inside a footprint with nDSM = DSM - DTM >= min_height_m. Then, per building,
/// - planes mode: every roof plane (roof_planes: normal-guided region growing on 4-connected cells,
///   robust least-squares plane fits, merging of adjacent coplanar segments, competitive reassignment of
///   cells to the best-fitting plane); each plane's fitted tilt and azimuth, horizontal area (cells x cell^2),
///   sloped area = area / cos(tilt), kWp = sloped area / m2_per_kwp, and suitability: tilt in [15, 60],
///   azimuth in [90, 270], sloped area >= 8 m^2 (flat planes under flat_below_deg by their own rule);
/// - paper mode (Palmer et al., appendix steps 1-12): Horn slope and truncated integer aspect of the nDSM;
///   tilt = the building's mean slope; aspect mode -> azimuth_mode_select; east-south-west filter; cells
///   within +-1/2 std of the PV azimuth; 4-connected patches of >= paper_min_patch_cells; boundary clean
///   twice; one patch per building (its surviving cells), areas and kWp as above.
/// Patch ids are numbered 1.. by building id, then plane order. Annual yield from solar records is not
/// computed here (combine patch_id with irradiance_maps). O(cells log cells).
/// @throws invalid_input if the shapes differ from g, g is invalid, a building id is negative, or an option
/// is out of range; cancelled if run.progress returns false.
template <raster_input Dsm, raster_input Dtm, raster_input Ids>
roof_suitability_result roof_suitability(const Dsm& dsm, const Dtm& dtm, const Ids& building_id, const grid& g,
                                         const roof_suitability_options& opt = {});

}  // namespace lidarfx

#include "lidarfx/pipelines/pv/detail/roof_suitability_impl.hpp"
