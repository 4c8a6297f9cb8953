#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Writes python/lidarfx/__init__.pyi from the built module's signatures and docstrings (the test test_stubs.py
fails when they drift apart). Usage: PYTHONPATH=build/python /usr/bin/python3 python/tools/make_stubs.py"""
import os
import re

import lidarfx._lidarfx as extension

RESULTS = {"azimuth_mode_select": "AzimuthSelection", "clear_sky_year": "Weather",
           "connected_components": "Components", "extract_buildings": "Buildings",
           "extract_waterbodies": "Waterbodies", "hydro_flatten": "HydroFlattened", "irradiance_maps": "IrradianceMaps", "ks_one_sided": "KsResult",
           "rasterize": "Rasters", "read_survey": "Survey", "read_tmy3": "Weather",
           "roof_suitability": "RoofSuitability", "slope_aspect": "SlopeAspect", "remove_surface_outliers": "SurfaceOutliers", "sun_position": "SunPosition",
           "count_points_above": "Union[np.ndarray, Tuple[np.ndarray, np.ndarray]]"}
ARGUMENTS = {"rasters": "Union[Rasters, Mapping[str, ArrayLike], Any]", "weather": "Weather",
             "grid": "Optional[Grid]", "time": "Union[datetime, str, float]",
             "progress": "Optional[Callable[[float], Optional[bool]]]", "utc_offset_h": "Optional[float]"}
ARRAYS = {"z", "dsm", "mask", "dtm", "building_id", "hist360", "previous", "current", "x", "y", "reference"}
OPTIONAL_ARRAYS = {"intensity", "return_number", "number_of_returns", "classification", "ground", "vegetation",
                   "surface_tilt_deg", "surface_azimuth_deg", "point_count", "multiple_return_count", "building_cells",
                   "raised_count", "lowest_raised"}
HEAD = '''# SPDX-License-Identifier: Apache-2.0
# Type stubs of the lidarfx module (the extension _lidarfx re-exported), written by python/tools/make_stubs.py;
# tests/test_stubs.py keeps them in step with the module's signatures and docstrings.
from datetime import datetime
from typing import Any, Callable, Mapping, Optional, Tuple, Union

import numpy as np
from numpy.typing import ArrayLike

from ._types import (AzimuthSelection, Building, Buildings, ChannelJoin, Components, Grid, HydroBody, HydroCheck,
                     HydroFlattened, IrradianceMaps, KsResult, Rasters,
                     RoofPatch, RoofSuitability, RoofSurface, SlopeAspect, SunPosition, SurfaceOutliers, Survey, WaterIssue,
                     Waterbodies, Waterbody, Weather)

__version__: str
has_io: bool


class Cancelled(RuntimeError):
    """A long call stopped because its progress callable returned False."""


'''


def annotation(name, runtime_type, default):
    if name in OPTIONAL_ARRAYS and default is None:  # required here (fill_ground's ground)
        return "ArrayLike"
    if name == "grid" and default is None:  # required here (count_points_above's grid)
        return "Grid"
    if name in ARGUMENTS:
        return ARGUMENTS[name]
    if name in ARRAYS:
        return "ArrayLike"
    if name in OPTIONAL_ARRAYS:
        return "Optional[ArrayLike]"
    if runtime_type in ("handle", "object"):
        return "Optional[float]" if default == "None" else "Any"
    return runtime_type


def stub(name, function):
    first, doc = function.__doc__.split("\n", 1)
    params, _ = first.split("(", 1)[1].rsplit(") -> ", 1)
    out = []
    for p in params.split(", "):
        if p == "*":
            out.append("*")
            continue
        pname, ptype, default = re.match(r"(\w+): ([\w.]+)(?: = (.*))?", p).groups()
        out.append(f"{pname}: {annotation(pname, ptype, default)}" + (f" = {default}" if default is not None else ""))
    doc = doc.strip().replace("\\", "\\\\")
    return f'def {name}({", ".join(out)}) -> {RESULTS.get(name, "np.ndarray")}:\n    """{doc}"""\n    ...\n'


def main():
    functions = [stub(n, getattr(extension, n)) for n in sorted(dir(extension))
                 if not n.startswith("_") and callable(getattr(extension, n)) and getattr(extension, n).__doc__
                 and "(" in getattr(extension, n).__doc__.splitlines()[0]]
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "lidarfx", "__init__.pyi")
    with open(path, "w") as f:
        f.write(HEAD + "\n\n".join(functions))
    print(f"wrote {os.path.normpath(path)} ({len(functions)} functions)")


if __name__ == "__main__":
    main()
