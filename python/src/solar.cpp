// SPDX-License-Identifier: Apache-2.0
// Bindings of the sun: position, cast shadows, horizons, sky view factor, clear-sky years and annual
// irradiation maps.
#include <chrono>
#include <cmath>
#include <vector>

#include <lidarfx/kernels/solar/clear_sky.hpp>
#include <lidarfx/kernels/solar/horizon_map.hpp>
#include <lidarfx/kernels/solar/raylines_shadow.hpp>
#include <lidarfx/kernels/solar/sky_view_factor.hpp>
#include <lidarfx/kernels/solar/sun_position.hpp>
#include <lidarfx/pipelines/solar/irradiance_maps.hpp>

#include "binding.hpp"

namespace lidarfx::python {

namespace {

namespace chr = std::chrono;

/// A time as UTC: a datetime (naive = UTC; aware = converted), an ISO 8601 string (same rule), or POSIX seconds.
chr::sys_time<chr::microseconds> utc_time(const py::handle& t, const char* function)
{
    using namespace pybind11::literals;
    const py::module_ dt = py::module_::import("datetime");
    py::object value = py::reinterpret_borrow<py::object>(t);
    if (py::isinstance<py::str>(value)) {
        const std::string text = value.cast<std::string>();
        try {
            value = dt.attr("datetime")
                        .attr("fromisoformat")(text.back() == 'Z' ? text.substr(0, text.size() - 1) + "+00:00" : text);
        } catch (py::error_already_set&) {
            value_error(function, "time must be an ISO 8601 date and time (got '" + text + "')");
        }
    }
    double seconds = 0;
    if (py::isinstance(value, dt.attr("datetime"))) {
        if (value.attr("tzinfo").is_none()) value = value.attr("replace")("tzinfo"_a = dt.attr("timezone").attr("utc"));
        seconds = value.attr("timestamp")().cast<double>();
    } else if (py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value)) {
        seconds = value.cast<double>();
    } else {
        throw py::type_error(std::string(function) +
                             ": time must be a datetime, an ISO 8601 string or POSIX seconds (UTC)");
    }
    if (!std::isfinite(seconds)) value_error(function, "time must be finite");
    return chr::sys_time<chr::microseconds>(chr::microseconds(std::llround(seconds * 1e6)));
}

sun_model sun_model_arg(const std::string& model, const char* function)
{
    if (model == "spa") return sun_model::spa;
    if (model == "simple") return sun_model::simple;
    value_error(function, "model must be 'spa' or 'simple' (got '" + model + "')");
}

sky_view_factor_method svf_method_arg(const std::string& method, const char* function)
{
    if (method == "source_share") return sky_view_factor_method::source_share;
    if (method == "cosine_weighted") return sky_view_factor_method::cosine_weighted;
    value_error(function, "method must be 'source_share' or 'cosine_weighted' (got '" + method + "')");
}

py::object sun_position_binding(const py::handle& time, double latitude_deg, double longitude_deg,
                                const std::string& model, double elevation_m, double pressure_mbar,
                                double temperature_c, bool refraction, double delta_t_s)
{
    constexpr const char* fn = "sun_position";
    const sun_position_options opt{.model = sun_model_arg(model, fn),
                                   .delta_t_s = delta_t_s,
                                   .pressure_mbar = pressure_mbar,
                                   .temperature_c = temperature_c,
                                   .elevation_m = elevation_m,
                                   .refraction = refraction};
    const sun_position_result s = sun_position(utc_time(time, fn), latitude_deg, longitude_deg, opt);
    py::dict fields;
    fields["azimuth_deg"] = s.azimuth_deg;
    fields["elevation_deg"] = s.elevation_deg;
    fields["zenith_deg"] = s.zenith_deg;
    return make_result("SunPosition", fields);
}

py::array raylines_shadow_binding(const py::handle& dsm, double cell_m, double azimuth_deg, double elevation_deg,
                                  int nan_cell, int line_phases, int threads, py::object progress)
{
    constexpr const char* fn = "raylines_shadow";
    if (nan_cell < 0 || nan_cell > 255)
        value_error(fn, "nan_cell must be in [0, 255] (got " + std::to_string(nan_cell) + ")");
    const array_input<float> z(dsm, fn, "dsm");
    run_settings rs(threads, std::move(progress));
    const raylines_shadow_options opt{
        .nan_cell = static_cast<std::uint8_t>(nan_cell), .line_phases = line_phases, .run = rs.run()};
    return to_numpy(rs.call([&] { return raylines_shadow(z.view(), cell_m, azimuth_deg, elevation_deg, opt); }));
}

py::array horizon_map_binding(const py::handle& dsm, double cell_m, double azimuth_deg, int line_phases, int threads,
                              py::object progress)
{
    const array_input<float> z(dsm, "horizon_map", "dsm");
    run_settings rs(threads, std::move(progress));
    const horizon_map_options opt{.line_phases = line_phases, .run = rs.run()};
    return to_numpy(rs.call([&] { return horizon_map(z.view(), cell_m, azimuth_deg, opt); }));
}

py::array sky_view_factor_binding(const py::handle& dsm, double cell_m, const std::string& method, int directions,
                                  int threads, py::object progress)
{
    constexpr const char* fn = "sky_view_factor";
    const array_input<float> z(dsm, fn, "dsm");
    run_settings rs(threads, std::move(progress));
    const sky_view_factor_options opt{.method = svf_method_arg(method, fn), .directions = directions, .run = rs.run()};
    return to_numpy(rs.call([&] { return sky_view_factor(z.view(), cell_m, opt); }));
}

/// The records of a Weather (start_utc as datetime64 or POSIX seconds, DNI, DHI, GHI in W/m^2, interval_s).
std::vector<irradiance_record> weather_records(const py::handle& weather, const char* function)
{
    for (const char* name : {"start_utc", "dni_w_m2", "dhi_w_m2", "ghi_w_m2", "interval_s"}) {
        if (!py::hasattr(weather, name)) {
            throw py::type_error(std::string(function) + ": weather must be a lidarfx.Weather (no attribute " + name +
                                 ")");
        }
    }
    const py::module_ np = py::module_::import("numpy");
    py::object start = np.attr("asarray")(weather.attr("start_utc"));
    if (std::string(py::str(start.attr("dtype").attr("kind"))) == "M")
        start = start.attr("astype")("datetime64[s]").attr("astype")("int64");
    const auto t = vector_input<std::int64_t>(start, function, "weather.start_utc");
    const auto dni = vector_input<double>(weather.attr("dni_w_m2"), function, "weather.dni_w_m2");
    const auto dhi = vector_input<double>(weather.attr("dhi_w_m2"), function, "weather.dhi_w_m2");
    const auto ghi = vector_input<double>(weather.attr("ghi_w_m2"), function, "weather.ghi_w_m2");
    const auto interval = weather.attr("interval_s").cast<long long>();
    if (dni.size() != t.size() || dhi.size() != t.size() || ghi.size() != t.size()) {
        value_error(function, "weather's start_utc, dni_w_m2, dhi_w_m2 and ghi_w_m2 must have the same length");
    }
    std::vector<irradiance_record> records(static_cast<std::size_t>(t.size()));
    for (py::ssize_t i = 0; i < t.size(); ++i) {
        records[static_cast<std::size_t>(i)] = {.start_utc = chr::sys_seconds(chr::seconds(t.at(i))),
                                                .interval = chr::seconds(interval),
                                                .dni_w_m2 = dni.at(i),
                                                .dhi_w_m2 = dhi.at(i),
                                                .ghi_w_m2 = ghi.at(i)};
    }
    return records;
}

py::object clear_sky_year_binding(int year, double latitude_deg, double longitude_deg, int interval_s)
{
    clear_sky_options opt;
    opt.interval = chr::seconds(interval_s);
    std::vector<irradiance_record> records;
    {
        py::gil_scoped_release release;
        records = clear_sky_records(year, latitude_deg, longitude_deg, opt);
    }
    return weather_from_records(records, latitude_deg, longitude_deg, 0.0);
}

py::object irradiance_maps_binding(const py::handle& dsm, double cell_m, const py::handle& weather,
                                   const py::handle& latitude, const py::handle& longitude,
                                   const py::handle& utc_offset, double meridian_convergence_deg,
                                   const std::string& svf_method, int svf_directions, const std::string& diffuse,
                                   double albedo, const py::handle& surface_tilt, const py::handle& surface_azimuth,
                                   int shadow_line_phases, int threads, py::object progress)
{
    constexpr const char* fn = "irradiance_maps";
    const array_input<float> z(dsm, fn, "dsm");
    const auto from_weather = [&](const py::handle& given, const char* name) {
        if (!given.is_none()) return given.cast<double>();
        if (!py::hasattr(weather, name) || weather.attr(name).is_none()) {
            value_error(fn, std::string(name) + " is needed (the weather does not carry it)");
        }
        return weather.attr(name).cast<double>();
    };
    solar_site site{.latitude_deg = from_weather(latitude, "latitude_deg"),
                    .longitude_deg = from_weather(longitude, "longitude_deg"),
                    .utc_offset_h = from_weather(utc_offset, "utc_offset_h"),
                    .meridian_convergence_deg = meridian_convergence_deg};
    const std::vector<irradiance_record> records = weather_records(weather, fn);
    std::optional<array_input<float>> tilt, azimuth;
    if (!surface_tilt.is_none()) tilt.emplace(surface_tilt, fn, "surface_tilt_deg");
    if (!surface_azimuth.is_none()) azimuth.emplace(surface_azimuth, fn, "surface_azimuth_deg");
    irradiance_maps_options opt;
    opt.sky.svf_method = svf_method_arg(svf_method, fn);
    opt.sky.svf_directions = svf_directions;
    if (diffuse == "perez") {
        opt.sky.diffuse = diffuse_model::perez;
    } else if (diffuse != "isotropic") {
        value_error(fn, "diffuse must be 'isotropic' or 'perez' (got '" + diffuse + "')");
    }
    opt.sky.albedo = albedo;
    opt.shadow_line_phases = shadow_line_phases;
    run_settings rs(threads, std::move(progress));
    opt.run = rs.run();
    irradiance_maps_result r = rs.call([&] {
        return irradiance_maps(z.view(), cell_m, site, records, tilt ? tilt->view() : raster_view<const float>{},
                               azimuth ? azimuth->view() : raster_view<const float>{}, opt);
    });
    py::list months;
    for (auto& month : r.month_kwh_m2) months.append(to_numpy(std::move(month)));
    py::dict fields;
    fields["annual_kwh_m2"] = to_numpy(std::move(r.annual_kwh_m2));
    fields["month_kwh_m2"] = py::module_::import("numpy").attr("stack")(months);
    fields["sky_view_factor"] = to_numpy(std::move(r.sky_view_factor));
    fields["ghi_kwh_m2"] = r.ghi_kwh_m2;
    fields["month_ghi_kwh_m2"] = py::cast(std::vector<double>(r.month_ghi_kwh_m2.begin(), r.month_ghi_kwh_m2.end()));
    fields["sun_up_records"] = r.sun_up_records;
    return make_result("IrradianceMaps", fields);
}

}  // namespace

