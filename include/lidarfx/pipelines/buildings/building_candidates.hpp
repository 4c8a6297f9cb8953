// SPDX-License-Identifier: Apache-2.0
// building_candidates: the cells that may be buildings (inside an edge hull, high above the terrain, not
// vegetation), grouped into 4-connected parts of at least the minimum footprint (extract_buildings step 2).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "lidarfx/core/error.hpp"
#include "lidarfx/core/parallel.hpp"
#include "lidarfx/core/raster.hpp"
#include "lidarfx/core/raster_view.hpp"
#include "lidarfx/kernels/label/connected_components.hpp"
#include "lidarfx/pipelines/buildings/ground_model.hpp"

namespace lidarfx {

/// Settings of building_candidates.
struct building_candidates_options {
    double min_height_m = 2.5;  ///< building surface where z - ground > this, metres; finite and > 0
    /// Parts of a smaller footprint are dropped (and holes below it filled), m^2; >= 0. 15: a garage or shed of
    /// 20 m^2 can hold the smallest PV system (8 m^2 of modules), and at 1 m cells its outline loses a few mixed
    /// edge cells, so the parts found are smaller than the footprint.
    double min_area_m2 = 15.0;
};

/// Candidate building parts of a surface model.
struct building_candidates_result {
    raster<std::int32_t> building_id;  ///< part of each cell, 1.. by decreasing area (ties by first cell); 0 = none
    raster<std::uint8_t> vegetation;   ///< vegetation cells as used (the mask grown into empty DSM cells next to it)
    std::size_t count = 0;             ///< number of parts (largest id)
};

/// Candidate building parts (dissertation 3.2.1): a cell is a candidate when its centre lies inside an edge
/// object's hull (terrain.in_hull), terrain.surface - terrain.ground > min_height_m, and it is not vegetation;
/// the vegetation mask (1 = vegetation; empty = none) is first grown into the DSM's NaN cells (no return) that
/// touch it (8-neighbours). 4-connected holes under min_area_m2 are filled; 4-connected parts under
/// min_area_m2 (at least one cell) are dropped; the rest are numbered by size, largest first. Heights in metres,
/// cell_m the cell size in metres. O(cells). Same result for any run.threads.
/// @throws invalid_input on bad options or cell_m, or if dsm, terrain and vegetation differ in shape.
template <raster_input In>
building_candidates_result building_candidates(const In& dsm, const ground_model_result& terrain, double cell_m,
                                               raster_view<const std::uint8_t> vegetation = {},
                                               const building_candidates_options& opt = {}, const execution& run = {});

/// Building parts of a given mask of building cells (1 = building, e.g. the cells where at least half of the
/// points carry the vendor's building class, ASPRS 6): 4-connected holes under min_area_m2 filled, 4-connected
/// parts under min_area_m2 dropped, the rest numbered by size, largest first (as building_candidates numbers
/// its parts; min_height_m is not used: the mask says what is building). The vegetation of the result is
/// empty (all 0). cell_m in metres. O(cells). Same result for any run.threads.
/// @throws invalid_input on bad options or cell_m.
inline building_candidates_result classified_building_parts(raster_view<const std::uint8_t> building_cells,
                                                            double cell_m, const building_candidates_options& opt = {},
                                                            const execution& run = {});

namespace detail {

inline void check_building_candidates(const building_candidates_options& opt, const char* function)
{
    require_positive(opt.min_height_m, function, "min_height_m");
    require(opt.min_area_m2 >= 0 && opt.min_area_m2 < 1e300, function, "min_area_m2", "finite and >= 0",
            opt.min_area_m2);
}

/// The fewest cells of cell_m metres that cover area_m2 (at least 1; huge areas clamp to more cells than any
/// raster holds).
inline std::size_t cells_covering(double area_m2, double cell_m)
{
    const double cells = std::ceil(area_m2 / (cell_m * cell_m) - 1e-9);
    if (!(cells < 1e18)) return std::size_t{1} << 60;  // more cells than any raster holds (and no UB in the cast)
    return std::max<std::size_t>(1, static_cast<std::size_t>(std::max(cells, 0.0)));
}

/// The fewest cells of a part building_candidates keeps (min_area_m2 in cells of cell_m, at least 1).
inline std::size_t min_part_cells(const building_candidates_options& opt, double cell_m)
{
    return cells_covering(opt.min_area_m2, cell_m);
}

/// The parts of a mask (nonzero = building) as building_candidates keeps them, written to `ids` (the mask's
/// shape): 4-connected holes under min_cells filled, parts under min_cells dropped, the rest numbered by size,
/// largest first. Returns their number.
inline std::size_t number_parts(raster_view<const std::uint8_t> mask, std::size_t min_cells, const execution& run,
                                raster<std::int32_t>& ids)
{
    const raster<std::uint8_t> filled = fill_holes(mask, min_cells - 1, connectivity::four);
    components parts = connected_components(
        filled, connected_components_options{.conn = connectivity::four, .run = {run.threads, {}}});
    rank_by_size(parts);
    std::size_t kept = 0;
    while (kept < parts.count() && parts.sizes[kept + 1] >= min_cells) ++kept;
    for (std::ptrdiff_t i = 0; i < ids.size(); ++i) {
        const auto l = static_cast<std::size_t>(parts.labels.data()[i]);
        ids.data()[i] = l <= kept ? static_cast<std::int32_t>(l) : 0;
    }
    return kept;
}

/// The vegetation mask as used: 1 where `vegetation` is 1, or where the DSM has no return and an 8-neighbour is
/// vegetation (leaves scatter the pulse: the hole under a crown belongs to the crown).
template <raster_input In>
raster<std::uint8_t> grown_vegetation(const In& dsm, raster_view<const std::uint8_t> vegetation)
{
    const std::ptrdiff_t rows = dsm.rows(), cols = dsm.cols();
    raster<std::uint8_t> out(rows, cols);
    if (vegetation.empty()) return out;
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            bool v = vegetation(r, c) != 0;
            if (!v && !std::isfinite(static_cast<float>(dsm(r, c)))) {
                for (std::ptrdiff_t dr = -1; dr <= 1 && !v; ++dr) {
                    for (std::ptrdiff_t dc = -1; dc <= 1 && !v; ++dc) {
                        const std::ptrdiff_t rr = r + dr, cc = c + dc;
                        v = rr >= 0 && cc >= 0 && rr < rows && cc < cols && vegetation(rr, cc) != 0;
                    }
                }
            }
            out(r, c) = v ? 1 : 0;
        }
    }
    return out;
}

}  // namespace detail

