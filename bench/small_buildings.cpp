// SPDX-License-Identifier: Apache-2.0
// Small buildings (issue 39): how many garages and sheds of 20-50 m^2 extract_buildings finds in the town
// family (synth/town_family.hpp), per pulse density and cell size, for several building_candidates
// min_area_m2, with what lowering the minimum costs (precision, false buildings, trees taken for buildings).
// A plain program, not a benchmark:
//   small_buildings [--first 1] [--count 20] [--density 1.5,2,4,8,20] [--cell 0.5,1] [--min-area 50,20,15]
//                   [--returns | --program | --no-mask] [--overhanging SHARE] [--no-under-crowns]
// By default extract_buildings gets the first returns' multiple_returns mask as its vegetation mask (as
// tests/pipelines/buildings/extract_buildings_towns.cpp does); --returns runs the overload that counts split
// pulses (pulse_returns); --program runs it as lidarfx solar --facades does on LAS input (every return binned,
// the terrain from the class-2 points filled by fill_ground, each building's rim decided by the points raised
// above it); --no-mask gives it no return information (trees are rejected by roughness alone). --overhanging gives
// that share of the houses a tree whose crown reaches over the roof (town_family_options::overhanging_tree_share);
// --no-under-crowns runs the program's route without the lowest raised points (no roof looked for under crowns).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include <lidarfx/core/las_class.hpp>
#include <lidarfx/kernels/interpolate/idw_fill.hpp>
#include <lidarfx/kernels/points/count_points_above.hpp>
#include <lidarfx/kernels/points/rasterize.hpp>
#include <lidarfx/pipelines/buildings/extract_buildings.hpp>
#include <lidarfx/synth/town_family.hpp>

#include "program_buildings.hpp"

