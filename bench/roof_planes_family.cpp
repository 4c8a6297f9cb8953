// SPDX-License-Identifier: Apache-2.0
// Roof planes per pulse density (issue 39): roof_suitability's planes mode run the way `lidarfx roofs` runs it
// on LAS input, on the town family (synth/town_family.hpp: houses with flat, shed, gable and hip roofs of
// 5-55 degrees, garages and sheds of 20-42 m^2, trees over roofs), scored against the true planes.
// A plain program, not a benchmark:
//   roof_planes_family [--first 1] [--count 6] [--density 1.5,2,4,8,20] [--cell 1] [--worst 6]
// The program's route: highest point of each cell, gaps filled by ground_model (IDW), the DTM from the lowest
// class-2 point of each cell (the vendor's ground; --ground auto on a classified survey), the footprints the
// truth's (cell-centre rule). Truth planes count from a sloped area of 8 m^2 (the smallest PV system), as in
// bench/pv_accuracy; planes of 3-8 m^2 are reported on their own line.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include <lidarfx/core/las_class.hpp>
#include <lidarfx/kernels/points/rasterize.hpp>
#include <lidarfx/pipelines/buildings/ground_model.hpp>
#include <lidarfx/pipelines/pv/roof_suitability.hpp>
#include <lidarfx/synth/roof_metrics.hpp>
#include <lidarfx/synth/town_family.hpp>

