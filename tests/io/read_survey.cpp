// SPDX-License-Identifier: Apache-2.0
// The program's survey reading (examples/cli/cli_common) on hostile and careless inputs, all generated here.
#include <doctest/doctest.h>

#include "cli/cli_common.hpp"
#include "io/geotiff.hpp"
#include "io/las_writer.hpp"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "io_test_util.hpp"

using namespace lidarfx;
using namespace lidarfx::io;
using io_test::contains;
using io_test::error_of;

namespace {

las_points points_at(const std::vector<std::array<double, 3>>& xyz)
{
    las_points p;
    for (const auto& [x, y, z] : xyz) {
        p.x.push_back(x);
        p.y.push_back(y);
        p.z.push_back(z);
    }
    return p;
}

/// A small dense survey: n x n points one metre apart with some height.
las_points grid_points(int n, double x0 = 500000.0, double y0 = 4000000.0)
{
    std::vector<std::array<double, 3>> xyz;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) xyz.push_back({x0 + j, y0 + i, 10.0 + 0.01 * i * j});
    return points_at(xyz);
}

cli::survey_options quiet(double cell_m = 2.0)
{
    cli::survey_options o;
    o.cell_m = cell_m;
    o.show_progress = false;
    return o;
}

}  // namespace

TEST_CASE("io/read_survey: header bounds near 2^48 are refused before any allocation, with the way out")
{
    // Two points 4.2e14 m apart (scale 1e5 keeps them in 32-bit integers): rows * cols would wrap an int64.
    io_test::temp_dir dir;
    const auto path = dir.file("far.las");
    write_las(path, points_at({{-2.1e14, -2.1e14, 0.0}, {2.1e14, 2.1e14, 0.0}}),
              {.scale = {1e5, 1e5, 0.01}, .offset = std::array<double, 3>{0.0, 0.0, 0.0}});
    auto o = quiet(2.0);
    o.memory_budget_bytes = std::uint64_t{1} << 30;
    const auto why = error_of([&] { cli::read_survey({path}, o); });
    CHECK(contains(why, "over the memory budget of 1 GiB"));
    CHECK(contains(why, "use --cell"));
    // Even with the most generous budget and --force, the answer is an error, never a wrapped size: at
    // 10 km cells the estimate fits the budget, and the library refuses the 1.8e15-cell grid itself.
    o.memory_budget_bytes = std::numeric_limits<std::uint64_t>::max() / 2;
    o.force = true;
    o.cell_m = 1e7;
    const auto library = error_of([&] { cli::read_survey({path}, o); });
    CHECK(contains(library, "2^40"));
}

TEST_CASE("io/read_survey: a survey whose coordinates are all non-finite is an error, not empty rasters")
{
    io_test::temp_dir dir;
    const auto path = dir.file("inf.las");
    auto bytes = encode_las(grid_points(4), {.scale = {1.0, 1.0, 1.0}, .offset = std::array<double, 3>{0.0, 0.0, 0.0}});
    const double huge_scale = 1e305;  // x = 500000 * 1e305 overflows to +inf in every point
    std::memcpy(bytes.data() + 131, &huge_scale, sizeof huge_scale);
    io_test::write_bytes(path, bytes);
    const auto why = error_of([&] { cli::read_survey({path}, quiet(1.0)); });
    CHECK(contains(why, "no point of the input has finite coordinates"));
}

TEST_CASE("io/read_survey: the same file twice, by another name or a link, is refused")
{
    io_test::temp_dir dir;
    const auto path = dir.file("a.las");
    write_las(path, grid_points(10));
    std::filesystem::create_symlink(path, dir.file("link.las"));
    CHECK(contains(error_of([&] { cli::read_survey({path, dir.file("link.las")}, quiet()); }), "is the same file as"));
    CHECK(contains(error_of([&] { cli::read_survey({path, path}, quiet()); }), "give each file once"));
}

TEST_CASE("io/read_survey: points outside the bounds a header declares are an error naming that file")
{
    io_test::temp_dir dir;
    const auto good = dir.file("good.las"), lying = dir.file("lying.las");
    write_las(good, grid_points(10));
    auto bytes = encode_las(grid_points(10, 500020.0));
    const double max_x = 500021.0;  // the true maximum is 500029
    std::memcpy(bytes.data() + 179, &max_x, sizeof max_x);
    io_test::write_bytes(lying, bytes);
    const auto why = error_of([&] { cli::read_survey({good, lying}, quiet(1.0)); });
    CHECK(contains(why, lying + ": "));
    CHECK(contains(why, "points lie outside the bounds its LAS header declares"));
}

