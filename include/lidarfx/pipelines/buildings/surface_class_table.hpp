// SPDX-License-Identifier: Apache-2.0
// surface_class_table and bill_savings: the dissertation's Table 1 (irradiation of north, south, east and west
// facades and rooftops per quarter and year) and Table 2 (what a small PV system there would save on the bill).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>

#include "lidarfx/core/error.hpp"
#include "lidarfx/pipelines/buildings/surface_energy.hpp"

namespace lidarfx {

/// The surface classes of the dissertation's Tables 1 and 2, in their row order.
enum class surface_class : std::size_t { north_facade, south_facade, east_facade, west_facade, rooftop };

/// One row of Table 1: area-weighted mean irradiation of a surface class.
struct surface_class_row {
    surface_class kind = surface_class::rooftop;
    double area_m2 = 0;                          ///< total area of the class's patches, m^2
    std::array<double, 4> quarter_kwh_m2_day{};  ///< Jan-Mar, Apr-Jun, Jul-Sep, Oct-Dec, kWh/m^2/day
    double annual_kwh_m2 = 0;                    ///< kWh/m^2/yr
};

/// Settings of bill_savings; defaults are the dissertation's (Table 2).
struct bill_savings_options {
    double module_efficiency = 0.16;    ///< conversion efficiency of the modules, (0, 1] (poly-crystalline 16 %)
    double inverter_efficiency = 0.95;  ///< (0, 1]
    double temperature_loss = 0.06;     ///< reduction for temperature, [0, 1) (the dissertation's -6 %)
    int modules = 12;                   ///< modules of the system, >= 1
    double module_width_in = 65.0;      ///< module size, inches, > 0
    double module_height_in = 39.0;     ///< inches, > 0
    double tariff_per_kwh = 0.11;       ///< electricity price per kWh (Dallas 2019: $0.11), >= 0
};

/// One row of Table 2: the money a system on a surface class saves.
struct bill_savings_row {
    surface_class kind = surface_class::rooftop;
    std::array<double, 4> quarter_per_day{};  ///< per day in each quarter, in the tariff's currency
    double annual = 0;                        ///< per year
};

/// The class of a facade facing azimuth_deg: north [315, 45), east [45, 135), south [135, 225), west [225, 315).
inline surface_class facade_class(double facing_azimuth_deg) noexcept
{
    double a = std::fmod(facing_azimuth_deg, 360.0);
    if (a < 0.0) a += 360.0;
    if (a >= 45.0 && a < 135.0) return surface_class::east_facade;
    if (a >= 135.0 && a < 225.0) return surface_class::south_facade;
    if (a >= 225.0 && a < 315.0) return surface_class::west_facade;
    return surface_class::north_facade;
}

/// Table 1 of the dissertation from surface_energy's result: for each class (facades by facade_class of their
/// facing azimuth, rooftop = all roof patches) the area-weighted mean of its patches' quarterly kWh/m^2/day and
/// annual kWh/m^2/yr: sum(area * value) / sum(area). A class without patches has area 0 and zeros.
inline std::array<surface_class_row, 5> surface_class_table(const surface_energy_result& e)
{
    std::array<surface_class_row, 5> rows{};
    for (std::size_t k = 0; k < 5; ++k) rows[k].kind = static_cast<surface_class>(k);
    const auto add = [&](surface_class_row& row, double area, const patch_energy& pe) {
        row.area_m2 += area;
        row.annual_kwh_m2 += area * pe.annual_kwh_m2;
        for (std::size_t q = 0; q < 4; ++q) row.quarter_kwh_m2_day[q] += area * pe.quarter_kwh_m2_day[q];
    };
    for (std::size_t i = 0; i < e.facades.size() && i < e.facade_energy.size(); ++i) {
        add(rows[static_cast<std::size_t>(facade_class(e.facades[i].facing_azimuth_deg))], e.facades[i].area_m2,
            e.facade_energy[i]);
    }
    for (std::size_t i = 0; i < e.roofs.size() && i < e.roof_energy.size(); ++i) {
        add(rows[static_cast<std::size_t>(surface_class::rooftop)], e.roofs[i].area_m2, e.roof_energy[i]);
    }
    for (surface_class_row& row : rows) {
        if (row.area_m2 <= 0.0) continue;
        row.annual_kwh_m2 /= row.area_m2;
        for (double& v : row.quarter_kwh_m2_day) v /= row.area_m2;
    }
    return rows;
}

/// Table 2 of the dissertation: the bill saving of `modules` modules of module_width_in x module_height_in inches
/// on each surface class, saving = irradiation (kWh/m^2) * module area (m^2, 0.0254 m per inch) * module
/// efficiency * inverter efficiency * (1 - temperature loss) * tariff; per day for the quarters, per year for
/// the annual column. With the defaults, 1780.80 kWh/m^2/yr gives about 549 (the dissertation prints 547.45).
/// @throws invalid_input if an option is out of range.
inline std::array<bill_savings_row, 5> bill_savings(const std::array<surface_class_row, 5>& table,
                                                    const bill_savings_options& opt = {})
{
    constexpr const char* fn = "bill_savings";
    const auto in01 = [&](double v, const char* name) {
        detail::require(v > 0.0 && v <= 1.0, fn, name, "in (0, 1]", v);
    };
    in01(opt.module_efficiency, "module_efficiency");
    in01(opt.inverter_efficiency, "inverter_efficiency");
    detail::require(opt.temperature_loss >= 0.0 && opt.temperature_loss < 1.0, fn, "temperature_loss", "in [0, 1)",
                    opt.temperature_loss);
    detail::require(opt.modules >= 1, fn, "modules", ">= 1", opt.modules);
    detail::require_positive(opt.module_width_in, fn, "module_width_in");
    detail::require_positive(opt.module_height_in, fn, "module_height_in");
    detail::require(opt.tariff_per_kwh >= 0.0 && std::isfinite(opt.tariff_per_kwh), fn, "tariff_per_kwh",
                    "finite and >= 0", opt.tariff_per_kwh);
    const double area_m2 = opt.modules * (opt.module_width_in * 0.0254) * (opt.module_height_in * 0.0254);
    const double factor =
        area_m2 * opt.module_efficiency * opt.inverter_efficiency * (1.0 - opt.temperature_loss) * opt.tariff_per_kwh;
    std::array<bill_savings_row, 5> out{};
    for (std::size_t k = 0; k < 5; ++k) {
        out[k].kind = table[k].kind;
        for (std::size_t q = 0; q < 4; ++q) out[k].quarter_per_day[q] = table[k].quarter_kwh_m2_day[q] * factor;
        out[k].annual = table[k].annual_kwh_m2 * factor;
    }
    return out;
}

}  // namespace lidarfx
