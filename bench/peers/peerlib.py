# SPDX-License-Identifier: Apache-2.0
"""Shared helpers for the peer comparisons: time a Python peer, run a lidarfx Google Benchmark on the
same input files, print the ratio.  Run with Debian's /usr/bin/python3 (numpy, scipy, cv2 live there)."""
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

# The bench preset builds into build/bench and puts the benchmark programs in its bench/ folder.
BUILD_DIR = os.environ.get("LIDARFX_BENCH_BUILD", os.path.join(os.path.dirname(__file__), "..", "..",
                                                                "build", "bench", "bench"))


def best_time(fn, repeat=5, warmup=1, clock=time.perf_counter):
    """Minimum time in seconds of fn() over `repeat` runs after `warmup` untimed runs; wall time by default,
    clock=time.process_time for the CPU time of this process (fair on a loaded machine for one thread)."""
    for _ in range(warmup):
        fn()
    best = float("inf")
    for _ in range(repeat):
        t0 = clock()
        fn()
        best = min(best, clock() - t0)
    return best


def input_dir():
    """A scratch folder for raw inputs shared by the peer and lidarfx (kept for the whole run)."""
    d = os.environ.get("LIDARFX_BENCH_INPUT_DIR")
    if not d:
        d = tempfile.mkdtemp(prefix="lidarfx-bench-")
        os.environ["LIDARFX_BENCH_INPUT_DIR"] = d
    return d


def write_raw(array, name):
    """Writes array (C order, native endian) as <input_dir>/<name>.raw, the format bench::load_raw reads."""
    path = os.path.join(input_dir(), name + ".raw")
    np.ascontiguousarray(array).tofile(path)
    return path


def run_gbench(binary, bench_filter, threads_env=None, field="real_time"):
    """Runs a lidarfx benchmark binary (from BUILD_DIR) with --benchmark_filter and returns
    {benchmark name: seconds per iteration}, of wall time (field="real_time") or CPU time ("cpu_time")."""
    exe = binary if os.path.isabs(binary) else os.path.join(BUILD_DIR, binary)
    if not os.path.exists(exe):
        sys.exit(f"{exe} not found: build with `cmake --preset bench && cmake --build --preset bench`")
    env = dict(os.environ)
    if threads_env:
        env.update(threads_env)
    out = subprocess.run([exe, f"--benchmark_filter={bench_filter}", "--benchmark_format=json",
                          "--benchmark_min_time=0.5"], check=True, capture_output=True, text=True, env=env).stdout
    scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}
    return {b["name"]: b[field] * scale[b["time_unit"]] for b in json.loads(out)["benchmarks"]
            if b.get("run_type", "iteration") == "iteration"}


def report(rows):
    """Prints one line per comparison: (case, lidarfx_s, peer name, peer_s, target ratio or None).
    Ratio = peer time / lidarfx time (> 1: lidarfx is faster)."""
    print(f"{'case':58s} {'lidarfx ms':>11s} {'peer':>28s} {'peer ms':>10s} {'ratio':>7s} {'target':>7s}")
    ok = True
    for case, ours, peer_name, theirs, target in rows:
        ratio = theirs / ours
        mark = "" if target is None else (" ok" if ratio >= target else " MISSED")
        ok &= target is None or ratio >= target
        print(f"{case:58s} {ours * 1e3:11.3f} {peer_name:>28s} {theirs * 1e3:10.3f} {ratio:7.2f} "
              f"{'' if target is None else f'>={target:g}':>7s}{mark}")
    return ok
