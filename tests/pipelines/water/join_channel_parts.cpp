// SPDX-License-Identifier: Apache-2.0
// join_channel_parts: the pieces of one river cut apart at a weir or a deck are one body again; a lake, a pond
// beside a dam, a parallel channel or a ditch stay apart.
#include <doctest/doctest.h>

#include <lidarfx/core/error.hpp>
#include <lidarfx/core/grid.hpp>
#include <lidarfx/core/raster.hpp>
#include <lidarfx/pipelines/water/hydro_flatten.hpp>
#include <lidarfx/pipelines/water/join_channel_parts.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

using namespace lidarfx;

namespace join_channel_parts_test {

/// A land raster of 100 × 400 one-metre cells.
raster<std::int32_t> land()
{
    return raster<std::int32_t>(100, 400, 0);
}

/// Paints label `l` on rows [r0, r1) and columns [c0, c1).
void paint(raster<std::int32_t>& labels, std::int32_t l, std::ptrdiff_t r0, std::ptrdiff_t r1, std::ptrdiff_t c0,
           std::ptrdiff_t c1)
{
    for (std::ptrdiff_t r = r0; r < r1; ++r)
        for (std::ptrdiff_t c = c0; c < c1; ++c) labels(r, c) = l;
}

/// The bounding box of every label up to the largest.
std::vector<cell_box> boxes_of(const raster<std::int32_t>& labels)
{
    std::vector<cell_box> box(1);
    for (std::ptrdiff_t r = 0; r < labels.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < labels.cols(); ++c)
            if (const std::int32_t l = labels(r, c); l > 0) {
                if (box.size() <= static_cast<std::size_t>(l)) box.resize(static_cast<std::size_t>(l) + 1);
                box[static_cast<std::size_t>(l)].extend(r, c);
            }
    return box;
}

/// The water's heights: 100 m on every body, or `level[l]` on label l; NaN on land.
raster<float> heights_of(const raster<std::int32_t>& labels, const std::vector<float>& level = {})
{
    raster<float> z(labels.rows(), labels.cols(), NAN);
    for (std::ptrdiff_t r = 0; r < labels.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < labels.cols(); ++c)
            if (const std::int32_t l = labels(r, c); l > 0)
                z(r, c) = static_cast<std::size_t>(l) < level.size() ? level[static_cast<std::size_t>(l)] : 100.0f;
    return z;
}

std::size_t cells_of(const raster<std::int32_t>& labels, std::int32_t l)
{
    std::size_t n = 0;
    for (const std::int32_t v : labels) n += v == l;
    return n;
}

}  // namespace join_channel_parts_test

using join_channel_parts_test::boxes_of;
using join_channel_parts_test::cells_of;
using join_channel_parts_test::heights_of;
using join_channel_parts_test::paint;

TEST_CASE("water/join_channel_parts: two pieces of a channel that touch at a weir become one body")
{
    auto labels = join_channel_parts_test::land();
    paint(labels, 1, 40, 60, 20, 200);   // 20 m wide, 180 m long
    paint(labels, 2, 40, 60, 200, 380);  // the pool below the weir
    auto box = boxes_of(labels);
    const auto joins = join_channel_parts(labels, box, heights_of(labels), 1.0);
    REQUIRE(joins.size() == 1);
    CHECK(joins[0].kept == 1);
    CHECK(joins[0].part_a == 1);
    CHECK(joins[0].part_b == 2);
    CHECK(joins[0].gap_m == 0);
    CHECK(joins[0].gap_cells == 0);
    CHECK(joins[0].contact_m == doctest::Approx(20).epsilon(0.2));
    CHECK(cells_of(labels, 1) == 20 * 360);
    CHECK(cells_of(labels, 2) == 0);
    CHECK(box[1] == cell_box{40, 20, 59, 379});
    CHECK(box[2].empty());
}

TEST_CASE("water/join_channel_parts: across a deck the water under it joins, the banks beside it stay land")
{
    auto labels = join_channel_parts_test::land();
    paint(labels, 1, 40, 60, 20, 200);
    paint(labels, 2, 40, 60, 212, 380);  // a 12 m deck over columns 200-211
    auto box = boxes_of(labels);
    const auto joins = join_channel_parts(labels, box, heights_of(labels), 1.0);
    REQUIRE(joins.size() == 1);
    CHECK(joins[0].gap_m == doctest::Approx(12).epsilon(0.01));
    CHECK(joins[0].gap_cells == 12 * 20);
    for (std::ptrdiff_t c = 200; c < 212; ++c) {
        CAPTURE(c);
        CHECK(labels(39, c) == 0);  // the banks beside the deck
        CHECK(labels(40, c) == 1);
        CHECK(labels(59, c) == 1);
        CHECK(labels(60, c) == 0);
    }
    CHECK(cells_of(labels, 1) == 20 * 360);
}

