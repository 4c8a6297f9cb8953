# SPDX-License-Identifier: Apache-2.0
"""What the algorithms share: running the lidarfx program with Processing feedback, reading and writing
rasters with GDAL for the algorithms that call the lidarfx Python module, and a common base class."""
import math
import os
import queue
import re
import shutil
import subprocess
import threading
import uuid

from qgis.core import (QgsCoordinateReferenceSystem, QgsCoordinateTransform, QgsPointXY, QgsProcessingAlgorithm,
                       QgsProcessingException, QgsProcessingUtils, QgsProject, QgsUnitTypes)

PROGRESS_LINE = re.compile(r"^(?P<label>.*?)\s*(?P<percent>\d{1,3})\s*%$")


def program():
    """The lidarfx program: $LIDARFX_PROGRAM, else `lidarfx` on PATH, else /usr/local/bin/lidarfx."""
    candidates = [os.environ.get("LIDARFX_PROGRAM"), shutil.which("lidarfx"), "/usr/local/bin/lidarfx"]
    for path in candidates:
        if path and os.path.isfile(path) and os.access(path, os.X_OK):
            return path
    raise QgsProcessingException(
        "The lidarfx program was not found (set LIDARFX_PROGRAM, or install it with "
        "scripts/install-qgis-plugin.sh from the lidarfx repository).")


def python_module():
    """The lidarfx Python module, with a clear message when it is not installed."""
    try:
        import lidarfx
    except ImportError as error:
        raise QgsProcessingException(
            f"The lidarfx Python module is not installed for QGIS's Python ({error}); install it with "
            "scripts/install-python.sh from the lidarfx repository.")
    return lidarfx


def work_folder():
    """A new folder of its own in Processing's temporary folder, for one run of the program."""
    path = os.path.join(QgsProcessingUtils.tempFolder(), "lidarfx_" + uuid.uuid4().hex[:12])
    os.makedirs(path)
    return path


def run_program(arguments, feedback):
    """Runs `lidarfx ARGUMENTS`; "label NN %" lines on its stderr drive the progress bar, other lines go to the
    log. Cancelling in QGIS stops the program (which keeps or removes only its own files). Raises
    QgsProcessingException with the program's message on failure or when cancelled."""
    command = [program()] + [str(a) for a in arguments]
    feedback.pushCommandInfo(" ".join(f'"{c}"' if " " in c else c for c in command))
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                               errors="replace", bufsize=1)
    lines = queue.Queue()

    def read():
        for line in process.stdout:
            lines.put(line.rstrip("\n"))
        lines.put(None)

    threading.Thread(target=read, daemon=True).start()
    log = []
    while True:
        try:
            line = lines.get(timeout=0.2)
        except queue.Empty:
            line = ""
        if feedback.isCanceled():
            process.terminate()
            try:
                process.wait(timeout=10)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()
            process.stdout.close()
            raise QgsProcessingException("Cancelled")
        if line is None:
            break
        if not line:
            continue
        match = PROGRESS_LINE.match(line)
        if match:
            feedback.setProgressText(match.group("label"))
            feedback.setProgress(min(100, int(match.group("percent"))))
        else:
            log.append(line)
            feedback.pushInfo(line)
    code = process.wait()
    process.stdout.close()
    if code != 0:
        reasons = {1: "an error while running", 2: "the input or an option was refused",
                   3: "the data cannot support the method (the 'run anyway' option forces it)"}
        raise QgsProcessingException(
            f"lidarfx stopped with exit code {code} ({reasons.get(code, 'failed')}):\n" + "\n".join(log[-15:]))


def deliver(produced, destination, feedback):
    """Copies the program's output file to the path the user chose (converting with GDAL/OGR when the chosen
    format differs) and returns that path."""
    if not os.path.exists(produced):
        raise QgsProcessingException(f"lidarfx did not write {os.path.basename(produced)}")
    folder = os.path.dirname(os.path.abspath(destination))
    if folder:
        os.makedirs(folder, exist_ok=True)
    same_format = os.path.splitext(produced)[1].lower() == os.path.splitext(destination)[1].lower()
    if same_format:
        shutil.copyfile(produced, destination)
        return destination
    from osgeo import gdal
    gdal.UseExceptions()
    if produced.lower().endswith((".tif", ".asc")):
        gdal.Translate(destination, produced)
    else:
        gdal.VectorTranslate(destination, produced)
    feedback.pushInfo(f"converted {os.path.basename(produced)} to {destination}")
    return destination


def layer_file(layer, what):
    """The file a raster layer reads (only file-based layers can be handed to the program)."""
    path = layer.source().split("|")[0]
    if not os.path.isfile(path):
        raise QgsProcessingException(f"{what} must be a raster file (got the layer source '{layer.source()}')")
    return path


