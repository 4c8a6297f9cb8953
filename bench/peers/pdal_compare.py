# SPDX-License-Identifier: Apache-2.0
"""Helper of bench/peers/pdal_rasterize.sh: the PDAL pipeline on lidarfx's grid, and the cell-for-cell
comparison of lidarfx's min_z / max_z / count GeoTIFFs with the bands of PDAL's writers.gdal output.

    pdal_compare.py pipeline LIDARFX_DIR LIDARFX_LOG CELL IN.las OUT.tif THREADS  -> pipeline JSON on stdout
    pdal_compare.py compare  LIDARFX_DIR LIDARFX_LOG CELL IN.las PDAL.tif         -> table of differing cells;
                                                                                     exit 1 if a difference
                                                                                     is not the edge rule's
    pdal_compare.py gdalopts                                                       -> PDAL's creation options
LIDARFX_DIR holds the outputs of `lidarfx rasterize IN.las --cell CELL`, LIDARFX_LOG its standard output.

Same coordinates: lidarfx works in metres (x, y and z of a file in feet are multiplied by the metres per
unit, then binned on a grid of CELL-metre cells); for such a file PDAL gets the same products first
(filters.assign X = X * u, Y = Y * u, Z = Z * u_z), so both bin and write the same doubles. The unit comes
from lidarfx's grid (CELL over its GeoTIFF's pixel size, snapped to the unit it names) and its log line
"read in <unit> (z <unit>), converted to metres".

Same files: PDAL's writers.gdal (GDAL's GTiff driver) gets the creation options lidarfx's COG writer uses,
read from examples/io/geotiff.cpp: the compression and its level (COG's LEVEL is GTiff's ZLEVEL), the
predictor and the tile size. lidarfx also writes overviews, PDAL does not.

Same grid: PDAL gets origin_x = x0, origin_y = y0 - rows * cell, width = cols and height = rows of lidarfx's
grid. Two binning rules remain (docs/conventions.md, "One edge rule"): lidarfx puts a point on an interior
horizontal lattice line into the cell south of it, PDAL into the cell north of it (PDAL counts rows from its
south-west origin); and a point on the grid's east or north border belongs to lidarfx's last column / first
row but lies outside PDAL's grid of the same size (PDAL drops it). The comparison bins the file's points by
both rules in NumPy; a cell whose points differ between the rules is "explained by the edge rule"; any
other differing cell is a real mismatch. Run with Debian's /usr/bin/python3 (python3-gdal, numpy).
"""
import json
import os
import re
import sys

try:  # `gdalopts` needs neither
    import numpy as np
    from osgeo import gdal
except ImportError:
    np = gdal = None

if gdal is not None:
    gdal.UseExceptions()


# Metres per unit, by the names lidarfx prints (examples/io/crs.cpp).
UNITS = {"metre": 1.0, "foot": 0.3048, "US survey foot": 1200.0 / 3937.0, "Clarke's foot": 0.3047972654,
         "fathom": 1.8288, "nautical mile": 1852.0, "kilometre": 1000.0}


def unit_m(name):
    """Metres per unit named `name` (a UNITS key or "unit of <m> m")."""
    if name in UNITS:
        return UNITS[name]
    match = re.fullmatch(r"unit of (\S+) m", name)
    if not match:
        sys.exit(f"unknown unit '{name}' in lidarfx's log")
    return float(match.group(1))


def survey_units(lidarfx_dir, log, cell_m):
    """(metres per x/y unit, metres per z unit) lidarfx applied: the horizontal one from the grid (CELL
    metres over the GeoTIFF's pixel size), snapped to the unit the log names; 1, 1 when nothing was converted."""
    text = open(log, errors="replace").read()
    match = re.search(r"read in (.+?) \(z (.+?)\), converted to metres", text)
    if not match:
        return 1.0, 1.0
    ratio = cell_m / gdal.Open(f"{lidarfx_dir}/min_z.tif").GetGeoTransform()[1]
    u_xy, u_z = unit_m(match.group(1)), unit_m(match.group(2))
    if abs(ratio - u_xy) > 1e-9 * u_xy:
        sys.exit(f"{lidarfx_dir}/min_z.tif: pixel size {cell_m / ratio} is not {cell_m} m in {match.group(1)}")
    return u_xy, u_z


