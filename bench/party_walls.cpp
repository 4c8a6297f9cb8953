// SPDX-License-Identifier: Apache-2.0
// Party walls: how extract_buildings splits the touching houses of terraced rows and semi-detached pairs in the
// town family (synth/town_family.hpp) at their shared walls, per pulse density, and whether it cuts single houses
// in two (synth/party_wall_metrics.hpp). extract_buildings runs as `lidarfx solar --facades` runs it on LAS input
// (bench/program_buildings.hpp). A plain program, not a benchmark:
//   party_walls [--seeds 401-412] [--density 1.5,2,4,8,20] [--terraces 3] [--pairs 3] [--cell 1] [--party-step 1]
// (--party-step inf: blocks never split, the route before party walls).
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <lidarfx/synth/party_wall_metrics.hpp>
#include <lidarfx/synth/town_family.hpp>

#include "program_buildings.hpp"

namespace {

using namespace lidarfx;

/// Command-line settings.
struct settings {
    unsigned first_seed = 401;                        ///< first town seed
    unsigned last_seed = 412;                         ///< last town seed (inclusive)
    std::vector<double> densities{1.5, 2, 4, 8, 20};  ///< pulses per m^2
    int terraces = 3;                                 ///< town_family_options::terraced_rows
    int pairs = 3;                                    ///< town_family_options::semi_detached_pairs
    double cell_m = 1.0;                              ///< grid cell (and truth cell), metres
    double party_step_m = 1.0;                        ///< party_walls_options::min_step_m (inf: never split)
};

/// The scores of one town.
struct town_result {
    unsigned seed = 0;                 ///< town seed
    synth::party_wall_scores scores;   ///< its counts
    std::size_t walls_left_whole = 0;  ///< separable walls not split
    /// Mistakes: separable walls not split, merged walls split, houses cut in two.
    std::size_t mistakes() const { return walls_left_whole + scores.walls_merged_split + scores.houses_split; }
};

/// The scores of the town of `seed` scanned at `density` pulses per m^2.
town_result run_town(const settings& set, unsigned seed, double density)
{
    synth::town_family_options o;
    o.seed = seed;
    o.min_density = o.max_density = density;
    o.terraced_rows = set.terraces;
    o.semi_detached_pairs = set.pairs;
    o.truth_cell_m = set.cell_m;
    const auto town = synth::town_family(o);
    const grid& g = town.town.truth.g;
    extract_buildings_options options;
    options.party_walls.min_step_m = set.party_step_m;
    const auto found = bench::program_buildings(bench::program_inputs_of(town.town.points.cloud(), g), g, options);
    town_result r;
    r.seed = seed;
    r.scores = synth::score_party_walls(town.town.truth, town.party_walls, found.building_id, g);
    r.walls_left_whole = r.scores.walls_separable - r.scores.walls_split;
    return r;
}

void print_header()
{
    std::printf("%-8s %6s | %6s %6s | %9s %6s | %7s %6s | %6s\n", "seed", "dens", "houses", "walls", "separable",
                "split", "merged", "split", "cut");
}

/// One line: `label` (a seed or "total"), the density and the counts.
void print_row(const char* label, double density, const synth::party_wall_scores& s)
{
    std::printf("%-8s %6.1f | %6zu %6zu | %9zu %6zu | %7zu %6zu | %6zu\n", label, density, s.row_houses,
                s.walls_separable + s.walls_merged, s.walls_separable, s.walls_split, s.walls_merged,
                s.walls_merged_split, s.houses_split);
    std::fflush(stdout);
}

[[noreturn]] void usage()
{
    std::fprintf(stderr,
                 "usage: party_walls [--seeds 401-412] [--density 1.5,2,4,8,20] [--terraces 3] [--pairs 3] [--cell 1] "
                 "[--party-step 1]\n");
    std::exit(2);
}

/// "401-412" (or "401") into the first and last seed.
void parse_seeds(const char* text, settings& s)
{
    char* end = nullptr;
    s.first_seed = static_cast<unsigned>(std::strtoul(text, &end, 10));
    s.last_seed = *end == '-' ? static_cast<unsigned>(std::strtoul(end + 1, &end, 10)) : s.first_seed;
    if (*end != '\0' || s.last_seed < s.first_seed) usage();
}

settings parse(int argc, char** argv)
{
    settings s;
    for (int i = 1; i < argc; ++i) {
        const bool has_value = i + 1 < argc;
        if (std::strcmp(argv[i], "--seeds") == 0 && has_value) {
            parse_seeds(argv[++i], s);
        } else if (std::strcmp(argv[i], "--density") == 0 && has_value) {
            s.densities = bench::parse_list(argv[++i]);
        } else if (std::strcmp(argv[i], "--terraces") == 0 && has_value) {
            s.terraces = std::atoi(argv[++i]);
        } else if (std::strcmp(argv[i], "--pairs") == 0 && has_value) {
            s.pairs = std::atoi(argv[++i]);
        } else if (std::strcmp(argv[i], "--cell") == 0 && has_value) {
            s.cell_m = std::strtod(argv[++i], nullptr);
        } else if (std::strcmp(argv[i], "--party-step") == 0 && has_value) {
            s.party_step_m = std::strtod(argv[++i], nullptr);
        } else {
            usage();
        }
    }
    if (s.terraces < 0 || s.pairs < 0 || !(s.cell_m > 0) || !(s.party_step_m > 0)) usage();
    return s;
}

}  // namespace

int main(int argc, char** argv)
{
    const settings set = parse(argc, argv);
    std::printf(
        "town family (200 m) with %d terraced rows and %d semi-detached pairs asked for, seeds %u-%u, %.2f m cells; "
        "extract_buildings as lidarfx solar --facades runs it on LAS input, party walls at %.2f m steps\n",
        set.terraces, set.pairs, set.first_seed, set.last_seed, set.cell_m, set.party_step_m);
    std::printf(
        "houses: row and pair houses placed; walls: party walls; separable: walls with a roof step > %.1f m "
        "along >= %.0f %% of them, split: of them, the two houses' dominant found buildings (>= %.0f %% of "
        "a house) differ; merged: the other walls (one roof to the eye), split: split anyway; cut: truth "
        "buildings (all) two or more found buildings each cover >= %.0f m^2 of\n",
        synth::party_wall_step_m, 100 * synth::separable_step_share, 100 * synth::dominant_cover_share,
        synth::split_piece_m2);
    print_header();
    for (const double density : set.densities) {
        synth::party_wall_scores total;
        town_result worst;
        bool any = false;
        for (unsigned seed = set.first_seed; seed <= set.last_seed; ++seed) {
            const town_result r = run_town(set, seed, density);
            print_row(std::to_string(seed).c_str(), density, r.scores);
            total.add(r.scores);
            if (!any || r.mistakes() > worst.mistakes()) worst = r;
            any = true;
        }
        print_row("total", density, total);
        std::printf(
            "worst town at %.1f per m^2: seed %u (%zu separable walls left whole, %zu merged walls split, "
            "%zu houses cut)\n",
            density, worst.seed, worst.walls_left_whole, worst.scores.walls_merged_split, worst.scores.houses_split);
    }
    return 0;
}
