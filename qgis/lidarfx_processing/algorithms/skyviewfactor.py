# SPDX-License-Identifier: Apache-2.0
"""Sky view factor of a surface model: the lidarfx Python module's sky_view_factor."""
import numpy as np
from qgis.core import (QgsProcessingParameterEnum, QgsProcessingParameterNumber,
                       QgsProcessingParameterRasterDestination, QgsProcessingParameterRasterLayer)

from ..engine import LidarfxAlgorithm, Raster, layer_file, module_progress, python_module

METHODS = ["cosine_weighted", "source_share"]


class SkyViewFactorAlgorithm(LidarfxAlgorithm):
    _name = "skyviewfactor"
    _display = "Sky view factor"
    _help = ("The share of the sky each cell of a surface model (DSM) sees, 0-1 (1 on open flat ground), from an "
             "exact horizon sweep towards each of N azimuths (default 72, every 5°). Methods: cosine-weighted "
             "(the view factor of a horizontal surface under a uniform sky, the mean of cos² of the horizon "
             "angle: the SVF of GRASS r.skyview and SAGA) or source share (the share of 1,081 point sources "
             "at 15°-85° and the zenith that the cell sees, as in the solar maps). Heights and cells must be in "
             "the same unit (metres or feet). Runs the lidarfx Python module.")

    def initAlgorithm(self, config=None):  # noqa: N802
        self.addParameter(QgsProcessingParameterRasterLayer("DSM", "Surface model (DSM)"))
        self.addParameter(QgsProcessingParameterEnum(
            "METHOD", "Definition: cosine-weighted or source share [cosine_weighted]", METHODS, defaultValue=0))
        self.addParameter(QgsProcessingParameterNumber(
            "DIRECTIONS", "Azimuths swept (>= 4) [72]", QgsProcessingParameterNumber.Integer, 72, minValue=4))
        self.addParameter(QgsProcessingParameterRasterDestination("OUTPUT", "Sky view factor (0-1)"))

    def processAlgorithm(self, parameters, context, feedback):  # noqa: N802
        lidarfx = python_module()
        dsm = Raster(layer_file(self.parameterAsRasterLayer(parameters, "DSM", context), "DSM"))
        svf = lidarfx.sky_view_factor(dsm.values, dsm.cell, method=METHODS[self.parameterAsEnum(
            parameters, "METHOD", context)], directions=self.parameterAsInt(parameters, "DIRECTIONS", context),
            threads=0, progress=module_progress(feedback))
        path = self.parameterAsOutputLayer(parameters, "OUTPUT", context)
        dsm.write(path, svf.astype(np.float32), nodata=float("nan"))
        return {"OUTPUT": path}