namespace {

using namespace lidarfx;

struct settings {
    unsigned first_seed = 1;
    unsigned seed_count = 6;
    std::vector<double> densities{1.5, 2, 4, 8, 20};
    double cell_m = 1.0;
    std::size_t worst = 6;
};

/// Plane-level suitability and flat roofs, beyond synth::roof_scores.
struct plane_tally {
    std::size_t suitable_pitched = 0, suitable_pitched_found = 0;  ///< truly suitable planes >= 15 degrees
    std::size_t pitched_suitable_patches = 0, right_patches = 0;   ///< patches judged suitable and pitched
    std::size_t flat = 0, flat_reported_flat = 0;                  ///< true flat planes found, reported flat
    std::size_t small = 0, small_found = 0;                        ///< true planes of 3-8 m^2 sloped area
    void add(const plane_tally& o)
    {
        suitable_pitched += o.suitable_pitched, suitable_pitched_found += o.suitable_pitched_found;
        pitched_suitable_patches += o.pitched_suitable_patches, right_patches += o.right_patches;
        flat += o.flat, flat_reported_flat += o.flat_reported_flat;
        small += o.small, small_found += o.small_found;
    }
};

/// A family town as a synth::roof_town on its 1 m truth grid with the program's DSM and DTM.
synth::roof_town program_town(const synth::town_family_scene& town)
{
    const auto& t = town.town.truth;
    const auto cloud = town.town.points.cloud();
    const auto rasters = rasterize(cloud, t.g);
    ground_model_result ground = ground_model(rasters.max_z, t.g.cell);
    // The lowest class-2 point of each cell, as read_survey's class_ground.
    const raster<float> class_ground = rasterize(cloud, t.g, {.classes = {.include = {las_class::ground}}}).min_z;
    replace_ground(ground, class_ground.view(), t.g.cell);
    synth::roof_town out = synth::roof_town_from_truth(t, town.density_per_m2);
    out.dsm = std::move(ground.surface);
    out.dtm = std::move(ground.ground);
    return out;
}

/// Plane-level counts of `r` on `t` (see plane_tally).
void tally_planes(const synth::roof_town& t, const roof_suitability_result& r, const roof_suitability_options& o,
                  const synth::roof_scores& s, plane_tally& out)
{
    std::map<std::pair<std::int32_t, std::int32_t>, std::size_t> overlap;  // (plane, patch) -> cells
    std::map<std::int32_t, std::size_t> plane_cells;
    for (std::ptrdiff_t i = 0; i < t.plane_id.size(); ++i) {
        const auto tp = t.plane_id.data()[i], pp = r.patch_id.data()[i];
        if (tp > 0) ++plane_cells[tp];
        if (tp > 0 && pp > 0) ++overlap[{tp, pp}];
    }
    std::map<std::int32_t, std::pair<std::int32_t, std::size_t>> majority;  // patch -> (plane, cells)
    for (const auto& [key, n] : overlap) {
        auto& m = majority[key.second];
        if (n > m.second) m = {key.first, n};
    }
    std::map<std::int32_t, const synth::roof_town_plane*> plane_by_id;
    for (const auto& tp : t.planes) plane_by_id[tp.plane_id] = &tp;
    const auto truly_suitable_pitched = [&](const synth::roof_town_plane& tp) {
        return tp.tilt_deg >= o.flat_below_deg && synth::truth_suitable(tp, o);
    };
    std::map<std::int32_t, bool> found_suitable;
    for (const auto& p : r.patches) {
        if (!p.suitable || p.flat) continue;
        ++out.pitched_suitable_patches;
        const auto m = majority.find(p.patch_id);
        if (m == majority.end()) continue;
        const auto& tp = *plane_by_id.at(m->second.first);
        if (truly_suitable_pitched(tp)) {
            ++out.right_patches;
            found_suitable[tp.plane_id] = true;
        }
    }
    for (const auto& tp : t.planes) {
        if (tp.sloped_area_m2 >= 3 && tp.sloped_area_m2 < 8) {
            ++out.small;
            std::size_t best = 0;
            for (const auto& [key, n] : overlap)
                if (key.first == tp.plane_id && majority[key.second].first == tp.plane_id) best += n;
            out.small_found += 2 * best >= plane_cells[tp.plane_id] ? 1 : 0;
        }
        if (tp.sloped_area_m2 < 8 || !truly_suitable_pitched(tp)) continue;
        ++out.suitable_pitched;
        out.suitable_pitched_found += found_suitable[tp.plane_id] ? 1 : 0;
    }
    for (const auto& m : s.matches) {
        if (m.true_tilt != 0) continue;
        ++out.flat;
        out.flat_reported_flat += m.tilt < o.flat_below_deg ? 1 : 0;
    }
}

double share(std::size_t part, std::size_t whole)
{
    return whole == 0 ? 0.0 : static_cast<double>(part) / static_cast<double>(whole);
}

void print_row(const char* density, const synth::roof_scores& total, const plane_tally& planes)
{
    std::printf("%6s %6zu %6.3f %6.3f %6.3f %6.3f | %6zu %6.3f %6.3f | %6zu %6.3f | %zu %.3f\n", density,
                total.true_planes, total.found_share(), total.tilt5(), total.tilt10(), total.azimuth15(),
                planes.suitable_pitched, share(planes.suitable_pitched_found, planes.suitable_pitched),
                share(planes.right_patches, planes.pitched_suitable_patches), planes.flat,
                share(planes.flat_reported_flat, planes.flat), planes.small, share(planes.small_found, planes.small));
}

std::vector<double> parse_list(const char* text)
{
    std::vector<double> out;
    for (const char* p = text; *p != '\0';) {
        char* end = nullptr;
        out.push_back(std::strtod(p, &end));
        if (end == p) {
            std::fprintf(stderr, "roof_planes_family: not a number list: %s\n", text);
            std::exit(2);
        }
        p = *end == ',' ? end + 1 : end;
    }
    return out;
}

settings parse(int argc, char** argv)
{
    settings s;
    for (int k = 1; k < argc; ++k) {
        const auto value = [&]() -> const char* {
            if (k + 1 >= argc) {
                std::fprintf(stderr, "roof_planes_family: %s needs a value\n", argv[k]);
                std::exit(2);
            }
            return argv[++k];
        };
        if (std::strcmp(argv[k], "--first") == 0) {
            s.first_seed = static_cast<unsigned>(std::strtoul(value(), nullptr, 10));
        } else if (std::strcmp(argv[k], "--count") == 0) {
            s.seed_count = static_cast<unsigned>(std::strtoul(value(), nullptr, 10));
        } else if (std::strcmp(argv[k], "--density") == 0) {
            s.densities = parse_list(value());
        } else if (std::strcmp(argv[k], "--cell") == 0) {
            s.cell_m = parse_list(value()).at(0);
        } else if (std::strcmp(argv[k], "--worst") == 0) {
            s.worst = static_cast<std::size_t>(std::strtoul(value(), nullptr, 10));
        } else {
            std::fprintf(
                stderr, "usage: roof_planes_family [--first N] [--count N] [--density D,...] [--cell M] [--worst N]\n");
            std::exit(2);
        }
    }
    return s;
}

}  // namespace

