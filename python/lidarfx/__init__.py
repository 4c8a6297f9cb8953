# SPDX-License-Identifier: Apache-2.0
"""lidarfx: algorithms for airborne LiDAR on NumPy arrays.

Waterbodies and hydro-flattening, sun position, cast shadows, horizons, sky view, annual irradiation, buildings and rooftop PV,
computed by the C++ library lidarfx. Rasters are 2-D NumPy arrays, row 0 north, square cells of cell_m metres;
heights in metres, angles in degrees (azimuths clockwise from north). Every long call takes threads= (1 by
default, 0 = all cores; results never depend on it) and progress= (a callable taking the fraction done;
returning False cancels with lidarfx.Cancelled); Ctrl-C cancels too. Invalid input raises ValueError (or
TypeError for a wrong type) with the library's message.
"""
from ._lidarfx import *  # noqa: F401,F403
from ._lidarfx import Cancelled, has_io  # noqa: F401
from ._types import (AzimuthSelection, Building, Buildings, ChannelJoin, Components, Grid, HydroBody, HydroCheck,  # noqa: F401
                     HydroFlattened, IrradianceMaps, KsResult, Rasters, RoofPatch, RoofSuitability, RoofSurface, SlopeAspect, SunPosition, SurfaceOutliers,
                     Survey,
                     WaterIssue, Waterbodies, Waterbody, Weather)

__version__ = "0.1.0"
