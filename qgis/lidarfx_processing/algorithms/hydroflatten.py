# SPDX-License-Identifier: Apache-2.0
"""Hydro-flattened DEMs from LAS/LAZ surveys: `lidarfx hydroflatten`."""
import os

from qgis.core import (QgsProcessing, QgsProcessingParameterBoolean, QgsProcessingParameterEnum,
                       QgsProcessingParameterFileDestination, QgsProcessingParameterNumber,
                       QgsProcessingParameterRasterDestination, QgsProcessingParameterVectorDestination)

from ..engine import LidarfxAlgorithm, deliver, run_program, work_folder
from .water import add_survey_parameters, survey_files

SHORELINE_RULES = ["lift", "flag"]


class HydroFlattenAlgorithm(LidarfxAlgorithm):
    _name = "hydroflatten"
    _display = "Hydro-flattened DEM"
    _help = ("Hydro-flattens the bare-earth DEM of an airborne LiDAR survey (LAS/LAZ, coordinates in metres or "
             "feet): finds its waterbodies as the Waterbodies algorithm does, gives every lake one level and every "
             "river flat cross-sections whose levels only fall downstream (water under bridges at the level the "
             "river has there), flattens islands under the minimum island area with the water and raises shore "
             "ground that lies below the water beside it ('lift'; 'flag' only counts it). Water under the minimum "
             "sizes is left to the terrain; the defaults are the USGS Lidar Base Specification's (2 acres, 100 ft, "
             "1 acre) in metres. The bare-earth DEM is the lowest return per cell, holes filled by inverse distance "
             "weighting.\n\nOutputs: the flattened DEM (metres, the survey's CRS), the breaklines (3D water-body "
             "polygons and river centrelines) and the checks per body (hydro_qa.csv: flatness, monotonic fall, "
             "shoreline, minimum size, with the worst offender). Runs the lidarfx program (lidarfx hydroflatten).")

    def initAlgorithm(self, config=None):  # noqa: N802
        add_survey_parameters(self)
        self.addParameter(QgsProcessingParameterNumber(
            "CELL", "Cell size (metres) [2]", QgsProcessingParameterNumber.Double, 2.0, minValue=0.1))
        self.addParameter(QgsProcessingParameterNumber(
            "MIN_LAKE_AREA", "Smallest lake flattened (m²) [8093.71 = 2 acres]", QgsProcessingParameterNumber.Double,
            8093.71, minValue=0.0))
        self.addParameter(QgsProcessingParameterNumber(
            "MIN_RIVER_WIDTH", "Narrowest river flattened (metres) [30.48 = 100 ft]",
            QgsProcessingParameterNumber.Double, 30.48, minValue=0.0))
        self.addParameter(QgsProcessingParameterNumber(
            "MIN_ISLAND_AREA", "Smallest island kept as land (m²) [4046.86 = 1 acre]",
            QgsProcessingParameterNumber.Double, 4046.86, minValue=0.0))
        self.addParameter(QgsProcessingParameterEnum(
            "SHORELINE", "Shore ground below the water [lift]", SHORELINE_RULES, defaultValue=0))
        self.addParameter(QgsProcessingParameterBoolean(
            "FORCE", "Run anyway when the data cannot support the waterbody method [off]", False))
        self.addParameter(QgsProcessingParameterRasterDestination("DEM", "Hydro-flattened DEM"))
        self.addParameter(QgsProcessingParameterVectorDestination(
            "BREAKLINES", "Breaklines (3D water-body polygons)", QgsProcessing.TypeVectorPolygon))
        self.addParameter(QgsProcessingParameterFileDestination(
            "QA", "Checks per waterbody (CSV)", "CSV files (*.csv)"))

    def processAlgorithm(self, parameters, context, feedback):  # noqa: N802
        files = survey_files(self, parameters, context, "FILES", "FOLDER")
        out = work_folder()
        arguments = ["hydroflatten", *files, "--cell", self.parameterAsDouble(parameters, "CELL", context),
                     "--out", out,
                     "--min-lake-area", self.parameterAsDouble(parameters, "MIN_LAKE_AREA", context),
                     "--min-river-width", self.parameterAsDouble(parameters, "MIN_RIVER_WIDTH", context),
                     "--min-island-area", self.parameterAsDouble(parameters, "MIN_ISLAND_AREA", context),
                     "--shoreline", SHORELINE_RULES[self.parameterAsEnum(parameters, "SHORELINE", context)]]
        if self.parameterAsBoolean(parameters, "FORCE", context):
            arguments.append("--force")
        run_program(arguments, feedback)
        dem = deliver(os.path.join(out, "dem_hydroflattened.tif"),
                      self.parameterAsOutputLayer(parameters, "DEM", context), feedback)
        breaklines = deliver(os.path.join(out, "breaklines.gpkg"),
                             self.parameterAsOutputLayer(parameters, "BREAKLINES", context), feedback)
        qa = deliver(os.path.join(out, "hydro_qa.csv"),
                     self.parameterAsFileOutput(parameters, "QA", context), feedback)
        return {"DEM": dem, "BREAKLINES": breaklines, "QA": qa}