int main(int argc, char** argv)
{
    const settings cfg = parse(argc, argv);
    std::printf("town family seeds %u-%u, %.2f m cells, planes mode, the program's DSM (highest point, IDW-filled)\n",
                cfg.first_seed, cfg.first_seed + cfg.seed_count - 1, cfg.cell_m);
    std::printf("%6s %6s %6s %6s %6s %6s | %6s %6s %6s | %6s %6s | %6s\n", "dens", "planes", "found", "tilt5", "tilt10",
                "az15", "suit", "found", "prec", "flat", "asflat", "3-8m2");
    synth::roof_scores pooled;
    plane_tally pooled_planes;
    for (const double density : cfg.densities) {
        synth::roof_scores total;
        plane_tally planes;
        std::vector<synth::roof_match> missed;  // the first cfg.worst true planes not found
        for (unsigned seed = cfg.first_seed; seed < cfg.first_seed + cfg.seed_count; ++seed) {
            synth::town_family_options fo;
            fo.seed = seed;
            fo.truth_cell_m = cfg.cell_m;
            fo.min_density = fo.max_density = density;
            const auto town = synth::town_family(fo);
            const synth::roof_town t = program_town(town);
            roof_suitability_options o;
            const auto r = roof_suitability(t.dsm, t.dtm, t.building_id, t.g, o);
            synth::roof_scores s;
            synth::score_roofs(t, r, o, s);
            tally_planes(t, r, o, s, planes);
            for (const auto& tp : t.planes) {
                const bool found = std::any_of(s.matches.begin(), s.matches.end(),
                                               [&](const synth::roof_match& m) { return m.plane_id == tp.plane_id; });
                if (!found && tp.sloped_area_m2 >= 8 && missed.size() < cfg.worst)
                    missed.push_back({static_cast<std::int32_t>(seed) * 1000 + tp.building_id, tp.plane_id,
                                      synth::roof_town_kind::flat, tp.tilt_deg, 0, tp.azimuth_deg, 0, tp.sloped_area_m2,
                                      0});
            }
            for (auto& m : s.matches) m.building_id += static_cast<std::int32_t>(seed) * 1000;
            total.add(s);
        }
        char label[16];
        std::snprintf(label, sizeof label, "%.1f", density);
        print_row(label, total, planes);
        pooled.add(total);
        pooled_planes.add(planes);
        auto worst = total.matches;
        std::sort(worst.begin(), worst.end(),
                  [](const auto& a, const auto& b) { return a.tilt_error() > b.tilt_error(); });
        for (std::size_t k = 0; k < std::min(cfg.worst, worst.size()); ++k)
            std::printf("    worst tilt: seed %d building %d tilt %.1f vs %.1f, azimuth %.0f vs %.0f, %.1f m2\n",
                        worst[k].building_id / 1000, worst[k].building_id % 1000, worst[k].tilt, worst[k].true_tilt,
                        worst[k].azimuth, worst[k].true_azimuth, worst[k].true_area);
        for (const auto& m : missed)
            std::printf("    missed: seed %d building %d, tilt %.1f, azimuth %.0f, %.1f m2\n", m.building_id / 1000,
                        m.building_id % 1000, m.true_tilt, m.true_azimuth, m.true_area);
        std::fflush(stdout);
    }
    print_row("all", pooled, pooled_planes);
    return 0;
}
