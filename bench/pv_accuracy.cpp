// SPDX-License-Identifier: Apache-2.0
// Prints the accuracy table of docs/pv.md: roof_suitability in planes and paper mode on the randomized roof
// towns (synth/roof_towns.hpp) of the reporting seeds 4-9 (parameters were chosen on seeds 1-3: pass
// `--tuning` to score those), with the rooftop PV paper's metrics and the worst planes.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include <lidarfx/kernels/points/rasterize.hpp>
#include <lidarfx/pipelines/pv/roof_suitability.hpp>
#include <lidarfx/synth/roof_metrics.hpp>
#include <lidarfx/synth/roof_towns.hpp>
#include <lidarfx/synth/scenes.hpp>

namespace {

/// The project's town (synth::town_scene, 2 points/m^2) as a roof town: DSM = highest point of each 1 m cell,
/// DTM = the truth ground, footprints and planes from the truth (sloped areas of whole faces).
lidarfx::synth::roof_town project_town(unsigned seed)
{
    using namespace lidarfx;
    synth::scene_options so;
    so.seed = seed;
    so.truth_cell_m = 1.0;
    const auto sc = synth::town_scene(so);
    synth::roof_town t = synth::roof_town_from_truth(sc.truth, so.density_per_m2);
    t.dsm = rasterize(sc.points.cloud(), t.g).max_z;
    t.dtm = sc.truth.ground_z;
    return t;
}

}  // namespace

int main(int argc, char** argv)
{
    using namespace lidarfx;
    const bool tuning = argc > 1 && std::strcmp(argv[1], "--tuning") == 0;
    const unsigned first = tuning ? 1 : 4, last = tuning ? 3 : 9;
    std::printf("roof towns, seeds %u-%u, 36 buildings each, 1 m cells\n", first, last);
    std::printf("%-7s %7s %7s %7s %7s %7s %7s %7s %7s %7s %7s\n", "mode", "planes", "found", "tilt5", "tilt10", "az15",
                "az45", "recall", "prec", "areaRMSE", "density");
    for (const roof_mode mode : {roof_mode::planes, roof_mode::paper}) {
        {
            const auto town = project_town(1);
            roof_suitability_options o;
            o.mode = mode;
            const auto r = roof_suitability(town.dsm, town.dtm, town.building_id, town.g, o);
            synth::roof_scores s;
            synth::score_roofs(town, r, o, s);
            std::printf(
                "  project town (town_scene seed 1, %zu buildings, 2 pts/m2, max z in 1 m cells): found %.3f tilt5 "
                "%.3f "
                "tilt10 %.3f az15 %.3f recall %.3f prec %.3f area %.3f\n",
                town.buildings.size(), s.found_share(), s.tilt5(), s.tilt10(), s.azimuth15(), s.recall(), s.precision(),
                s.area_rmse());
        }
        synth::roof_scores total;
        for (unsigned seed = first; seed <= last; ++seed) {
            synth::roof_town_options to;
            to.seed = seed;
            const auto town = synth::make_roof_town(to);
            roof_suitability_options o;
            o.mode = mode;
            const auto r = roof_suitability(town.dsm, town.dtm, town.building_id, town.g, o);
            synth::roof_scores s;
            synth::score_roofs(town, r, o, s);
            std::printf(
                "  seed %u: found %.3f tilt5 %.3f tilt10 %.3f az15 %.3f recall %.3f prec %.3f area %.3f  (%.1f "
                "pts/m2)\n",
                seed, s.found_share(), s.tilt5(), s.tilt10(), s.azimuth15(), s.recall(), s.precision(), s.area_rmse(),
                town.density_per_m2);
            for (auto& m : s.matches) m.building_id += static_cast<std::int32_t>(seed) * 1000;
            total.add(s);
        }
        std::printf("%-7s %7zu %7.3f %7.3f %7.3f %7.3f %7.3f %7.3f %7.3f %7.3f\n",
                    mode == roof_mode::planes ? "planes" : "paper", total.true_planes, total.found_share(),
                    total.tilt5(), total.tilt10(), total.azimuth15(), total.azimuth45(), total.recall(),
                    total.precision(), total.area_rmse());
        auto worst = total.matches;
        std::sort(worst.begin(), worst.end(),
                  [](const auto& a, const auto& b) { return a.tilt_error() > b.tilt_error(); });
        for (std::size_t k = 0; k < std::min<std::size_t>(4, worst.size()); ++k)
            std::printf("    worst tilt: seed %d building %d (%s) tilt %.1f vs %.1f\n", worst[k].building_id / 1000,
                        worst[k].building_id % 1000, synth::kind_name(worst[k].kind), worst[k].tilt,
                        worst[k].true_tilt);
        std::erase_if(worst, [](const auto& m) { return m.true_tilt < 5; });  // no azimuth on flat planes
        std::sort(worst.begin(), worst.end(),
                  [](const auto& a, const auto& b) { return a.azimuth_error() > b.azimuth_error(); });
        for (std::size_t k = 0; k < std::min<std::size_t>(4, worst.size()); ++k)
            std::printf("    worst azimuth: seed %d building %d (%s) azimuth %.1f vs %.1f (tilt %.1f)\n",
                        worst[k].building_id / 1000, worst[k].building_id % 1000, synth::kind_name(worst[k].kind),
                        worst[k].azimuth, worst[k].true_azimuth, worst[k].true_tilt);
        std::sort(worst.begin(), worst.end(), [](const auto& a, const auto& b) {
            return std::fabs(a.area / a.true_area - 1) > std::fabs(b.area / b.true_area - 1);
        });
        for (std::size_t k = 0; k < std::min<std::size_t>(4, worst.size()); ++k)
            std::printf("    worst area: seed %d building %d (%s) %.1f vs %.1f m2\n", worst[k].building_id / 1000,
                        worst[k].building_id % 1000, synth::kind_name(worst[k].kind), worst[k].area,
                        worst[k].true_area);
    }
    return 0;
}
