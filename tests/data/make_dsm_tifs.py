#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
# Writes the GeoTIFF DSM fixtures of the cli_solar_geotiff test (python3-gdal): 16 x 16 cells, flat ground at
# 100 with a 4 x 4 block 6 higher, the corner cells (0, 0) and (15, 15) NoData (-9999). Run from tests/data.
import numpy as np
from osgeo import gdal, osr

gdal.UseExceptions()


def srs(code):
    s = osr.SpatialReference()
    s.ImportFromEPSG(code)
    s.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    return s


def centre(code, lat, lon):
    """The point (lat, lon) in EPSG:code, to the millimetre (the DSM is centred on it)."""
    x, y, _ = osr.CoordinateTransformation(srs(4326), srs(code)).TransformPoint(lon, lat)
    return round(x, 3), round(y, 3)


def dsm(path, code, cx, cy, cell, unit, rotation=0.0):
    n = 16
    z = np.full((n, n), 100.0 * unit, dtype=np.float32)
    z[6:10, 6:10] = 106.0 * unit
    z[0, 0] = z[15, 15] = -9999
    ds = gdal.GetDriverByName('GTiff').Create(path, n, n, 1, gdal.GDT_Float32, ['COMPRESS=DEFLATE', 'PREDICTOR=3'])
    ds.SetGeoTransform([cx - n / 2 * cell, cell, rotation, cy + n / 2 * cell, 0.0, -cell])
    ds.SetProjection(srs(code).ExportToWkt())
    band = ds.GetRasterBand(1)
    band.SetNoDataValue(-9999)
    band.WriteArray(z)
    ds = None


utm = centre(32613, 40.0, -103.0)            # UTM 13N, 2 degrees east of its central meridian
dsm('dsm_utm13n.tif', 32613, *utm, 1.0, 1.0)
ft = 1.0 / 0.3048                             # feet per metre (EPSG:2269 is in international feet)
dsm('dsm_oregon_north_ft.tif', 2269, *centre(2269, 45.5, -122.0), ft, ft)   # 1 m cells and heights in feet
dsm('dsm_epsg4326.tif', 4326, -103.0, 40.0, 1e-5, 1.0)                        # degrees: refused
dsm('dsm_rotated.tif', 32613, *utm, 1.0, 1.0, rotation=0.3)                   # not north-up: refused
