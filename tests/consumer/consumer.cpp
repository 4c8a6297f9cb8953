// A separate project using the installed package: exits non-zero if the library misbehaves.
#include <lidarfx/lidarfx.hpp>

int main()
{
    lidarfx::raster<float> z(3, 4, 1.5f);
    const lidarfx::raster_view<const float> v = z;
    const lidarfx::grid g{1000.0, 2000.0, 2.0, 3, 4};
    const auto cell = g.cell_of(1003.0, 1999.0);
    return (v.rows() == 3 && v(2, 3) == 1.5f && cell && cell->row == 0 && cell->col == 1) ? 0 : 1;
}
