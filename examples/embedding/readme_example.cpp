// SPDX-License-Identifier: Apache-2.0
// The embedding example of the README, compiled so that it stays true: a host's points in three spans,
// rasterized, filtered and searched for waterbodies without copying the input.
#include <cstdio>
#include <string>
#include <vector>

#include <lidarfx/lidarfx.hpp>
#include <lidarfx/synth/scenes.hpp>  // only for the stand-in points

namespace {
void report(const std::string& why)
{
    std::printf("cannot map water: %s\n", why.c_str());
}
void use(std::int32_t label, double area_m2, double level_m)
{
    std::printf("body %d: %.0f m2 at %.2f m\n", label, area_m2, level_m);
}
}  // namespace

int main()
{
    const auto scene = lidarfx::synth::lake_scene({.size_m = 400});  // stands in for the host's own points
    const std::vector<double>&xs = scene.points.x, &ys = scene.points.y, &zs = scene.points.z;
    const auto& intensities = scene.points.intensity;
    const auto &returns = scene.points.return_number, &nreturns = scene.points.number_of_returns;

    // --- as in the README ---
    lidarfx::soa_cloud<> cloud(xs, ys, zs, intensities, returns, nreturns);
    const lidarfx::grid g = lidarfx::snapped_grid(lidarfx::bounds_of(cloud), 2.0);  // 2 m cells on a 2 m lattice
    const auto pr = lidarfx::rasterize(cloud, g, {.run = {.threads = 0}});          // min/max z, intensity, dropouts

    const auto angles = lidarfx::angular_filter(pr.min_z, g.cell);  // degrees, NaN-aware
    const auto seeds = lidarfx::morph_open(pr.dropout, 5);          // 5x5, bit-packed
    const auto blobs = lidarfx::connected_components(seeds, lidarfx::connectivity::eight);

    const auto water = lidarfx::extract_waterbodies(pr, {.run = {.threads = 0}});         // the whole method
    for (const auto& issue : water.diagnostics.issues)                                    // coded, with values
        if (issue.severity == lidarfx::water_severity::problem) report(issue.message());  // why it cannot run
    for (const auto& body : water.bodies) use(body.label, body.area_m2, body.water_level_m);
    // --- end of the README's lines ---

    std::printf("%td x %td cells, %zu dropout blobs, max angle %.1f deg\n", g.rows, g.cols, blobs.sizes.size() - 1,
                static_cast<double>(angles(g.rows / 2, g.cols / 2)));
    return water.ran && !water.bodies.empty() ? 0 : 1;
}
