# SPDX-License-Identifier: Apache-2.0
"""Cast shadows of a surface model at one instant: the lidarfx Python module's sun_position and
raylines_shadow."""
from datetime import datetime, timezone

from qgis.PyQt.QtCore import Qt
from qgis.core import (QgsProcessingException, QgsProcessingOutputNumber, QgsProcessingParameterDateTime,
                       QgsProcessingParameterNumber, QgsProcessingParameterRasterDestination,
                       QgsProcessingParameterRasterLayer)

from ..engine import LidarfxAlgorithm, Raster, layer_file, module_progress, python_module


class ShadowsAlgorithm(LidarfxAlgorithm):
    _name = "shadows"
    _display = "Cast shadows at a date and time"
    _help = ("Which cells of a surface model (DSM) the sun lights at one instant: 1 lit, 0 in a cast shadow (or "
             "the sun below the horizon), 255 NoData. The date and time are UTC (one written with its offset, "
             "2024-06-21T14:00:00+02:00, is converted). The sun's position (NREL SPA) is taken at the DSM's "
             "centre, its azimuth turned to grid north by the meridian convergence there. Heights and cells must "
             "be in the same unit. Also reports the sun's azimuth (degrees clockwise from true north) and "
             "elevation (degrees). Runs the lidarfx Python module.")

    def initAlgorithm(self, config=None):  # noqa: N802
        self.addParameter(QgsProcessingParameterRasterLayer("DSM", "Surface model (DSM)"))
        self.addParameter(QgsProcessingParameterDateTime("DATETIME", "Date and time (UTC)"))
        self.addParameter(QgsProcessingParameterNumber(
            "LINE_PHASES", "Ray line families (1-64; more = shadow edges closer to exact) [4]",
            QgsProcessingParameterNumber.Integer, 4, minValue=1, maxValue=64))
        self.addParameter(QgsProcessingParameterRasterDestination("OUTPUT", "Lit (1) or shadow (0)"))
        self.addOutput(QgsProcessingOutputNumber(
            "SUN_AZIMUTH_DEG", "Sun azimuth (degrees clockwise from true north)"))
        self.addOutput(QgsProcessingOutputNumber("SUN_ELEVATION_DEG", "Sun elevation (degrees above the horizon)"))

    def processAlgorithm(self, parameters, context, feedback):  # noqa: N802
        lidarfx = python_module()
        dsm = Raster(layer_file(self.parameterAsRasterLayer(parameters, "DSM", context), "DSM"))
        if not dsm.wkt:
            raise QgsProcessingException("The DSM has no CRS: the sun's position needs its place")
        when = self.parameterAsDateTime(parameters, "DATETIME", context)
        if not when.isValid():
            raise QgsProcessingException("Give a valid date and time (UTC)")
        if when.timeSpec() != Qt.LocalTime:  # a time given with its offset (…Z, …+02:00): brought to UTC
            when = when.toUTC()
        day, clock = when.date(), when.time()  # a time without offset: its clock reading is UTC
        moment = datetime(day.year(), day.month(), day.day(), clock.hour(), clock.minute(), clock.second(),
                          tzinfo=timezone.utc)
        latitude, longitude, convergence = dsm.center_lat_lon()
        sun = lidarfx.sun_position(moment, latitude, longitude)
        azimuth_grid = (sun.azimuth_deg - convergence) % 360.0
        feedback.pushInfo(f"sun at {moment:%Y-%m-%d %H:%M:%S} UTC over {latitude:.5f} N {longitude:.5f} E: azimuth "
                          f"{sun.azimuth_deg:.2f}° from true north ({azimuth_grid:.2f}° from grid north), elevation "
                          f"{sun.elevation_deg:.2f}°")
        lit = lidarfx.raylines_shadow(dsm.values, dsm.cell, azimuth_grid, sun.elevation_deg,
                                      line_phases=self.parameterAsInt(parameters, "LINE_PHASES", context),
                                      threads=0, progress=module_progress(feedback))
        path = self.parameterAsOutputLayer(parameters, "OUTPUT", context)
        dsm.write(path, lit, data_type="Byte", nodata=255)
        return {"OUTPUT": path, "SUN_AZIMUTH_DEG": sun.azimuth_deg, "SUN_ELEVATION_DEG": sun.elevation_deg}