namespace {

using namespace lidarfx;

/// What extract_buildings learns of the returns.
enum class vegetation_input {
    mask,          ///< the first returns' multiple_returns raster as the vegetation mask
    pulse_counts,  ///< the pulse_returns overload (points and split-pulse points per cell)
    program,       ///< as lidarfx solar --facades on LAS: every return, class-2 terrain, the rim by raised points
    none           ///< nothing: trees are told from roofs by roughness alone
};

const char* describe(vegetation_input v)
{
    return v == vegetation_input::mask           ? "the first returns' multiple_returns mask"
           : v == vegetation_input::pulse_counts ? "pulse counts (pulse_returns)"
           : v == vegetation_input::program
               ? "the program's route (every return, class-2 terrain, pulse counts, the rim by raised points)"
               : "no return information (roughness alone)";
}

/// Command-line settings.
struct settings {
    unsigned first_seed = 1;                               ///< first town seed
    unsigned seed_count = 20;                              ///< towns per density and cell size
    std::vector<double> densities{1.5, 2, 4, 8, 20};       ///< pulses per m^2
    std::vector<double> cells{0.5, 1.0};                   ///< raster cell sizes, metres
    std::vector<double> min_areas{50, 20, 15};             ///< building_candidates min_area_m2 values, m^2
    vegetation_input vegetation = vegetation_input::mask;  ///< what extract_buildings learns of the returns
    double overhanging = 0;                                ///< town_family_options::overhanging_tree_share
    bool under_crowns = true;  ///< --program: the lowest raised points given (the roof under crowns looked for)
};

/// Totals of one (cell, density, min_area) over the seeds.
struct tally {
    std::size_t small = 0, small_found = 0;  ///< truth buildings with 20 <= footprint < 50 m^2
    std::size_t small_flat = 0, small_flat_found = 0;
    double small_iou_sum = 0;                         ///< IoU with the best detected building, over found small ones
    std::size_t all = 0, all_found = 0;               ///< every truth building
    std::size_t detected_cells = 0, true_cells = 0;   ///< detected building cells, of them truth building cells
    std::size_t detected = 0;                         ///< detected buildings
    std::size_t false_buildings = 0;                  ///< detected buildings < 50 % on truth buildings
    std::size_t false_on_trees = 0;                   ///< of them, mostly on canopy (truth surface)
    std::size_t false_small = 0;                      ///< of them, under 50 m^2
    double false_area_m2 = 0;                         ///< their area
    std::size_t trees = 0, trees_hit = 0;             ///< trees with >= 2 m^2 of visible crown in detected buildings
    std::size_t over_trees = 0, over_trees_hit = 0;   ///< of them, trees whose crowns reach over roofs
    std::size_t covered_roof = 0, covered_found = 0;  ///< truth roof cells under a crown, of them building cells
};

/// Area of a closed ring, m^2 (shoelace).
double ring_area(const std::vector<std::array<double, 2>>& ring)
{
    double twice = 0;
    for (std::size_t i = 0; i + 1 < ring.size(); ++i) {
        twice += ring[i][0] * ring[i + 1][1] - ring[i + 1][0] * ring[i][1];
    }
    return 0.5 * std::abs(twice);
}

/// Trees with >= 2 m^2 of visible crown (not under a truth roof) in detected buildings, as in
/// extract_buildings_towns.cpp.
std::size_t trees_taken_for_buildings(const synth::scene_truth& t, const std::vector<synth::tree>& trees,
                                      const raster<std::int32_t>& found)
{
    std::size_t hit = 0;
    for (const auto& tr : trees)
        hit += static_cast<double>(synth::crown_cells_in_buildings(tr, t, found)) * t.g.cell * t.g.cell >= 2.0 ? 1 : 0;
    return hit;
}

/// Scores detected buildings `found` (count of them) against the town's truth into `s`.
void score(const synth::town_family_scene& town, const raster<std::int32_t>& found, std::size_t count, tally& s)
{
    const auto& t = town.town.truth;
    const double cell2 = t.g.cell * t.g.cell;
    const std::size_t nb = t.footprints.size();
    std::vector<std::size_t> truth_cells(nb + 1, 0), truth_covered(nb + 1, 0), found_cells(count + 1, 0),
        found_on_truth(count + 1, 0), found_on_canopy(count + 1, 0);
    std::vector<std::map<std::int32_t, std::size_t>> overlap(nb + 1);
    for (std::ptrdiff_t i = 0; i < t.building_id.size(); ++i) {
        const auto tb = static_cast<std::size_t>(t.building_id.data()[i]);
        const auto db = static_cast<std::size_t>(found.data()[i]);
        ++truth_cells[tb];
        ++found_cells[db];
        if (db > 0) {
            ++s.detected_cells;
            if (tb > 0) {
                ++s.true_cells;
                ++found_on_truth[db];
                ++truth_covered[tb];
                ++overlap[tb][static_cast<std::int32_t>(db)];
            }
            if (t.surface.data()[i] == las_class::high_vegetation) ++found_on_canopy[db];
        }
        if (tb > 0 && t.surface.data()[i] == las_class::high_vegetation) {  // a roof under a crown
            ++s.covered_roof;
            s.covered_found += db > 0 ? 1 : 0;
        }
    }
    std::vector<bool> flat(nb + 1, false);
    for (const auto& p : t.roof_planes) flat[static_cast<std::size_t>(p.building_id)] = p.tilt_deg == 0;
    for (std::size_t k = 1; k <= nb; ++k) {
        const double area = ring_area(t.footprints[k - 1]);
        const bool is_found = truth_cells[k] > 0 && 2 * truth_covered[k] >= truth_cells[k];
        ++s.all;
        s.all_found += is_found ? 1 : 0;
        if (area < 20 || area >= 50) continue;
        ++s.small;
        s.small_flat += flat[k] ? 1 : 0;
        if (!is_found) continue;
        ++s.small_found;
        s.small_flat_found += flat[k] ? 1 : 0;
        std::size_t best = 0, best_n = 0;
        for (const auto& [d, n] : overlap[k]) {
            if (n > best_n) {
                best = static_cast<std::size_t>(d);
                best_n = n;
            }
        }
        s.small_iou_sum +=
            static_cast<double>(best_n) / static_cast<double>(truth_cells[k] + found_cells[best] - best_n);
    }
    s.detected += count;
    for (std::size_t d = 1; d <= count; ++d) {
        if (2 * found_on_truth[d] >= found_cells[d]) continue;
        ++s.false_buildings;
        s.false_on_trees += 2 * found_on_canopy[d] >= found_cells[d] ? 1 : 0;
        s.false_small += static_cast<double>(found_cells[d]) * cell2 < 50 ? 1 : 0;
        s.false_area_m2 += static_cast<double>(found_cells[d]) * cell2;
    }
    s.trees += town.trees.size();
    s.trees_hit += trees_taken_for_buildings(t, town.trees, found);
    std::vector<synth::tree> over;
    std::copy_if(town.trees.begin(), town.trees.end(), std::back_inserter(over),
                 [](const synth::tree& tr) { return tr.over_roofs; });
    s.over_trees += over.size();
    s.over_trees_hit += trees_taken_for_buildings(t, over, found);
}

/// Buildings of a town, rasterized on its truth grid (first returns, highest z per cell).
extract_buildings_result buildings_of(const synth::town_family_scene& town, const rasterize_result& dsm,
                                      double min_area_m2, vegetation_input vegetation)
{
    extract_buildings_options o;
    o.candidates.min_area_m2 = min_area_m2;
    const grid& g = town.town.truth.g;
    if (vegetation == vegetation_input::pulse_counts) {
        const pulse_returns returns{dsm.count.view(), dsm.multiple_return_count.view()};
        return extract_buildings(dsm.max_z, g, {}, returns, o);
    }
    if (vegetation == vegetation_input::none) return extract_buildings(dsm.max_z, g, o);
    return extract_buildings(dsm.max_z, g, {}, dsm.multiple_returns, o);
}

double share(std::size_t part, std::size_t whole)
{
    return whole == 0 ? 0.0 : static_cast<double>(part) / static_cast<double>(whole);
}

void print_header()
{
    std::printf("%5s %6s %6s | %5s %7s %6s %7s %6s | %5s %7s | %7s %6s | %6s %5s %5s %8s | %s\n", "cell", "dens",
                "minA", "small", "found", "flat", "shed", "IoU", "all", "found", "prec", "det", "false", "tree", "<50",
                "false_m2", "trees hit (over roofs), roof under crowns found");
}

void print_row(double cell, double density, double min_area, const tally& s)
{
    const std::size_t shed = s.small - s.small_flat, shed_found = s.small_found - s.small_flat_found;
    std::printf(
        "%5.2f %6.1f %6.0f | %5zu %7.3f %6.3f %7.3f %6.3f | %5zu %7.3f | %7.4f %6zu | %6zu %5zu %5zu %8.0f | "
        "%zu/%zu (%zu/%zu), %zu/%zu\n",
        cell, density, min_area, s.small, share(s.small_found, s.small), share(s.small_flat_found, s.small_flat),
        share(shed_found, shed), s.small_found ? s.small_iou_sum / static_cast<double>(s.small_found) : 0.0, s.all,
        share(s.all_found, s.all), share(s.true_cells, s.detected_cells), s.detected, s.false_buildings,
        s.false_on_trees, s.false_small, s.false_area_m2, s.trees_hit, s.trees, s.over_trees_hit, s.over_trees,
        s.covered_found, s.covered_roof);
    std::fflush(stdout);
}

settings parse(int argc, char** argv)
{
    settings s;
    for (int i = 1; i < argc; ++i) {
        const bool has_value = i + 1 < argc;
        if (std::strcmp(argv[i], "--first") == 0 && has_value) {
            s.first_seed = static_cast<unsigned>(std::strtoul(argv[++i], nullptr, 10));
        } else if (std::strcmp(argv[i], "--count") == 0 && has_value) {
            s.seed_count = static_cast<unsigned>(std::strtoul(argv[++i], nullptr, 10));
        } else if (std::strcmp(argv[i], "--density") == 0 && has_value) {
            s.densities = bench::parse_list(argv[++i]);
        } else if (std::strcmp(argv[i], "--cell") == 0 && has_value) {
            s.cells = bench::parse_list(argv[++i]);
        } else if (std::strcmp(argv[i], "--min-area") == 0 && has_value) {
            s.min_areas = bench::parse_list(argv[++i]);
        } else if (std::strcmp(argv[i], "--returns") == 0) {
            s.vegetation = vegetation_input::pulse_counts;
        } else if (std::strcmp(argv[i], "--program") == 0) {
            s.vegetation = vegetation_input::program;
        } else if (std::strcmp(argv[i], "--no-mask") == 0) {
            s.vegetation = vegetation_input::none;
        } else if (std::strcmp(argv[i], "--no-under-crowns") == 0) {
            s.under_crowns = false;
        } else if (std::strcmp(argv[i], "--overhanging") == 0 && has_value) {
            s.overhanging = std::strtod(argv[++i], nullptr);
        } else {
            std::fprintf(stderr,
                         "usage: small_buildings [--first N] [--count K] [--density 1.5,2,4,8,20] [--cell 0.5,1] "
                         "[--min-area 50,20,15] [--returns | --program | --no-mask] [--overhanging SHARE] "
                         "[--no-under-crowns]\n");
            std::exit(2);
        }
    }
    return s;
}

}  // namespace

