#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Draws the pictures of docs/qgis.md with headless QGIS: the Processing toolbox filtered on lidarfx, and the
result of the waterbodies algorithm on a generated survey over its lowest-return raster.

Usage: QT_QPA_PLATFORM=offscreen LIDARFX_PROGRAM=build/release/lidarfx PYTHONPATH=build/release/python \\
       /usr/bin/python3 qgis/render_screenshots.py SURVEY.las [MORE.las ...] OUT_DIR"""
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

from qgis.core import (QgsApplication, QgsColorRampShader, QgsCoordinateReferenceSystem,  # noqa: E402
                       QgsFillSymbol, QgsMapRendererParallelJob, QgsMapSettings, QgsRasterLayer,
                       QgsRasterShader, QgsSingleBandPseudoColorRenderer, QgsVectorLayer)
from qgis.PyQt.QtCore import QSize  # noqa: E402
from qgis.PyQt.QtGui import QColor  # noqa: E402


def toolbox_picture(path):
    from qgis.gui import QgsProcessingToolboxProxyModel, QgsProcessingToolboxTreeView
    view = QgsProcessingToolboxTreeView(None, QgsApplication.processingRegistry())
    view.setFilters(QgsProcessingToolboxProxyModel.FilterToolbox)
    view.setFilterString("lidarfx")
    view.setHeaderHidden(True)
    view.expandAll()
    view.resize(430, 230)
    view.grab().save(path)


def result_picture(surveys, path):
    import processing
    folder = tempfile.mkdtemp(prefix="lidarfx_screens_")
    result = processing.run("lidarfx:water", {"FILES": surveys, "CELL": 2.0,
                                              "WATER": os.path.join(folder, "water.tif"),
                                              "BODIES": os.path.join(folder, "bodies.gpkg")})
    import subprocess
    ground = os.path.join(folder, "ground")
    subprocess.run([os.environ.get("LIDARFX_PROGRAM", "lidarfx"), "rasterize", *surveys, "--cell", "2", "--out",
                    ground, "--formats", "tif"], check=True, capture_output=True)
    # The relief under the result: the lowest return per cell, its empty cells (water dropouts, gaps between
    # flight lines) filled from their neighbours so that the hillshade has no holes, then shaded.
    from osgeo import gdal
    gdal.UseExceptions()
    filled = os.path.join(folder, "min_z_filled.tif")
    gdal.Translate(filled, os.path.join(ground, "min_z.tif"))
    dataset = gdal.Open(filled, gdal.GA_Update)
    gdal.FillNodata(dataset.GetRasterBand(1), None, 20, 0)
    dataset = None
    shade = os.path.join(folder, "hillshade.tif")
    subprocess.run(["gdaldem", "hillshade", "-q", "-compute_edges", filled, shade], check=True)
    relief = QgsRasterLayer(shade, "relief")
    water = QgsRasterLayer(result["WATER"], "water")
    ramp = QgsColorRampShader()
    ramp.setColorRampType(QgsColorRampShader.Discrete)
    ramp.setColorRampItemList([QgsColorRampShader.ColorRampItem(0.5, QColor(0, 0, 0, 0), "land"),
                               QgsColorRampShader.ColorRampItem(1.5, QColor(30, 110, 230, 200), "water")])
    shader = QgsRasterShader()
    shader.setRasterShaderFunction(ramp)
    water.setRenderer(QgsSingleBandPseudoColorRenderer(water.dataProvider(), 1, shader))
    bodies = QgsVectorLayer(result["BODIES"], "waterbodies", "ogr")
    bodies.renderer().setSymbol(QgsFillSymbol.createSimple(
        {"color": "0,0,0,0", "outline_color": "255,200,0", "outline_width": "0.6"}))
    settings = QgsMapSettings()
    settings.setLayers([bodies, water, relief])
    settings.setDestinationCrs(QgsCoordinateReferenceSystem(water.crs()))
    settings.setExtent(relief.extent())
    settings.setOutputSize(QSize(800, 400))
    settings.setBackgroundColor(QColor(255, 255, 255))
    job = QgsMapRendererParallelJob(settings)
    job.start()
    job.waitForFinished()
    job.renderedImage().save(path)
    return water.crs().authid()


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    *surveys, out = sys.argv[1:]
    os.makedirs(out, exist_ok=True)
    app = QgsApplication([], True)
    app.initQgis()
    sys.path.append("/usr/share/qgis/python/plugins")
    from processing.core.Processing import Processing
    Processing.initialize()
    from lidarfx_processing.provider import LidarfxProvider
    provider = LidarfxProvider()
    QgsApplication.processingRegistry().addProvider(provider)
    toolbox_picture(os.path.join(out, "qgis-toolbox.png"))
    crs = result_picture(surveys, os.path.join(out, "qgis-water.png"))
    print(f"wrote {out}/qgis-toolbox.png and {out}/qgis-water.png (layers in {crs})")
    app.exitQgis()


if __name__ == "__main__":
    main()
