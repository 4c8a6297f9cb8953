# SPDX-License-Identifier: Apache-2.0
"""Registers the lidarfx provider with Processing (desktop and qgis_process alike)."""
from qgis.core import QgsApplication

from .provider import LidarfxProvider


class LidarfxPlugin:
    def __init__(self, iface=None):
        self.iface = iface
        self.provider = None

    def initProcessing(self):  # noqa: N802 (called by qgis_process for plugins with a provider)
        if self.provider is None:
            self.provider = LidarfxProvider()
            QgsApplication.processingRegistry().addProvider(self.provider)

    def initGui(self):  # noqa: N802
        self.initProcessing()

    def unload(self):
        if self.provider is not None:
            QgsApplication.processingRegistry().removeProvider(self.provider)
            self.provider = None