// ---- implementation ----

template <raster_input In>
building_candidates_result building_candidates(const In& dsm, const ground_model_result& terrain, double cell_m,
                                               raster_view<const std::uint8_t> vegetation,
                                               const building_candidates_options& opt, const execution& run)
{
    constexpr const char* function = "building_candidates";
    detail::require_positive(cell_m, function, "cell_m");
    detail::check_building_candidates(opt, function);
    detail::check_execution(run, function);
    detail::require_same_shape(dsm, terrain.surface, function, "dsm", "terrain");
    if (!vegetation.empty()) detail::require_same_shape(dsm, vegetation, function, "dsm", "vegetation");
    const std::ptrdiff_t rows = dsm.rows(), cols = dsm.cols();
    building_candidates_result out{raster<std::int32_t>(rows, cols), detail::grown_vegetation(dsm, vegetation), 0};
    raster<std::uint8_t> candidate(rows, cols);
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        for (std::ptrdiff_t c = 0; c < cols; ++c) {
            const bool high = static_cast<double>(terrain.surface(r, c)) - static_cast<double>(terrain.ground(r, c)) >
                              opt.min_height_m;
            candidate(r, c) = terrain.in_hull(r, c) && high && !out.vegetation(r, c) ? 1 : 0;
        }
    }
    out.count = detail::number_parts(candidate, detail::min_part_cells(opt, cell_m), run, out.building_id);
    return out;
}

inline building_candidates_result classified_building_parts(raster_view<const std::uint8_t> building_cells,
                                                            double cell_m, const building_candidates_options& opt,
                                                            const execution& run)
{
    constexpr const char* function = "classified_building_parts";
    detail::require_positive(cell_m, function, "cell_m");
    detail::check_building_candidates(opt, function);
    detail::check_execution(run, function);
    const std::ptrdiff_t rows = building_cells.rows(), cols = building_cells.cols();
    building_candidates_result out{raster<std::int32_t>(rows, cols), raster<std::uint8_t>(rows, cols), 0};
    out.count = detail::number_parts(building_cells, detail::min_part_cells(opt, cell_m), run, out.building_id);
    return out;
}

}  // namespace lidarfx