py::object weather_from_records(const std::vector<irradiance_record>& records, double latitude_deg,
                                double longitude_deg, double utc_offset_h)
{
    const auto n = static_cast<py::ssize_t>(records.size());
    py::array_t<std::int64_t> start(n);
    py::array_t<double> dni(n), dhi(n), ghi(n);
    for (py::ssize_t i = 0; i < n; ++i) {
        const irradiance_record& r = records[static_cast<std::size_t>(i)];
        start.mutable_at(i) = r.start_utc.time_since_epoch().count();
        dni.mutable_at(i) = r.dni_w_m2;
        dhi.mutable_at(i) = r.dhi_w_m2;
        ghi.mutable_at(i) = r.ghi_w_m2;
    }
    py::dict fields;
    fields["start_utc"] = start.attr("astype")("datetime64[s]");
    fields["dni_w_m2"] = dni;
    fields["dhi_w_m2"] = dhi;
    fields["ghi_w_m2"] = ghi;
    fields["interval_s"] = records.empty() ? 3600 : records.front().interval.count();
    fields["latitude_deg"] = latitude_deg;
    fields["longitude_deg"] = longitude_deg;
    fields["utc_offset_h"] = utc_offset_h;
    return make_result("Weather", fields);
}

void bind_solar(py::module_& m)
{
    using namespace pybind11::literals;
    m.def("sun_position", &sun_position_binding, "time"_a, "lat"_a, "lon"_a, py::kw_only(), "model"_a = "spa",
          "elevation_m"_a = 0.0, "pressure_mbar"_a = 1013.25, "temperature_c"_a = 12.0, "refraction"_a = true,
          "delta_t_s"_a = 69.0, R"doc(
Sun position at a time and place. time: a datetime (naive = UTC; aware ones are converted to UTC), an ISO 8601
string (same rule) or POSIX seconds. lat: latitude, degrees north in [-90, 90]; lon: longitude, degrees east
in [-180, 180].
model: 'spa' (NREL's Solar Position Algorithm, +-0.0003 deg; default) or 'simple' (equation of time,
declination and hour angle). elevation_m: observer height above sea level, metres; pressure_mbar and
temperature_c: annual means for refraction; delta_t_s: TT - UT in seconds (SPA).
Returns SunPosition(azimuth_deg clockwise from true north in [0, 360), elevation_deg above the horizon,
zenith_deg = 90 - elevation_deg).)doc");

    m.def("raylines_shadow", &raylines_shadow_binding, "dsm"_a, "cell_m"_a, "azimuth_deg"_a, "elevation_deg"_a,
          py::kw_only(), "nan_cell"_a = 255, "line_phases"_a = 4, "threads"_a = 1, "progress"_a = py::none(), R"doc(
Cast shadows for one sun position: 1 = lit, 0 = shadow, nan_cell (default 255) where the DSM is NaN.
A cell p is in shadow when a cell q before it on the ray line towards the sun has z_q - d tan(elevation) > z_p,
d the distance between them along the sun's azimuth in metres; NaN cells cast no shadow. Every cell takes
the nearest of line_phases (1..64, default 4) families of parallel lines. Cost O(cells).
dsm: 2-D heights in metres, row 0 north (float32 read in place). cell_m: cell size in metres.
azimuth_deg: clockwise from north (grid north); elevation_deg above the horizon (<= 0: all shadow).
Returns a uint8 array of dsm's shape.)doc");

    m.def("horizon_map", &horizon_map_binding, "dsm"_a, "cell_m"_a, "azimuth_deg"_a, py::kw_only(), "line_phases"_a = 1,
          "threads"_a = 1, "progress"_a = py::none(), R"doc(
Horizon angle of every cell looking towards azimuth_deg (clockwise from north): max(0, max over the cells q
before p on p's ray line of atan((z_q - z_p) / distance)), degrees in [0, 90); NaN for NaN cells. Exact upper
convex hull sweep, O(cells) per line family. line_phases (1..64, default 1): each cell's line comes from the
nearest of that many families of parallel lines, as in raylines_shadow; with the same line_phases a cell is lit
by a sun of this azimuth exactly when its horizon is at or below the sun's elevation. dsm in metres (float32
read in place), cell_m in metres. Returns float32.)doc");

    m.def("sky_view_factor", &sky_view_factor_binding, "dsm"_a, "cell_m"_a, py::kw_only(), "method"_a = "source_share",
          "directions"_a = 72, "threads"_a = 1, "progress"_a = py::none(), R"doc(
Sky view factor of every cell in [0, 1] (1 on open flat ground; NaN for NaN cells), from one exact horizon
sweep per azimuth i * 360 / directions (directions >= 4, default 72 = 5 degree steps).
method='source_share' (default): the share of point sources visible from the cell, one at each elevation
15, 20, ..., 85 degrees of each azimuth plus the zenith (1,081 sources for 72 azimuths).
method='cosine_weighted': the view factor of a horizontal surface under an isotropic sky, the mean over the
azimuths of cos^2(horizon angle) (the SVF of GRASS r.skyview and SAGA). Returns float32.)doc");

    m.def("clear_sky_year", &clear_sky_year_binding, "year"_a, "latitude_deg"_a, "longitude_deg"_a, py::kw_only(),
          "interval_s"_a = 3600, R"doc(
A clear-sky weather year at a place: one record per interval_s (default hourly) from 1 January 00:00 UTC,
with the sun at the middle of each interval; night records hold zeros. Returns a Weather for
irradiance_maps (utc_offset_h 0: months are UTC months).)doc");

    m.def("irradiance_maps", &irradiance_maps_binding, "dsm"_a, "cell_m"_a, "weather"_a, py::kw_only(),
          "latitude_deg"_a = py::none(), "longitude_deg"_a = py::none(), "utc_offset_h"_a = py::none(),
          "meridian_convergence_deg"_a = 0.0, "svf_method"_a = "source_share", "svf_directions"_a = 72,
          "diffuse"_a = "isotropic", "albedo"_a = 0.0, "surface_tilt_deg"_a = py::none(),
          "surface_azimuth_deg"_a = py::none(), "shadow_line_phases"_a = 4, "threads"_a = 1, "progress"_a = py::none(),
          R"doc(
Annual and monthly irradiation of every cell, kWh/m^2: for each weather record with the sun up, beam
DNI cos(incidence) on lit cells (raylines_shadow at the sun of the record's middle) plus diffuse light
(isotropic: DHI SVF (1 + cos tilt) / 2; 'perez': Perez 1990 with the circumsolar part shaded) plus
albedo-reflected light, times the record's interval.

dsm: heights in metres, row 0 north (float32 read in place); cell_m in metres. weather: a Weather
(read_tmy3 or clear_sky_year, or lidarfx.Weather(start_utc, dni_w_m2, dhi_w_m2, ghi_w_m2, interval_s)).
latitude_deg, longitude_deg, utc_offset_h: the site (default: the weather's). Months are those of local
standard time UTC + utc_offset_h. meridian_convergence_deg: angle from true north to grid north (east
positive). surface_tilt_deg / surface_azimuth_deg: optional per-cell surface orientation (default horizontal).
Returns IrradianceMaps(annual_kwh_m2, month_kwh_m2 (12 x rows x cols), sky_view_factor, ghi_kwh_m2,
month_ghi_kwh_m2, sun_up_records).)doc");
}

}  // namespace lidarfx::python
