// SPDX-License-Identifier: Apache-2.0
// libFuzzer target for the GeoJSON footprint reader (parse_footprints_geojson): any bytes must give footprints
// or an invalid_input, never a crash, a sanitizer report, another exception or memory beyond a few times the
// input. What it accepts keeps the documented promises: ids in 1 .. 2^31 - 1 and unique, features in file
// order, closed rings of at least 4 finite positions within footprint_max_abs_coordinate. The reported peak is
// the budget's own measure: a budget of exactly that accepts the same text, one byte less refuses it.
// Built and run by scripts/fuzz.sh.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <set>
#include <string>

#include <lidarfx/core/error.hpp>

#include "io/footprints.hpp"

namespace {

using lidarfx::io::footprint_collection;

void check(const footprint_collection& c, std::size_t text_size)
{
    if (c.peak_bytes < text_size) std::abort();
    std::set<std::int32_t> ids;
    std::size_t last = 0;
    bool first = true;
    for (const auto& f : c.footprints) {
        if (f.building_id < 1 || !ids.insert(f.building_id).second) std::abort();
        if (!first && f.feature <= last) std::abort();
        first = false;
        last = f.feature;
        if (f.parts.empty()) std::abort();
        for (const auto& p : f.parts) {
            if (p.rings.empty()) std::abort();
            for (const auto& ring : p.rings) {
                if (ring.size() < 4 || ring.front() != ring.back()) std::abort();
                for (const auto& v : ring)
                    for (const double x : v)
                        if (!(std::abs(x) <= lidarfx::io::footprint_max_abs_coordinate)) std::abort();
            }
        }
    }
    for (const auto& p : c.problems) {
        if (p.building_id < 1 || !ids.insert(p.building_id).second || p.problem.empty()) std::abort();
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::string text(reinterpret_cast<const char*>(data), size);
    footprint_collection c;
    try {
        c = lidarfx::io::parse_footprints_geojson(text, "fuzz", {.memory_budget_bytes = 256u << 20});
    } catch (const lidarfx::invalid_input&) {
        return 0;
    }
    check(c, size);
    const auto again = lidarfx::io::parse_footprints_geojson(text, "fuzz", {.memory_budget_bytes = c.peak_bytes});
    if (again.footprints.size() != c.footprints.size() || again.problems.size() != c.problems.size()) std::abort();
    try {
        (void)lidarfx::io::parse_footprints_geojson(text, "fuzz", {.memory_budget_bytes = c.peak_bytes - 1});
    } catch (const lidarfx::invalid_input&) {
        return 0;
    }
    std::abort();  // one byte under its own peak, the read must be refused
}
