// SPDX-License-Identifier: Apache-2.0
// Bindings of buildings and rooftop PV: buildings with their roof surfaces from a DSM, which roof patches
// suit PV, and the paper's azimuth choice from an aspect histogram.
#include <lidarfx/pipelines/buildings/extract_buildings.hpp>
#include <lidarfx/pipelines/pv/azimuth_mode_select.hpp>
#include <lidarfx/pipelines/pv/roof_suitability.hpp>

#include "binding.hpp"
#include "grid_arg.hpp"

namespace lidarfx::python {

namespace {

/// The grid of a raster argument: `grid` when given, else one of `cell_m` cells with its corner at (0, 0).
grid grid_for(const py::handle& grid_arg, const py::handle& cell_arg, std::ptrdiff_t rows, std::ptrdiff_t cols,
              const char* fn)
{
    if (std::optional<grid> g = grid_from_python(grid_arg, fn)) {
        if (g->rows != rows || g->cols != cols) {
            value_error(fn, "grid must have the DSM's shape (got " + std::to_string(g->rows) + "x" +
                                std::to_string(g->cols) + " and " + std::to_string(rows) + "x" + std::to_string(cols) +
                                ")");
        }
        return *g;
    }
    if (cell_arg.is_none()) value_error(fn, "grid or cell_m is needed");
    grid g{.x0 = 0, .y0 = 0, .cell = cell_arg.cast<double>(), .rows = rows, .cols = cols};
    g.validate(fn);
    return g;
}

/// A building's outline as a GeoJSON MultiPolygon (world coordinates of the grid).
py::dict geojson(const std::vector<polygon>& parts)
{
    py::list polygons;
    for (const polygon& p : parts) {
        py::list rings;
        for (const auto& ring : p.rings) {
            py::list coords;
            for (const auto& xy : ring) coords.append(py::make_tuple(xy[0], xy[1]));
            rings.append(coords);
        }
        polygons.append(rings);
    }
    py::dict g;
    g["type"] = "MultiPolygon";
    g["coordinates"] = polygons;
    return g;
}

py::object extract_buildings_binding(const py::handle& dsm, const py::handle& cell_arg, const py::handle& grid_arg,
                                     const py::handle& ground_arg, const py::handle& vegetation_arg,
                                     const py::handle& points_arg, const py::handle& split_arg,
                                     const py::handle& raised_arg, const py::handle& lowest_arg,
                                     const py::handle& building_cells_arg, double min_height_m, double min_area_m2,
                                     double party_wall_step_m, int threads, py::object progress)
{
    constexpr const char* fn = "extract_buildings";
    const array_input<float> z(dsm, fn, "dsm");
    const grid g = grid_for(grid_arg, cell_arg, z.rows(), z.cols(), fn);
    std::optional<array_input<float>> ground;
    std::optional<array_input<std::uint8_t>> vegetation;
    if (!ground_arg.is_none()) ground.emplace(ground_arg, fn, "ground");
    if (!vegetation_arg.is_none()) vegetation.emplace(vegetation_arg, fn, "vegetation");
    if (points_arg.is_none() != split_arg.is_none())
        value_error(fn, "point_count and multiple_return_count go together");
    if (!points_arg.is_none() && vegetation) value_error(fn, "give vegetation or the pulse counts, not both");
    if (!raised_arg.is_none() && points_arg.is_none()) value_error(fn, "raised_count needs point_count");
    if (!raised_arg.is_none() && ground_arg.is_none())
        value_error(fn, "raised_count needs the ground it was counted against");
    if (!lowest_arg.is_none() && raised_arg.is_none()) value_error(fn, "lowest_raised needs raised_count");
    std::optional<array_input<std::uint8_t>> building_cells;
    if (!building_cells_arg.is_none()) {
        if (vegetation || !points_arg.is_none())
            value_error(fn, "building_cells are the buildings: give no vegetation or pulse counts with them");
        building_cells.emplace(building_cells_arg, fn, "building_cells");
    }
    std::optional<array_input<std::uint32_t>> points, split, raised;
    if (!points_arg.is_none()) {
        points.emplace(points_arg, fn, "point_count");
        split.emplace(split_arg, fn, "multiple_return_count");
    }
    if (!raised_arg.is_none()) raised.emplace(raised_arg, fn, "raised_count");
    std::optional<array_input<float>> lowest;
    if (!lowest_arg.is_none()) lowest.emplace(lowest_arg, fn, "lowest_raised");
    extract_buildings_options opt;
    opt.candidates.min_height_m = min_height_m;
    opt.candidates.min_area_m2 = min_area_m2;
    opt.party_walls.min_step_m = party_wall_step_m;
    run_settings rs(threads, std::move(progress));
    opt.run = rs.run();
    extract_buildings_result r = rs.call([&] {
        const raster_view<const float> terrain = ground ? ground->view() : raster_view<const float>{};
        if (building_cells) return extract_classified_buildings(z.view(), g, terrain, building_cells->view(), opt);
        if (points)
            return extract_buildings(z.view(), g, terrain,
                                     pulse_returns{points->view(), split->view(),
                                                   raised ? raised->view() : raster_view<const std::uint32_t>{},
                                                   lowest ? lowest->view() : raster_view<const float>{}},
                                     opt);
        return extract_buildings(z.view(), g, terrain,
                                 vegetation ? vegetation->view() : raster_view<const std::uint8_t>{}, opt);
    });
    py::list buildings;
    for (const building_record& b : r.buildings) {
        py::dict f;
        f["id"] = b.id;
        f["outline"] = geojson(b.outline);
        f["ground_z"] = b.ground_z;
        f["eave_z"] = b.eave_z;
        f["ridge_z"] = b.ridge_z;
        f["roof_area_horizontal_m2"] = b.roof_area_horizontal_m2;
        f["roof_area_sloped_m2"] = b.roof_area_sloped_m2;
        f["surfaces"] = py::cast(b.surfaces);
        f["clipped"] = b.clipped;
        buildings.append(make_result("Building", f));
    }
    py::list surfaces;
    for (const roof_surface& s : r.surfaces) {
        py::dict f;
        f["id"] = s.id;
        f["building"] = s.building;
        f["tilt_deg"] = s.tilt_deg;
        f["azimuth_deg"] = s.azimuth_deg;
        f["horizontal_area_m2"] = s.horizontal_area_m2;
        f["area_m2"] = s.area_m2;
        surfaces.append(make_result("RoofSurface", f));
    }
    py::dict fields;
    fields["building_id"] = to_numpy(std::move(r.building_id));
    fields["surface_id"] = to_numpy(std::move(r.surface_id));
    fields["ground"] = to_numpy(std::move(r.ground));
    fields["vegetation"] = to_numpy(std::move(r.vegetation), true);
    fields["under_crowns"] = to_numpy(std::move(r.under_crowns), true);
    fields["buildings"] = buildings;
    fields["surfaces"] = surfaces;
    fields["grid"] = grid_to_python(g);
    return make_result("Buildings", fields);
}

py::object roof_suitability_binding(const py::handle& dsm, const py::handle& dtm, const py::handle& building_id,
                                    const py::handle& cell_arg, const py::handle& grid_arg, const std::string& mode,
                                    double min_height_m, double min_patch_m2, double m2_per_kwp, double min_tilt_deg,
                                    double max_tilt_deg, double min_azimuth_deg, double max_azimuth_deg,
                                    double flat_below_deg, int threads, py::object progress)
{
    constexpr const char* fn = "roof_suitability";
    const array_input<float> z(dsm, fn, "dsm"), ground(dtm, fn, "dtm");
    const array_input<std::int32_t> ids(building_id, fn, "building_id");
    const grid g = grid_for(grid_arg, cell_arg, z.rows(), z.cols(), fn);
    roof_suitability_options opt{.min_height_m = min_height_m,
                                 .min_patch_m2 = min_patch_m2,
                                 .m2_per_kwp = m2_per_kwp,
                                 .min_tilt_deg = min_tilt_deg,
                                 .max_tilt_deg = max_tilt_deg,
                                 .min_azimuth_deg = min_azimuth_deg,
                                 .max_azimuth_deg = max_azimuth_deg,
                                 .flat_below_deg = flat_below_deg};
    if (mode == "paper") {
        opt.mode = roof_mode::paper;
    } else if (mode != "planes") {
        value_error(fn, "mode must be 'planes' or 'paper' (got '" + mode + "')");
    }
    run_settings rs(threads, std::move(progress));
    opt.run = rs.run();
    roof_suitability_result r = rs.call([&] { return roof_suitability(z.view(), ground.view(), ids.view(), g, opt); });
    py::list patches;
    for (const roof_patch& p : r.patches) {
        py::dict f;
        f["building_id"] = p.building_id;
        f["patch_id"] = p.patch_id;
        f["tilt_deg"] = p.tilt_deg;
        f["azimuth_deg"] = p.azimuth_deg;
        f["area_m2"] = p.area_m2;
        f["sloped_area_m2"] = p.sloped_area_m2;
        f["kwp"] = p.kwp;
        f["suitable"] = p.suitable;
        f["flat"] = p.flat;
        f["centroid_x"] = p.centroid_x;
        f["centroid_y"] = p.centroid_y;
        f["rms_m"] = p.rms_m;
        f["reason"] = p.reason;
        patches.append(make_result("RoofPatch", f));
    }
    py::dict fields;
    fields["patch_id"] = to_numpy(std::move(r.patch_id));
    fields["patches"] = patches;
    return make_result("RoofSuitability", fields);
}

const char* roof_form_name(roof_form f)
{
    switch (f) {
        case roof_form::no_cells:
            return "no_cells";
        case roof_form::one_plane:
            return "one_plane";
        case roof_form::two_planes:
            return "two_planes";
        case roof_form::three_planes:
            return "three_planes";
        case roof_form::four_planes:
            return "four_planes";
        case roof_form::complex:
            return "complex";
    }
    return "complex";
}

const char* reason_name(azimuth_reason r)
{
    switch (r) {
        case azimuth_reason::no_cells:
            return "no_cells";
        case azimuth_reason::too_many_planes:
            return "too_many_planes";
        case azimuth_reason::kept:
            return "kept";
        case azimuth_reason::swapped:
            return "swapped";
        case azimuth_reason::swap_abandoned:
            return "swap_abandoned";
        case azimuth_reason::turned_west:
            return "turned_west";
        case azimuth_reason::kept_east:
            return "kept_east";
    }
    return "kept";
}

py::object azimuth_mode_select_binding(const py::handle& histogram, double window_deg)
{
    constexpr const char* fn = "azimuth_mode_select";
    const auto h = vector_input<std::int64_t>(histogram, fn, "hist360");
    std::vector<std::uint32_t> counts(static_cast<std::size_t>(h.size()));
    for (py::ssize_t i = 0; i < h.size(); ++i) {
        if (h.at(i) < 0 || h.at(i) > 0xffffffffLL) value_error(fn, "hist360 must hold counts in [0, 2^32)");
        counts[static_cast<std::size_t>(i)] = static_cast<std::uint32_t>(h.at(i));
    }
    const azimuth_selection s = azimuth_mode_select(counts, {.window_deg = window_deg});
    py::dict fields;
    fields["azimuth_deg"] = s.azimuth_deg;
    fields["mode_deg"] = s.mode_deg;
    fields["planes"] = s.planes;
    fields["form"] = roof_form_name(s.form);
    fields["reason"] = reason_name(s.reason);
    fields["suitable"] = s.suitable;
    return make_result("AzimuthSelection", fields);
}

}  // namespace

py::object fill_ground_binding(const py::handle& ground_arg, double cell_m, int threads)
{
    const array_input<float> ground(ground_arg, "fill_ground", "ground");
    return to_numpy(fill_ground(ground.view(), cell_m, {}, {.threads = threads}));
}

void bind_buildings(py::module_& m)
{
    using namespace pybind11::literals;
    m.def("extract_buildings", &extract_buildings_binding, "dsm"_a, "cell_m"_a = py::none(), py::kw_only(),
          "grid"_a = py::none(), "ground"_a = py::none(), "vegetation"_a = py::none(), "point_count"_a = py::none(),
          "multiple_return_count"_a = py::none(), "raised_count"_a = py::none(), "lowest_raised"_a = py::none(),
          "building_cells"_a = py::none(), "min_height_m"_a = 2.5, "min_area_m2"_a = 15.0, "party_wall_step_m"_a = 1.0,
          "threads"_a = 1, "progress"_a = py::none(), R"doc(
Buildings and their roof surfaces from a DSM: a terrain model (edges of >= 45 degrees, hulls, IDW; or the given
ground), cells higher than min_height_m above it in footprints of at least min_area_m2 that are roofs (planar
enough, or with the pulse counts: few split pulses), roof surfaces grown from local planes and merged, then
numbered by area.

dsm: heights in metres, row 0 north (float32 read in place). cell_m or grid (a Grid; outlines are in its world
coordinates, else in metres from the top-left corner). ground: optional terrain (DTM) in metres; vegetation:
optional bool mask of trees; or point_count and multiple_return_count (uint32, Rasters.count and
Rasters.multiple_return_count of the DSM's points): trees told from roofs by their split pulses (a cell with
half its points from pulses of several returns is vegetation, a part with 20 %); with them raised_count (uint32,
count_points_above against the ground, which must then be filled: fill_ground) decides each building's one-cell
rim by its points: a cell leaves when under half its points stand min_height_m above the ground, a cell beside
the roof at its height (within 0.5 m) with half its points raised joins; and with lowest_raised (float32, the
lowest of each cell's raised points: count_points_above(..., return_lowest=True)) the roof under an overhanging
crown joins its building when 90 % of a cell's points are raised and the lowest lies on the roof's plane (within
0.3 m plus half the plane's fall across a cell). Or building_cells (bool or uint8, e.g.
where at least half of the points are of the vendor's building class 6): those cells are the buildings (parts
under min_area_m2 dropped, holes under it filled), only their roof surfaces are found. A block is split into
buildings where two of its roof surfaces do not meet along most of their boundary but stand more than
party_wall_step_m (metres, > 0; inf never splits) apart: terraced houses of different heights. Returns Buildings(building_id, surface_id: int32 rasters (0 = none), ground,
vegetation, under_crowns (bool: roof cells found under overhanging crowns, whose DSM is the crown), buildings: list of Building (outline as a GeoJSON MultiPolygon, ground_z, eave_z, ridge_z, roof
areas in m^2, surface ids), surfaces: list of RoofSurface (tilt_deg, azimuth_deg, areas), grid).)doc");

    m.def("fill_ground", &fill_ground_binding, "ground"_a, "cell_m"_a, py::kw_only(), "threads"_a = 1, R"doc(
A terrain model (metres, e.g. Rasters.min_z of the class-2 points) with its NaN cells filled by IDW from the
finite ones (8 nearest, weights 1 / distance), exactly as extract_buildings fills a given ground. cell_m: cell size in metres.
Returns a float32 raster.)doc");

    m.def("roof_suitability", &roof_suitability_binding, "dsm"_a, "dtm"_a, "building_id"_a, "cell_m"_a = py::none(),
          py::kw_only(), "grid"_a = py::none(), "mode"_a = "planes", "min_height_m"_a = 2.0, "min_patch_m2"_a = 8.0,
          "m2_per_kwp"_a = 8.0, "min_tilt_deg"_a = 15.0, "max_tilt_deg"_a = 60.0, "min_azimuth_deg"_a = 90.0,
          "max_azimuth_deg"_a = 270.0, "flat_below_deg"_a = 15.0, "threads"_a = 1, "progress"_a = py::none(), R"doc(
Which roof patches suit PV panels. Roof cells are the cells of each building (building_id > 0, int32, e.g. from
extract_buildings or burned footprints) standing min_height_m above the DTM. mode='planes' (default): every
roof plane is segmented and judged on its fitted tilt and azimuth; 'paper': one PV plane per building (mean
tilt, aspect mode). A patch suits when its sloped area >= min_patch_m2 and its tilt lies in [min_tilt_deg,
max_tilt_deg] and its azimuth in [min_azimuth_deg, max_azimuth_deg] (clockwise from north); a patch flatter than
flat_below_deg suits on its area alone. kwp = sloped area / m2_per_kwp.
Returns RoofSuitability(patch_id: int32 raster, patches: list of RoofPatch).)doc");

    m.def("azimuth_mode_select", &azimuth_mode_select_binding, "hist360"_a, py::kw_only(), "window_deg"_a = 10.0,
          R"doc(
The PV azimuth of a roof from its aspect histogram (360 one-degree bins of cell counts, bin i = aspects in
[i, i + 1) degrees clockwise from north): the mode, swapped by 180 degrees for two-plane roofs facing north,
turned west for three- and four-plane roofs when more cells face west; unsuitable for no cells or more than
four planes. Returns AzimuthSelection(azimuth_deg (NaN when unsuitable), mode_deg, planes, form, reason,
suitable).)doc");
}

}  // namespace lidarfx::python
