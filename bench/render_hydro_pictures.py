#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""The pictures and the QA table of docs/hydro-flattening.md, from the folders `lidarfx hydroflatten` wrote.

  table RUN [FLAG_RUN]
      prints the markdown QA table of RUN (hydro_bodies.csv and hydro_qa.csv, one row per body, its checks and
      pass/fail); FLAG_RUN, the same run with --shoreline flag, adds the shore cells that RUN lifted and the
      deepest of them.
  pictures BEFORE AFTER IMG_DIR [--title TEXT] [--note X,Y,TEXT ...]
      writes IMG_DIR/hydro-dem-before-after.png (hillshaded DEMs before and after, one colour scale) and
      IMG_DIR/hydro-breaklines.png (water_bodies outlined and river_centrelines over a hillshade of the
      flattened DEM, coloured by their Z). AFTER is a hydroflatten folder; BEFORE is one whose minimum sizes
      flatten nothing, so its dem_hydroflattened.tif is the bare-earth DEM before flattening (lowest return
      per cell, holes filled by inverse distance weighting), made by the same code. --note writes TEXT at X,Y
      (the survey's CRS) on both pictures, e.g. to point at water the method missed.

Needs numpy, matplotlib, Pillow and GDAL's Python bindings (Debian: python3-matplotlib python3-pil python3-gdal).
Usage: /usr/bin/python3 bench/render_hydro_pictures.py pictures BEFORE AFTER docs/img   (bench/hydro_real_survey.sh
runs it)"""
import argparse
import csv
import io
import json
import pathlib
import re

import numpy as np


def read_dem(folder):
    """The DEM of a hydroflatten folder as float64 (NaN for no data), its geotransform and its EPSG code."""
    from osgeo import gdal, osr
    gdal.UseExceptions()
    ds = gdal.Open(str(pathlib.Path(folder) / "dem_hydroflattened.tif"))
    band = ds.GetRasterBand(1)
    z = band.ReadAsArray().astype(np.float64)
    nodata = band.GetNoDataValue()
    if nodata is not None:
        z[z == nodata] = np.nan
    srs = osr.SpatialReference(wkt=ds.GetProjection())
    code = srs.GetAuthorityCode(None) if srs.AutoIdentifyEPSG() == 0 else None
    if code is None:
        matches = [m for m, confidence in srs.FindMatches() if confidence >= 70]
        code = matches[0].GetAuthorityCode(None) if matches else None
    return z, ds.GetGeoTransform(), code


def read_layer(folder, name):
    """The features of one layer of breaklines.gpkg: (properties, list of parts, each an (n, 3) array)."""
    from osgeo import ogr
    ogr.UseExceptions()
    ds = ogr.Open(str(pathlib.Path(folder) / "breaklines.gpkg"))
    layer = ds.GetLayerByName(name)
    out = []
    if layer is None:
        return out
    for f in layer:
        g = f.GetGeometryRef()
        parts = []

        def walk(geom):
            if geom.GetGeometryCount() == 0:
                parts.append(np.array(geom.GetPoints(), dtype=np.float64).reshape(-1, 3))
            for i in range(geom.GetGeometryCount()):
                walk(geom.GetGeometryRef(i))
        walk(g)
        out.append(({k: f.GetField(k) for k in f.keys()}, parts))
    return out


def run_options(folder):
    """The minimum sizes a hydroflatten folder was made with, read from its manifest's command line."""
    command = json.loads((pathlib.Path(folder) / "manifest.json").read_text())["command"]
    value = {"min-lake-area": "8093.71", "min-river-width": "30.48", "min-island-area": "4046.86", "cell": "2"}
    for name in value:
        m = re.search(r"--" + name + r"[ =](\S+)", command)
        if m:
            value[name] = m.group(1)
    return value, command


def hillshade(z, cell, azimuth=315.0, altitude=45.0, exaggeration=1.0):
    """Hillshade in [0, 1] of z (NaN kept NaN), the sun at azimuth/altitude degrees."""
    filled = np.where(np.isnan(z), np.nanmean(z), z)
    gy, gx = np.gradient(filled * exaggeration, cell)  # gy: along rows (southwards)
    slope = np.arctan(np.hypot(gx, gy))
    aspect = np.arctan2(-gx, gy)  # downslope direction, clockwise from north
    az, alt = np.radians(azimuth), np.radians(altitude)
    shade = np.sin(alt) * np.cos(slope) + np.cos(alt) * np.sin(slope) * np.cos(az - aspect)
    return np.where(np.isnan(z), np.nan, np.clip(shade, 0, 1))


def tinted(z, shade, cmap, norm):
    """z coloured by cmap/norm and darkened by the hillshade (soft-light style), RGBA, transparent where NaN."""
    rgba = cmap(norm(np.where(np.isnan(z), norm.vmin, z)))
    light = 0.6 + 0.5 * np.nan_to_num(shade, nan=1.0)
    rgba[..., :3] = np.clip(rgba[..., :3] * light[..., None], 0, 1)
    rgba[..., 3] = np.where(np.isnan(z), 0, 1)
    return rgba


def scale_bar(ax, extent, length_m=None):
    """A scale bar in the lower left corner of a map in metres."""
    width = extent[1] - extent[0]
    if length_m is None:
        length_m = next(v for v in (1000, 500, 200, 100, 50, 20, 10) if v <= width / 3)
    x0 = extent[0] + 0.04 * width
    y0 = extent[2] + 0.04 * (extent[3] - extent[2])
    ax.plot([x0, x0 + length_m], [y0, y0], color="black", lw=4, solid_capstyle="butt")
    ax.plot([x0, x0 + length_m], [y0, y0], color="white", lw=2, solid_capstyle="butt")
    ax.text(x0 + length_m / 2, y0 + 0.015 * width, f"{length_m:g} m", ha="center", va="bottom", fontsize=9,
            path_effects=halo())


def halo():
    import matplotlib.patheffects as pe
    return [pe.withStroke(linewidth=3, foreground="white")]


def outlines(ax, bodies, **style):
    for _, parts in bodies:
        for ring in parts:
            ax.plot(ring[:, 0], ring[:, 1], **style)


def body_masks(bodies, z_shape, gt):
    """Raster mask (True on the flattened water) from the water_bodies polygons, on the DEM's grid."""
    from matplotlib.path import Path
    rows, cols = z_shape
    xs = gt[0] + (np.arange(cols) + 0.5) * gt[1]
    ys = gt[3] + (np.arange(rows) + 0.5) * gt[5]
    gx, gy = np.meshgrid(xs, ys)
    points = np.column_stack([gx.ravel(), gy.ravel()])
    mask = np.zeros(rows * cols, dtype=bool)
    for _, parts in bodies:
        if not parts:
            continue
        inside = Path(parts[0][:, :2]).contains_points(points)
        for hole in parts[1:]:
            inside &= ~Path(hole[:, :2]).contains_points(points)
        mask |= inside
    return mask.reshape(rows, cols)


def save_small(fig, path, limit_bytes=300_000):
    """Saves fig as an optimized PNG; a palette PNG (256 colours) when the full-colour one is over the limit."""
    from PIL import Image
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png")
    image = Image.open(buffer).convert("RGB")
    image.save(path, optimize=True)
    if path.stat().st_size > limit_bytes:
        image.quantize(colors=256, method=Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE).save(path, optimize=True)
    return path.stat().st_size


def label_place(ring, centrelines, clearance):
    """A point inside ring for a body's label: its mean vertex, or the nearest point of a grid inside the ring
    that lies at least `clearance` (metres) from every centreline vertex."""
    from matplotlib.path import Path
    cx, cy = ring[:, 0].mean(), ring[:, 1].mean()
    if not centrelines:
        return cx, cy
    vertices = np.concatenate(centrelines)
    xs = np.linspace(ring[:, 0].min(), ring[:, 0].max(), 40)
    ys = np.linspace(ring[:, 1].min(), ring[:, 1].max(), 40)
    gx, gy = np.meshgrid(xs, ys)
    candidates = np.column_stack([gx.ravel(), gy.ravel()])
    candidates = candidates[Path(ring[:, :2]).contains_points(candidates)]
    if len(candidates) == 0:
        return cx, cy
    gap = np.min(np.hypot(candidates[:, None, 0] - vertices[None, :, 0], candidates[:, None, 1] - vertices[None, :, 1]),
                 axis=1)
    good = candidates[gap >= clearance]
    if len(good) == 0:
        good = candidates[gap == gap.max()]
    best = np.argmin(np.hypot(good[:, 0] - cx, good[:, 1] - cy))
    return good[best, 0], good[best, 1]


def parse_notes(notes):
    """--note X,Y,TEXT values as (x, y, text)."""
    out = []
    for n in notes:
        x, y, text = n.split(",", 2)
        out.append((float(x), float(y), text.replace("\\n", "\n")))
    return out


def draw_notes(ax, notes):
    for x, y, text in notes:
        ax.text(x, y, text, ha="center", va="center", fontsize=8.5, style="italic", color="#7a1010",
                path_effects=halo(), zorder=6)


def pictures(before_dir, after_dir, img_dir, title, notes=()):
    import textwrap

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection
    from matplotlib.colors import Normalize

    before, gt, epsg = read_dem(before_dir)
    after, gt_after, _ = read_dem(after_dir)
    if before.shape != after.shape or not np.allclose(gt, gt_after):
        raise SystemExit("render_hydro_pictures: BEFORE and AFTER are not on the same grid (same survey, --cell?)")
    cell = gt[1]
    rows, cols = before.shape
    extent = [gt[0], gt[0] + cols * cell, gt[3] - rows * cell, gt[3]]
    bodies = read_layer(after_dir, "water_bodies")
    lines = read_layer(after_dir, "river_centrelines")
    options, _ = run_options(after_dir)
    if not epsg:  # GDAL did not name the CRS: the manifest's units note does
        units = json.loads((pathlib.Path(after_dir) / "manifest.json").read_text()).get("units", "")
        m = re.search(r"EPSG:(\d+)", units)
        epsg = m.group(1) if m else None
    water = body_masks(bodies, before.shape, gt)
    diff = after - before
    lifted = (~water) & (diff > 1e-6)
    lowered = water & (diff < -1e-6)
    crs = f"EPSG:{epsg}" if epsg else "the survey's CRS"
    sizes = (f"minimum lake {float(options['min-lake-area']):g} m², river width "
             f"{float(options['min-river-width']):g} m, island {float(options['min-island-area']):g} m²")
    notes = parse_notes(notes)
    img_dir = pathlib.Path(img_dir)
    img_dir.mkdir(parents=True, exist_ok=True)
    plt.rcParams.update({"font.size": 10, "axes.titlesize": 11})

    def lifted_cells(ax, size):
        if lifted.any():
            r, c = np.nonzero(lifted)
            ax.scatter(gt[0] + (c + 0.5) * cell, gt[3] - (r + 0.5) * cell, s=size, marker="s", facecolor="none",
                       edgecolor="#d62728", lw=1.0, label=f"shore cells lifted ({lifted.sum()})", zorder=5)

    # 1. Before and after, one colour scale.
    norm = Normalize(np.nanmin([np.nanmin(before), np.nanmin(after)]),
                     np.nanmax([np.nanmax(before), np.nanmax(after)]))
    cmap = plt.get_cmap("gist_earth")
    fig = plt.figure(figsize=(12, 6.1), dpi=100)
    axes = [fig.add_axes([0.01, 0.12, 0.44, 0.74]), fig.add_axes([0.46, 0.12, 0.44, 0.74])]
    bar_ax = fig.add_axes([0.915, 0.18, 0.015, 0.6])
    count = len({props["id"] for props, _ in bodies})
    panels = [(before, "before: lowest return per cell, empty cells filled by IDW"),
              (after, f"after: lidarfx hydroflatten, {count} flattened water bod{'y' if count == 1 else 'ies'}")]
    for ax, (z, label) in zip(axes, panels):
        ax.imshow(tinted(z, hillshade(z, cell), cmap, norm), extent=extent, interpolation="nearest")
        outlines(ax, bodies, color="#0b3d91", lw=0.9, ls=(0, (3, 2)))
        ax.set_title(label)
        ax.set_xticks([]), ax.set_yticks([])
        scale_bar(ax, extent)
        draw_notes(ax, notes)
    lifted_cells(axes[1], 10)
    if lifted.any():
        axes[1].legend(loc="upper right", fontsize=8, framealpha=0.85)
    bar = fig.colorbar(plt.cm.ScalarMappable(norm=norm, cmap=cmap), cax=bar_ax)
    bar.set_label("ground height (m)")
    fig.suptitle(f"{title}: bare-earth DEM before and after hydro-flattening", fontsize=13, y=0.975)
    change = ""
    if lowered.any():
        change = (f"On the water the DEM changes by {np.nanmin(diff[water]):+.2f} to {np.nanmax(diff[water]):+.2f} m "
                  f"(median {np.nanmedian(diff[water]):+.2f} m); ")
    if lifted.any():
        change += f"{lifted.sum()} shore cells lifted by at most {diff[lifted].max():.2f} m."
    fig.text(0.01, 0.02, f"{cell:g} m cells, {crs}, north up; {sizes}. Hillshade from the north-west (315°, 45°); "
             f"dashed: the flattened water.\n{change}", fontsize=8.5, va="bottom")
    size1 = save_small(fig, img_dir / "hydro-dem-before-after.png")
    plt.close(fig)

    # 2. Breaklines over the flattened DEM.
    fig = plt.figure(figsize=(12, 9.4), dpi=100)
    ax = fig.add_axes([0.02, 0.1, 0.70, 0.82])
    shade = hillshade(after, cell)
    ax.imshow(np.where(np.isnan(shade), np.nan, 0.5 + 0.4 * shade), cmap="gray", vmin=0, vmax=1, extent=extent,
              interpolation="nearest")
    zs = np.concatenate([p[:, 2] for _, parts in bodies + lines for p in parts] or [np.zeros(1)])
    lo, hi = float(zs.min()), float(zs.max())
    if hi - lo < 0.01:
        lo, hi = lo - 0.05, hi + 0.05
    znorm = Normalize(lo, hi)
    zmap = plt.get_cmap("viridis")
    for _, parts in bodies:
        for ring in parts:
            segs = np.stack([ring[:-1, :2], ring[1:, :2]], axis=1)
            ax.add_collection(LineCollection(segs, colors=zmap(znorm((ring[:-1, 2] + ring[1:, 2]) / 2)),
                                             linewidths=2.4))
    # Centrelines: coloured by their fall below their own top section, so that centimetres of fall show.
    fall_max = max([props["level_max_m"] - props["level_min_m"] for props, _ in lines] + [0.01])
    fnorm = Normalize(0, fall_max)
    fmap = plt.get_cmap("autumn_r")
    for props, parts in lines:
        for line in parts:
            segs = np.stack([line[:-1, :2], line[1:, :2]], axis=1)
            fall = props["level_max_m"] - (line[:-1, 2] + line[1:, 2]) / 2
            ax.add_collection(LineCollection(segs, colors="black", linewidths=5.0, zorder=3))
            ax.add_collection(LineCollection(segs, colors=fmap(fnorm(fall)), linewidths=3.2, zorder=3))
            for k in (len(line) // 3, 2 * len(line) // 3):  # two arrowheads pointing downstream
                k = min(max(k, 1), len(line) - 1)
                d = line[min(k + 3, len(line) - 1), :2] - line[max(k - 3, 0), :2]  # smooth over the sections' wobble
                d = d / max(np.hypot(*d), 1e-9) * 0.5 * cell
                ax.annotate("", xy=line[k, :2] + d, xytext=line[k, :2] - d, zorder=4,
                            arrowprops={"arrowstyle": "-|>,head_length=0.8,head_width=0.45", "facecolor": "white",
                                        "edgecolor": "black", "lw": 1.0, "shrinkA": 0, "shrinkB": 0})
            for end, va in ((line[0], "bottom"), (line[-1], "top")):
                ax.text(end[0], end[1], f"{end[2]:.2f}", fontsize=8.5, path_effects=halo(), va=va, ha="center",
                        zorder=6)
    labelled = set()
    for props, parts in bodies:
        if props["id"] in labelled or not parts:
            continue
        labelled.add(props["id"])
        ring = max((ps[0] for pr, ps in bodies if pr["id"] == props["id"] and ps), key=len)
        cx, cy = label_place(ring, [ln[:, :2] for pr, ls in lines if pr["id"] == props["id"] for ln in ls],
                             0.07 * (extent[3] - extent[2]))
        if props["type"] == "lake":
            text = f"#{props['id']} lake\n{props['level_min_m']:.2f} m"
        else:
            text = f"#{props['id']} river\n{props['level_max_m']:.2f} → {props['level_min_m']:.2f} m"
        ax.text(cx, cy, text, ha="center", va="center", fontsize=9.5, weight="bold", path_effects=halo(), zorder=6)
    lifted_cells(ax, 16)
    draw_notes(ax, notes)
    ax.set_xlim(extent[:2]), ax.set_ylim(extent[2:])
    ax.set_xticks([]), ax.set_yticks([])
    scale_bar(ax, extent)
    ax.set_title(f"{title}: breaklines over the hydro-flattened DEM", fontsize=13)
    cax = fig.add_axes([0.76, 0.58, 0.022, 0.32])
    cb = fig.colorbar(plt.cm.ScalarMappable(norm=znorm, cmap=zmap), cax=cax)
    cb.set_label("water_bodies: Z of the outline (m)")
    cb.ax.ticklabel_format(useOffset=False)
    if lines:
        cax2 = fig.add_axes([0.76, 0.24, 0.022, 0.28])
        cb2 = fig.colorbar(plt.cm.ScalarMappable(norm=fnorm, cmap=fmap), cax=cax2)
        cb2.set_label("river_centrelines: fall below the\nriver's top section (m)")
    legend = ["Outlines: water_bodies (3D polygons),", "centrelines: river_centrelines (3D lines),",
              "from breaklines.gpkg.", "Arrowheads point downstream; the", "numbers at a centreline's ends are",
              "its levels (m)."]
    if lifted.any():
        legend += ["Red squares: shore cells lifted", f"to the water ({lifted.sum()})."]
    fig.text(0.745, 0.195, "\n".join(legend), fontsize=8.5, va="top")
    fig.text(0.02, 0.03, "\n".join(textwrap.wrap(
        f"{cell:g} m cells, {crs}, north up; {sizes}. Grey: hillshade of dem_hydroflattened.tif from the "
        f"north-west (315°, 45°).", 120)), fontsize=8.5)
    size2 = save_small(fig, img_dir / "hydro-breaklines.png")
    plt.close(fig)
    print(f"wrote {img_dir / 'hydro-dem-before-after.png'} ({size1 // 1024} KB), "
          f"{img_dir / 'hydro-breaklines.png'} ({size2 // 1024} KB)")


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def qa_checks(path):
    """hydro_qa.csv as {id: {check: {value, limit, unit, pass, worst_x_crs, worst_y_crs}}}. Reads both layouts:
    one row per check (columns check, value, limit, unit, pass) and one row per body (flatness_m, ...)."""
    rows = read_csv(path)
    out = {}
    if rows and "check" in rows[0]:
        for r in rows:
            out.setdefault(r["id"], {})[r["check"]] = r
        return out
    for r in rows:
        def get(name):
            return r.get(name) or ""

        river = r.get("type") == "river"
        worst = get("worst_check")
        checks = {
            "flatness": (get("flatness_m"), get("flatness_limit_m"), "m", get("flatness_pass")),
            "monotonic_fall": (get("uphill_sections"), "0", "sections", get("monotonic_pass")),
            "shoreline": (get("shore_cells_below"), "0", "cells", get("shoreline_pass")),
            "minimum_size": ((get("width_m"), get("min_width_m"), "m") if river else
                             (get("area_m2"), get("min_area_m2"), "m2")) + (get("size_pass"),),
        }
        body = out.setdefault(r["id"], {})
        for name, (value, limit, unit, passed) in checks.items():
            if passed == "" or (name == "monotonic_fall" and not river):
                continue
            here = name == worst
            body[name] = {"value": value, "limit": limit, "unit": unit, "pass": passed,
                          "worst_x_crs": get("worst_x_crs") if here else "",
                          "worst_y_crs": get("worst_y_crs") if here else ""}
            if name == "shoreline" and get("shore_worst_m"):
                body[name]["worst_m"] = get("shore_worst_m")
    return out


def table(run_dir, flag_dir=None):
    """Prints the QA of one hydroflatten folder as a markdown table."""
    run_dir = pathlib.Path(run_dir)
    bodies = read_csv(run_dir / "hydro_bodies.csv")
    qa = qa_checks(run_dir / "hydro_qa.csv")
    flag = {i: c["shoreline"] for i, c in qa_checks(pathlib.Path(flag_dir) / "hydro_qa.csv").items()
            if "shoreline" in c} if flag_dir else {}
    checks = ["flatness", "monotonic_fall", "shoreline", "minimum_size"]
    head = ["id", "type", "area m²", "level m", "width m", "flatness m", "monotonic fall", "shoreline cells",
            "minimum size", "worst offender"]
    if flag:
        head.insert(-1, "shore cells lifted (the deepest)")
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    for b in bodies:
        mine = qa.get(b["id"], {})
        if b["flattened"] != "1":
            level = "not flattened"
        elif b["type"] == "lake":
            level = b["level_m"]
        else:
            level = f"{b['level_max_m']} → {b['level_min_m']} ({b['sections']} sections, {b['weirs']} weirs)"
        row = [b["id"], b["type"], b["area_m2"], level, b["width_m"]]
        for name in checks:
            q = mine.get(name)
            if q is None:
                row.append("–")
                continue
            op = "≤" if name != "minimum_size" else "≥"
            unit = f" {q['unit']}" if name == "minimum_size" else ""
            row.append(f"{q['value']}{unit} {op} {q['limit']}{unit}: {'pass' if q['pass'] == '1' else '**FAIL**'}")
        if flag:
            f = flag.get(b["id"])
            if f and f["value"] != "0":
                depth = f" {float(f['worst_m']):.2f} m below the water" if f.get("worst_m") else ""
                where = f" at {f['worst_x_crs']}, {f['worst_y_crs']}" if f["worst_x_crs"] else ""
                row.append(f"{f['value']} (deepest{depth}{where})" if depth or where else f["value"])
            else:
                row.append("0" if f else "–")
        worst = [f"{n}: ({q['worst_x_crs']}, {q['worst_y_crs']})" for n, q in mine.items()
                 if q["pass"] != "1" and q["worst_x_crs"]]
        failed = [n for n, q in mine.items() if q["pass"] != "1"]
        row.append("; ".join(worst) or (", ".join(failed) + " failed" if failed else "none"))
        print("| " + " | ".join(row) + " |")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = parser.add_subparsers(dest="what", required=True)
    t = sub.add_parser("table", help="print the markdown QA table of a hydroflatten folder")
    t.add_argument("run")
    t.add_argument("flag_run", nargs="?")
    p = sub.add_parser("pictures", help="write hydro-dem-before-after.png and hydro-breaklines.png")
    p.add_argument("before")
    p.add_argument("after")
    p.add_argument("img_dir")
    p.add_argument("--title", default="")
    p.add_argument("--note", action="append", default=[], metavar="X,Y,TEXT")
    a = parser.parse_args()
    if a.what == "table":
        table(a.run, a.flag_run)
    else:
        pictures(a.before, a.after, a.img_dir, a.title or pathlib.Path(a.after).name, a.note)


if __name__ == "__main__":
    main()
