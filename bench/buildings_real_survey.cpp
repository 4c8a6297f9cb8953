// SPDX-License-Identifier: Apache-2.0
// Scores extract_buildings on a real classified survey against the survey's own building class (ASPRS 6) and,
// when given, independent footprint polygons. Run by bench/buildings_real_surveys.sh.
//   buildings_real_survey SURVEY.las|laz... [--cell M] [--ground model|class2|filter] [--vegetation returns|any]
//                         [--rim points|dsm] [--under-crowns on|off] [--min-area M2] [--party-step M] [--party-share S]
//                         [--footprints FILE]
//                         [--truth-ignore CLASS]...
//                         [--map OUT.asc]
// The surface is built as `lidarfx solar --facades` builds it: the highest return per cell (NaN cells filled
// by IDW), isolated spikes and pits removed. Trees are told from roofs by the share of split pulses
// (extract_buildings with pulse_returns, the default) or, with --vegetation any, every cell holding a point of
// a split pulse is vegetation and rough parts are dropped. The terrain is ground_model's (hull and IDW), or
// with --ground class2 the lowest class-2 point per cell, or with --ground filter morphological_ground's cells
// of the lowest point per cell (the classes unused). With a given terrain (class2, filter) each building's rim
// is decided by the share of its points raised above it (refine_building_rim); --rim dsm leaves it to the DSM.
// With the rim by the points, the roof under overhanging crowns is found by the lowest raised points
// (join_roof_under_crowns), as the program does; --under-crowns off leaves it out.
// Truth, on the cells with points (noise, classes 7 and 18, and the --truth-ignore classes left out):
//   - class truth: a cell is building when at least half of its points are class 6;
//   - polygon truth (--footprints, any file the program reads footprints from): the cell's centre lies inside
//     a footprint (even-odd over its rings).
// Prints, per truth, recall and precision by area (the share of true building area found, of found area that
// is building), IoU, the true and found areas in m² and the buildings found.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <map>
#include <string>
#include <vector>

#include <lidarfx/core/raster.hpp>
#include <lidarfx/kernels/filter/surface_outliers.hpp>
#include <lidarfx/kernels/interpolate/idw_fill.hpp>
#include <lidarfx/kernels/points/count_points_above.hpp>
#include <lidarfx/kernels/points/rasterize.hpp>
#include <lidarfx/kernels/vector/burn_polygons.hpp>
#include <lidarfx/pipelines/buildings/extract_buildings.hpp>
#include <lidarfx/pipelines/buildings/morphological_ground.hpp>

#include "io/ascii_grid.hpp"
#include "io/footprints.hpp"
#include "io/las.hpp"

using namespace lidarfx;

namespace {

// The points the rasters were made of (noise, classes 7 and 18, left out), as a point cloud.
struct kept_points {
    const io::las_points& all;
    std::vector<std::size_t> index;
    std::size_t size() const { return index.size(); }
    double x(std::size_t i) const { return all.x[index[i]]; }
    double y(std::size_t i) const { return all.y[index[i]]; }
    double z(std::size_t i) const { return all.z[index[i]]; }
};

struct scores {
    std::size_t tp = 0, fp = 0, fn = 0;
};

void print_scores(const char* what, const scores& s, double cell_area)
{
    const auto pct = [](std::size_t a, std::size_t b) {
        return b ? 100.0 * static_cast<double>(a) / static_cast<double>(b) : NAN;
    };
    std::printf("%s: building true %.0f m2, found %.0f m2: recall %.2f %%, precision %.2f %%, IoU %.2f %%\n", what,
                static_cast<double>(s.tp + s.fn) * cell_area, static_cast<double>(s.tp + s.fp) * cell_area,
                pct(s.tp, s.tp + s.fn), pct(s.tp, s.tp + s.fp), pct(s.tp, s.tp + s.fp + s.fn));
}

}  // namespace

/// Buildings one by one against the footprint polygons (`footprints` labels each polygon's cells): of the
/// footprints of >= 15 m^2 that one found building covers at least half of (their dominant building), how many
/// have a building of their own (dominant for no other footprint), and how many are cut in two (two found
/// buildings cover >= 15 m^2 of it each).
void print_separation(const raster<std::int32_t>& footprints, const raster<std::int32_t>& found, double cell_area)
{
    std::map<std::int32_t, std::map<std::int32_t, std::size_t>> cover;  // footprint -> found building -> cells
    std::map<std::int32_t, std::size_t> cells;
    for (std::ptrdiff_t i = 0; i < footprints.size(); ++i) {
        const std::int32_t f = footprints.data()[i];
        if (f <= 0) continue;
        ++cells[f];
        if (found.data()[i] > 0) ++cover[f][found.data()[i]];
    }
    const auto min_cells = static_cast<std::size_t>(std::ceil(15.0 / cell_area));
    std::map<std::int32_t, std::int32_t> dominant;
    std::map<std::int32_t, int> dominated;
    std::size_t large = 0, cut = 0;
    for (const auto& [f, n] : cells) {
        if (n < min_cells) continue;
        ++large;
        std::size_t best = 0, parts = 0;
        std::int32_t best_id = 0;
        for (const auto& [id, k] : cover[f]) {
            parts += k >= min_cells ? 1 : 0;
            if (k > best) best = k, best_id = id;
        }
        cut += parts >= 2 ? 1 : 0;
        if (2 * best >= n) {
            dominant[f] = best_id;
            ++dominated[best_id];
        }
    }
    std::size_t own = 0;
    for (const auto& [f, id] : dominant) own += dominated[id] == 1 ? 1 : 0;
    std::printf(
        "  footprints of >= 15 m^2: %zu; found (half covered by one building): %zu; with a building of their "
        "own: %zu; sharing one: %zu; cut in two: %zu\n",
        large, dominant.size(), own, dominant.size() - own, cut);
}

