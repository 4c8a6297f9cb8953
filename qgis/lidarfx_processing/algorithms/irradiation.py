# SPDX-License-Identifier: Apache-2.0
"""Annual solar irradiation of a surface model: `lidarfx solar`."""
import os

from qgis.core import (QgsProcessingException, QgsProcessingParameterBoolean, QgsProcessingParameterEnum,
                       QgsProcessingParameterFile, QgsProcessingParameterNumber,
                       QgsProcessingParameterRasterDestination, QgsProcessingParameterRasterLayer)

from ..engine import LidarfxAlgorithm, deliver, layer_file, run_program, work_folder


def add_place_parameters(algorithm):
    algorithm.addParameter(QgsProcessingParameterFile(
        "TMY", "Weather: a TMY3 year (CSV); empty = a clear-sky year", extension="csv", optional=True))
    algorithm.addParameter(QgsProcessingParameterNumber(
        "LAT", "Latitude (degrees north); empty = the DSM's centre", QgsProcessingParameterNumber.Double,
        optional=True, minValue=-90, maxValue=90))
    algorithm.addParameter(QgsProcessingParameterNumber(
        "LON", "Longitude (degrees east); empty = the DSM's centre", QgsProcessingParameterNumber.Double,
        optional=True, minValue=-180, maxValue=180))


def place_arguments(algorithm, parameters, context):
    arguments = []
    tmy = algorithm.parameterAsFile(parameters, "TMY", context)
    if tmy:
        arguments += ["--tmy", tmy]
    if parameters.get("LAT") is not None and parameters.get("LON") is not None:
        arguments += ["--lat", algorithm.parameterAsDouble(parameters, "LAT", context),
                      "--lon", algorithm.parameterAsDouble(parameters, "LON", context)]
    return arguments


class IrradiationAlgorithm(LidarfxAlgorithm):
    _name = "irradiation"
    _display = "Annual solar irradiation"
    _help = ("Irradiation of every cell of a surface model (DSM) over a year, kWh/m²: the beam where the cell sees "
             "the sun (cast shadows for every daylight hour) plus the diffuse light its sky view lets in. "
             "Weather: a TMY3 file, or a cloudless year from the clear-sky model. The place: latitude and "
             "longitude when given, else the DSM's centre (from its CRS), else the TMY station; sun azimuths are "
             "turned to grid north. DSM heights and cells in its CRS's units (feet become metres). Outputs the "
             "annual map and, optionally, the sky view factor used (0-1). Runs the lidarfx program "
             "(lidarfx solar).")

    def initAlgorithm(self, config=None):  # noqa: N802
        self.addParameter(QgsProcessingParameterRasterLayer("DSM", "Surface model (DSM)"))
        add_place_parameters(self)
        self.addParameter(QgsProcessingParameterNumber(
            "YEAR", "Year the weather is placed in [2021]", QgsProcessingParameterNumber.Integer, 2021,
            minValue=1901, maxValue=2099))
        self.addParameter(QgsProcessingParameterBoolean(
            "YEAR_FROM_TMY", "Keep the TMY rows' own years instead of the year above (needs a TMY3 file) [off]",
            False))
        self.addParameter(QgsProcessingParameterEnum(
            "DIFFUSE", "Diffuse sky model [isotropic]", ["isotropic", "perez"], defaultValue=0))
        self.addParameter(QgsProcessingParameterEnum(
            "SVF_METHOD", "Sky view factor definition: cosine-weighted (as GRASS and SAGA) or the share of "
            "point sources [cosine]", ["cosine", "share"], defaultValue=0))
        self.addParameter(QgsProcessingParameterNumber(
            "SVF_DIRECTIONS", "Azimuths of the horizon sweeps (>= 4) [72]", QgsProcessingParameterNumber.Integer,
            72, minValue=4, maxValue=3600))
        self.addParameter(QgsProcessingParameterEnum(
            "SURFACE", "Surfaces: horizontal, or each cell's own slope and aspect (terrain) [horizontal]",
            ["horizontal", "terrain"], defaultValue=0))
        self.addParameter(QgsProcessingParameterBoolean(
            "KEEP_OUTLIERS", "Keep the DSM's isolated spikes and pits (birds, canopy gaps) instead of replacing "
            "them by their neighbours' median [off]", False))
        self.addParameter(QgsProcessingParameterRasterDestination("OUTPUT", "Annual irradiation (kWh/m²)"))
        self.addParameter(QgsProcessingParameterRasterDestination(
            "SVF", "Sky view factor (0-1)", optional=True, createByDefault=False))

    def processAlgorithm(self, parameters, context, feedback):  # noqa: N802
        dsm = layer_file(self.parameterAsRasterLayer(parameters, "DSM", context), "DSM")
        out = work_folder()
        diffuse = ["isotropic", "perez"][self.parameterAsEnum(parameters, "DIFFUSE", context)]
        svf_method = ["cosine", "share"][self.parameterAsEnum(parameters, "SVF_METHOD", context)]
        surface = ["horizontal", "terrain"][self.parameterAsEnum(parameters, "SURFACE", context)]
        arguments = ["solar", dsm, "--out", out, "--formats", "tif,csv", "--diffuse", diffuse, "--svf", svf_method,
                     "--svf-directions", self.parameterAsInt(parameters, "SVF_DIRECTIONS", context),
                     "--surface", surface, *place_arguments(self, parameters, context)]
        if self.parameterAsBoolean(parameters, "YEAR_FROM_TMY", context):
            if "--tmy" not in arguments:
                raise QgsProcessingException("'Keep the TMY rows' own years' needs a TMY3 file")
            arguments.append("--year-from-tmy")
        else:
            arguments += ["--year", self.parameterAsInt(parameters, "YEAR", context)]
        if self.parameterAsBoolean(parameters, "KEEP_OUTLIERS", context):
            arguments.append("--keep-outliers")
        run_program(arguments, feedback)
        results = {"OUTPUT": deliver(os.path.join(out, "annual_kwh_m2.tif"),
                                     self.parameterAsOutputLayer(parameters, "OUTPUT", context), feedback)}
        svf = self.parameterAsOutputLayer(parameters, "SVF", context)
        if svf:
            results["SVF"] = deliver(os.path.join(out, "svf.tif"), svf, feedback)
        return results
