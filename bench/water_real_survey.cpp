// SPDX-License-Identifier: Apache-2.0
// Scores a `lidarfx water` map of a real survey against the survey's own truth: the vendor's water class
// (ASPRS 9) or independent water polygons. Run by bench/water_real_surveys.sh, which makes the maps.
//   water_real_survey SURVEY.las|laz WATER.asc [--polygons FILE] [--deck-class N]
// WATER.asc: the program's `water` raster (--formats asc): 1 water, 0 land, NoData outside the survey's
// footprint. Truth on the same grid:
//   - class truth (default): a cell is water when at least half of its points are class 9. A cell without
//     points is water when at least 90 % of the cells with points around its gap (an 8-connected component
//     of empty cells inside the footprint) are: a lake's interior without returns, ringed by class-9 returns
//     along its shore. Other gaps are not scored: a vendor classifies the returns it has, and the shore of
//     a lake without returns is often left as ground;
//   - polygon truth (--polygons, any file the program reads footprints from, read as footprints are: GeoJSON
//     features need an integer building_id, OGR layers use their FIDs): a cell is water when its
//     centre lies inside a polygon (even-odd over its rings). Two lines are printed: the cells with points
//     (the scoring rule of docs/waterbodies.md), then every cell inside the footprint, with or without points
//     (water that returns nothing, under trees or bright sky, counts there).
// Noise points (classes 7 and 18) are left out. Cells holding a bridge-deck point (class 17, or the class
// given by --deck-class: AHN marks bridges and other structures 26), and the cells next to them, are not
// scored. Prints accuracy, sensitivity, specificity and IoU in %, the cells scored and the true and found
// water in m² (the cell's area from the grid's unit, metres assumed).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include <lidarfx/core/raster.hpp>
#include <lidarfx/kernels/filter/morphology.hpp>
#include <lidarfx/kernels/label/connected_components.hpp>
#include <lidarfx/kernels/vector/burn_polygons.hpp>

#include "io/ascii_grid.hpp"
#include "io/footprints.hpp"
#include "io/las.hpp"

using namespace lidarfx;

