# SPDX-License-Identifier: Apache-2.0
"""Buildings with the energy of their roofs and facades: `lidarfx solar --facades`."""
import os

from qgis.core import (QgsProcessing, QgsProcessingException, QgsProcessingParameterEnum,
                       QgsProcessingParameterFileDestination, QgsProcessingParameterNumber,
                       QgsProcessingParameterRasterDestination,
                       QgsProcessingParameterRasterLayer, QgsProcessingParameterVectorDestination)

from ..engine import LidarfxAlgorithm, deliver, layer_file, run_program, work_folder
from .irradiation import add_place_parameters, place_arguments
from .water import add_survey_parameters, survey_files


class BuildingsAlgorithm(LidarfxAlgorithm):
    _name = "buildings"
    _display = "Buildings and facade energy"
    _help = ("Finds the buildings of a LAS/LAZ survey or a DSM (raised roofs of at least 15 m²; from a survey, trees "
             "told from roofs by their split pulses and the terrain from its ground class 2 when it has one) and the "
             "solar energy of every roof patch and facade sub-patch over a year (cast shadows each daylight hour, "
             "sky view of walls and roofs). Outputs: building outlines with their ground, eave and ridge heights "
             "(m) and roof areas (m²); the facade patches table (building, facing azimuth, height, area, annual "
             "kWh/m² and quarterly kWh/m²/day); the annual irradiation map (kWh/m²). Weather and place as in "
             "'Annual solar irradiation'. From a survey the edge cells of each building are decided by the share of "
             "their points standing 2.5 m above the terrain; 'Buildings from' can take the survey's own building "
             "class (6) instead. Runs the lidarfx program (lidarfx solar --facades).")

    SOURCES = [("points", "found from the points (surface, terrain, returns)"),
               ("class6", "the survey's building class (ASPRS 6)")]

    def initAlgorithm(self, config=None):  # noqa: N802
        add_survey_parameters(self)
        self.addParameter(QgsProcessingParameterRasterLayer("DSM", "Or: surface model (DSM)", optional=True))
        self.addParameter(QgsProcessingParameterNumber(
            "CELL", "Cell size for a LAS/LAZ survey (metres) [1]", QgsProcessingParameterNumber.Double, 1.0,
            minValue=0.1))
        self.addParameter(QgsProcessingParameterEnum(
            "SOURCE", "Buildings from (LAS/LAZ survey)", [label for _, label in self.SOURCES], defaultValue=0))
        add_place_parameters(self)
        self.addParameter(QgsProcessingParameterVectorDestination(
            "BUILDINGS", "Buildings", QgsProcessing.TypeVectorPolygon))
        self.addParameter(QgsProcessingParameterFileDestination(
            "FACADES", "Facade patches (CSV)", "CSV files (*.csv)"))
        self.addParameter(QgsProcessingParameterRasterDestination(
            "IRRADIATION", "Annual irradiation (kWh/m²)", optional=True, createByDefault=False))

    def processAlgorithm(self, parameters, context, feedback):  # noqa: N802
        dsm_layer = self.parameterAsRasterLayer(parameters, "DSM", context)
        source = self.SOURCES[self.parameterAsEnum(parameters, "SOURCE", context)][0]
        if dsm_layer is not None:
            if source != "points":
                raise QgsProcessingException("'Buildings from' the survey's class 6 needs a LAS/LAZ survey, not a DSM")
            inputs = [layer_file(dsm_layer, "DSM")]
        else:
            inputs = survey_files(self, parameters, context, "FILES", "FOLDER")
            inputs += ["--cell", self.parameterAsDouble(parameters, "CELL", context)]
            if source != "points":
                inputs += ["--buildings", source]
        out = work_folder()
        run_program(["solar", *inputs, "--out", out, "--facades", "--formats", "tif,csv,gpkg",
                     *place_arguments(self, parameters, context)], feedback)
        results = {
            "BUILDINGS": deliver(os.path.join(out, "buildings.gpkg"),
                                 self.parameterAsOutputLayer(parameters, "BUILDINGS", context), feedback),
            "FACADES": deliver(os.path.join(out, "facade_patches.csv"),
                               self.parameterAsFileOutput(parameters, "FACADES", context), feedback),
        }
        irradiation = self.parameterAsOutputLayer(parameters, "IRRADIATION", context)
        if irradiation:
            results["IRRADIATION"] = deliver(os.path.join(out, "annual_kwh_m2.tif"), irradiation, feedback)
        if not os.path.exists(results["BUILDINGS"]):
            raise QgsProcessingException("no buildings layer was written")
        return results
