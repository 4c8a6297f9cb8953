// SPDX-License-Identifier: Apache-2.0
// The Grid argument and result: lidarfx.Grid(x0, y0, cell_m, rows, cols) <-> lidarfx::grid.
#pragma once

#include <optional>

#include <lidarfx/core/grid.hpp>

#include "binding.hpp"

namespace lidarfx::python {

/// A Grid (any object with x0, y0, cell_m, rows and cols) as the library's grid; nullopt for None.
inline std::optional<grid> grid_from_python(const py::handle& g, const char* function)
{
    if (g.is_none()) return std::nullopt;
    for (const char* name : {"x0", "y0", "cell_m", "rows", "cols"}) {
        if (!py::hasattr(g, name)) {
            throw py::type_error(std::string(function) + ": grid must be a lidarfx.Grid (no attribute " + name + ")");
        }
    }
    grid out{.x0 = g.attr("x0").cast<double>(),
             .y0 = g.attr("y0").cast<double>(),
             .cell = g.attr("cell_m").cast<double>(),
             .rows = g.attr("rows").cast<std::ptrdiff_t>(),
             .cols = g.attr("cols").cast<std::ptrdiff_t>()};
    out.validate(function);
    return out;
}

/// The library's grid as a lidarfx.Grid.
inline py::object grid_to_python(const grid& g)
{
    py::dict fields;
    fields["x0"] = g.x0;
    fields["y0"] = g.y0;
    fields["cell_m"] = g.cell;
    fields["rows"] = g.rows;
    fields["cols"] = g.cols;
    return make_result("Grid", fields);
}

}  // namespace lidarfx::python
