// SPDX-License-Identifier: Apache-2.0
// rasterize with a choice of returns and classes: a DSM of first returns and a ground raster of class 2.
#include <doctest/doctest.h>

#include <lidarfx/kernels/points/rasterize.hpp>

#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

using namespace lidarfx;

namespace {

/// One pulse through a tree over cell (0, 0): canopy (first of 3, class 5), branch (2 of 3, class 4), ground
/// (3 of 3, class 2); a single roof return (class 6) in cell (0, 1); a noise point (class 7) in cell (0, 1).
struct two_cells {
    std::vector<double> x{0.5, 0.5, 0.5, 1.5, 1.5}, y{0.5, 0.5, 0.5, 0.5, 0.5}, z{12, 6, 1, 8, 30};
    std::vector<std::uint16_t> intensity{10, 20, 30, 40, 50};
    std::vector<std::uint8_t> rn{1, 2, 3, 1, 1}, nr{3, 3, 3, 1, 1}, cls{5, 4, 2, 6, 7};
    soa_cloud<> cloud() const { return soa_cloud<>(x, y, z, intensity, rn, nr, cls); }
};

const grid g2{0.0, 1.0, 1.0, 1, 2};

/// Points with x, y, z only (no return numbers, no classes).
struct bare_cloud {
    std::vector<double> v{0.5};
    std::size_t size() const { return 1; }
    double x(std::size_t) const { return 0.5; }
    double y(std::size_t) const { return 0.5; }
    double z(std::size_t) const { return 1.0; }
};

}  // namespace

TEST_CASE("rasterize/selection: the default bins every point, first returns give the top surface")
{
    const two_cells pts;
    const auto all = rasterize(pts.cloud(), g2);
    CHECK(all.points_used == 5);
    CHECK(all.points_unselected == 0);
    CHECK(all.min_z(0, 0) == 1.0f);
    CHECK(all.max_z(0, 1) == 30.0f);

    rasterize_options first;
    first.returns = return_selection::first;
    const auto dsm = rasterize(pts.cloud(), g2, first);
    CHECK(dsm.points_used == 3);
    CHECK(dsm.points_unselected == 2);
    CHECK(dsm.min_z(0, 0) == 12.0f);  // only the canopy return
    CHECK(dsm.max_z(0, 0) == 12.0f);
    CHECK(dsm.multiple_returns(0, 0) == 1);  // the first return of a 3-return pulse
    CHECK(dsm.multiple_returns(0, 1) == 0);
    CHECK(dsm.mean_intensity(0, 0) == 10.0f);
}

TEST_CASE("rasterize/selection: last returns and class sets")
{
    const two_cells pts;
    rasterize_options last;
    last.returns = return_selection::last;
    const auto low = rasterize(pts.cloud(), g2, last);
    CHECK(low.max_z(0, 0) == 1.0f);
    CHECK(low.count(0, 0) == 1);

    rasterize_options ground;
    ground.classes.include = {2};
    const auto dtm = rasterize(pts.cloud(), g2, ground);
    CHECK(dtm.min_z(0, 0) == 1.0f);
    CHECK(dtm.count(0, 0) == 1);
    CHECK(std::isnan(dtm.min_z(0, 1)));
    CHECK(dtm.dropout(0, 1) == 1);

    rasterize_options no_noise;
    no_noise.classes.exclude = {7};
    const auto clean = rasterize(pts.cloud(), g2, no_noise);
    CHECK(clean.max_z(0, 1) == 8.0f);
    CHECK(clean.points_unselected == 1);

    rasterize_options both;  // first returns of classes 2..6 minus 5: only the roof
    both.returns = return_selection::first;
    both.classes.include = {2, 3, 4, 5, 6};
    both.classes.exclude = {5};
    const auto roof = rasterize(pts.cloud(), g2, both);
    CHECK(roof.points_used == 1);
    CHECK(roof.count(0, 0) == 0);
    CHECK(roof.max_z(0, 1) == 8.0f);
}

TEST_CASE("rasterize/selection: same bits with threads and chunks")
{
    std::vector<double> x, y, z;
    std::vector<std::uint16_t> in;
    std::vector<std::uint8_t> rn, nr, cls;
    for (int i = 0; i < 20000; ++i) {
        x.push_back(std::fmod(i * 0.618034, 1.0) * 16);
        y.push_back(std::fmod(i * 0.414214, 1.0) * 16);
        z.push_back(std::fmod(i * 0.7071, 1.0) * 10);
        in.push_back(static_cast<std::uint16_t>(i % 300));
        nr.push_back(static_cast<std::uint8_t>(1 + i % 3));
        rn.push_back(static_cast<std::uint8_t>(1 + (i / 3) % nr.back()));
        cls.push_back(static_cast<std::uint8_t>(i % 7));
    }
    const soa_cloud<> cloud(x, y, z, in, rn, nr, cls);
    const grid g{0.0, 16.0, 1.0, 16, 16};
    rasterize_options one;
    one.returns = return_selection::first;
    one.classes.exclude = {3};
    rasterize_options many = one;
    many.chunk_points = 777;
    many.run.threads = 3;
    const auto a = rasterize(cloud, g, one), b = rasterize(cloud, g, many);
    CHECK(a.points_used == b.points_used);
    CHECK(a.points_used + a.points_unselected == x.size());
    bool same = true;
    for (std::ptrdiff_t r = 0; r < 16; ++r) {
        for (std::ptrdiff_t c = 0; c < 16; ++c) {
            same = same && a.count(r, c) == b.count(r, c) && a.max_z(r, c) == b.max_z(r, c) &&
                   a.mean_intensity(r, c) == b.mean_intensity(r, c);
        }
    }
    CHECK(same);
}

TEST_CASE("rasterize/selection: a selection the cloud cannot serve is refused with a clear message")
{
    const bare_cloud bare;
    CHECK(rasterize(bare, g2).points_used == 1);
    rasterize_options first;
    first.returns = return_selection::first;
    CHECK_THROWS_WITH_AS(rasterize(bare, g2, first), doctest::Contains("needs return numbers"), invalid_input);
    rasterize_options ground;
    ground.classes.include = {2};
    CHECK_THROWS_WITH_AS(rasterize(bare, g2, ground), doctest::Contains("needs classification codes"), invalid_input);
    const two_cells pts;
    rasterize_options bad;
    bad.classes.exclude = {256};
    CHECK_THROWS_WITH_AS(rasterize(pts.cloud(), g2, bad), doctest::Contains("in [0, 255]"), invalid_input);
}