int main(int argc, char** argv)
{
    const settings set = parse(argc, argv);
    std::printf(
        "town family (200 m, garages and sheds %.2f per house, trees over %.2f of the houses' roofs), seeds "
        "%u-%u; extract_buildings with %s\n",
        synth::town_family_options{}.small_buildings_per_house, set.overhanging, set.first_seed,
        set.first_seed + set.seed_count - 1, describe(set.vegetation));
    std::printf(
        "small: truth buildings of 20-50 m^2 (found: >= 50 %% of their cells are building cells; flat / "
        "shed roofs; IoU: mean over the found, with the best-overlapping building); all: every truth "
        "building; prec: building cells on truth buildings; det: buildings found; false: found buildings "
        "< 50 %% on truth buildings (tree: mostly on canopy, <50: under 50 m^2); trees hit: trees with >= 2 "
        "m^2 of crown outside roofs in buildings (in brackets: trees whose crowns reach over roofs); roof under "
        "crowns found: truth roof cells under a crown that are building cells. The family has no cars.\n");
    print_header();
    for (const double cell : set.cells) {
        for (const double density : set.densities) {
            std::vector<tally> totals(set.min_areas.size());
            for (unsigned seed = set.first_seed; seed < set.first_seed + set.seed_count; ++seed) {
                synth::town_family_options o;
                o.seed = seed;
                o.min_density = o.max_density = density;
                o.truth_cell_m = cell;
                o.overhanging_tree_share = set.overhanging;
                const auto town = synth::town_family(o);
                rasterize_options first;
                first.returns = return_selection::first;
                const grid& g = town.town.truth.g;
                if (set.vegetation == vegetation_input::program) {
                    const auto inputs = bench::program_inputs_of(town.town.points.cloud(), g);
                    for (std::size_t m = 0; m < set.min_areas.size(); ++m) {
                        extract_buildings_options eo;
                        eo.candidates.min_area_m2 = set.min_areas[m];
                        const auto b = bench::program_buildings(inputs, g, eo, set.under_crowns);
                        score(town, b.building_id, b.buildings.size(), totals[m]);
                    }
                    continue;
                }
                const auto dsm = rasterize(town.town.points.cloud(), g, first);
                for (std::size_t m = 0; m < set.min_areas.size(); ++m) {
                    const auto b = buildings_of(town, dsm, set.min_areas[m], set.vegetation);
                    score(town, b.building_id, b.buildings.size(), totals[m]);
                }
            }
            for (std::size_t m = 0; m < set.min_areas.size(); ++m)
                print_row(cell, density, set.min_areas[m], totals[m]);
        }
    }
    return 0;
}
