// A separate project using the installed lidarfx::synth target: a small lake scene rasterizes onto its grid.
#include <lidarfx/kernels/points/rasterize.hpp>
#include <lidarfx/synth/scenes.hpp>

int main()
{
    const auto scene = lidarfx::synth::lake_scene({.size_m = 100});
    const auto rasters = lidarfx::rasterize(scene.points.cloud(), scene.truth.g);
    return rasters.points_used > 0 && rasters.min_z.rows() == scene.truth.g.rows ? 0 : 1;
}
