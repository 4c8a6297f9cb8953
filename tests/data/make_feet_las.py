#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
# Writes scene_oregon_ft.las, the feet survey of the cli_raster_units test (python3 only): LAS 1.2, point format 0,
# GeoKeys naming EPSG:2994 (NAD83(HARN) / Oregon GIC Lambert (ft), international feet) with x, y and z in feet.
# The scene, in metres: 60 m x 60 m of flat ground at 100 m, a 12 m x 12 m block 8 m high in its middle and a
# 4 m x 20 m wall 12 m high west of it; points every 0.5 m (four per 1 m cell), 14400 in all. Run from tests/data.
import struct

FOOT = 0.3048
X0, Y0 = 637000.0, 849000.0  # feet, near Eugene, Oregon (44.06 N, 123.07 W)
STEP, SIDE = 0.5, 60.0       # metres


def height_m(x, y):
    if 24 <= x < 36 and 24 <= y < 36:
        return 108.0
    if 10 <= x < 14 and 20 <= y < 40:
        return 112.0
    return 100.0


points = []
n = int(SIDE / STEP)
for i in range(n):
    for j in range(n):
        x, y = (j + 0.5) * STEP, (i + 0.5) * STEP
        z = height_m(x, y)
        points.append((X0 + x / FOOT, Y0 + y / FOOT, z / FOOT, 2 if z == 100.0 else 6))

scale = 0.001
offset = (X0, Y0, 0.0)
keys = [1, 1, 0, 5,
        1024, 0, 1, 1,      # GTModelTypeGeoKey: projected
        1025, 0, 1, 1,      # GTRasterTypeGeoKey: pixel is area
        3072, 0, 1, 2994,   # ProjectedCSTypeGeoKey: EPSG:2994
        3076, 0, 1, 9002,   # ProjLinearUnitsGeoKey: international foot
        4099, 0, 1, 9002]   # VerticalUnitsGeoKey: international foot
key_bytes = struct.pack('<%dH' % len(keys), *keys)
vlr = struct.pack('<H16sHH32s', 0, b'LASF_Projection', 34735, len(key_bytes), b'GeoKeyDirectoryTag') + key_bytes
header_size = 227
offset_to_points = header_size + len(vlr)
xs, ys, zs = [p[0] for p in points], [p[1] for p in points], [p[2] for p in points]
q = [round((v - o) / scale) * scale + o for v, o in zip((max(xs), min(xs), max(ys), min(ys), max(zs), min(zs)),
                                                         (X0, X0, Y0, Y0, 0.0, 0.0))]
header = struct.pack('<4sHH16sBB32s32sHHHIIBHI5I3d3d6d', b'LASF', 0, 0, bytes(16), 1, 2, b'lidarfx tests',
                     b'make_feet_las.py', 1, 2026, header_size, offset_to_points, 1, 0, 20, len(points),
                     len(points), 0, 0, 0, 0, scale, scale, scale, *offset, *q)
assert len(header) == header_size
with open('scene_oregon_ft.las', 'wb') as f:
    f.write(header)
    f.write(vlr)
    for x, y, z, cls in points:
        f.write(struct.pack('<iiiHBBbBH', round((x - X0) / scale), round((y - Y0) / scale), round(z / scale), 0,
                            0b00001001, cls, 0, 0, 0))
