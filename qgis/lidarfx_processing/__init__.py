# SPDX-License-Identifier: Apache-2.0
"""The lidarfx QGIS plugin: a Processing provider whose algorithms run the lidarfx library."""


def classFactory(iface):  # noqa: N802 (QGIS's name)
    from .plugin import LidarfxPlugin
    return LidarfxPlugin(iface)