def lidarfx_grid(lidarfx_dir, cell_m, u_xy):
    """lidarfx's grid in metres, (x0, y0, cell, rows, cols), from min_z.tif (in the file's units): corners
    on multiples k * cell_m as snapped_grid computes them."""
    ds = gdal.Open(f"{lidarfx_dir}/min_z.tif")
    x0, cell, _, y0, _, neg_cell = ds.GetGeoTransform()
    if cell != -neg_cell:
        sys.exit(f"{lidarfx_dir}/min_z.tif: cells are not square ({cell} x {-neg_cell})")
    if u_xy == 1.0:
        if cell != cell_m:
            sys.exit(f"{lidarfx_dir}/min_z.tif: pixel size {cell}, not the {cell_m} asked for")
        return x0, y0, cell, ds.RasterYSize, ds.RasterXSize
    x0_m, y0_m = round(x0 * u_xy / cell_m) * cell_m, round(y0 * u_xy / cell_m) * cell_m
    if (x0_m / u_xy, y0_m / u_xy) != (x0, y0):  # to_crs_units (examples/cli/cli_common.cpp) divides
        sys.exit(f"{lidarfx_dir}/min_z.tif: corner ({x0!r}, {y0!r}) is not on the {cell_m} m lattice")
    return x0_m, y0_m, cell_m, ds.RasterYSize, ds.RasterXSize


def pdal_origin_y(grid):
    """PDAL's south-west origin y for lidarfx's grid, as the double PDAL parses from its repr."""
    x0, y0, cell, rows, cols = grid
    return float(repr(y0 - rows * cell))


GEOTIFF_CPP = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples", "io", "geotiff.cpp")


def gdalopts(source=None):
    """GTiff creation options equal to the COG options of lidarfx's GeoTIFF writer (examples/io/geotiff.cpp):
    COMPRESS, its LEVEL (as ZLEVEL), PREDICTOR (FLOATING_POINT = 3) and BLOCKSIZE (as 256 x 256 tiles)."""
    text = open(source or GEOTIFF_CPP, encoding="utf-8").read()
    found = dict(re.findall(r'"(COMPRESS|LEVEL|PREDICTOR|BLOCKSIZE)=([A-Z0-9_]+)"', text))
    missing = {"COMPRESS", "LEVEL", "PREDICTOR", "BLOCKSIZE"} - set(found)
    if missing:
        raise SystemExit(f"pdal_compare.py: {sorted(missing)} not found in {source or GEOTIFF_CPP}")
    predictor = {"FLOATING_POINT": "3", "HORIZONTAL": "2", "NO": "1"}.get(found["PREDICTOR"], found["PREDICTOR"])
    return (f"COMPRESS={found['COMPRESS']},ZLEVEL={found['LEVEL']},PREDICTOR={predictor},TILED=YES,"
            f"BLOCKXSIZE={found['BLOCKSIZE']},BLOCKYSIZE={found['BLOCKSIZE']},BIGTIFF=IF_SAFER")


def pipeline(lidarfx_dir, log, cell_m, las, out_tif, threads):
    """readers.las [-> filters.assign to metres] -> writers.gdal (binmode, min/max/count/mean, float32,
    DEFLATE tiled, the same creation options as lidarfx's examples/io/geotiff.cpp) on lidarfx's grid."""
    u_xy, u_z = survey_units(lidarfx_dir, log, float(cell_m))
    grid = lidarfx_grid(lidarfx_dir, float(cell_m), u_xy)
    x0, y0, cell, rows, cols = grid
    stages = [{"type": "readers.las", "filename": las, "threads": int(threads)}]
    if (u_xy, u_z) != (1.0, 1.0):
        stages.append({"type": "filters.assign",
                       "value": [f"X = X * {u_xy!r}", f"Y = Y * {u_xy!r}", f"Z = Z * {u_z!r}"]})
    stages.append({"type": "writers.gdal", "filename": out_tif, "resolution": cell, "binmode": True,
                   "output_type": "min,max,count,mean", "data_type": "float", "nodata": -9999,
                   "origin_x": x0, "origin_y": pdal_origin_y(grid), "width": cols, "height": rows,
                   "gdalopts": gdalopts()})
    return {"pipeline": stages}


