// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/synth/roofs.hpp>

#include "synth/scene_stats.hpp"

#include <cmath>
#include <vector>

using namespace lidarfx::synth;
using lidarfx::deg_to_rad;
using synth_test::angle_difference;
using synth_test::fit_plane;

namespace {

building_truth random_building(rng& r, roof_kind_truth kind)
{
    building_truth b;
    b.id = 3;
    b.x = r.uniform(-100, 100);
    b.y = r.uniform(-100, 100);
    b.width_m = r.uniform(6, 16);
    b.length_m = b.width_m * r.uniform(1.0, 2.2);
    b.axis_azimuth_deg = r.uniform(0, 360);
    b.kind = kind;
    b.tilt_deg = kind == roof_kind_truth::flat ? 0.0 : r.uniform(5, 50);
    b.shed_facing = r.between(0, 3);
    b.eave_z = r.uniform(50, 60);
    return b;
}

}  // namespace

TEST_CASE("synth/building_truth: every face is the plane its truth states")
{
    rng r(21);
    for (const auto kind :
         {roof_kind_truth::flat, roof_kind_truth::shed, roof_kind_truth::gable, roof_kind_truth::hip}) {
        for (int trial = 0; trial < 25; ++trial) {
            const building_truth b = random_building(r, kind);
            const auto planes = b.planes();
            std::vector<std::vector<std::array<double, 3>>> samples(planes.size());
            std::vector<int> hits(planes.size(), 0);
            const double R = b.bounding_radius();
            int inside = 0;
            bool valid = true;
            for (int k = 0; k < 8000; ++k) {
                const double x = b.x + r.uniform(-R, R), y = b.y + r.uniform(-R, R);
                if (!b.contains(x, y)) continue;
                ++inside;
                const auto hit = b.roof_at(x, y);
                const auto f = static_cast<std::size_t>(hit.face);
                valid = valid && hit.face >= 0 && f < planes.size() && hit.z >= b.eave_z - 1e-9;
                if (!valid) break;
                samples[f].push_back({x, y, hit.z});
                ++hits[f];
            }
            REQUIRE(valid);
            double horizontal = 0;
            for (std::size_t f = 0; f < planes.size(); ++f) {
                CHECK(planes[f].building_id == 3);
                CHECK(planes[f].azimuth_deg >= 0.0);
                CHECK(planes[f].azimuth_deg < 360.0);
                // Exact points on a plane: the fit recovers tilt and azimuth to rounding.
                const auto fit = fit_plane(samples[f]);
                CHECK(fit.tilt_deg == doctest::Approx(planes[f].tilt_deg).epsilon(1e-6));
                if (planes[f].tilt_deg > 0) CHECK(angle_difference(fit.azimuth_deg, planes[f].azimuth_deg) < 1e-6);
                const double face_horizontal = planes[f].area_m2 * std::cos(deg_to_rad(planes[f].tilt_deg));
                horizontal += face_horizontal;
                // Monte Carlo share of the footprint; 8000 draws on about 60 % of them: a few % of error.
                const double share = static_cast<double>(hits[f]) / inside;
                CHECK(share == doctest::Approx(face_horizontal / (b.length_m * b.width_m)).epsilon(0.1));
            }
            CHECK(horizontal == doctest::Approx(b.length_m * b.width_m).epsilon(1e-9));
        }
    }
}

TEST_CASE("synth/building_truth: gable and hip roofs close at the ridge and meet the eaves")
{
    rng r(22);
    for (const auto kind : {roof_kind_truth::gable, roof_kind_truth::hip}) {
        const building_truth b = random_building(r, kind);
        const double rise = std::tan(deg_to_rad(b.tilt_deg)) * 0.5 * b.width_m;
        // Centre of the footprint: the ridge.
        CHECK(b.roof_at(b.x, b.y).z == doctest::Approx(b.eave_z + rise));
        // Corners: the eaves.
        const auto ring = b.footprint();
        for (std::size_t i = 0; i + 1 < ring.size(); ++i)
            CHECK(b.roof_at(ring[i][0], ring[i][1]).z == doctest::Approx(b.eave_z).epsilon(1e-9));
    }
    // Hip faces meet on the hip lines: continuity across them.
    building_truth hip = random_building(r, roof_kind_truth::hip);
    hip.axis_azimuth_deg = 0;  // long axis north: u = y, v = x
    const double l = hip.length_m, w = hip.width_m;
    for (double t = 0.05; t < 0.5; t += 0.05) {
        const double along = 0.5 * l - t * w, across = 0.5 * w - t * w;  // on the hip line
        CHECK(hip.roof_at(hip.x + across + 1e-7, hip.y + along).z ==
              doctest::Approx(hip.roof_at(hip.x + across - 1e-7, hip.y + along).z));
    }
}

TEST_CASE("synth/building_truth: footprints are closed counter-clockwise rectangles matching contains()")
{
    rng r(23);
    for (int trial = 0; trial < 40; ++trial) {
        const building_truth b = random_building(r, roof_kind_truth::gable);
        const auto ring = b.footprint();
        REQUIRE(ring.size() == 5);
        CHECK(ring.front() == ring.back());
        double twice_area = 0;
        for (std::size_t i = 0; i + 1 < ring.size(); ++i)
            twice_area += ring[i][0] * ring[i + 1][1] - ring[i + 1][0] * ring[i][1];
        CHECK(0.5 * twice_area == doctest::Approx(b.length_m * b.width_m));  // positive: counter-clockwise
        int mismatches = 0;
        for (int k = 0; k < 2000; ++k) {
            const double x = b.x + r.uniform(-20, 20), y = b.y + r.uniform(-20, 20);
            mismatches += b.contains(x, y) != synth_test::inside_ring(ring, x, y);
        }
        CHECK(mismatches == 0);
    }
}

TEST_CASE("synth/building_truth: facing azimuths follow the axis and the face numbering")
{
    building_truth b;
    b.axis_azimuth_deg = 30;
    b.kind = roof_kind_truth::hip;
    const auto planes = b.planes();
    REQUIRE(planes.size() == 4);
    CHECK(planes[0].azimuth_deg == doctest::Approx(120));
    CHECK(planes[1].azimuth_deg == doctest::Approx(300));
    CHECK(planes[2].azimuth_deg == doctest::Approx(30));
    CHECK(planes[3].azimuth_deg == doctest::Approx(210));
    b.kind = roof_kind_truth::shed;
    b.shed_facing = 3;
    CHECK(b.planes().at(0).azimuth_deg == doctest::Approx(210));
    b.kind = roof_kind_truth::flat;
    CHECK(b.planes().at(0).tilt_deg == 0.0);
    CHECK(b.planes().at(0).area_m2 == doctest::Approx(b.length_m * b.width_m));
}
