// SPDX-License-Identifier: Apache-2.0
// Bindings of the single-purpose kernels: angular filter, morphology, connected components, the one-sided
// KS test and rasterization of points.
#include <lidarfx/kernels/filter/angular_filter.hpp>
#include <lidarfx/kernels/filter/morphology.hpp>
#include <lidarfx/kernels/filter/slope_aspect.hpp>
#include <lidarfx/kernels/filter/surface_outliers.hpp>
#include <lidarfx/kernels/label/connected_components.hpp>
#include <lidarfx/kernels/points/count_points_above.hpp>
#include <lidarfx/kernels/points/rasterize.hpp>
#include <lidarfx/kernels/stats/ks_one_sided.hpp>

#include <chrono>
#include <limits>
#include <vector>

#include "binding.hpp"
#include "grid_arg.hpp"

namespace lidarfx::python {

namespace {

py::array angular_filter_binding(const py::handle& z, double cell_m, int radius_cells, int threads, py::object progress)
{
    const array_input<float> in(z, "angular_filter", "z");
    run_settings rs(threads, std::move(progress));
    const angular_filter_options opt{.radius_cells = radius_cells, .run = rs.run()};
    return to_numpy(rs.call([&] { return angular_filter(in.view(), cell_m, opt); }));
}

py::object slope_aspect_binding(const py::handle& z, double cell_m, double flat_slope_deg, int threads,
                                py::object progress)
{
    const array_input<float> in(z, "slope_aspect", "z");
    run_settings rs(threads, std::move(progress));
    const slope_aspect_options opt{.flat_slope_deg = flat_slope_deg, .run = rs.run()};
    slope_aspect_result r = rs.call([&] { return slope_aspect(in.view(), cell_m, opt); });
    py::dict fields;
    fields["slope_deg"] = to_numpy(std::move(r.slope_deg));
    fields["aspect_deg"] = to_numpy(std::move(r.aspect_deg));
    fields["flat"] = to_numpy(std::move(r.flat), true);
    return make_result("SlopeAspect", fields);
}

py::object remove_surface_outliers_binding(const py::handle& z, int radius, double spike_height_m, double pit_depth_m,
                                           int min_support_cells, int threads, py::object progress)
{
    const array_input<float> in(z, "remove_surface_outliers", "z");
    run_settings rs(threads, std::move(progress));
    const surface_outliers_options opt{.radius_cells = radius,
                                       .spike_height_m = spike_height_m,
                                       .pit_depth_m = pit_depth_m,
                                       .min_support_cells = min_support_cells,
                                       .run = rs.run()};
    surface_outliers_result r = rs.call([&] { return remove_surface_outliers(in.view(), opt); });
    py::dict fields;
    fields["surface"] = to_numpy(std::move(r.surface));
    fields["outlier"] = to_numpy(std::move(r.outlier));
    fields["spikes"] = r.spikes;
    fields["pits"] = r.pits;
    return make_result("SurfaceOutliers", fields);
}

/// Defines morph_dilate, morph_erode, morph_open or morph_close: one docstring sentence, the shared rest.
template <class Operation>
void def_morphology(py::module_& m, const Operation& operation, const char* name, const char* sentence)
{
    using namespace pybind11::literals;
    const std::string doc = std::string(sentence) + R"doc(
Binary morphology with a size x height rectangle of cells (height 0 = square), clipped at the border;
the cost does not depend on the size. mask: 2-D bool or uint8 (nonzero = set; read in place), integer
masks are converted. size: odd width of the rectangle in cells, >= 1 (default 5); height: its height in
cells (0 = size). Returns a bool array of mask's shape.)doc";
    m.def(
        name,
        [&operation, name](const py::handle& mask, int size_cells, int height_cells, int threads, py::object progress) {
            const array_input<std::uint8_t> in(mask, name, "mask");
            run_settings rs(threads, std::move(progress));
            const morphology_options opt{.size_cells = size_cells, .height_cells = height_cells, .run = rs.run()};
            return to_numpy(rs.call([&] { return operation(in.view(), opt); }), true);
        },
        "mask"_a, "size"_a = 5, py::kw_only(), "height"_a = 0, "threads"_a = 1, "progress"_a = py::none(), doc.c_str());
}

py::object connected_components_binding(const py::handle& mask, int connectivity_cells, int threads,
                                        py::object progress)
{
    if (connectivity_cells != 4 && connectivity_cells != 8) {
        value_error("connected_components",
                    "connectivity must be 4 or 8 (got " + std::to_string(connectivity_cells) + ")");
    }
    const array_input<std::uint8_t> in(mask, "connected_components", "mask");
    run_settings rs(threads, std::move(progress));
    const connected_components_options opt{.conn = connectivity_cells == 4 ? connectivity::four : connectivity::eight,
                                           .run = rs.run()};
    components c = rs.call([&] { return connected_components(in.view(), opt); });
    py::array_t<std::int64_t> sizes(static_cast<py::ssize_t>(c.sizes.size()));
    for (std::size_t i = 0; i < c.sizes.size(); ++i)
        sizes.mutable_at(static_cast<py::ssize_t>(i)) = static_cast<std::int64_t>(c.sizes[i]);
    py::dict fields;
    fields["labels"] = to_numpy(std::move(c.labels));
    fields["sizes"] = sizes;
    return make_result("Components", fields);
}

py::object ks_one_sided_binding(const py::handle& previous, const py::handle& current, double alpha,
                                const std::string& critical)
{
    ks_one_sided_options opt{.alpha = alpha};
    if (critical == "documents_table") {
        opt.critical = ks_critical::documents_table;
    } else if (critical == "one_sided") {
        opt.critical = ks_critical::one_sided;
    } else {
        value_error("ks_one_sided", "critical must be 'documents_table' or 'one_sided' (got '" + critical + "')");
    }
    const auto a = vector_input<double>(previous, "ks_one_sided", "previous");
    const auto b = vector_input<double>(current, "ks_one_sided", "current");
    const std::span<const double> sa(a.data(), static_cast<std::size_t>(a.size()));
    const std::span<const double> sb(b.data(), static_cast<std::size_t>(b.size()));
    ks_result r;
    {
        py::gil_scoped_release release;
        r = ks_one_sided(sa, sb, opt);
    }
    py::dict fields;
    fields["d"] = r.d;
    fields["critical"] = r.critical;
    fields["reject"] = r.reject;
    fields["p_value"] = r.p_value;
    return make_result("KsResult", fields);
}

template <class T>
std::span<const T> optional_points(const std::optional<py::array_t<T, py::array::c_style | py::array::forcecast>>& a)
{
    if (!a) return {};
    return {a->data(), static_cast<std::size_t>(a->size())};
}

py::object rasterize_binding(const py::handle& x, const py::handle& y, const py::handle& z, const py::handle& intensity,
                             const py::handle& return_number, const py::handle& number_of_returns, double cell_m,
                             const py::handle& classification, const py::handle& grid_arg, const std::string& returns,
                             int threads, py::object progress)
{
    constexpr const char* fn = "rasterize";
    const auto xs = vector_input<double>(x, fn, "x"), ys = vector_input<double>(y, fn, "y"),
               zs = vector_input<double>(z, fn, "z");
    using small = std::uint8_t;
    std::optional<py::array_t<std::uint16_t, py::array::c_style | py::array::forcecast>> in;
    std::optional<py::array_t<small, py::array::c_style | py::array::forcecast>> rn, nr, cls;
    if (!intensity.is_none()) in = vector_input<std::uint16_t>(intensity, fn, "intensity");
    if (!return_number.is_none()) rn = vector_input<small>(return_number, fn, "returns");
    if (!number_of_returns.is_none()) nr = vector_input<small>(number_of_returns, fn, "nreturns");
    if (!classification.is_none()) cls = vector_input<small>(classification, fn, "classification");
    rasterize_options opt;
    if (returns == "first") {
        opt.returns = return_selection::first;
    } else if (returns == "last") {
        opt.returns = return_selection::last;
    } else if (returns != "all") {
        value_error(fn, "return_selection must be 'all', 'first' or 'last' (got '" + returns + "')");
    }
    run_settings rs(threads, std::move(progress));
    opt.run = rs.run();
    const soa_cloud<> cloud({xs.data(), static_cast<std::size_t>(xs.size())},
                            {ys.data(), static_cast<std::size_t>(ys.size())},
                            {zs.data(), static_cast<std::size_t>(zs.size())}, optional_points(in), optional_points(rn),
                            optional_points(nr), optional_points(cls));
    const std::optional<grid> given = grid_from_python(grid_arg, fn);
    rasterize_result r = rs.call([&] {
        const grid g = given ? *given : snapped_grid(bounds_of(cloud), cell_m);
        return rasterize(cloud, g, opt);
    });
    py::dict fields;
    fields["grid"] = grid_to_python(r.g);
    fields["min_z"] = to_numpy(std::move(r.min_z));
    fields["max_z"] = to_numpy(std::move(r.max_z));
    fields["mean_intensity"] = to_numpy(std::move(r.mean_intensity));
    fields["count"] = to_numpy(std::move(r.count));
    fields["dropout"] = to_numpy(std::move(r.dropout), true);
    fields["multiple_returns"] = to_numpy(std::move(r.multiple_returns), true);
    fields["multiple_return_count"] = to_numpy(std::move(r.multiple_return_count));
    fields["points_used"] = r.points_used;
    fields["points_outside"] = r.points_outside;
    fields["points_nan"] = r.points_nan;
    fields["points_unselected"] = r.points_unselected;
    return make_result("Rasters", fields);
}

py::object count_points_above_binding(const py::handle& x, const py::handle& y, const py::handle& z,
                                      const py::handle& reference, double height_m, const py::handle& grid_arg,
                                      bool return_lowest)
{
    constexpr const char* fn = "count_points_above";
    const auto xs = vector_input<double>(x, fn, "x"), ys = vector_input<double>(y, fn, "y"),
               zs = vector_input<double>(z, fn, "z");
    const array_input<float> ref(reference, fn, "reference");
    const std::optional<grid> g = grid_from_python(grid_arg, fn);
    if (!g) value_error(fn, "grid is required: the Grid the reference raster lies on");
    const soa_cloud<> cloud({xs.data(), static_cast<std::size_t>(xs.size())},
                            {ys.data(), static_cast<std::size_t>(ys.size())},
                            {zs.data(), static_cast<std::size_t>(zs.size())});
    if (!return_lowest) return to_numpy(count_points_above(cloud, *g, ref.view(), height_m));
    g->validate(fn);
    raster<std::uint32_t> counts(g->rows, g->cols);
    raster<float> lowest(g->rows, g->cols, std::numeric_limits<float>::quiet_NaN());
    count_points_above(cloud, *g, ref.view(), height_m, counts.view(), lowest.view());
    return py::make_tuple(to_numpy(std::move(counts)), to_numpy(std::move(lowest)));
}

/// The benchmark's C++ side: seconds of each of `repeats` angular_filter calls made in C++ on the same view
/// the binding reads (no Python between them), for bench/python_overhead.py.
std::vector<double> angular_filter_cpp_seconds(const py::handle& z, double cell_m, int radius_cells, int threads,
                                               int repeats)
{
    const array_input<float> in(z, "angular_filter", "z");
    std::vector<double> seconds;
    py::gil_scoped_release release;
    for (int i = 0; i < repeats; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        const raster<float> out =
            angular_filter(in.view(), cell_m, {.radius_cells = radius_cells, .run = {threads, {}}});
        seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    return seconds;
}

}  // namespace

void bind_kernels(py::module_& m)
{
    using namespace pybind11::literals;
    m.def("angular_filter", &angular_filter_binding, "z"_a, "cell_m"_a, "radius"_a = 2, py::kw_only(), "threads"_a = 1,
          "progress"_a = py::none(), R"doc(
Angular filter: for every cell p, the steepest angle to any cell q of the (2 radius + 1)^2 window around
it, max atan(|z(q) - z(p)| / (cell_m |p - q|)), degrees in [0, 90]: 0 on flat ground, near 90 beside walls.
NaN neighbours are skipped, a NaN centre gives NaN, a cell without a valid neighbour gives 0.

z: 2-D elevations in metres (float32 read in place; other real or integer dtypes are converted).
cell_m: cell size in metres, > 0. radius: window half-size in cells, >= 1 (default 2: "two tiers").
Returns a float32 array of z's shape.)doc");

    def_morphology(m, morph_dilate, "morph_dilate",
                   "Dilation: a cell is set when any cell of the rectangle centred on it is set.");
    def_morphology(m, morph_erode, "morph_erode",
                   "Erosion: a cell stays set when every cell of the rectangle inside the raster is set.");
    def_morphology(m, morph_open, "morph_open",
                   "Opening: erosion then dilation; removes set parts narrower than the rectangle.");
    def_morphology(m, morph_close, "morph_close",
                   "Closing: dilation then erosion; fills gaps narrower than the rectangle.");

    m.def("slope_aspect", &slope_aspect_binding, "z"_a, "cell_m"_a, py::kw_only(), "flat_slope_deg"_a = 0.0,
          "threads"_a = 1, "progress"_a = py::none(), R"doc(
Slope and aspect by Horn's 3 x 3 weighted differences (row 0 north): slope = atan(|grad z|), degrees in [0, 90];
aspect = azimuth of the down-slope direction, degrees clockwise from north in [0, 360), NaN where flat (slope
<= flat_slope_deg, default 0). At borders and beside NaN cells no cell is invented: one-sided differences are
used, so planes come out exact everywhere. z in metres (float32 read in place), cell_m in metres.
Returns SlopeAspect(slope_deg, aspect_deg: float32; flat: bool). slope_deg and aspect_deg are the
surface_tilt_deg and surface_azimuth_deg of irradiance_maps.)doc");

    m.def("remove_surface_outliers", &remove_surface_outliers_binding, "z"_a, py::kw_only(), "radius"_a = 2,
          "spike_height_m"_a = 10.0, "pit_depth_m"_a = 10.0, "min_support_cells"_a = 3, "threads"_a = 1,
          "progress"_a = py::none(), R"doc(
Isolated spikes (birds, noise) and pits (returns through canopy gaps) of a surface model, replaced by the median of
their neighbours. A cell is a spike when fewer than k of the finite cells of its (2 radius + 1)^2 window stand at
or above its height minus spike_height_m, a pit when fewer than k lie at or below its height plus pit_depth_m;
k = min_support_cells (default 3) scaled to the part of the window inside the raster. Defaults: 5 x 5 window,
10 m. z in metres (float32 read in place). Returns SurfaceOutliers(surface: float32, outlier: uint8 (0 none,
1 spike, 2 pit), spikes, pits).)doc");

    m.def("connected_components", &connected_components_binding, "mask"_a, "connectivity"_a = 8, py::kw_only(),
          "threads"_a = 1, "progress"_a = py::none(), R"doc(
Connected components of a mask (nonzero = foreground) under 4- or 8-connectivity (default 8).

Returns Components(labels, sizes): labels, int32 of mask's shape, 0 = background and 1..n in raster order
(first cell met row by row); sizes, int64 of length n + 1, sizes[0] = background cells, sizes[l] = cells of
component l. The result does not depend on threads.)doc");

    m.def("ks_one_sided", &ks_one_sided_binding, "previous"_a, "current"_a, "alpha"_a = 0.05, py::kw_only(),
          "critical"_a = "documents_table", R"doc(
One-sided two-sample Kolmogorov-Smirnov test: is `current` significantly larger (shifted up) than `previous`?

d = sup_x (F_previous(x) - F_current(x)); reject when d > c(alpha) sqrt((n + m) / (n m)), n and m the sample
sizes. critical='documents_table' (default) takes c(alpha) from the table 0.10, 0.05, 0.025, 0.01, 0.005, 0.001
-> 1.22, 1.36, 1.48, 1.63, 1.73, 1.95 (sqrt(-ln(alpha / 2) / 2) for other alpha); 'one_sided' takes
sqrt(-ln(alpha) / 2). p_value = exp(-2 d^2 n m / (n + m)). alpha in (0, 1), default 0.05.
Returns KsResult(d, critical, reject, p_value).)doc");

    m.def("_angular_filter_cpp_seconds", &angular_filter_cpp_seconds, "z"_a, "cell_m"_a, "radius_cells"_a = 2,
          "threads"_a = 1, "repeats"_a = 5, "Benchmark hook: seconds of each angular_filter call timed in C++.");

    m.def("count_points_above", &count_points_above_binding, "x"_a, "y"_a, "z"_a, "reference"_a, "height_m"_a,
          py::kw_only(), "grid"_a, "return_lowest"_a = false, R"doc(
Per cell of grid, the points standing at least height_m above the reference surface there (z >= reference +
height_m, metres; a cell whose reference is NaN counts none): with the terrain as reference and
height_m = 2.5, the raised points extract_buildings decides each building's rim by (raised_count).

x, y, z: 1-D coordinates in metres (float64; others converted). reference: float32 raster of the grid's shape
(e.g. fill_ground of the class-2 terrain). grid: the Grid the points are binned on, as in rasterize. Returns a
uint32 raster; with return_lowest, a tuple (counts, lowest): lowest is the lowest of each cell's counted points
(float32 metres, NaN where none), extract_buildings' lowest_raised.)doc");

    m.def("rasterize", &rasterize_binding, "x"_a, "y"_a, "z"_a, "intensity"_a = py::none(), "returns"_a = py::none(),
          "nreturns"_a = py::none(), "cell_m"_a = 1.0, py::kw_only(), "classification"_a = py::none(),
          "grid"_a = py::none(), "return_selection"_a = "all", "threads"_a = 1, "progress"_a = py::none(), R"doc(
Bins points into rasters: per cell the lowest and highest z (metres, NaN where no point), the mean intensity
(0 where no point), the point count, the dropout mask (True = no return) and the multiple-returns mask (True =
some point has number_of_returns > 1).

x, y, z: 1-D coordinates in metres (float64; others converted). intensity (uint16), returns (the return
number of each point), nreturns (its pulse's number of returns), classification (uint8): optional, of the
same length. cell_m: cell size in metres (default
1). grid: a Grid to bin on; default the snapped grid around the points (corners on multiples of cell_m).
return_selection: the points binned, 'all' (default), 'first' or 'last' returns. Points outside the grid or with NaN coordinates are counted, not
binned. Returns Rasters (min_z, max_z, mean_intensity, count, dropout, multiple_returns, multiple_return_count,
grid, point counts).)doc");
}

}  // namespace lidarfx::python