def las_xy(path, u_xy):
    """World x, y in metres (float64: (X * scale + offset) * u_xy as both programs compute them) of every
    point of a LAS file."""
    with open(path, "rb") as f:
        head = f.read(375)
    if head[:4] != b"LASF":
        sys.exit(f"{path}: not a LAS file")
    minor = head[25]
    offset_to_points = int(np.frombuffer(head, "<u4", 1, 96)[0])
    record_length = int(np.frombuffer(head, "<u2", 1, 105)[0])
    count = int(np.frombuffer(head, "<u4", 1, 107)[0])
    if minor >= 4 and count == 0:
        count = int(np.frombuffer(head, "<u8", 1, 247)[0])
    scale = np.frombuffer(head, "<f8", 3, 131)
    offset = np.frombuffer(head, "<f8", 3, 155)
    record = np.dtype({"names": ["X", "Y"], "formats": ["<i4", "<i4"], "offsets": [0, 4],
                       "itemsize": record_length})
    points = np.memmap(path, record, "r", offset_to_points, (count,))
    x = points["X"].astype(np.float64) * scale[0] + offset[0]
    y = points["Y"].astype(np.float64) * scale[1] + offset[1]
    if u_xy != 1.0:
        x *= u_xy
        y *= u_xy
    return x, y


def bin_both_ways(x, y, grid, origin_y):
    """Flat cell index of every point by lidarfx's rule (grid::cell_of) and by PDAL's (floor from the
    south-west origin, half-open grid), -1 where the point is outside; row 0 is the north row in both."""
    x0, y0, cell, rows, cols = grid
    fc, fr = (x - x0) / cell, (y0 - y) / cell
    inside = (fc >= 0) & (fr >= 0) & (fc <= cols) & (fr <= rows)
    c = np.minimum(np.floor(fc), cols - 1).astype(np.int64)
    r = np.minimum(np.floor(fr), rows - 1).astype(np.int64)
    ours = np.where(inside, r * cols + c, -1)
    i = np.floor((x - x0) / cell).astype(np.int64)
    j = np.floor((y - origin_y) / cell).astype(np.int64)
    inside = (i >= 0) & (j >= 0) & (i < cols) & (j < rows)
    theirs = np.where(inside, (rows - 1 - j) * cols + i, -1)
    return ours, theirs


def read_band(path, band=1):
    """Band as float64 with its no-data value as NaN."""
    ds = gdal.Open(path)  # kept alive while its band is read
    b = ds.GetRasterBand(band)
    v = b.ReadAsArray().astype(np.float64)
    nodata = b.GetNoDataValue()
    if nodata is not None:
        v[v == np.float32(nodata)] = np.nan
    return v


def height_unit(lidarfx_dir):
    """(metres per unit of lidarfx's min_z / max_z files, tolerance in metres): lidarfx writes heights in the z unit
    of the CRS its files record (manifest.json: "min_z and max_z in <unit>"); (1, 0) in metres."""
    with open(os.path.join(lidarfx_dir, "manifest.json"), encoding="utf-8") as f:
        units = json.load(f).get("units", "")
    match = re.match(r"min_z and max_z in ([^;]+);", units)
    if not match or unit_m(match.group(1)) == 1.0:
        return 1.0, 0.0
    return unit_m(match.group(1)), 1e-4


def pdal_bands(path):
    """{band description: band number} of PDAL's writers.gdal output (min, max, mean, count)."""
    ds = gdal.Open(path)
    return {ds.GetRasterBand(k).GetDescription(): k for k in range(1, ds.RasterCount + 1)}