int main(int argc, char** argv)
{
    const char* polygon_file = nullptr;
    int deck_class = 17;
    bool usage = argc < 3;
    for (int a = 3; a < argc && !usage; a += 2) {
        if (a + 1 >= argc)
            usage = true;
        else if (!std::strcmp(argv[a], "--polygons"))
            polygon_file = argv[a + 1];
        else if (!std::strcmp(argv[a], "--deck-class"))
            deck_class = std::atoi(argv[a + 1]);
        else
            usage = true;
    }
    if (usage) {
        std::fprintf(stderr, "usage: water_real_survey SURVEY.las|laz WATER.asc [--polygons FILE] [--deck-class N]\n");
        return 2;
    }
    try {
        grid g;
        const raster<float> found = io::read_ascii_grid(argv[2], g);
        const io::las_points pts = io::read_las(argv[1]);
        raster<std::uint32_t> points(g.rows, g.cols, 0), water_points(g.rows, g.cols, 0);
        raster<std::uint8_t> deck(g.rows, g.cols, 0);
        for (std::size_t i = 0; i < pts.size(); ++i) {
            const int cls = pts.classification[i];
            if (cls == 7 || cls == 18) continue;
            const auto c = static_cast<std::ptrdiff_t>(std::floor((pts.x[i] - g.x0) / g.cell));
            const auto r = static_cast<std::ptrdiff_t>(std::floor((g.y0 - pts.y[i]) / g.cell));
            if (r < 0 || c < 0 || r >= g.rows || c >= g.cols) continue;
            points(r, c) += 1;
            water_points(r, c) += cls == 9;
            if (cls == deck_class) deck(r, c) = 1;
        }
        // Polygon truth: the cells whose centre a polygon contains (burn_polygons' cell-centre rule).
        raster<std::int32_t> lakes;
        if (polygon_file) {
            std::vector<labelled_polygon> polygons;
            for (auto& fp : io::read_footprints(polygon_file).footprints) polygons.push_back({1, std::move(fp.parts)});
            lakes = burn_polygons(polygons, g).labels;
        }
        // Gaps: 8-connected components of empty cells inside the footprint, and the cells with points on
        // their rim (8-neighbours), counted as water or land.
        raster<std::uint8_t> empty(g.rows, g.cols, 0);
        for (std::ptrdiff_t r = 0; r < g.rows; ++r)
            for (std::ptrdiff_t c = 0; c < g.cols; ++c) empty(r, c) = points(r, c) == 0 && !std::isnan(found(r, c));
        const auto gaps = connected_components(empty, connectivity::eight);
        std::vector<double> rim_water(gaps.sizes.size(), 0), rim_cells(gaps.sizes.size(), 0);
        for (std::ptrdiff_t r = 0; r < g.rows; ++r) {
            for (std::ptrdiff_t c = 0; c < g.cols; ++c) {
                if (points(r, c) == 0) continue;
                std::int32_t seen[9] = {}, k = 0;  // each gap once per rim cell
                for (std::ptrdiff_t dr = -1; dr <= 1; ++dr) {
                    for (std::ptrdiff_t dc = -1; dc <= 1; ++dc) {
                        if (r + dr < 0 || c + dc < 0 || r + dr >= g.rows || c + dc >= g.cols) continue;
                        const std::int32_t l = gaps.labels(r + dr, c + dc);
                        if (l == 0 || std::find(seen, seen + k, l) != seen + k) continue;
                        seen[k++] = l;
                        rim_cells[static_cast<std::size_t>(l)] += 1;
                        rim_water[static_cast<std::size_t>(l)] += 2 * water_points(r, c) >= points(r, c);
                    }
                }
            }
        }
        const auto near_deck = morph_dilate(deck, 3);  // a deck cell and its 8 neighbours are not scored
        // Scores the cells (with points only, or all) and prints one line.
        const auto score = [&](bool with_points_only, const char* what) {
            std::size_t tp = 0, fp = 0, fn = 0, tn = 0;
            for (std::ptrdiff_t r = 0; r < g.rows; ++r) {
                for (std::ptrdiff_t c = 0; c < g.cols; ++c) {
                    if (std::isnan(found(r, c))) continue;  // outside the footprint
                    if (with_points_only && points(r, c) == 0) continue;
                    if (near_deck(r, c)) continue;
                    bool truth = false;
                    if (lakes.empty()) {
                        if (points(r, c) == 0) {
                            const auto l = static_cast<std::size_t>(gaps.labels(r, c));
                            const double share = rim_cells[l] > 0 ? rim_water[l] / rim_cells[l] : 0.5;
                            if (share < 0.9) continue;  // a gap is water by its rim, or not scored
                            truth = true;
                        } else {
                            truth = 2 * water_points(r, c) >= points(r, c);
                        }
                    } else {
                        truth = lakes(r, c) > 0;
                    }
                    const bool water = found(r, c) > 0.5f;
                    (truth ? (water ? tp : fn) : (water ? fp : tn)) += 1;
                }
            }
            const double n = static_cast<double>(tp + fp + fn + tn), area = g.cell * g.cell;
            const auto pct = [](std::size_t a, std::size_t b) {
                return b ? 100.0 * static_cast<double>(a) / static_cast<double>(b) : NAN;
            };
            std::printf(
                "%scells %.0f, water true %.0f m2, found %.0f m2: accuracy %.2f %%, sensitivity %.2f %%, "
                "specificity %.2f %%, IoU %.2f %%\n",
                what, n, static_cast<double>(tp + fn) * area, static_cast<double>(tp + fp) * area,
                pct(tp + tn, tp + fp + fn + tn), pct(tp, tp + fn), pct(tn, tn + fp), pct(tp, tp + fp + fn));
        };
        if (lakes.empty()) {
            score(false, "");
        } else {
            score(true, "cells with points: ");
            score(false, "every footprint cell: ");
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "water_real_survey: %s\n", e.what());
        return 1;
    }
    return 0;
}
