// SPDX-License-Identifier: Apache-2.0
// Prints an FNV-1a checksum of every kernel's and pipeline's output on the synthetic scenes (lake, river,
// town; seeds 1-2). Used to show that a refactoring changes no result: run before and after, diff the output.
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <lidarfx/lidarfx.hpp>
#include <lidarfx/synth/scenes.hpp>

namespace {

struct fnv {
    std::uint64_t h = 1469598103934665603ull;
    void bytes(const void* p, std::size_t n)
    {
        const auto* b = static_cast<const unsigned char*>(p);
        for (std::size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
    }
    template <class T>
    void value(const T& v)
    {
        bytes(&v, sizeof v);
    }
};

template <class View>
std::uint64_t raster_hash(const View& v)
{
    fnv f;
    f.value(static_cast<std::int64_t>(v.rows()));
    f.value(static_cast<std::int64_t>(v.cols()));
    for (std::ptrdiff_t r = 0; r < v.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < v.cols(); ++c) f.value(v(r, c));
    return f.h;
}

void print(const std::string& scene, const char* what, std::uint64_t h)
{
    std::printf("%-10s %-28s %016llx\n", scene.c_str(), what, static_cast<unsigned long long>(h));
}

}  // namespace

int main()
{
    using namespace lidarfx;
    for (unsigned seed = 1; seed <= 2; ++seed) {
        synth::scene_options so;
        so.seed = seed;
        const std::vector<std::pair<std::string, synth::scene>> scenes{
            {"lake" + std::to_string(seed), synth::lake_scene(so)},
            {"river" + std::to_string(seed), synth::river_scene(so)},
            {"town" + std::to_string(seed), synth::town_scene(so)}};
        for (const auto& [name, sc] : scenes) {
            const auto pr = rasterize(sc.points.cloud(), sc.truth.g);
            print(name, "rasterize.min_z", raster_hash(pr.min_z.view()));
            print(name, "rasterize.max_z", raster_hash(pr.max_z.view()));
            print(name, "rasterize.mean_intensity", raster_hash(pr.mean_intensity.view()));
            print(name, "rasterize.count", raster_hash(pr.count.view()));
            print(name, "rasterize.dropout", raster_hash(pr.dropout.view()));
            print(name, "rasterize.multiple_returns", raster_hash(pr.multiple_returns.view()));
            const double cell = pr.g.cell;
            const auto filled = idw_fill(pr.min_z.view(), cell);
            print(name, "idw_fill", raster_hash(filled.filled.view()));
            print(name, "angular_filter", raster_hash(angular_filter(filled.filled.view(), cell, 2).view()));
            const auto sa = slope_aspect(filled.filled.view(), cell);
            print(name, "slope_aspect.slope", raster_hash(sa.slope_deg.view()));
            print(name, "slope_aspect.aspect", raster_hash(sa.aspect_deg.view()));
            const auto veg = vegetation_mask(pr.min_z.view(), pr.max_z.view());
            print(name, "vegetation_mask", raster_hash(veg.view()));
            const auto dropout = pr.dropout.view();
            print(name, "morph_open5", raster_hash(morph_open(dropout, 5).view()));
            print(name, "morph_close7", raster_hash(morph_close(dropout, 7).view()));
            print(name, "morph_dilate3", raster_hash(morph_dilate(dropout, 3).view()));
            print(name, "morph_erode3", raster_hash(morph_erode(dropout, 3).view()));
            const auto cc8 = connected_components(dropout, connectivity::eight);
            const auto cc4 = connected_components(dropout, connectivity::four);
            print(name, "components8", raster_hash(cc8.labels.view()));
            print(name, "components4", raster_hash(cc4.labels.view()));
            print(name, "remove_small_components", raster_hash(remove_small_components(dropout, 20).view()));
            print(name, "fill_holes", raster_hash(fill_holes(dropout, 19).view()));  // holes of <= 19 cells
            fnv poly;
            for (const auto& lp : polygonize(cc8.labels.view(), pr.g)) {
                poly.value(lp.label);
                for (const auto& p : lp.polygons)
                    for (const auto& ring : p.rings)
                        for (const auto& xy : ring) poly.value(xy);
            }
            print(name, "polygonize", poly.h);
            std::vector<float> a, b;
            for (std::ptrdiff_t r = 0; r < pr.mean_intensity.rows(); ++r)
                for (std::ptrdiff_t c = 0; c < pr.mean_intensity.cols(); ++c)
                    (r < pr.mean_intensity.rows() / 2 ? a : b).push_back(pr.mean_intensity(r, c));
            const auto ks = ks_one_sided(a, b);
            fnv kh;
            kh.value(ks.d);
            kh.value(ks.critical);
            kh.value(ks.reject);
            print(name, "ks_one_sided", kh.h);
            const auto wb = extract_waterbodies(pr);
            print(name, "waterbodies.labels", raster_hash(wb.labels.view()));
            fnv bh;
            for (const auto& body : wb.bodies) {
                bh.value(body.area_m2);
                bh.value(body.theta_deg);
                bh.value(body.water_level_m);
                bh.value(body.mean_intensity);
            }
            print(name, "waterbodies.bodies", bh.h);
            const auto cf = confusion_counts(wb.water.view(), sc.truth.water_filled.view(), cell);
            std::printf("%-10s %-28s %.6f %.6f %.6f\n", name.c_str(), "confusion", cf.accuracy(), cf.sensitivity(),
                        cf.specificity());
        }
    }
}
