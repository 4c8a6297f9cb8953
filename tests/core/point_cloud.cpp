// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/core/point_cloud.hpp>

#include <array>
#include <cstdint>
#include <vector>

using namespace lidarfx;

namespace {

struct las_point {
    double x, y, z;
    std::uint16_t intensity;
    std::uint8_t return_number, number_of_returns;
};

struct xyz_only {
    std::size_t size() const { return 1; }
    double x(std::size_t) const { return 1; }
    double y(std::size_t) const { return 2; }
    double z(std::size_t) const { return 3; }
};

struct missing_z {
    std::size_t size() const { return 1; }
    double x(std::size_t) const { return 1; }
    double y(std::size_t) const { return 2; }
};

}  // namespace

static_assert(point_cloud<xyz_only>);
static_assert(!has_intensity<xyz_only>);
static_assert(!point_cloud<missing_z>);
static_assert(point_cloud<soa_cloud<>>);
static_assert(has_intensity<soa_cloud<>> && has_number_of_returns<soa_cloud<>>);

TEST_CASE("core/point_cloud: struct-of-arrays spans are read in place")
{
    const std::vector<double> x{1, 2, 3}, y{4, 5, 6}, z{7, 8, 9};
    const std::vector<std::uint16_t> intensity{10, 20, 30};
    const std::vector<std::uint8_t> nret{1, 2, 2};
    soa_cloud<> c(x, y, z, intensity, {}, nret);
    CHECK(c.size() == 3);
    CHECK(c.x(1) == 2);
    CHECK(c.z(2) == 9);
    CHECK(c.intensity(2) == 30);
    CHECK(c.number_of_returns(1) == 2);
    CHECK(c.return_number(1) == 1);  // absent -> first return
    CHECK(c.has_intensity_values());

    soa_cloud<> bare(x, y, z);
    CHECK(bare.intensity(0) == 0);
    CHECK_FALSE(bare.has_intensity_values());
    CHECK_THROWS_WITH_AS(soa_cloud<>(x, y, std::span<const double>(z).first(2)),
                         "soa_cloud: x, y and z must have the same length", invalid_input);
    CHECK_THROWS_WITH_AS(soa_cloud<>(x, y, z, std::span<const std::uint16_t>(intensity).first(1)),
                         "soa_cloud: intensity must be empty or of length x.size() (got 1)", invalid_input);
}

TEST_CASE("core/point_cloud: arrays of structs through member projections")
{
    std::vector<las_point> pts{{1, 2, 3, 100, 1, 2}, {4, 5, 6, 200, 2, 2}};
    aos_cloud c(std::span<const las_point>(pts), &las_point::x, &las_point::y, &las_point::z, &las_point::intensity,
                &las_point::return_number, &las_point::number_of_returns);
    static_assert(point_cloud<decltype(c)>);
    static_assert(has_intensity<decltype(c)> && has_return_number<decltype(c)>);
    static_assert(!has_classification<decltype(c)>);
    CHECK(c.size() == 2);
    CHECK(c.y(1) == 5);
    CHECK(c.intensity(1) == 200);
    CHECK(c.return_number(1) == 2);
    pts[1].z = 60;  // a view, not a copy
    CHECK(c.z(1) == 60);

    aos_cloud xyz(std::span<const las_point>(pts), &las_point::x, &las_point::y,
                  [](const las_point& p) { return -p.z; });
    static_assert(!has_intensity<decltype(xyz)>);
    CHECK(xyz.z(0) == -3);
    CHECK(intensity_of(xyz, 0) == 0.0);
    CHECK(number_of_returns_of(xyz, 0) == 1);
    CHECK(intensity_of(c, 0) == 100.0);
}