def compare(lidarfx_dir, log, cell_m, las, pdal_tif):
    u_xy, u_z = survey_units(lidarfx_dir, log, float(cell_m))
    grid = lidarfx_grid(lidarfx_dir, float(cell_m), u_xy)
    x0, y0, cell, rows, cols = grid
    x, y = las_xy(las, u_xy)
    ours, theirs = bin_both_ways(x, y, grid, pdal_origin_y(grid))
    moved = ours != theirs
    affected = np.zeros(rows * cols, bool)
    affected[ours[moved & (ours >= 0)]] = True
    affected[theirs[moved & (theirs >= 0)]] = True
    affected = affected.reshape(rows, cols)
    print(f"grid {rows} x {cols} cells of {cell:g} at ({x0:.17g}, {y0:.17g}); {len(x)} points"
          + ("" if (u_xy, u_z) == (1.0, 1.0) else f"; x, y times {u_xy!r}, z times {u_z!r} (metres) on both sides"))
    print(f"edge rule: {np.count_nonzero(moved & (theirs >= 0))} points on interior horizontal lattice lines "
          f"(lidarfx: cell south, PDAL: cell north), {np.count_nonzero(theirs < 0)} on the east/north border "
          f"(outside PDAL's grid); {np.count_nonzero(affected)} cells touched")

    bands = pdal_bands(pdal_tif)
    ds = gdal.Open(pdal_tif)
    if (ds.RasterYSize, ds.RasterXSize) != (rows, cols):
        sys.exit(f"{pdal_tif}: PDAL's grid is not {rows} x {cols}")
    print(f"{'raster':8s} {'cells differing':>15s} {'by edge rule':>13s} {'unexplained':>12s} "
          f"{'max |diff| unexpl.':>19s} {'max |diff| all':>15s} {'data one side':>14s}")
    unexplained_total = 0
    z_file, z_tolerance = height_unit(lidarfx_dir)
    if z_file != 1.0:
        print(f"lidarfx writes min_z and max_z in the file's unit: times {z_file!r} to metres, equal within "
              f"{z_tolerance:g} m (float32 rounding on both sides)")
    for ours_name, theirs_name in (("min_z", "min"), ("max_z", "max"), ("count", "count")):
        a = read_band(f"{lidarfx_dir}/{ours_name}.tif")
        b = read_band(pdal_tif, bands[theirs_name])
        tolerance = 0.0
        if theirs_name == "count":  # an empty cell: 0 or no data, depending on the writer
            a, b = np.nan_to_num(a), np.nan_to_num(b)
        elif z_file != 1.0:
            a, tolerance = a * z_file, z_tolerance
        both = ~np.isnan(a) & ~np.isnan(b)
        differ = ~((np.abs(a - b) <= tolerance) | (np.isnan(a) & np.isnan(b)))
        unexplained = differ & ~affected
        gap = np.abs(a - b)
        largest_unexplained = np.max(gap[both & unexplained], initial=0.0)
        largest = np.max(gap[both & differ], initial=0.0)
        one_side = np.count_nonzero(np.isnan(a) != np.isnan(b))
        unexplained_total += np.count_nonzero(unexplained)
        print(f"{ours_name:8s} {np.count_nonzero(differ):15d} {np.count_nonzero(differ & affected):13d} "
              f"{np.count_nonzero(unexplained):12d} {largest_unexplained:19.6g} {largest:15.6g} {one_side:14d}")
        if theirs_name == "count":
            # Each side against NumPy binning by its own rule: the rules are what the two programs do.
            for name, index, counts in (("lidarfx", ours, a), ("PDAL", theirs, b)):
                own = np.bincount(index[index >= 0], minlength=rows * cols).reshape(rows, cols)
                print(f"         {name} count vs NumPy binning by {name}'s rule: "
                      f"{np.count_nonzero(own != counts)} cells differ")
    print("rasters equal up to the edge rule" if unexplained_total == 0
          else f"MISMATCH: {unexplained_total} differing cells the edge rule does not explain")
    return 0 if unexplained_total == 0 else 1


def main(argv):
    if len(argv) == 8 and argv[1] == "pipeline":
        print(json.dumps(pipeline(*argv[2:]), indent=2))
        return 0
    if len(argv) == 7 and argv[1] == "compare":
        return compare(*argv[2:])
    if len(argv) == 2 and argv[1] == "gdalopts":
        print(gdalopts())
        return 0
    sys.exit(__doc__)


if __name__ == "__main__":
    sys.exit(main(sys.argv))
