// SPDX-License-Identifier: Apache-2.0
// libFuzzer target for the TMY3 reader (parse_tmy3): any bytes must give a weather year or an exception of a
// documented type (invalid_input, std::runtime_error), never a crash, a sanitizer report or another exception.
// What it accepts keeps the year's rules of tmy3.hpp: one record per hour present, hours present + missing =
// 8760 with at most tmy3_max_missing_hours missing, irradiances within their bounds. Built and run by
// scripts/fuzz.sh.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string_view>

#include <lidarfx/core/error.hpp>

#include "io/tmy3.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    namespace io = lidarfx::io;
    io::tmy3_data d;
    try {
        d = io::parse_tmy3(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz");
    } catch (const lidarfx::invalid_input&) {
        return 0;
    } catch (const std::runtime_error&) {
        return 0;
    }
    const auto& c = d.coverage;
    if (static_cast<std::size_t>(c.hours_present) != d.records.size()) std::abort();
    if (c.hours_present + c.hours_missing != io::tmy3_hours_of_year) std::abort();
    if (c.hours_missing < 0 || c.hours_missing > io::tmy3_max_missing_hours) std::abort();
    for (const auto& r : d.records) {
        if (!(r.dni_w_m2 >= 0 && r.dni_w_m2 <= io::tmy3_max_dni_w_m2)) std::abort();
        if (!(r.ghi_w_m2 >= 0 && r.ghi_w_m2 <= io::tmy3_max_ghi_dhi_w_m2)) std::abort();
        if (!(r.dhi_w_m2 >= 0 && r.dhi_w_m2 <= io::tmy3_max_ghi_dhi_w_m2)) std::abort();
        if (r.interval.count() <= 0) std::abort();
    }
    (void)io::coverage_line(d, "fuzz");
    return 0;
}