TEST_CASE("io/read_survey: points on the header's east and south bounds are inside at any cell size (500 sizes)")
{
    // The bounds of PDAL's 4_6_crop.las and Autzen: a maximum such as 1010 that is not a multiple of the cell.
    // Before one rounding rule served sizing and lookup, 14 of 500 cell sizes rejected such a valid file.
    io_test::temp_dir dir;
    const auto path = dir.file("edges.las");
    std::vector<std::array<double, 3>> xyz;
    for (int i = 0; i <= 20; ++i) {
        xyz.push_back({1000.0 + 0.5 * i, 2000.0, 1.0});  // south edge, west to east
        xyz.push_back({1010.0, 2000.0 + 0.5 * i, 1.0});  // east edge, south to north
        xyz.push_back({1000.0, 2000.0 + 0.5 * i, 1.0});  // west edge
        xyz.push_back({1000.0 + 0.5 * i, 2010.0, 1.0});  // north edge
    }
    write_las(path, points_at(xyz));
    int refused = 0;
    for (int k = 1; k <= 500; ++k) {
        auto o = quiet(0.01 * k);
        o.force = true;  // the density refusal is not what this tests
        const auto why = error_of([&] {
            const auto s = cli::read_survey({path}, o);
            if (s.rasters.points_used != xyz.size()) throw std::runtime_error("points lost");
        });
        if (why != "<no error>") {
            ++refused;
            MESSAGE("cell ", 0.01 * k, ": ", why);
        }
    }
    CHECK(refused == 0);
}

TEST_CASE("io/read_survey: a cell far too small for the density is refused unless forced; --crop keeps a box")
{
    io_test::temp_dir dir;
    const auto path = dir.file("sparse.las");
    // 1,000 points scattered over 5 km x 5 km.
    std::vector<std::array<double, 3>> xyz;
    for (int i = 0; i < 1000; ++i) xyz.push_back({500000.0 + (i * 7919) % 5000, 4000000.0 + (i * 104729) % 5000, 1.0});
    write_las(path, points_at(xyz));
    const auto why = error_of([&] { cli::read_survey({path}, quiet(1.0)); });
    CHECK(contains(why, "over 99 % of the cells would be empty"));
    CHECK(contains(why, "Use --cell 200 or more"));
    auto forced = quiet(50.0);
    forced.force = true;
    const auto s = cli::read_survey({path}, forced);
    CHECK(s.rasters.points_used == 1000);
    auto cropped = quiet(50.0);
    cropped.force = true;
    cropped.crop = bounds{500000.0, 4000000.0, 502499.0, 4002499.0};
    const auto c = cli::read_survey({path}, cropped);
    CHECK(c.rasters.points_used + c.rasters.points_outside == 1000);
    CHECK(c.rasters.points_used < 1000);
    CHECK(c.rasters.g.x1() <= 502550.0);
}

TEST_CASE("io/read_survey: rasters do not depend on --threads")
{
    io_test::temp_dir dir;
    std::vector<std::string> paths;
    for (int k = 0; k < 3; ++k) {
        paths.push_back(dir.file("tile" + std::to_string(k) + ".las"));
        write_las(paths.back(), grid_points(40, 500000.0 + 40 * k));
    }
    auto one = quiet(1.0), two = quiet(1.0);
    one.threads = 1;
    two.threads = 2;
    const auto a = cli::read_survey(paths, one), b = cli::read_survey(paths, two);
    CHECK(a.points == 4800);
    CHECK(io_test::same_cells(a.rasters.min_z, b.rasters.min_z));
    CHECK(io_test::same_cells(a.rasters.max_z, b.rasters.max_z));
    CHECK(a.rasters.count == b.rasters.count);
}

TEST_CASE("io/read_survey: a point far from the rest is reported with the crop that keeps the others")
{
    io_test::temp_dir dir;
    const auto path = dir.file("outlier.las");
    auto p = grid_points(100);
    p.x.push_back(700000.0);  // 200 km east of a 100 m survey
    p.y.push_back(4000050.0);
    p.z.push_back(12.0);
    write_las(path, p);
    const auto why = error_of([&] { cli::read_survey({path}, quiet(1.0)); });
    CHECK(contains(why, "1 of 10001 points lie far from the rest (the most near x 699"));
    CHECK(contains(why, "Use --crop 500000,"));
    // Forced, the point is kept: the grid then spans 200 km, which the memory budget refuses.
    auto forced = quiet(1.0);
    forced.force = true;
    forced.memory_budget_bytes = std::uint64_t{1} << 30;
    CHECK(contains(error_of([&] { cli::read_survey({path}, forced); }), "over the memory budget"));
    // The survey alone raises nothing.
    write_las(dir.file("alone.las"), grid_points(100));
    CHECK(cli::read_survey({dir.file("alone.las")}, quiet(1.0)).rasters.points_used == 10000);
}

TEST_CASE("io/read_survey: a WKT record nobody can read is dropped with a warning instead of failing the run")
{
    io_test::temp_dir dir;
    const auto path = dir.file("odd_crs.las");
    write_las(path, grid_points(10), {.version_minor = 4, .point_format = 6, .wkt = "NOT A COORDINATE SYSTEM["});
    const auto s = cli::read_survey({path}, quiet(1.0));
    CHECK(s.rasters.points_used == 100);
    CHECK(s.crs_wkt.empty());  // neither GDAL nor the reader without it can read it: the outputs go without a CRS
    CHECK(contains(s.crs.warnings.at(0), "WKT record is unreadable"));
}
