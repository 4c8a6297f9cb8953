// SPDX-License-Identifier: Apache-2.0
#include <doctest/doctest.h>

#include <lidarfx/synth/bucket_index.hpp>
#include <lidarfx/synth/random.hpp>

#include <algorithm>
#include <array>
#include <vector>

using namespace lidarfx::synth;

TEST_CASE("synth/bucket_index: lists every box covering a point (against brute force)")
{
    rng r(51);
    for (const double bucket : {1.0, 7.0, 30.0, 500.0}) {
        bucket_index index(100, bucket);
        std::vector<std::array<double, 4>> boxes;
        for (std::int32_t i = 0; i < 300; ++i) {
            const double x = r.uniform(-10, 110), y = r.uniform(-10, 110), w = r.uniform(0, 15), h = r.uniform(0, 15);
            boxes.push_back({x, y, x + w, y + h});
            index.insert(i, x, y, x + w, y + h);
        }
        int missing = 0;
        for (int k = 0; k < 5000; ++k) {
            const double x = r.uniform(0, 99.999), y = r.uniform(0, 99.999);
            const auto listed = index.at(x, y);
            for (std::int32_t i = 0; i < 300; ++i) {
                const auto& b = boxes[static_cast<std::size_t>(i)];
                const bool covers = x >= b[0] && x <= b[2] && y >= b[1] && y <= b[3];
                if (covers && std::find(listed.begin(), listed.end(), i) == listed.end()) ++missing;
            }
        }
        CHECK(missing == 0);
        CHECK(index.at(-1, 5).empty());
        CHECK(index.at(5, 100.5).empty());
    }
    CHECK(bucket_index().at(0, 0).empty());
}