int main(int argc, char** argv)
{
    double cell = 1.0;
    std::string ground_mode = "model", vegetation_mode = "returns", rim_mode = "points", under_crowns = "on";
    const char* footprint_file = nullptr;
    const char* ids_file = nullptr;
    const char* map_file = nullptr;
    std::vector<std::string> files;
    std::vector<int> truth_ignore;  // classes the truth rule leaves out (e.g. 12, overlap points on roofs and ground)
    extract_buildings_options opt;
    int a0 = 1;
    for (; a0 < argc && std::strncmp(argv[a0], "--", 2) != 0; ++a0) files.emplace_back(argv[a0]);
    bool usage = files.empty();
    for (int a = a0; a < argc && !usage; a += 2) {
        if (a + 1 >= argc)
            usage = true;
        else if (!std::strcmp(argv[a], "--cell"))
            cell = std::strtod(argv[a + 1], nullptr);
        else if (!std::strcmp(argv[a], "--ground"))
            ground_mode = argv[a + 1];
        else if (!std::strcmp(argv[a], "--min-area"))
            opt.candidates.min_area_m2 = std::strtod(argv[a + 1], nullptr);
        else if (!std::strcmp(argv[a], "--vegetation"))
            vegetation_mode = argv[a + 1];
        else if (!std::strcmp(argv[a], "--truth-ignore"))
            truth_ignore.push_back(std::atoi(argv[a + 1]));
        else if (!std::strcmp(argv[a], "--rim"))
            rim_mode = argv[a + 1];
        else if (!std::strcmp(argv[a], "--under-crowns"))
            under_crowns = argv[a + 1];
        else if (!std::strcmp(argv[a], "--party-step"))
            opt.party_walls.min_step_m = std::strtod(argv[a + 1], nullptr);  // inf: blocks are never split
        else if (!std::strcmp(argv[a], "--party-share"))
            opt.party_walls.min_wall_share = std::strtod(argv[a + 1], nullptr);
        else if (!std::strcmp(argv[a], "--footprints"))
            footprint_file = argv[a + 1];
        else if (!std::strcmp(argv[a], "--map"))
            map_file = argv[a + 1];
        else if (!std::strcmp(argv[a], "--ids"))
            ids_file = argv[a + 1];
        else
            usage = true;
    }
    if (usage || !(cell > 0) || (ground_mode != "model" && ground_mode != "class2" && ground_mode != "filter") ||
        (vegetation_mode != "returns" && vegetation_mode != "any") || (rim_mode != "points" && rim_mode != "dsm") ||
        (under_crowns != "on" && under_crowns != "off")) {
        std::fprintf(
            stderr,
            "usage: buildings_real_survey SURVEY.las|laz... [--cell M] [--ground model|class2|filter] "
            "[--vegetation returns|any] [--rim points|dsm] [--under-crowns on|off] [--min-area M2] [--party-step M] "
            "[--party-share S] "
            "[--footprints FILE] [--truth-ignore CLASS]... [--map OUT.asc] [--ids OUT.asc]\n");
        return 2;
    }
    try {
        io::las_points pts;
        for (const std::string& f : files) pts.append(io::read_las(f));
        double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
        for (std::size_t i = 0; i < pts.size(); ++i) {
            xmin = std::min(xmin, pts.x[i]), xmax = std::max(xmax, pts.x[i]);
            ymin = std::min(ymin, pts.y[i]), ymax = std::max(ymax, pts.y[i]);
        }
        const double x0 = std::floor(xmin / cell) * cell, y0 = (std::floor(ymax / cell) + 1) * cell;
        const grid g{x0, y0, cell, static_cast<std::ptrdiff_t>(std::ceil((y0 - ymin) / cell)),
                     static_cast<std::ptrdiff_t>(std::floor((xmax - x0) / cell)) + 1};
        const rasterize_result all = rasterize(pts.cloud(), g, {.classes = {.exclude = {7, 18}}});
        raster<float> dsm = idw_fill(all.max_z, cell).filled;
        dsm = remove_surface_outliers(dsm).surface;
        raster<float> class2;
        if (ground_mode == "class2") class2 = rasterize(pts.cloud(), g, {.classes = {.include = {2}}}).min_z;
        if (ground_mode == "filter") class2 = morphological_ground(all.min_z, cell).ground;
        // With a given terrain, the rim is decided by the points raised above it (as the program does).
        raster<std::uint32_t> raised;
        raster<float> lowest_raised;
        if (!class2.empty() && rim_mode == "points") {
            class2 = fill_ground(class2, cell);
            kept_points kept{pts, {}};
            for (std::size_t i = 0; i < pts.size(); ++i)
                if (pts.classification[i] != 7 && pts.classification[i] != 18) kept.index.push_back(i);
            raised = raster<std::uint32_t>(g.rows, g.cols, 0);
            lowest_raised = raster<float>(g.rows, g.cols, NAN);
            count_points_above(kept, g, class2.view(), opt.candidates.min_height_m, raised.view(),
                               lowest_raised.view());
            if (under_crowns == "off") lowest_raised = {};
        }
        const extract_buildings_result b =
            vegetation_mode == "returns"
                ? extract_buildings(
                      dsm, g, class2.view(),
                      pulse_returns{all.count, all.multiple_return_count, raised.view(), lowest_raised.view()}, opt)
                : extract_buildings(dsm, g, class2.view(), all.multiple_returns.view(), opt);
        // Class truth per cell (the cells' points as rasterized above, noise left out), and polygon truth.
        raster<std::uint32_t> points = all.count;
        if (!truth_ignore.empty()) {
            const raster<std::uint32_t> ignored =
                rasterize(pts.cloud(), g, {.classes = {.include = truth_ignore}}).count;
            for (std::ptrdiff_t i = 0; i < points.size(); ++i) points.data()[i] -= ignored.data()[i];
        }
        const raster<std::uint32_t> building_points = rasterize(pts.cloud(), g, {.classes = {.include = {6}}}).count;
        raster<std::int32_t> footprints;
        if (footprint_file) {
            std::vector<labelled_polygon> polygons;
            for (auto& fp : io::read_footprints(footprint_file).footprints)
                polygons.push_back({static_cast<std::int32_t>(polygons.size()) + 1, std::move(fp.parts)});
            footprints = burn_polygons(polygons, g).labels;
        }
        scores by_class, by_polygon;
        for (std::ptrdiff_t r = 0; r < g.rows; ++r) {
            for (std::ptrdiff_t c = 0; c < g.cols; ++c) {
                if (points(r, c) == 0) continue;
                const bool found = b.building_id(r, c) > 0;
                const bool truth = 2 * building_points(r, c) >= points(r, c);
                if (truth && found) ++by_class.tp;
                if (truth && !found) ++by_class.fn;
                if (!truth && found) ++by_class.fp;
                if (!footprints.empty()) {
                    const bool inside = footprints(r, c) > 0;
                    if (inside && found) ++by_polygon.tp;
                    if (inside && !found) ++by_polygon.fn;
                    if (!inside && found) ++by_polygon.fp;
                }
            }
        }
        std::printf(
            "%s%s, %.2f m cells, ground %s, vegetation %s, rim %s, under crowns %s: %zu buildings found (%zu clipped), "
            "%zu "
            "rejected as vegetation\n",
            files[0].c_str(), files.size() > 1 ? " and more" : "", cell, ground_mode.c_str(), vegetation_mode.c_str(),
            rim_mode.c_str(), lowest_raised.empty() ? "off" : "on", b.buildings.size(),
            static_cast<std::size_t>(std::count_if(b.buildings.begin(), b.buildings.end(),
                                                   [](const building_record& br) { return br.clipped; })),
            b.rejected_rough);
        print_scores("class 6, cells with points", by_class, cell * cell);
        if (!footprints.empty()) {
            print_scores("footprints, cells with points", by_polygon, cell * cell);
            print_separation(footprints, b.building_id, cell * cell);
        }
        if (ids_file) {  // building ids and roof surfaces, for a look at the blocks
            raster<float> ids(g.rows, g.cols), surfaces(g.rows, g.cols);
            for (std::ptrdiff_t i = 0; i < ids.size(); ++i) {
                ids.data()[i] = static_cast<float>(b.building_id.data()[i]);
                surfaces.data()[i] = static_cast<float>(b.surface_id.data()[i]);
            }
            io::write_ascii_grid(ids_file, ids, g);
            io::write_ascii_grid(std::string(ids_file) + ".surfaces.asc", surfaces, g);
            io::write_ascii_grid(std::string(ids_file) + ".dsm.asc", dsm, g);
        }
        if (map_file) {
            raster<float> map(g.rows, g.cols);
            for (std::ptrdiff_t r = 0; r < g.rows; ++r)
                for (std::ptrdiff_t c = 0; c < g.cols; ++c) {
                    const bool truth = 2 * building_points(r, c) >= points(r, c) && points(r, c) > 0;
                    map(r, c) = static_cast<float>((b.building_id(r, c) > 0 ? 1 : 0) + (truth ? 2 : 0));
                }
            io::write_ascii_grid(map_file, map, g);  // 0 neither, 1 found only, 2 truth only, 3 both
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "buildings_real_survey: %s\n", e.what());
        return 1;
    }
    return 0;
}
