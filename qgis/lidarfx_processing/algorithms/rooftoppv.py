# SPDX-License-Identifier: Apache-2.0
"""Rooftop PV suitability of every roof plane: `lidarfx roofs`."""
import os

from qgis.core import (QgsProcessing, QgsProcessingException, QgsProcessingParameterEnum,
                       QgsProcessingParameterFeatureSource, QgsProcessingParameterField, QgsProcessingParameterNumber,
                       QgsProcessingParameterRasterLayer, QgsProcessingParameterVectorDestination)

from ..engine import LidarfxAlgorithm, deliver, layer_file, run_program, vector_file, work_folder
from .irradiation import add_place_parameters, place_arguments
from .water import add_survey_parameters, survey_files


class RooftopPvAlgorithm(LidarfxAlgorithm):
    _name = "rooftoppv"
    _display = "Rooftop PV suitability"
    _help = ("Which roof planes suit PV panels, inside building footprints (a polygon layer with an integer id "
             "field: the one chosen, else building_id, else the feature ids). Roofs come from a LAS/LAZ survey "
             "(highest return per cell; terrain from the surface's edges) or from a DSM and a DTM on one grid. "
             "Mode planes: every roof plane with its fitted tilt, azimuth (clockwise from north) and area; mode "
             "paper: one PV plane per building. A plane suits with 15-60° tilt facing 90-270° and at least 8 m² "
             "(flat roofs: 8 m² whatever their facing); kWp = sloped area / 8 m². With weather (TMY3 or a "
             "clear-sky year at the place) each patch also gets its annual kWh/m² and kWh. Output: the roof "
             "patches as polygons in the survey's CRS. Runs the lidarfx program (lidarfx roofs).")

    def initAlgorithm(self, config=None):  # noqa: N802
        add_survey_parameters(self)
        self.addParameter(QgsProcessingParameterRasterLayer("DSM", "Or: surface model (DSM)", optional=True))
        self.addParameter(QgsProcessingParameterRasterLayer("DTM", "and terrain model (DTM)", optional=True))
        self.addParameter(QgsProcessingParameterFeatureSource(
            "FOOTPRINTS", "Building footprints", [QgsProcessing.TypeVectorPolygon]))
        self.addParameter(QgsProcessingParameterField(
            "ID_FIELD", "Footprints' integer id field [building_id, else the feature ids]",
            parentLayerParameterName="FOOTPRINTS", type=QgsProcessingParameterField.Numeric, optional=True))
        self.addParameter(QgsProcessingParameterNumber(
            "CELL", "Cell size for a LAS/LAZ survey (metres) [1]", QgsProcessingParameterNumber.Double, 1.0,
            minValue=0.1))
        self.addParameter(QgsProcessingParameterEnum(
            "MODE", "Mode: planes (every roof plane) or paper (one plane per building) [planes]", ["planes", "paper"],
            defaultValue=0))
        add_place_parameters(self)
        self.addParameter(QgsProcessingParameterVectorDestination(
            "OUTPUT", "Roof patches", QgsProcessing.TypeVectorPolygon))

    def processAlgorithm(self, parameters, context, feedback):  # noqa: N802
        footprints = vector_file(self, parameters, "FOOTPRINTS", context, feedback)
        dsm_layer = self.parameterAsRasterLayer(parameters, "DSM", context)
        dtm_layer = self.parameterAsRasterLayer(parameters, "DTM", context)
        if dsm_layer is not None or dtm_layer is not None:
            if dsm_layer is None or dtm_layer is None:
                raise QgsProcessingException("Give both a DSM and a DTM, or a LAS/LAZ survey")
            inputs = [layer_file(dsm_layer, "DSM"), layer_file(dtm_layer, "DTM")]
            cell = []
        else:
            inputs = survey_files(self, parameters, context, "FILES", "FOLDER")
            cell = ["--cell", self.parameterAsDouble(parameters, "CELL", context)]
        out = work_folder()
        mode = ["planes", "paper"][self.parameterAsEnum(parameters, "MODE", context)]
        weather = place_arguments(self, parameters, context)
        id_field = self.parameterAsFields(parameters, "ID_FIELD", context)
        id_argument = ["--id-field", id_field[0]] if id_field else []
        run_program(["roofs", *inputs, footprints, "--out", out, "--mode", mode, *cell, *id_argument,
                     *weather], feedback)
        patches = deliver(os.path.join(out, "roof_patches.gpkg"),
                          self.parameterAsOutputLayer(parameters, "OUTPUT", context), feedback)
        return {"OUTPUT": patches}
