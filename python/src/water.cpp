// SPDX-License-Identifier: Apache-2.0
// Binding of the waterbody method: rasters in, water map, labelled bodies with their levels and the
// diagnostics out.
#include <lidarfx/pipelines/water/extract_waterbodies.hpp>

#include "binding.hpp"

namespace lidarfx::python {

namespace {

/// The raster `name` of `rasters` (attribute or mapping key), or None.
py::object raster_field(const py::handle& rasters, const char* name)
{
    if (py::isinstance<py::dict>(rasters)) {
        const auto d = py::reinterpret_borrow<py::dict>(rasters);
        if (!d.contains(name)) return py::none();
        return py::reinterpret_borrow<py::object>(d[name]);
    }
    if (!py::hasattr(rasters, name)) return py::none();
    return rasters.attr(name);
}

extract_waterbodies_options water_method(const std::string& method)
{
    if (method == "flat_seeds") return flat_seed_water_method();
    if (method == "dropout_seeds") return extract_waterbodies_options{};
    value_error("extract_waterbodies", "method must be 'flat_seeds' or 'dropout_seeds' (got '" + method + "')");
}

const char* severity_name(water_severity s)
{
    return s == water_severity::problem ? "problem" : "warning";
}

py::object extract_waterbodies_binding(const py::handle& rasters, const py::handle& cell_arg, const std::string& method,
                                       bool check_inputs, double island_min_area_m2, double theta_max_deg, int threads,
                                       py::object progress)
{
    constexpr const char* fn = "extract_waterbodies";
    double cell_m = 0;
    if (!cell_arg.is_none()) {
        cell_m = cell_arg.cast<double>();
    } else {
        const py::object g = raster_field(rasters, "grid");
        if (g.is_none()) value_error(fn, "cell_m is needed (rasters carry no grid)");
        cell_m = g.attr("cell_m").cast<double>();
    }
    std::vector<const char*> missing;
    for (const char* name : {"min_z", "max_z", "mean_intensity", "dropout"}) {
        if (raster_field(rasters, name).is_none()) missing.push_back(name);
    }
    if (!missing.empty()) {
        std::string names;
        for (const char* n : missing) names += std::string(names.empty() ? "" : ", ") + n;
        value_error(fn, "rasters must hold min_z, max_z, mean_intensity and dropout (missing " + names + ")");
    }
    const array_input<float> min_z(raster_field(rasters, "min_z"), fn, "min_z");
    const array_input<float> max_z(raster_field(rasters, "max_z"), fn, "max_z");
    const array_input<float> intensity(raster_field(rasters, "mean_intensity"), fn, "mean_intensity");
    const array_input<std::uint8_t> dropout(raster_field(rasters, "dropout"), fn, "dropout");
    std::optional<array_input<std::uint8_t>> multiple, footprint;
    std::optional<array_input<std::uint32_t>> count;
    if (py::object a = raster_field(rasters, "multiple_returns"); !a.is_none())
        multiple.emplace(a, fn, "multiple_returns");
    if (py::object a = raster_field(rasters, "count"); !a.is_none()) count.emplace(a, fn, "count");
    if (py::object a = raster_field(rasters, "footprint"); !a.is_none()) footprint.emplace(a, fn, "footprint");
    const water_rasters in{.min_z = min_z.view(),
                           .max_z = max_z.view(),
                           .mean_intensity = intensity.view(),
                           .dropout = dropout.view(),
                           .multiple_returns = multiple ? multiple->view() : raster_view<const std::uint8_t>{},
                           .count = count ? count->view() : raster_view<const std::uint32_t>{},
                           .footprint = footprint ? footprint->view() : raster_view<const std::uint8_t>{}};
    extract_waterbodies_options opt = water_method(method);
    opt.check_inputs = check_inputs;
    opt.islands.island_min_area_m2 = island_min_area_m2;
    opt.grow.theta_max_deg = theta_max_deg;
    run_settings rs(threads, std::move(progress));
    opt.run = rs.run();
    extract_waterbodies_result r = rs.call([&] { return extract_waterbodies(in, cell_m, opt); });

    py::list bodies;
    for (const waterbody& b : r.bodies) {
        py::dict f;
        f["label"] = b.label;
        f["cells"] = b.cells;
        f["area_m2"] = b.area_m2;
        f["row_min"] = b.box.row_min;
        f["col_min"] = b.box.col_min;
        f["row_max"] = b.box.row_max;
        f["col_max"] = b.box.col_max;
        f["water_level_m"] = b.water_level_m;
        f["mean_intensity"] = b.mean_intensity;
        f["dropout_fraction"] = b.dropout_fraction;
        f["theta_deg"] = b.theta_deg;
        f["stopped_by_ks"] = b.stopped_by_ks;
        f["seed"] = b.seed;
        bodies.append(make_result("Waterbody", f));
    }
    py::list issues;
    for (const water_issue& i : r.diagnostics.issues) {
        py::dict f;
        f["severity"] = severity_name(i.severity);
        f["message"] = i.message();
        issues.append(make_result("WaterIssue", f));
    }
    py::dict fields;
    fields["water"] = to_numpy(std::move(r.water), true);
    fields["labels"] = to_numpy(std::move(r.labels));
    fields["bodies"] = bodies;
    fields["issues"] = issues;
    fields["ran"] = r.ran;
    fields["points_per_cell"] = r.diagnostics.points_per_cell;
    fields["suggested_cell_m"] = r.diagnostics.suggested_cell_m;
    fields["seeds_found"] = r.seeds_found;
    fields["seeds_grown"] = r.seeds_grown;
    return make_result("Waterbodies", fields);
}

}  // namespace

void bind_water(py::module_& m)
{
    using namespace pybind11::literals;
    m.def("extract_waterbodies", &extract_waterbodies_binding, "rasters"_a, "cell_m"_a = py::none(), py::kw_only(),
          "method"_a = "flat_seeds", "check_inputs"_a = true, "island_min_area_m2"_a = 200.0, "theta_max_deg"_a = 30.0,
          "threads"_a = 1, "progress"_a = py::none(), R"doc(
Waterbodies from point-cloud rasters: seeds where the laser found no return (water absorbs it) or, with the
default method, level low cells with fewer returns; each seed grows over cells whose angular filter value stays
under a rising threshold theta (2, 3, ... theta_max_deg degrees) while a one-sided KS test on the intensity
says the new cells are not brighter than the body so far, and while the cells keep the body's level.

rasters: a Rasters (from rasterize) or any object or dict with min_z, max_z (metres, NaN = no return),
mean_intensity, dropout (bool/uint8) and optionally multiple_returns, count (uint32) and footprint (1 = inside
the surveyed area). cell_m: cell size in metres (default: rasters.grid.cell_m).
method: 'flat_seeds' (default; the lidarfx program's default, the most accurate on the project's test family)
or 'dropout_seeds' (the library's defaults: dropout seeds only). check_inputs: refuse (ran = False, issues say
why) data that cannot support the method, such as too few points per cell. island_min_area_m2: smaller holes
inside a body become water (default 200 m^2). theta_max_deg: last angular threshold (default 30).
Returns Waterbodies(water: bool map, labels: int32 (0 land, 1..n by decreasing area), bodies: list of
Waterbody (area_m2, water_level_m = median lowest return, ...), issues, ran, ...).)doc");
}

}  // namespace lidarfx::python
