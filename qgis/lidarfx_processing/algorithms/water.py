# SPDX-License-Identifier: Apache-2.0
"""Waterbodies from LAS/LAZ surveys: `lidarfx water`."""
import glob
import os

from qgis.core import (QgsProcessing, QgsProcessingException, QgsProcessingParameterBoolean,
                       QgsProcessingParameterFile, QgsProcessingParameterMultipleLayers, QgsProcessingParameterNumber,
                       QgsProcessingParameterRasterDestination, QgsProcessingParameterVectorDestination)

from ..engine import LidarfxAlgorithm, deliver, run_program, work_folder


def survey_files(algorithm, parameters, context, files_name, folder_name):
    """The LAS/LAZ files of the FILES (list of files) and FOLDER (*.las and *.laz in it) parameters."""
    files = list(algorithm.parameterAsFileList(parameters, files_name, context) or []) if files_name else []
    folder = algorithm.parameterAsFile(parameters, folder_name, context) if folder_name else ""
    if folder:
        files += sorted(glob.glob(os.path.join(folder, "*.las")) + glob.glob(os.path.join(folder, "*.laz")))
    files = [f.split("|")[0] for f in files if f]  # an unset FILES parameter reads as ['']
    if not files:
        raise QgsProcessingException("Give LAS/LAZ files or a folder holding them")
    return files


def add_survey_parameters(algorithm, optional=False):
    algorithm.addParameter(QgsProcessingParameterMultipleLayers(
        "FILES", "Survey: LAS/LAZ files (projected CRS, metres or feet)", QgsProcessing.TypeFile, optional=True))
    algorithm.addParameter(QgsProcessingParameterFile(
        "FOLDER", "Survey: a folder of LAS/LAZ files (its *.las and *.laz)", QgsProcessingParameterFile.Folder,
        optional=True))


class WaterAlgorithm(LidarfxAlgorithm):
    _name = "water"
    _display = "Waterbodies"
    _help = ("Maps the waterbodies of an airborne LiDAR survey (LAS/LAZ, coordinates in metres or feet; a "
             "geographic CRS is refused). Water absorbs or mirrors the laser: cells without returns, and level "
             "low cells with fewer returns, seed bodies that grow over level ground while the intensity stays "
             "water-like. Outputs: a water raster (1 water, 0 land, NoData where nothing was flown) and the "
             "waterbody polygons with their area (m²) and water level (m), both in the survey's CRS.\n\n"
             "Cell size: metres (default 2 m; about 2 points per cell are needed: the run is refused with "
             "the reason otherwise, unless 'run anyway' is ticked). Runs the lidarfx program "
             "(lidarfx water).")

    def initAlgorithm(self, config=None):  # noqa: N802
        add_survey_parameters(self)
        self.addParameter(QgsProcessingParameterNumber(
            "CELL", "Cell size (metres) [2]", QgsProcessingParameterNumber.Double, 2.0, minValue=0.1))
        self.addParameter(QgsProcessingParameterBoolean(
            "DROPOUT_SEEDS_ONLY", "Seed only from cells without returns (faster; misses turbid water) [off]",
            False))
        self.addParameter(QgsProcessingParameterNumber(
            "ISLAND_MIN_AREA", "Smallest island kept as land (m²) [200]", QgsProcessingParameterNumber.Double, 200.0,
            minValue=0.0))
        self.addParameter(QgsProcessingParameterBoolean(
            "FORCE", "Run anyway when the data cannot support the method (too sparse, no intensity) [off]",
            False))
        self.addParameter(QgsProcessingParameterRasterDestination("WATER", "Water raster (1 water, 0 land)"))
        self.addParameter(QgsProcessingParameterVectorDestination(
            "BODIES", "Waterbody polygons", QgsProcessing.TypeVectorPolygon))

    def processAlgorithm(self, parameters, context, feedback):  # noqa: N802
        files = survey_files(self, parameters, context, "FILES", "FOLDER")
        out = work_folder()
        arguments = ["water", *files, "--cell", self.parameterAsDouble(parameters, "CELL", context), "--out", out,
                     "--island-min-area", self.parameterAsDouble(parameters, "ISLAND_MIN_AREA", context)]
        if self.parameterAsBoolean(parameters, "DROPOUT_SEEDS_ONLY", context):
            arguments.append("--dropout-seeds-only")
        if self.parameterAsBoolean(parameters, "FORCE", context):
            arguments.append("--force")
        run_program(arguments, feedback)
        water = deliver(os.path.join(out, "water.tif"),
                        self.parameterAsOutputLayer(parameters, "WATER", context), feedback)
        bodies = deliver(os.path.join(out, "waterbodies.gpkg"),
                         self.parameterAsOutputLayer(parameters, "BODIES", context), feedback)
        return {"WATER": water, "BODIES": bodies}
