// SPDX-License-Identifier: Apache-2.0
// Binding of the waterbody method: rasters in, water map, labelled bodies with their levels and the
// diagnostics out.
#include <lidarfx/pipelines/water/extract_waterbodies.hpp>
#include <lidarfx/pipelines/water/hydro_flatten.hpp>

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

py::object hydro_flatten_binding(const py::handle& dem_arg, const py::handle& labels_arg, const py::handle& min_z_arg,
                                 const py::handle& max_z_arg, double cell_m, double min_lake_area_m2,
                                 double min_river_width_m, double min_island_area_m2, const std::string& shoreline,
                                 bool join_channels, bool to_banks, bool under_decks, int threads, py::object progress)
{
    constexpr const char* fn = "hydro_flatten";
    if (shoreline != "lift" && shoreline != "flag")
        value_error(fn, "shoreline must be 'lift' or 'flag' (got '" + shoreline + "')");
    const array_input<float> dem(dem_arg, fn, "dem");
    const array_input<std::int32_t> labels(labels_arg, fn, "labels");
    const array_input<float> min_z(min_z_arg, fn, "min_z");
    const array_input<float> max_z(max_z_arg, fn, "max_z");
    hydro_flatten_options opt;
    opt.min_lake_area_m2 = min_lake_area_m2;
    opt.min_river_width_m = min_river_width_m;
    opt.min_island_area_m2 = min_island_area_m2;
    opt.shoreline = shoreline == "lift" ? shoreline_rule::lift : shoreline_rule::flag;
    opt.join_channels = join_channels;
    opt.to_banks = to_banks;
    opt.under_decks = under_decks;
    run_settings rs(threads, std::move(progress));
    opt.run = rs.run();
    hydro_flatten_result r =
        rs.call([&] { return hydro_flatten(dem.view(), labels.view(), min_z.view(), max_z.view(), cell_m, opt); });

    py::list bodies;
    for (const hydro_body& b : r.bodies) {
        py::dict f;
        f["id"] = b.id;
        f["type"] = b.type == hydro_body_type::river ? "river" : "lake";
        f["flattened"] = b.flattened;
        f["area_m2"] = b.shape.area_m2;
        f["length_m"] = b.shape.length_m;
        f["width_m"] = b.shape.width_m;
        f["level_min_m"] = b.level_min_m;
        f["level_max_m"] = b.level_max_m;
        f["section_levels_m"] = b.river.level_m;
        f["weirs"] = b.river.weirs;
        f["shore_cells_lifted"] = b.shore_cells_lifted;
        bodies.append(make_result("HydroBody", f));
    }
    py::list checks;
    for (const hydro_check& q : r.qa) {
        py::dict f;
        f["body"] = q.body;
        f["check"] = std::string(hydro_check_name(q.kind));
        f["value"] = q.value;
        f["limit"] = q.limit;
        f["passed"] = q.pass;
        f["worst_row"] = q.worst_row;
        f["worst_col"] = q.worst_col;
        checks.append(make_result("HydroCheck", f));
    }
    py::list joins;
    for (const channel_join& j : r.joins) {
        py::dict f;
        f["kept"] = j.kept;
        f["part_a"] = j.part_a;
        f["part_b"] = j.part_b;
        f["gap_m"] = j.gap_m;
        f["contact_m"] = j.contact_m;
        f["gap_cells"] = j.gap_cells;
        joins.append(make_result("ChannelJoin", f));
    }
    py::dict fields;
    fields["dem"] = to_numpy(std::move(r.dem));
    fields["water_surface"] = to_numpy(std::move(r.water_surface));
    fields["body"] = to_numpy(std::move(r.body));
    fields["bodies"] = bodies;
    fields["checks"] = checks;
    fields["joins"] = joins;
    fields["shore_cells_below"] = r.shorelines.below;
    fields["deck_cells"] = r.decks.deck_cells;
    fields["deck_level_cells"] = r.decks.level_cells;
    return make_result("HydroFlattened", fields);
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

    m.def("hydro_flatten", &hydro_flatten_binding, "dem"_a, "labels"_a, "min_z"_a, "max_z"_a, "cell_m"_a, py::kw_only(),
          "min_lake_area_m2"_a = 8093.71, "min_river_width_m"_a = 30.48, "min_island_area_m2"_a = 4046.86,
          "shoreline"_a = "lift", "join_channels"_a = true, "to_banks"_a = true, "under_decks"_a = true,
          "threads"_a = 1, "progress"_a = py::none(), R"doc(
Hydro-flattens a bare-earth DEM with the waterbodies of the same survey: every lake at one level (the median of
its water heights in their densest 0.1 m), every river in flat cross-sections whose levels only fall downstream
(each section read at its lowest dense 0.1 m of heights; isotonic regression; decks and stretches without returns
at the interpolated level, lowered to their banks where those stand lower (to_banks); sections beside a weir cut
along its crest), pieces of one river cut apart at a weir
or a deck joined into one body first (join_channels, with the water under the deck), the rivers continued under
their bridge decks (under_decks: the water lost beside a deck taken back at the river's level within 8 m of it,
then runs of deck cells between two cells of the river at the level interpolated across), islands under
min_island_area_m2 flattened with the water, and shore ground below the water beside it lifted to it
(shoreline='lift') or only counted ('flag'). Water under the minimum sizes (defaults: the USGS Lidar Base
Specification's 2 acres, 100 ft, 1 acre, in metres) is left to the terrain.

dem: float32 bare-earth DEM, metres (NaN = unknown). labels: int32 waterbodies (0 land, 1..n), e.g.
extract_waterbodies(...).labels. min_z, max_z: the survey's lowest and highest return per cell, metres.
cell_m: cell size, metres. Returns HydroFlattened(dem, water_surface (NaN off the water), body (id per
flattened cell), bodies: list of HydroBody, checks: list of HydroCheck (flatness, monotonic_fall, shoreline,
minimum_size per flattened body), joins: list of ChannelJoin (kept, part_a, part_b labels, gap_m, contact_m, gap_cells),
shore_cells_below, deck_cells and deck_level_cells (cells the rivers took under and beside decks)).)doc");
}

}  // namespace lidarfx::python
