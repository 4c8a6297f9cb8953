// SPDX-License-Identifier: Apache-2.0
// extract_buildings on family towns with dormers and houses cut by the survey's edge: a dormer house stays one
// building, an edge house is found and clipped, and no other building is.
#include <doctest/doctest.h>

#include <lidarfx/kernels/points/rasterize.hpp>
#include <lidarfx/pipelines/buildings/extract_buildings.hpp>
#include <lidarfx/synth/town_family.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

using namespace lidarfx;

namespace {

/// Cells of each truth building (index = id) and of each detected building, and their overlaps.
struct dormer_edge_overlaps {
    std::vector<std::size_t> truth_cells, found_cells;
    std::vector<std::map<std::int32_t, std::size_t>> overlap;  ///< truth id -> detected id -> cells

    /// The detected building overlapping truth building `id` most, and its IoU (0, 0 when none).
    std::pair<std::int32_t, double> best(std::int32_t id) const
    {
        std::int32_t best_id = 0;
        std::size_t best_n = 0;
        for (const auto& [d, n] : overlap[static_cast<std::size_t>(id)]) {
            if (n > best_n) {
                best_id = d;
                best_n = n;
            }
        }
        if (best_id == 0) return {0, 0.0};
        const std::size_t join =
            truth_cells[static_cast<std::size_t>(id)] + found_cells[static_cast<std::size_t>(best_id)] - best_n;
        return {best_id, static_cast<double>(best_n) / static_cast<double>(join)};
    }

    /// Cells of truth building `id` in the detected building that overlaps it second most.
    std::size_t second(std::int32_t id) const
    {
        std::vector<std::size_t> n;
        for (const auto& [d, cells] : overlap[static_cast<std::size_t>(id)]) n.push_back(cells);
        std::sort(n.rbegin(), n.rend());
        return n.size() > 1 ? n[1] : 0;
    }
};

dormer_edge_overlaps dormer_edge_overlap_counts(const raster<std::int32_t>& truth, const raster<std::int32_t>& found,
                                                std::size_t truth_count, std::size_t found_count)
{
    dormer_edge_overlaps o;
    o.truth_cells.assign(truth_count + 1, 0);
    o.found_cells.assign(found_count + 1, 0);
    o.overlap.resize(truth_count + 1);
    for (std::ptrdiff_t i = 0; i < truth.size(); ++i) {
        const auto t = truth.data()[i], d = found.data()[i];
        ++o.truth_cells[static_cast<std::size_t>(t)];
        ++o.found_cells[static_cast<std::size_t>(d)];
        if (t > 0 && d > 0) ++o.overlap[static_cast<std::size_t>(t)][d];
    }
    return o;
}

/// Per id (index = id): whether building id of `ids` has a cell on the raster's border.
std::vector<bool> dormer_edge_on_border(const raster<std::int32_t>& ids, std::size_t count)
{
    std::vector<bool> border(count + 1, false);
    for (std::ptrdiff_t r = 0; r < ids.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < ids.cols(); ++c) {
            if (r == 0 || c == 0 || r + 1 == ids.rows() || c + 1 == ids.cols())
                border[static_cast<std::size_t>(ids(r, c))] = true;
        }
    }
    return border;
}

}  // namespace

TEST_CASE("extract_buildings/family: dormer houses stay whole, edge houses are found and clipped (seeds 31-33)")
{
    // Both ways of telling trees (a mask of split first returns; the share of split pulses, the program's way on
    // LAS input), as extract_buildings_towns.cpp runs them.
    std::size_t dormer_houses = 0, edge_houses = 0;
    for (unsigned seed = 31; seed <= 33; ++seed) {
        CAPTURE(seed);
        synth::town_family_options o;
        o.seed = seed;
        o.dormer_share = 0.6;
        o.edge_buildings = 3;
        const auto town = synth::town_family(o);
        const auto& t = town.town.truth;
        const grid g = t.g;
        rasterize_options first;
        first.returns = return_selection::first;
        const auto dsm = rasterize(town.town.points.cloud(), g, first);
        const auto every = rasterize(town.town.points.cloud(), g);
        const std::size_t nb = t.footprints.size();
        REQUIRE(town.buildings.size() == nb);
        const double cell2 = g.cell * g.cell;
        const auto truth_border = dormer_edge_on_border(t.building_id, nb);
        for (const bool by_returns : {false, true}) {
            CAPTURE(by_returns);
            const auto b = by_returns ? extract_buildings(dsm.max_z, g, {},
                                                          pulse_returns{every.count, every.multiple_return_count})
                                      : extract_buildings(dsm.max_z, g, {}, dsm.multiple_returns);
            const auto ov = dormer_edge_overlap_counts(t.building_id, b.building_id, nb, b.buildings.size());
            const auto found_border = dormer_edge_on_border(b.building_id, b.buildings.size());
            for (const auto& house : town.buildings) {
                const std::int32_t id = house.id;
                CAPTURE(id);
                const auto [found, iou] = ov.best(id);
                const bool edge = truth_border[static_cast<std::size_t>(id)];
                CHECK(edge == (static_cast<std::size_t>(id) + 3 > nb));  // the edge buildings are the last three
                const std::string way = by_returns ? "returns" : "mask";
                if (!house.dormers.empty()) {
                    dormer_houses += by_returns ? 0 : 1;
                    const auto& d = house.dormers.front();
                    const double second_m2 = static_cast<double>(ov.second(id)) * cell2;
                    const double step = 2 * d.hv * std::tan(house.tilt_deg * std::numbers::pi / 180) - d.front_drop_m;
                    MESSAGE("seed " << seed << " (" << town.density_per_m2 << " pts/m2, " << way << ") house " << id
                                    << " (" << std::string(house.kind == synth::roof_kind_truth::hip ? "hip" : "gable")
                                    << ", tilt " << house.tilt_deg << " deg, " << house.dormers.size() << " dormers "
                                    << 2 * d.hu << " x " << 2 * d.hv << " m, step " << step << " m): IoU " << iou
                                    << ", second building " << second_m2 << " m2");
                    CHECK(iou > 0.5);
                    CHECK(second_m2 < 15.0);
                }
                if (edge) {
                    edge_houses += by_returns ? 0 : 1;
                    MESSAGE("seed " << seed << " (" << way << ") edge house " << id << ": IoU " << iou << ", clipped "
                                    << (found > 0 && b.buildings[static_cast<std::size_t>(found - 1)].clipped));
                    CHECK(iou > 0.5);
                    if (found > 0) CHECK(b.buildings[static_cast<std::size_t>(found - 1)].clipped);
                } else if (found > 0 &&
                           static_cast<double>(ov.truth_cells[static_cast<std::size_t>(id)]) * cell2 >= 20.0) {
                    CHECK_FALSE(b.buildings[static_cast<std::size_t>(found - 1)].clipped);
                }
            }
            // A detected building is clipped exactly when it has a cell on the border.
            for (const auto& rec : b.buildings) {
                CAPTURE(rec.id);
                CHECK(rec.clipped == found_border[static_cast<std::size_t>(rec.id)]);
            }
        }
    }
    CHECK(dormer_houses >= 6);
    CHECK(edge_houses == 9);
}
