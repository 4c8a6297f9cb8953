#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Water and sun from a LiDAR survey, step by step, as one would in a notebook.

Usage: /usr/bin/python3 examples/python/water_and_sun.py SURVEY.las [MORE.las ...] [--tmy3 FILE]
       [--lat DEG --lon DEG] [--cell M] [--out DIR]

Reads the survey (LAS/LAZ, coordinates in metres), bins it into 2 m rasters, maps its waterbodies, fills the
water with its level to make a surface model, computes a year of solar irradiation on it (the TMY3 file's
weather, or a clear-sky year at --lat/--lon, or at the survey's own place when GDAL's Python bindings can
read its CRS), and saves water.png and irradiation.png (matplotlib, no display needed).
"""
import argparse
import os

import matplotlib

matplotlib.use("Agg")  # files only: no display needed
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import lidarfx  # noqa: E402

# %% Arguments
parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("surveys", nargs="+", help="LAS or LAZ files of one survey, coordinates in metres")
parser.add_argument("--tmy3", help="a TMY3 weather year (default: a clear-sky year)")
parser.add_argument("--lat", type=float, help="latitude of the survey, degrees north")
parser.add_argument("--lon", type=float, help="longitude of the survey, degrees east")
parser.add_argument("--cell", type=float, default=2.0, help="cell size in metres (default 2)")
parser.add_argument("--out", default=".", help="folder for the pictures (default: here)")
args = parser.parse_args()

# %% Read the survey: every point of every file, as NumPy arrays.
surveys = [lidarfx.read_survey(path) for path in args.surveys]
points = {k: np.concatenate([getattr(s, k) for s in surveys])
          for k in ("x", "y", "z", "intensity", "return_number", "number_of_returns")}
print(f"{len(points['x']):,} points from {len(surveys)} file(s), EPSG {surveys[0].epsg or 'unknown'}")

# %% Rasters: lowest and highest return, mean intensity, count and dropouts per cell.
rasters = lidarfx.rasterize(points["x"], points["y"], points["z"], points["intensity"],
                            points["return_number"], points["number_of_returns"], args.cell, threads=0)
g = rasters.grid
print(f"grid {g.rows} x {g.cols} cells of {g.cell_m} m")

# %% Waterbodies: the map, each body's area and level.
water = lidarfx.extract_waterbodies(rasters, threads=0)
for issue in water.issues:
    print(f"{issue.severity}: {issue.message}")
for body in water.bodies[:10]:
    print(f"waterbody {body.label}: {body.area_m2:,.0f} m², level {body.water_level_m:.2f} m")

# %% A surface model for the sun: the highest return, water at its body's level, gaps left as no data.
dsm = rasters.max_z.copy()
for body in water.bodies:
    dsm[water.labels == body.label] = body.water_level_m

# %% A year of weather at the survey's place.
if args.tmy3:
    weather = lidarfx.read_tmy3(args.tmy3)
    lat, lon = (args.lat or weather.latitude_deg), (args.lon or weather.longitude_deg)
else:
    lat, lon = args.lat, args.lon
    if lat is None or lon is None:
        from osgeo import osr  # python3-gdal: the survey's CRS to latitude and longitude
        source = osr.SpatialReference()
        if surveys[0].wkt:
            source.ImportFromWkt(surveys[0].wkt)
        else:
            source.ImportFromEPSG(surveys[0].epsg)
        target = osr.SpatialReference()
        target.ImportFromEPSG(4326)
        target.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
        source.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
        lon, lat, _ = osr.CoordinateTransformation(source, target).TransformPoint(*g.cell_center(g.rows / 2, g.cols / 2))
    weather = lidarfx.clear_sky_year(2025, lat, lon)
print(f"site {lat:.4f} N, {lon:.4f} E")

# %% Annual irradiation, kWh/m², with progress every 10 %.
shown = []


def show_progress(fraction):
    tenth = int(fraction * 10)
    if not shown or tenth > shown[-1]:
        shown.append(tenth)
        print(f"irradiation {10 * tenth} %", flush=True)


maps = lidarfx.irradiance_maps(dsm, g.cell_m, weather, latitude_deg=lat, longitude_deg=lon, threads=0,
                               progress=show_progress)
print(f"open ground receives {maps.ghi_kwh_m2:,.0f} kWh/m² a year; cells: median "
      f"{np.nanmedian(maps.annual_kwh_m2):,.0f}, 5th percentile {np.nanpercentile(maps.annual_kwh_m2, 5):,.0f}")

# %% Pictures.
os.makedirs(args.out, exist_ok=True)
extent = (g.x0, g.x0 + g.cols * g.cell_m, g.y0 - g.rows * g.cell_m, g.y0)
fig, ax = plt.subplots(figsize=(7, 6))
ax.imshow(np.where(np.isnan(rasters.min_z), np.nan, rasters.min_z), cmap="gist_earth", extent=extent)
ax.imshow(np.ma.masked_where(~water.water, water.water), cmap="winter", alpha=0.8, extent=extent)
ax.set_title(f"Waterbodies ({len(water.bodies)}) over the lowest return")
fig.savefig(os.path.join(args.out, "water.png"), dpi=100, bbox_inches="tight")
fig, ax = plt.subplots(figsize=(7, 6))
image = ax.imshow(maps.annual_kwh_m2, cmap="inferno", extent=extent)
fig.colorbar(image, ax=ax, label="kWh/m² a year")
ax.set_title("Annual solar irradiation")
fig.savefig(os.path.join(args.out, "irradiation.png"), dpi=100, bbox_inches="tight")
print(f"pictures: {os.path.join(args.out, 'water.png')}, {os.path.join(args.out, 'irradiation.png')}")