def vector_file(algorithm, parameters, name, context, feedback):
    """A file holding the features of a vector source parameter as its first layer, for the program (which reads
    the first layer of a file): the layer's own file when it can be, else a GeoPackage written for the run
    (memory layers, selections, filters, the second layer of a GeoPackage)."""
    path, layer_name = algorithm.parameterAsCompatibleSourceLayerPathAndLayerName(
        parameters, name, context, ["gpkg", "geojson", "shp"], "gpkg", feedback)
    if not layer_name:
        return path
    from osgeo import gdal, ogr
    gdal.UseExceptions()
    dataset = ogr.Open(path)
    first = dataset.GetLayer(0).GetName() if dataset is not None and dataset.GetLayerCount() else None
    dataset = None
    if first == layer_name:
        return path
    copy = os.path.join(work_folder(), "footprints.gpkg")
    gdal.VectorTranslate(copy, path, layers=[layer_name], format="GPKG")
    return copy


class Raster:
    """A single-band raster read with GDAL: heights as float32 (NoData as NaN), its geotransform and CRS."""

    def __init__(self, path):
        from osgeo import gdal, osr
        import numpy as np
        gdal.UseExceptions()
        dataset = gdal.Open(path)
        band = dataset.GetRasterBand(1)
        values = band.ReadAsArray().astype(np.float32)
        nodata = band.GetNoDataValue()
        if nodata is not None:
            values[values == np.float32(nodata)] = np.nan
        self.values = values
        self.geotransform = dataset.GetGeoTransform()
        self.wkt = dataset.GetProjection()
        x0, dx, rx, y0, ry, dy = self.geotransform
        if rx != 0 or ry != 0 or abs(abs(dx) - abs(dy)) > 1e-9 * abs(dx) or dy >= 0:
            raise QgsProcessingException(f"{path}: cells must be square and north-up (got geotransform "
                                         f"{self.geotransform})")
        self.cell = abs(dx)
        if self.wkt:
            srs = osr.SpatialReference(wkt=self.wkt)
            if srs.IsGeographic():
                raise QgsProcessingException(f"{path}: the CRS is geographic (degrees); reproject the DSM to a "
                                             "projected CRS in metres or feet first")

    def crs(self):
        return QgsCoordinateReferenceSystem.fromWkt(self.wkt)

    def center_lat_lon(self):
        """Latitude and longitude of the raster's centre, and the meridian convergence there (degrees from true
        north to grid north, east positive)."""
        rows, cols = self.values.shape
        x0, dx, _, y0, _, dy = self.geotransform
        centre = QgsPointXY(x0 + dx * cols / 2, y0 + dy * rows / 2)
        to_wgs84 = QgsCoordinateTransform(self.crs(), QgsCoordinateReferenceSystem("EPSG:4326"),
                                          QgsProject.instance())
        geo = to_wgs84.transform(centre)
        # True north seen on the grid: a point a little north of the centre, brought back to the grid.
        north = to_wgs84.transform(QgsPointXY(geo.x(), geo.y() + 1e-4), QgsCoordinateTransform.ReverseTransform)
        true_north_on_grid = math.degrees(math.atan2(north.x() - centre.x(), north.y() - centre.y()))
        convergence = -true_north_on_grid
        return geo.y(), geo.x(), convergence

    def write(self, path, values, data_type="Float32", nodata=None):
        """Writes `values` on this raster's grid and CRS (GeoTIFF, DEFLATE)."""
        from osgeo import gdal
        gdal.UseExceptions()
        types = {"Float32": gdal.GDT_Float32, "Byte": gdal.GDT_Byte}
        rows, cols = values.shape
        dataset = gdal.GetDriverByName("GTiff").Create(path, cols, rows, 1, types[data_type],
                                                      options=["COMPRESS=DEFLATE", "TILED=YES"])
        dataset.SetGeoTransform(self.geotransform)
        dataset.SetProjection(self.wkt)
        band = dataset.GetRasterBand(1)
        if nodata is not None:
            band.SetNoDataValue(nodata)
        band.WriteArray(values)
        dataset.FlushCache()
        dataset = None

    def xy_unit_factor(self):
        """Metres per unit of the CRS's horizontal axes (1 for metres, 0.3048 for feet)."""
        if not self.wkt:
            return 1.0
        return QgsUnitTypes.fromUnitToUnitFactor(self.crs().mapUnits(), QgsUnitTypes.DistanceMeters)


def module_progress(feedback):
    """A progress callable for the lidarfx Python module: drives the progress bar, cancels when asked."""
    def report(fraction):
        feedback.setProgress(100.0 * fraction)
        return not feedback.isCanceled()
    return report


class LidarfxAlgorithm(QgsProcessingAlgorithm):
    """Base of the lidarfx algorithms: group, instance creation, help text."""
    _name = ""
    _display = ""
    _help = ""

    def name(self):
        return self._name

    def displayName(self):  # noqa: N802
        return self._display

    def group(self):
        return ""

    def groupId(self):  # noqa: N802
        return ""

    def shortHelpString(self):  # noqa: N802
        return self._help

    def createInstance(self):  # noqa: N802
        return type(self)()
