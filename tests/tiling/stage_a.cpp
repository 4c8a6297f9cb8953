// SPDX-License-Identifier: Apache-2.0
// Stage A of docs/scale.md: points routed to tiles by tile_index_of, one raster_accumulator per tile on the survey
// grid, merged: the rasters equal one untiled accumulator's bit for bit.
#include <doctest/doctest.h>

#include <lidarfx/kernels/points/rasterize.hpp>
#include <lidarfx/tiling/tile_plan.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

using namespace lidarfx;

namespace {

struct points {
    std::vector<double> x, y, z;
    std::vector<std::uint16_t> intensity;
    void push(double px, double py, double pz, std::uint16_t i)
    {
        x.push_back(px), y.push_back(py), z.push_back(pz), intensity.push_back(i);
    }
    soa_cloud<> cloud() const { return soa_cloud<>(x, y, z, intensity); }
};

template <class T>
bool same_bits(const raster<T>& a, const raster<T>& b)
{
    if (a.rows() != b.rows() || a.cols() != b.cols()) return false;
    for (std::ptrdiff_t r = 0; r < a.rows(); ++r) {
        for (std::ptrdiff_t c = 0; c < a.cols(); ++c) {
            if constexpr (std::is_same_v<T, float>) {
                if (std::bit_cast<std::uint32_t>(a(r, c)) != std::bit_cast<std::uint32_t>(b(r, c))) return false;
            } else if (a(r, c) != b(r, c)) {
                return false;
            }
        }
    }
    return true;
}

}  // namespace

TEST_CASE("tiling/tile_index_of: per-tile accumulators on the survey grid merge to the untiled rasters")
{
    std::mt19937 rng(1520);
    std::uniform_real_distribution<double> u(0, 1);
    std::uniform_int_distribution<int> intensity(0, 65535);
    // A 0.3 m lattice (not a power of two: corners of tile windows round) and points on its lines.
    const double cell = 0.3;
    const bounds extent{512000.1, 4100000.2, 512030.0, 4100021.0};
    const grid g = snapped_grid(extent, cell);
    points all;
    for (int i = 0; i < 20000; ++i) {
        double x = extent.xmin + (extent.xmax - extent.xmin) * u(rng),
               y = extent.ymin + (extent.ymax - extent.ymin) * u(rng);
        if (i % 3 == 0) x = g.x0 + std::floor((x - g.x0) / cell) * cell;  // on a vertical lattice line
        if (i % 5 == 0) y = g.y0 - std::floor((g.y0 - y) / cell) * cell;  // on a horizontal one
        all.push(x, y, 10 + 5 * u(rng), std::uint16_t(intensity(rng)));
    }
    raster_accumulator whole(g);
    whole.add(all.cloud());
    const rasterize_result expected = whole.finish();

    for (const double edge_m : {0.3, 2.1, 18.0, 1000.0}) {
        CAPTURE(edge_m);
        const tile_plan plan = make_tile_plan(g, {}, {.tile_edge_m = edge_m});
        std::vector<points> routed(plan.tiles.size());
        for (std::size_t i = 0; i < all.x.size(); ++i) {
            const auto t = tile_index_of(plan, all.x[i], all.y[i]);
            REQUIRE(t);
            const auto at = g.cell_of(all.x[i], all.y[i]);
            const cell_box& core = plan.tiles[*t].core;
            CHECK((at->row >= core.row_min && at->row <= core.row_max && at->col >= core.col_min &&
                   at->col <= core.col_max));
            routed[*t].push(all.x[i], all.y[i], all.z[i], all.intensity[i]);
        }
        // Tiles in reverse order, each its own accumulator on the survey grid (sparse: memory follows its points).
        raster_accumulator total(g);
        for (std::size_t t = plan.tiles.size(); t-- > 0;) {
            raster_accumulator tile(g);
            tile.add(routed[t].cloud());
            total.merge(tile);
        }
        const rasterize_result got = total.finish();
        CHECK(same_bits(got.min_z, expected.min_z));
        CHECK(same_bits(got.max_z, expected.max_z));
        CHECK(same_bits(got.mean_intensity, expected.mean_intensity));
        CHECK(same_bits(got.count, expected.count));
        CHECK(same_bits(got.dropout, expected.dropout));
        CHECK(got.points_used == expected.points_used);
    }
    CHECK_FALSE(tile_index_of(make_tile_plan(g, {}), extent.xmin - 1, extent.ymin));
    CHECK_FALSE(tile_index_of(make_tile_plan(g, {}), std::nan(""), extent.ymin));
}
