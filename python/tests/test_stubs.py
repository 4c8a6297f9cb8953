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
