# SPDX-License-Identifier: Apache-2.0
"""The type stubs declare every function of the module with its parameters, defaults and keyword-only marks."""
import ast
import os
import re

import lidarfx
import lidarfx._lidarfx as extension


def runtime_signatures():
    out = {}
    for name in dir(extension):
        f = getattr(extension, name)
        if name.startswith("_") or not callable(f) or not f.__doc__ or "(" not in f.__doc__.splitlines()[0]:
            continue
        params = f.__doc__.splitlines()[0].split("(", 1)[1].rsplit(") ->", 1)[0]
        out[name] = [re.sub(r": [\w.]+", "", p.strip()) for p in params.split(", ")]
    return out


def stub_signatures():
    path = os.path.join(os.path.dirname(lidarfx.__file__), "__init__.pyi")
    tree = ast.parse(open(path).read())
    out = {}
    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            a = node.args
            positional = a.args
            defaults = [None] * (len(positional) - len(a.defaults)) + a.defaults
            params = [p.arg + ("" if d is None else " = " + ast.unparse(d)) for p, d in zip(positional, defaults)]
            if a.kwonlyargs:
                params.append("*")
                params += [p.arg + ("" if d is None else " = " + ast.unparse(d)) for p, d in zip(a.kwonlyargs, a.kw_defaults)]
            out[node.name] = params
    return out


def test_every_function_has_a_stub_with_the_same_parameters():
    runtime, stubs = runtime_signatures(), stub_signatures()
    assert set(runtime) == set(stubs)
    for name, params in runtime.items():
        assert [p.replace("'", '"') for p in params] == [p.replace("'", '"') for p in stubs[name]], name


def test_every_function_documents_itself():
    for name in runtime_signatures():
        doc = getattr(lidarfx, name).__doc__
        assert len(doc.splitlines()) >= 3, name


def test_the_stubs_carry_the_module_s_docstrings():
    path = os.path.join(os.path.dirname(lidarfx.__file__), "__init__.pyi")
    stubs = {n.name: ast.get_docstring(n, clean=False) for n in ast.parse(open(path).read()).body
             if isinstance(n, ast.FunctionDef)}
    for name in runtime_signatures():
        runtime = getattr(lidarfx, name).__doc__.split("\n", 1)[1].strip()
        assert (stubs[name] or "").strip() == runtime, name


def test_the_documented_spellings_work_as_keywords():
    import numpy as np
    z = np.zeros((8, 9), np.float32)
    m = np.zeros((8, 9), bool)
    lidarfx.angular_filter(z, cell_m=1.0, radius=2)
    for op in (lidarfx.morph_open, lidarfx.morph_close, lidarfx.morph_dilate, lidarfx.morph_erode):
        op(m, size=3)
    lidarfx.connected_components(m, connectivity=8)
    lidarfx.ks_one_sided(previous=[1, 2, 3], current=[2, 3, 4], alpha=0.05)
    lidarfx.raylines_shadow(dsm=z, cell_m=1.0, azimuth_deg=180.0, elevation_deg=30.0)
    lidarfx.horizon_map(dsm=z, cell_m=1.0, azimuth_deg=90.0)
    lidarfx.sky_view_factor(dsm=z, cell_m=1.0, method="cosine_weighted")
    lidarfx.sun_position(time="2024-06-21T12:00:00", lat=47.0, lon=8.0)
    lidarfx.azimuth_mode_select(hist360=np.ones(360))
    one = np.ones(3)
    r = lidarfx.rasterize(x=one, y=one, z=one, intensity=one, returns=one, nreturns=one, cell_m=1.0)
    lidarfx.extract_waterbodies(r, check_inputs=False)
    b = lidarfx.extract_buildings(z, cell_m=1.0)
    lidarfx.roof_suitability(z, z, b.building_id, cell_m=1.0)
