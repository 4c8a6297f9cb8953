# SPDX-License-Identifier: Apache-2.0
"""The lidarfx Processing provider: its algorithms, listed under "lidarfx" in the toolbox."""
from qgis.core import QgsProcessingProvider

from .algorithms.buildings import BuildingsAlgorithm
from .algorithms.hydroflatten import HydroFlattenAlgorithm
from .algorithms.irradiation import IrradiationAlgorithm
from .algorithms.rooftoppv import RooftopPvAlgorithm
from .algorithms.shadows import ShadowsAlgorithm
from .algorithms.skyviewfactor import SkyViewFactorAlgorithm
from .algorithms.water import WaterAlgorithm


class LidarfxProvider(QgsProcessingProvider):
    def id(self):
        return "lidarfx"

    def name(self):
        return "lidarfx"

    def longName(self):  # noqa: N802
        return "lidarfx: waterbodies, hydro-flattening, sun, buildings and rooftop PV from airborne LiDAR"

    def loadAlgorithms(self):  # noqa: N802
        for algorithm in (WaterAlgorithm(), HydroFlattenAlgorithm(), IrradiationAlgorithm(), SkyViewFactorAlgorithm(), ShadowsAlgorithm(),
                          RooftopPvAlgorithm(), BuildingsAlgorithm()):
            self.addAlgorithm(algorithm)
