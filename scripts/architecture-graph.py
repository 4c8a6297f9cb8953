#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Draws docs/img/architecture.svg: the folders of include/lidarfx/ by layer and which folder includes which
(read from the #include lines), plus the planned modules (dashed). Needs graphviz's `dot`.
Usage: python3 scripts/architecture-graph.py   (from the repository root)"""
import pathlib
import re
import subprocess

root = pathlib.Path("include/lidarfx")
layers = {0: "core", 1: "kernels", 2: "pipelines", 3: "tiling"}
planned = {  # folder -> (layer, what it will hold, folders it will include)
    "kernels/solar": (1, "sun_position, raylines_shadow,\nhorizon_map, sky_view_factor", ["core"]),
    "pipelines/solar": (2, "irradiance maps, lidarfx solar", ["kernels/solar", "kernels/filter"]),
    "pipelines/buildings": (2, "extract_buildings, patches,\nfacades", ["kernels/solar", "kernels/label", "kernels/interpolate", "kernels/filter"]),
    "pipelines/pv": (2, "azimuth_mode_select,\nroof_suitability", ["kernels/filter", "kernels/label", "kernels/stats", "kernels/vector"]),
    "tiling": (3, "tile_plan, halos, stitching", ["pipelines/water", "kernels/label"]),
}


def layer_of(folder):
    if folder == "core":
        return 0
    if folder == "adapters" or folder.startswith("kernels/"):
        return 1
    if folder.startswith("pipelines/"):
        return 2
    return 3


folders, edges = {}, set()
for header in sorted(root.rglob("*.hpp")):
    rel = header.relative_to(root)
    if rel.name == "lidarfx.hpp":
        continue
    folder = str(rel.parent)
    folders.setdefault(folder, []).append(rel.stem)
    for line in header.read_text().splitlines():
        m = re.match(r'\s*#\s*include\s*[<"]lidarfx/(.+)/[^/]+\.hpp[>"]', line)
        if m and m.group(1) != folder:
            edges.add((folder, m.group(1)))

out = ["digraph lidarfx {", '  rankdir=BT; node [shape=box, fontname="Helvetica", fontsize=10];',
       '  edge [color="#555555"]; newrank=true;']
for layer, name in layers.items():
    out.append(f'  subgraph layer_{name} {{ rank=same; "layer {layer}\\n{name}" [shape=plaintext, fontsize=14];')
    for folder, stems in sorted(folders.items()):
        if layer_of(folder) == layer:
            label = folder + "\\n" + "\\n".join(stems)
            out.append(f'    "{folder}" [label="{label}"];')
    for folder, (pl, what, _) in planned.items():
        if pl == layer and folder not in folders:
            label = folder + " (planned)\\n" + what.replace("\n", "\\n")
            out.append(f'    "{folder}" [label="{label}", style=dashed];')
    out.append("  }")
for a, b in sorted(edges):
    if b != "core":  # everything includes core; drawn once below to keep the picture readable
        out.append(f'  "{b}" -> "{a}" [dir=back];')
out.append('  "core" -> "kernels/filter" [dir=back, style=bold, label=" every folder"];')
for low, high in ((0, 1), (1, 2), (2, 3)):  # keeps the layer captions stacked
    out.append(f'  "layer {low}\\n{layers[low]}" -> "layer {high}\\n{layers[high]}" [style=invis];')
for folder, (_, _, uses) in planned.items():
    if folder not in folders:
        for b in uses:
            if b != "core":
                out.append(f'  "{b}" -> "{folder}" [dir=back, style=dashed];')
out.append("}")
dot = "\n".join(out) + "\n"
svg = subprocess.run(["dot", "-Tsvg"], input=dot.encode(), capture_output=True, check=True).stdout
pathlib.Path("docs/img/architecture.svg").write_bytes(svg)
png = subprocess.run(["dot", "-Tpng", "-Gdpi=80"], input=dot.encode(), capture_output=True, check=True).stdout
pathlib.Path("docs/img/architecture.png").write_bytes(png)
print("wrote docs/img/architecture.svg")