TEST_CASE("water/join_channel_parts: pools a weir apart join; water a dam or a bank apart does not")
{
    auto labels = join_channel_parts_test::land();
    paint(labels, 1, 40, 60, 20, 200);
    paint(labels, 2, 40, 60, 200, 380);
    auto box = boxes_of(labels);
    auto weir = labels, dam = labels;
    auto weir_box = box, dam_box = box;
    CHECK(join_channel_parts(weir, weir_box, heights_of(labels, {0, 100, 98.6f}), 1.0).size() == 1);  // 1.4 m
    CHECK(join_channel_parts(dam, dam_box, heights_of(labels, {0, 100, 97}), 1.0).empty());           // 3 m
    CHECK(dam == labels);
    CHECK(join_channel_parts(dam, dam_box, heights_of(labels, {0, 100, 97}), 1.0, {.max_level_step_m = INFINITY})
              .size() == 1);
    CHECK_THROWS_AS(join_channel_parts(dam, dam_box, heights_of(labels), 1.0, {.max_level_step_m = NAN}),
                    invalid_input);
    raster<float> other_shape(10, 10, 100.0f);
    CHECK_THROWS_AS(join_channel_parts(labels, box, other_shape, 1.0), invalid_input);
}

TEST_CASE("water/join_channel_parts: a pond beside a stream, its water 1 m higher and together no river, stays apart")
{
    auto labels = join_channel_parts_test::land();
    paint(labels, 1, 10, 30, 20, 220);  // a 20 m stream, 200 m long
    paint(labels, 2, 30, 70, 60, 150);  // a pond along its side, 40 m wide and 90 m long
    auto box = boxes_of(labels);
    CHECK(join_channel_parts(labels, box, heights_of(labels, {0, 100, 101}), 1.0).empty());
}

TEST_CASE("water/join_channel_parts: a gap wider than max_gap_m stays land, as a wider one at a larger max_gap_m joins")
{
    auto labels = join_channel_parts_test::land();
    paint(labels, 1, 40, 60, 20, 180);
    paint(labels, 2, 40, 60, 220, 380);  // 40 m of land
    auto box = boxes_of(labels);
    auto kept = labels;
    auto kept_box = box;
    CHECK(join_channel_parts(kept, kept_box, heights_of(kept), 1.0).empty());
    CHECK(kept == labels);
    const auto joins = join_channel_parts(labels, box, heights_of(labels), 1.0, {.max_gap_m = 45});
    REQUIRE(joins.size() == 1);
    CHECK(joins[0].gap_cells == 40 * 20);
}

TEST_CASE(
    "water/join_channel_parts: parallel channels, a lake the river flows into, ponds beside a dam and a ditch "
    "stay apart")
{
    SUBCASE("two channels 10 m apart, side by side along 300 m")
    {
        auto labels = join_channel_parts_test::land();
        paint(labels, 1, 10, 30, 40, 340);
        paint(labels, 2, 40, 60, 40, 340);
        auto box = boxes_of(labels);
        CHECK(join_channel_parts(labels, box, heights_of(labels), 1.0).empty());
    }
    SUBCASE("a 20 m river touching a lake 90 m across")
    {
        auto labels = join_channel_parts_test::land();
        paint(labels, 1, 40, 60, 0, 250);
        paint(labels, 2, 5, 95, 250, 340);
        auto box = boxes_of(labels);
        CHECK(join_channel_parts(labels, box, heights_of(labels), 1.0).empty());
    }
    SUBCASE("two 40 m ponds either side of a 3 m dam")
    {
        auto labels = join_channel_parts_test::land();
        paint(labels, 1, 30, 70, 100, 140);
        paint(labels, 2, 30, 70, 143, 183);
        auto box = boxes_of(labels);
        CHECK(join_channel_parts(labels, box, heights_of(labels), 1.0).empty());
        CHECK(join_channel_parts(labels, box, heights_of(labels), 1.0, {.min_elongation = 2}).size() ==
              1);  // as one body, 2 long
    }
    SUBCASE("a ditch 6 m wide touching a channel end to end")
    {
        auto labels = join_channel_parts_test::land();
        paint(labels, 1, 40, 60, 20, 200);
        paint(labels, 2, 47, 53, 200, 380);
        auto box = boxes_of(labels);
        CHECK(join_channel_parts(labels, box, heights_of(labels), 1.0).empty());
    }
}

TEST_CASE("water/join_channel_parts: a chain of pieces takes the smallest label; a third body on the way is kept")
{
    auto labels = join_channel_parts_test::land();
    paint(labels, 3, 40, 60, 0, 120);
    paint(labels, 1, 40, 60, 120, 250);
    paint(labels, 2, 40, 60, 258, 400);  // beyond a deck
    paint(labels, 4, 80, 90, 10, 30);    // a small pond, nowhere near
    auto box = boxes_of(labels);
    const auto joins = join_channel_parts(labels, box, heights_of(labels), 1.0);
    REQUIRE(joins.size() == 2);
    CHECK(joins[0].kept == 1);
    CHECK(joins[0].part_a == 1);
    CHECK(joins[0].part_b == 2);
    CHECK(joins[1].kept == 1);
    CHECK(joins[1].part_a == 1);
    CHECK(joins[1].part_b == 3);
    CHECK(cells_of(labels, 1) == 20 * 400);
    CHECK(cells_of(labels, 4) == 200);
    CHECK(box[2].empty());
    CHECK(box[3].empty());
}

