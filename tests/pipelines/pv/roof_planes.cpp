// SPDX-License-Identifier: Apache-2.0
// roof_planes on hand-made box surfaces: a gable's two faces, a flat roof, an empty box, a garage's gable at 1 m
// cells, the straight cut of two-faced planes against an exhaustive search, a noisy flat roof.
#include <doctest/doctest.h>

#include <lidarfx/pipelines/pv/roof_planes.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <vector>

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

namespace {

/// A garage's gable on 1 m cells as a LiDAR DSM reads it: each cell holds the highest of a 6 x 6 grid of
/// samples of the roof z = ridge - tan(tilt) |distance to the ridge line| over the cell, plus a fixed
/// +-1 cm pattern. The ridge runs at `axis_deg` (clockwise from north) through the box centre; the footprint
/// is `width` across the ridge and `length` along it; cells whose centre lies outside are not roof cells.
roof_box_surface small_gable(double tilt_deg, double axis_deg, double width, double length)
{
    roof_box_surface s;
    s.h = s.w = 12;
    s.cell_m = 1.0;
    s.z.assign(static_cast<std::size_t>(s.h * s.w), std::numeric_limits<double>::quiet_NaN());
    const double pi = 3.14159265358979323846, slope = std::tan(tilt_deg * pi / 180.0);
    const double ux = std::sin(axis_deg * pi / 180.0), uy = std::cos(axis_deg * pi / 180.0);  // along the ridge
    const double cx = 5.5, cy = -5.5;  // box centre in roof_box_surface coordinates
    const auto across = [&](double x, double y) { return (x - cx) * uy - (y - cy) * ux; };
    const auto along = [&](double x, double y) { return (x - cx) * ux + (y - cy) * uy; };
    for (std::ptrdiff_t i = 0; i < s.h * s.w; ++i) {
        const double x = s.x(i), y = s.y(i);
        if (std::fabs(across(x, y)) > width / 2 || std::fabs(along(x, y)) > length / 2) continue;
        double top = -1e9;
        for (int a = 0; a < 6; ++a)
            for (int b = 0; b < 6; ++b) {
                const double px = x - 0.5 + (a + 0.5) / 6, py = y - 0.5 + (b + 0.5) / 6;
                if (std::fabs(across(px, py)) > width / 2 || std::fabs(along(px, py)) > length / 2) continue;
                top = std::max(top, 3.0 - slope * std::fabs(across(px, py)));
            }
        s.z[static_cast<std::size_t>(i)] = top + 0.01 * static_cast<double>((i * 7) % 3 - 1);
    }
    return s;
}

/// Smallest angle between two azimuths, degrees.
double facing_difference_deg(double a, double b)
{
    const double d = std::fmod(std::fabs(a - b), 360.0);
    return std::min(d, 360.0 - d);
}

}  // namespace

TEST_CASE("pv/roof_planes: a garage's gable at 1 m cells, faces two to three cells deep, gives both faces")
{
    // Region growing alone sees every 3x3 window of such a roof straddle the ridge and took the two faces for
    // one plane (or lost one face); the cut of two-faced planes separates them.
    for (const double axis : {0.0, 20.0, 90.0, 135.0}) {
        for (const double width : {4.6, 5.6}) {
            CAPTURE(axis);
            CAPTURE(width);
            const auto p = roof_planes(small_gable(35.0, axis, width, 7.0));
            REQUIRE(p.fits.size() >= 2);
            // The two largest planes are the faces. The cells the ridge crosses read its height (the highest
            // return), so on a ridge oblique to the grid they may form a small flat third plane; nothing more.
            std::vector<std::size_t> by_size(p.fits.size());
            for (std::size_t k = 0; k < by_size.size(); ++k) by_size[k] = k;
            std::sort(by_size.begin(), by_size.end(),
                      [&](std::size_t a, std::size_t b) { return p.cells[a] > p.cells[b]; });
            const plane_fit& f0 = p.fits[by_size[0]];
            const plane_fit& f1 = p.fits[by_size[1]];
            const double down_a = std::fmod(axis + 90.0, 360.0), down_b = std::fmod(axis + 270.0, 360.0);
            const double az0 = f0.azimuth_deg(), az1 = f1.azimuth_deg();
            const bool matched =
                (facing_difference_deg(az0, down_a) <= 15 && facing_difference_deg(az1, down_b) <= 15) ||
                (facing_difference_deg(az0, down_b) <= 15 && facing_difference_deg(az1, down_a) <= 15);
            CHECK(matched);
            CHECK(f0.tilt_deg() == doctest::Approx(35.0).epsilon(0.15));  // within about 5 degrees
            CHECK(f1.tilt_deg() == doctest::Approx(35.0).epsilon(0.15));
            for (std::size_t k = 2; k < by_size.size(); ++k) {
                CHECK(p.cells[by_size[k]] <= 7);
                CHECK(p.fits[by_size[k]].tilt_deg() < 10.0);
            }
        }
    }
}

