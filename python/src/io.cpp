// SPDX-License-Identifier: Apache-2.0
// Bindings of the program's readers: LAS/LAZ surveys and TMY3 weather years (when built with them).
#include <filesystem>
#include <system_error>
#include <vector>

#include "binding.hpp"

#ifdef LIDARFX_PYTHON_HAVE_IO
#include "io/las.hpp"
#include "io/tmy3.hpp"
#endif

namespace lidarfx::python {

#ifdef LIDARFX_PYTHON_HAVE_IO
namespace {

/// The vector as a 1-D NumPy array that owns its elements (moved, not copied).
template <class T>
py::array to_numpy(std::vector<T>&& values)
{
    auto* owned = new std::vector<T>(std::move(values));
    py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
    static T empty{};
    return py::array(py::dtype::of<T>(), {static_cast<py::ssize_t>(owned->size())},
                     {static_cast<py::ssize_t>(sizeof(T))}, owned->empty() ? &empty : owned->data(), owner);
}

/// Refuses a path that names no file as Python does (FileNotFoundError naming it).
void require_file(const std::string& path)
{
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
        PyErr_SetString(PyExc_FileNotFoundError, (path + ": no such file").c_str());
        throw py::error_already_set();
    }
}

py::object read_survey_binding(const std::string& path)
{
    require_file(path);
    io::las_points p;
    io::las_header header;
    {
        py::gil_scoped_release release;
        io::las_reader reader(path);
        header = reader.header();
        p = reader.read_all();
    }
    py::dict fields;
    fields["x"] = to_numpy(std::move(p.x));
    fields["y"] = to_numpy(std::move(p.y));
    fields["z"] = to_numpy(std::move(p.z));
    fields["intensity"] = to_numpy(std::move(p.intensity));
    fields["return_number"] = to_numpy(std::move(p.return_number));
    fields["number_of_returns"] = to_numpy(std::move(p.number_of_returns));
    fields["classification"] = to_numpy(std::move(p.classification));
    fields["epsg"] = header.epsg();
    fields["wkt"] = header.wkt;
    fields["path"] = path;
    return make_result("Survey", fields);
}

py::object read_tmy3_binding(const std::string& path)
{
    require_file(path);
    io::tmy3_data data;
    {
        py::gil_scoped_release release;
        data = io::read_tmy3(path);
    }
    return weather_from_records(data.records, data.station.latitude_deg, data.station.longitude_deg,
                                data.station.utc_offset_h);
}

}  // namespace
#endif

void bind_io(py::module_& m)
{
    using namespace pybind11::literals;
#ifdef LIDARFX_PYTHON_HAVE_IO
    m.def("read_survey", &read_survey_binding, "path"_a, R"doc(
Reads every point of a LAS (1.0-1.4) or LAZ file. Returns Survey(x, y, z: float64 metres; intensity: uint16;
return_number, number_of_returns, classification: uint8; epsg: the horizontal EPSG code (0 = none);
wkt: the CRS as WKT when the file carries one). Errors name the file: FileNotFoundError for a missing file,
ValueError or RuntimeError for a malformed one.)doc");
    m.def("read_tmy3", &read_tmy3_binding, "path"_a, R"doc(
Reads a TMY3 weather year (NREL CSV: station line, header line, 8760 hourly rows stamped at the end of the hour
in local standard time). Returns a Weather: start_utc (datetime64[s], UTC start of each hour), dni_w_m2,
dhi_w_m2, ghi_w_m2 (W/m^2), interval_s = 3600, and the station's latitude_deg, longitude_deg, utc_offset_h.)doc");
    m.attr("has_io") = true;
#else
    m.attr("has_io") = false;
#endif
}

}  // namespace lidarfx::python
