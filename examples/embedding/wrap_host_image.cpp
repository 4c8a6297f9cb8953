// SPDX-License-Identifier: Apache-2.0
// Embedding example: a host's own image type (here shaped like cv::Mat / a GDAL block buffer: pointer,
// size, row step in bytes) used by lidarfx without copying, plus a GDAL geotransform turned into a grid.
#include <array>
#include <cstdio>
#include <vector>

#include <lidarfx/lidarfx.hpp>

namespace host {

// What a host application already has: a padded float image with a byte step, as cv::Mat stores it.
struct float_image {
    float* pixels;
    int rows_count, cols_count;
    std::size_t step_bytes;
};

// The adapter: four members and a value_type make it a lidarfx::strided_raster; nothing is copied.
struct float_image_view {
    using value_type = float;
    const float_image* img;
    std::ptrdiff_t rows() const { return img->rows_count; }
    std::ptrdiff_t cols() const { return img->cols_count; }
    std::ptrdiff_t row_stride() const { return static_cast<std::ptrdiff_t>(img->step_bytes / sizeof(float)); }
    const float* data() const { return img->pixels; }
    float operator()(std::ptrdiff_t r, std::ptrdiff_t c) const { return img->pixels[r * row_stride() + c]; }
};

}  // namespace host

int main()
{
    // A 100 x 120 elevation image whose rows are padded to 128 floats, as an aligned allocator would.
    std::vector<float> storage(100 * 128, 0.0f);
    host::float_image img{storage.data(), 100, 120, 128 * sizeof(float)};
    for (int r = 0; r < img.rows_count; ++r)
        for (int c = 0; c < img.cols_count; ++c)
            storage[static_cast<std::size_t>(r * 128 + c)] = 0.1f * static_cast<float>(c);

    static_assert(lidarfx::strided_raster<host::float_image_view>);
    const auto z = lidarfx::view_of(host::float_image_view{&img});  // no copy: same pointer, stride 128

    // GDAL's geotransform for the image (2 m cells, north-up) becomes a lidarfx grid.
    const std::array<double, 6> geotransform{500000.0, 2.0, 0.0, 4100000.0, 0.0, -2.0};
    const lidarfx::grid g = lidarfx::from_gdal(geotransform, z.rows(), z.cols());
    const auto [x, y] = g.center(99, 119);
    std::printf("view %tdx%td stride %td shares the host buffer: %s; last cell centre (%.1f, %.1f)\n", z.rows(),
                z.cols(), z.row_stride(), z.data() == storage.data() ? "yes" : "no", x, y);
    return z.data() == storage.data() ? 0 : 1;
}