TEST_CASE("pv/roof_planes: the best straight cut equals an exhaustive search over the same lines")
{
    // best_plane_cut sweeps prefix sums; the reference refits both sides of every cut from scratch.
    std::uint64_t state = 12345;
    const auto next = [&] {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        return static_cast<double>(state >> 11) / 9007199254740992.0;
    };
    for (int trial = 0; trial < 40; ++trial) {
        roof_box_surface s;
        s.h = 5 + trial % 4;
        s.w = 6 + trial % 3;
        s.cell_m = 1.0;
        s.z.resize(static_cast<std::size_t>(s.h * s.w));
        std::vector<std::ptrdiff_t> members;
        for (std::ptrdiff_t i = 0; i < s.h * s.w; ++i) {
            s.z[static_cast<std::size_t>(i)] = trial % 2 ? next() : 2.0 - 0.6 * std::fabs(s.x(i) - 3.3) + 0.05 * next();
            if (next() < 0.85) members.push_back(i);
        }
        detail::plane_cut cut;
        const double step = 15.0;
        const bool found = detail::best_plane_cut(s, members, 4, 0.0, 12, step, cut);
        double best = std::numeric_limits<double>::infinity();
        for (double angle = 0; angle < 180; angle += step) {
            const double cx = std::cos(angle * 3.14159265358979323846 / 180.0);
            const double cy = std::sin(angle * 3.14159265358979323846 / 180.0);
            for (const auto pivot : members) {
                const double t = cx * s.x(pivot) + cy * s.y(pivot);
                plane_sums a, b;
                for (const auto i : members) {
                    const double v = cx * s.x(i) + cy * s.y(i);
                    (v <= t + 1e-9 ? a : b).add(s.x(i), s.y(i), s.z[static_cast<std::size_t>(i)]);
                }
                if (a.n < 4 || b.n < 4) continue;
                const plane_fit fa = fit_plane(a), fb = fit_plane(b);
                if (!fa.ok || !fb.ok) continue;
                best = std::min(best, fa.rms * fa.rms * a.n + fb.rms * fb.rms * b.n);
            }
        }
        CAPTURE(trial);
        REQUIRE(found == std::isfinite(best));
        if (!found) continue;
        CHECK(cut.sse == doctest::Approx(best).epsilon(1e-6));
        CHECK(cut.first.size() + cut.second.size() == members.size());
        CHECK(cut.first.size() >= 4);
        CHECK(cut.second.size() >= 4);
    }
}

TEST_CASE("pv/roof_planes: a noisy flat garage roof stays one plane")
{
    // A cut must give two planes of different normals and explain far more than noise (F test; either guard
    // alone keeps this roof whole): +-15 cm of noise (rms 8.7 cm, above the 7.5 cm from which a cut is tried)
    // on a 5 x 6 m flat roof is not two faces.
    std::uint64_t state = 99;
    for (int trial = 0; trial < 20; ++trial) {
        roof_box_surface s;
        s.h = 6;
        s.w = 5;
        s.cell_m = 1.0;
        s.z.resize(30);
        for (auto& z : s.z) {
            state = state * 6364136223846793005ULL + 1442695040888963407ULL;
            z = 3.0 + 0.3 * (static_cast<double>(state >> 11) / 9007199254740992.0 - 0.5);
        }
        const auto p = roof_planes(s);
        CAPTURE(trial);
        REQUIRE(p.fits.size() == 1);
        CHECK(p.fits[0].tilt_deg() < 5.0);
    }
}
