#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Draws docs/img/architecture.svg: the folders of include/lidarfx/ by layer and which folder includes which
(read from the #include lines). An area's detail/ folder is drawn as part of its area. Needs graphviz's `dot`.
Usage: python3 scripts/architecture-graph.py   (from the repository root)"""
import pathlib
import re
import subprocess

root = pathlib.Path("include/lidarfx")
layers = {0: "core", 1: "kernels", 2: "pipelines", 3: "tiling"}


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
    folder = str(rel.parent).removesuffix("/detail")
    if not str(rel.parent).endswith("/detail"):
        folders.setdefault(folder, []).append(rel.stem)
    for line in header.read_text().splitlines():
        m = re.match(r'\s*#\s*include\s*[<"]lidarfx/(.+)/[^/]+\.hpp[>"]', line)
        if m and m.group(1).removesuffix("/detail") != folder:
            edges.add((folder, m.group(1).removesuffix("/detail")))

out = ["digraph lidarfx {", '  rankdir=BT; node [shape=box, fontname="Helvetica", fontsize=10];',
       '  edge [color="#555555"]; newrank=true;']
for layer, name in layers.items():
    out.append(f'  subgraph layer_{name} {{ rank=same; "layer {layer}\\n{name}" [shape=plaintext, fontsize=14];')
    for folder, stems in sorted(folders.items()):
        if layer_of(folder) == layer:
            label = folder + "\\n" + "\\n".join(stems)
            out.append(f'    "{folder}" [label="{label}"];')
    out.append("  }")
for a, b in sorted(edges):
    if b != "core":  # everything includes core; drawn once below to keep the picture readable
        out.append(f'  "{b}" -> "{a}" [dir=back];')
out.append('  "core" -> "kernels/filter" [dir=back, style=bold, label=" every folder"];')
for low, high in ((0, 1), (1, 2), (2, 3)):  # keeps the layer captions stacked
    out.append(f'  "layer {low}\\n{layers[low]}" -> "layer {high}\\n{layers[high]}" [style=invis];')
out.append("}")
dot = "\n".join(out) + "\n"
svg = subprocess.run(["dot", "-Tsvg"], input=dot.encode(), capture_output=True, check=True).stdout
pathlib.Path("docs/img/architecture.svg").write_bytes(svg)
png = subprocess.run(["dot", "-Tpng", "-Gdpi=80"], input=dot.encode(), capture_output=True, check=True).stdout
pathlib.Path("docs/img/architecture.png").write_bytes(png)
print("wrote docs/img/architecture.svg")
