// SPDX-License-Identifier: Apache-2.0
// roof_planes on hand-made box surfaces: a gable's two faces, a flat roof, an empty box.
#include <doctest/doctest.h>

#include <lidarfx/pipelines/pv/roof_planes.hpp>

#include <cmath>
#include <limits>
#include <set>

using namespace lidarfx;

namespace {

/// A 20 x 24 box of 0.5 m cells: a gable of `tilt` degrees, ridge north-south between columns 11 and 12 (west
/// face down to the west, east face down to the east); flat when tilt is 0.
roof_box_surface gable(double tilt)
{
    roof_box_surface s;
    s.h = 20;
    s.w = 24;
    s.cell_m = 0.5;
    s.z.resize(static_cast<std::size_t>(s.h * s.w));
    const double slope = std::tan(tilt * 3.14159265358979 / 180.0);
    for (std::ptrdiff_t i = 0; i < s.h * s.w; ++i) {
        const auto c = static_cast<double>(i % s.w);
        s.z[static_cast<std::size_t>(i)] = slope * std::min(c + 0.5, 24.0 - c - 0.5) * s.cell_m;
    }
    return s;
}

}  // namespace

TEST_CASE("pv/roof_planes: a gable gives two planes of its tilt, facing west and east")
{
    const auto s = gable(35.0);
    const auto p = roof_planes(s);
    REQUIRE(p.fits.size() == 2);
    std::set<long> facings;
    for (const auto& f : p.fits) {
        // Exact plane values: the fits recover the tilt to rounding.
        CHECK(f.tilt_deg() == doctest::Approx(35.0).epsilon(1e-6));
        facings.insert(std::lround(f.azimuth_deg()));
    }
    CHECK(facings == std::set<long>{90, 270});
    CHECK(p.label[5 * 24 + 3] != p.label[5 * 24 + 20]);
    CHECK(p.cells[0] + p.cells[1] <= 480);
}

TEST_CASE("pv/roof_planes: a flat roof is one plane; a box without roof cells has none")
{
    const auto p = roof_planes(gable(0.0));
    REQUIRE(p.fits.size() == 1);
    CHECK(p.fits[0].tilt_deg() < 1e-6);
    CHECK(p.cells[0] == 480);
    CHECK(p.sigma_m == doctest::Approx(0.02));  // the noise floor: sigma = max(0.02, median rms)

    roof_box_surface empty = gable(0.0);
    for (auto& v : empty.z) v = std::numeric_limits<double>::quiet_NaN();
    const auto none = roof_planes(empty);
    CHECK(none.fits.empty());
    CHECK(none.label.size() == 480);
}
