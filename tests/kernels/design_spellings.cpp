// SPDX-License-Identifier: Apache-2.0
// The public spellings the library promises (docs/conventions.md: the stable public API), written exactly as a caller
// with plain lidarfx types writes them, through the umbrella header only.
#include <doctest/doctest.h>

#include <lidarfx/lidarfx.hpp>

#include <cstdint>
#include <vector>

TEST_CASE("kernels/design: the section 2 spellings compile and answer on a small raster")
{
    lidarfx::raster<float> dem(6, 7, 10.0f);  // raster(rows, cols, fill)
    dem(3, 3) = 12.0f;
    CHECK(dem.rows() == 6);
    CHECK(dem.cols() == 7);
    CHECK(dem.data()[3 * 7 + 3] == 12.0f);
    const lidarfx::raster_view<const float> z = dem.view();
    const lidarfx::grid g{500000.0, 4000000.0, 2.0, 6, 7};  // x0, y0, cell, rows, cols
    CHECK(g.center(0, 0)[0] == 500001.0);

    const lidarfx::raster<float> angles = lidarfx::angular_filter(z, g.cell, 2);
    CHECK(angles(3, 4) == doctest::Approx(45.0));  // rise of 2 m over one 2 m cell

    lidarfx::raster<std::uint8_t> mask(6, 7, 0);
    mask(2, 2) = mask(2, 3) = mask(3, 2) = mask(3, 3) = 1;
    const lidarfx::raster_view<const std::uint8_t> m = mask.view();
    const lidarfx::raster<std::uint8_t> opened = lidarfx::morph_open(m, 3);
    const lidarfx::raster<std::uint8_t> closed = lidarfx::morph_close(m, 3);
    const lidarfx::raster<std::uint8_t> dilated = lidarfx::morph_dilate(m, 3);
    const lidarfx::raster<std::uint8_t> eroded = lidarfx::morph_erode(m, 3);
    CHECK(opened(2, 2) == 0);  // a 2x2 block does not hold a 3x3 square
    CHECK(closed(2, 2) == 1);
    CHECK(dilated(1, 1) == 1);
    CHECK(eroded(2, 2) == 0);

    const lidarfx::components comps = lidarfx::connected_components(m, lidarfx::connectivity::eight);
    CHECK(comps.sizes.size() == 2);  // background + one component
    CHECK(comps.sizes[1] == 4);
    CHECK(comps.labels(3, 3) == 1);
    CHECK(lidarfx::connected_components(m, lidarfx::connectivity::four).sizes[1] == 4);

    const std::vector<double> previous{1, 2, 3, 4, 5, 6, 7, 8}, current{5, 6, 7, 8, 9, 10, 11, 12};
    const lidarfx::ks_result ks = lidarfx::ks_one_sided(previous, current, 0.05);
    CHECK(ks.d == doctest::Approx(0.5));
    CHECK(ks.critical > 0);
    CHECK(ks.reject == (ks.d > ks.critical));
}