TEST_CASE("water/join_channel_parts: every pair is reported, also one whose smaller label is not the channel's")
{
    auto labels = join_channel_parts_test::land();
    paint(labels, 1, 40, 60, 0, 150);
    paint(labels, 3, 40, 60, 150, 300);
    paint(labels, 2, 40, 60, 300, 400);
    auto box = boxes_of(labels);
    const auto joins = join_channel_parts(labels, box, heights_of(labels), 1.0);
    REQUIRE(joins.size() == 2);
    CHECK((joins[0].kept == 1 && joins[0].part_a == 1 && joins[0].part_b == 3));
    CHECK((joins[1].kept == 1 && joins[1].part_a == 2 && joins[1].part_b == 3));
    CHECK(cells_of(labels, 1) == 20 * 400);
}

TEST_CASE("water/join_channel_parts: pieces a third body separates are not joined, and hydro_flatten keeps them apart")
{
    raster<std::int32_t> labels(60, 800, 0);
    paint(labels, 1, 10, 50, 5, 605);
    paint(labels, 3, 10, 50, 607, 608);  // a thin third body across the whole gap
    paint(labels, 2, 10, 50, 610, 760);
    auto box = boxes_of(labels);
    auto joined = labels;
    CHECK(join_channel_parts(joined, box, heights_of(labels), 1.0).empty());
    CHECK(joined == labels);
    const raster<float> z = heights_of(labels);
    raster<float> dem(labels.rows(), labels.cols(), 12.0f);
    const auto flat = hydro_flatten(dem, labels, z, z, 1.0);
    CHECK(flat.joins.empty());
    CHECK(flat.bodies.size() == 3);
}

TEST_CASE("water/join_channel_parts: refuses options out of range, negative labels and labels outside their box")
{
    auto labels = join_channel_parts_test::land();
    paint(labels, 1, 40, 60, 20, 200);
    auto box = boxes_of(labels);
    CHECK_THROWS_AS(join_channel_parts(labels, box, heights_of(labels), 0.0), invalid_input);
    CHECK_THROWS_AS(join_channel_parts(labels, box, heights_of(labels), 1.0, {.max_gap_m = -1}), invalid_input);
    CHECK_THROWS_AS(join_channel_parts(labels, box, heights_of(labels), 1.0, {.min_contact_share = 0}), invalid_input);
    CHECK_THROWS_AS(join_channel_parts(labels, box, heights_of(labels), 1.0, {.max_width_ratio = 0.5}), invalid_input);
    CHECK_THROWS_AS(join_channel_parts(labels, box, heights_of(labels), 1.0, {.min_elongation = NAN}), invalid_input);
    auto narrow = box;
    narrow[1].col_max = 100;
    CHECK_THROWS_AS(join_channel_parts(labels, narrow, heights_of(labels), 1.0), invalid_input);
    labels(0, 0) = 5;  // no box for it
    CHECK_THROWS_AS(join_channel_parts(labels, box, heights_of(labels), 1.0), invalid_input);
    labels(0, 0) = -1;
    CHECK_THROWS_AS(join_channel_parts(labels, box, heights_of(labels), 1.0), invalid_input);
}

TEST_CASE(
    "water/hydro_flatten: a river cut at a deck is one flattened river under the deck, unless join_channels is off")
{
    auto labels = join_channel_parts_test::land();
    paint(labels, 1, 40, 80, 0, 190);
    paint(labels, 2, 40, 80, 200, 400);  // a 10 m deck
    raster<float> dem(labels.rows(), labels.cols(), 103.0f), min_z(labels.rows(), labels.cols(), NAN);
    for (std::ptrdiff_t r = 0; r < labels.rows(); ++r)
        for (std::ptrdiff_t c = 0; c < labels.cols(); ++c) {
            if (labels(r, c) != 0) dem(r, c) = min_z(r, c) = 100.0f - 0.002f * static_cast<float>(c);
            if (labels(r, c) == 0 && r >= 40 && r < 80) dem(r, c) = min_z(r, c) = 106.0f;  // the deck
        }
    const raster<float> max_z = min_z;
    const auto joined = hydro_flatten(dem, labels, min_z, max_z, 1.0);
    REQUIRE(joined.joins.size() == 1);
    REQUIRE(joined.bodies.size() == 1);
    CHECK(joined.bodies[0].type == hydro_body_type::river);
    CHECK(joined.bodies[0].flattened);
    for (std::ptrdiff_t c = 190; c < 200; ++c) {
        CAPTURE(c);
        CHECK(joined.body(60, c) == 1);
        CHECK(joined.dem(60, c) ==
              doctest::Approx(100 - 0.002 * static_cast<double>(c)).epsilon(0.0003));  // no deck, no bowl
    }
    const auto apart = hydro_flatten(dem, labels, min_z, max_z, 1.0, {.join_channels = false});
    CHECK(apart.joins.empty());
    CHECK(apart.bodies.size() == 2);
    CHECK(apart.dem(60, 195) == 106.0f);
}
