# SPDX-License-Identifier: Apache-2.0
"""Peer comparison for the point-to-raster algorithms (bench/bench_raster.cpp).

rasterize: 10^7 points in acquisition order (flight strips, zigzag scan lines) into 2 m cells giving
min z, max z, mean intensity and count. Every NumPy approach we know is timed (ufunc.at, argsort +
reduceat, lexsort, sorted fancy assignment); the fastest is the peer. Targets: lidarfx on one thread
>= 5x the fastest NumPy approach, and >= 50 M points/s.

idw_fill: 2048 x 2048 float32 elevations with 30 % NaN cells in round blobs, k = 8, weights 1/d:
SciPy cKDTree over the data cells (query of every hole) is the peer; no target, the ratio is reported.

Run from the repository with Debian's Python, after building the benchmarks:
    cmake --preset bench && cmake --build --preset bench --target bench_raster
    /usr/bin/python3 bench/peers/peer_raster.py [--build DIR]
The inputs are written to $LIDARFX_BENCH_INPUT_DIR (a temporary folder by default) and read by
bench_raster, so both sides time the same data.
"""
import argparse
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import peerlib  # noqa: E402

POINTS = 10_000_000
CELL = 2.0
IDW_N = 2048


def survey(n, seed=42):
    """Points in acquisition order: 4 strips of 500 m (+5 % side overlap) over 2 km x 2 km, zigzag scan
    lines 0.5 m apart; 20 % of the points are in trees (two returns, up to 15 m above the ground)."""
    rng = np.random.default_rng(seed)
    strips, width, length, spacing = 4, 500.0, 2000.0, 0.5
    per_strip = int(length / spacing)
    lines = per_strip * strips
    per_line = n // lines + 1
    k = np.arange(lines)[:, None]
    t = (np.arange(per_line)[None, :] + 0.5) / per_line
    across = np.where(k % 2 == 1, 1.0 - t, t) * width * 1.1 - 0.05 * width
    x = (500000.0 + ((k // per_strip) % strips) * width + across).ravel()[:n]
    y = np.broadcast_to(4200000.0 + spacing * (k % per_strip), (lines, per_line)).ravel()[:n].copy()
    x += rng.uniform(-0.2, 0.2, n)
    y += rng.uniform(-0.2, 0.2, n)
    tree = rng.uniform(size=n) < 0.2
    ground = 100.0 + 10.0 * np.sin(x * 0.003) * np.cos(y * 0.002)
    z = ground + np.where(tree, 15.0 * rng.uniform(size=n), 0.05 * rng.uniform(-0.2, 0.2, n))
    intensity = (rng.uniform(size=n) * 4000.0).astype(np.uint16)
    returns = np.where(tree, 2, 1).astype(np.uint8)
    return x, y, z, intensity, returns


def snapped_grid(x, y, cell):
    """lidarfx::snapped_grid(bounds_of(cloud), cell): (x0, y0, rows, cols)."""
    xmin, xmax, ymin, ymax = x.min(), x.max(), y.min(), y.max()
    x0 = math.floor(xmin / cell) * cell
    y0 = math.ceil(ymax / cell) * cell
    cols = math.floor((xmax - x0) / cell) + 1
    rows = math.floor((y0 - ymin) / cell) + 1
    if cols > 1 and x0 + (cols - 1) * cell >= xmax:
        cols -= 1
    if rows > 1 and y0 - (rows - 1) * cell <= ymin:
        rows -= 1
    return x0, y0, rows, cols


def cell_index(x, y, grid):
    """Flat cell index as grid::cell_of (points on the far east/south edge go to the last cell). All
    points lie inside the grid here, so the outside/NaN bookkeeping lidarfx does is left out (in NumPy's favour)."""
    x0, y0, rows, cols = grid
    c = np.minimum(((x - x0) / CELL).astype(np.int64), cols - 1)
    r = np.minimum(((y0 - y) / CELL).astype(np.int64), rows - 1)
    return r * cols + c


def finish(count, total, zmin, zmax, shape):
    """Rasters from per-cell count, intensity sum and z extremes: NaN / 0 where no point."""
    empty = count == 0
    zmin = np.where(empty, np.nan, zmin).astype(np.float32).reshape(shape)
    zmax = np.where(empty, np.nan, zmax).astype(np.float32).reshape(shape)
    mean = (total / np.maximum(count, 1)).astype(np.float32).reshape(shape)
    return zmin, zmax, mean, count.astype(np.uint32).reshape(shape)


def numpy_rasterize(extremes):
    """A NumPy rasterization whose per-cell z extremes come from extremes(idx, z, zmin, zmax) (filling
    zmin/zmax in place); counts and intensity sums are np.bincount in every approach (the fastest way)."""
    def run(x, y, z, intensity, grid):
        idx = cell_index(x, y, grid)
        cells = grid[2] * grid[3]
        zmin = np.full(cells, np.inf)
        zmax = np.full(cells, -np.inf)
        extremes(idx, z, zmin, zmax)
        count = np.bincount(idx, minlength=cells)
        total = np.bincount(idx, weights=intensity, minlength=cells)
        return finish(count, total, zmin, zmax, (grid[2], grid[3]))
    return run


def ufunc_at(idx, z, zmin, zmax):
    np.minimum.at(zmin, idx, z)
    np.maximum.at(zmax, idx, z)


def argsort_reduceat(kind):
    def extremes(idx, z, zmin, zmax):
        order = np.argsort(idx, kind=kind)
        sidx = idx[order]
        starts = np.flatnonzero(np.r_[True, sidx[1:] != sidx[:-1]])
        zs = z[order]
        zmin[sidx[starts]] = np.minimum.reduceat(zs, starts)
        zmax[sidx[starts]] = np.maximum.reduceat(zs, starts)
    return extremes


def lexsort(idx, z, zmin, zmax):
    order = np.lexsort((z, idx))  # by cell, then z: first of a cell is its min, last its max
    sidx = idx[order]
    change = np.flatnonzero(sidx[1:] != sidx[:-1])
    zmin[sidx[np.r_[0, change + 1]]] = z[order[np.r_[0, change + 1]]]
    zmax[sidx[np.r_[change, len(sidx) - 1]]] = z[order[np.r_[change, len(sidx) - 1]]]


def sorted_assignment(idx, z, zmin, zmax):
    order = np.argsort(z)  # ascending: with repeated indices the last assignment wins -> max
    zmax[idx[order]] = z[order]
    zmin[idx[order[::-1]]] = z[order[::-1]]


def holes_raster(n, seed=11, share=0.3):
    """Smooth terrain with `share` NaN cells in round blobs of radius 2..40 cells."""
    rng = np.random.default_rng(seed)
    r, c = np.mgrid[0:n, 0:n]
    z = (20.0 + 5.0 * np.sin(0.01 * r) * np.cos(0.013 * c) + rng.normal(0, 0.05, (n, n))).astype(np.float32)
    holes = np.zeros((n, n), bool)
    while holes.mean() < share:
        r0, c0 = rng.integers(0, n, 2)
        rad = rng.uniform(2.0, 40.0)
        k = int(rad)
        rs, cs = slice(max(0, r0 - k), min(n, r0 + k + 1)), slice(max(0, c0 - k), min(n, c0 + k + 1))
        holes[rs, cs] |= (r[rs, cs] - r0) ** 2 + (c[rs, cs] - c0) ** 2 <= rad * rad
    z[holes] = np.nan
    return z


def scipy_idw(z, k=8, workers=1):
    from scipy.spatial import cKDTree
    holes = np.isnan(z)
    data = np.argwhere(~holes)
    tree = cKDTree(data)
    query = np.argwhere(holes)
    d, i = tree.query(query, k=k, workers=workers)
    w = 1.0 / (d * CELL)
    values = z[~holes][i]
    out = z.copy()
    out[holes] = (w * values).sum(axis=1) / w.sum(axis=1)
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", help="folder holding bench_raster (default: $LIDARFX_BENCH_BUILD or build/bench/bench)")
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    exe = os.path.abspath(os.path.join(args.build, "bench_raster")) if args.build else "bench_raster"

    x, y, z, intensity, returns = survey(POINTS)
    for name, a in (("x", x), ("y", y), ("z", z), ("intensity", intensity), ("returns", returns)):
        peerlib.write_raw(a, "points_" + name)
    grid = snapped_grid(x, y, CELL)
    print(f"rasterize: {POINTS} points into {grid[2]} x {grid[3]} cells of {CELL} m "
          f"(inputs in {peerlib.input_dir()})")

    approaches = {name: numpy_rasterize(fn) for name, fn in (
        ("np.minimum.at", ufunc_at), ("argsort(stable)+reduceat", argsort_reduceat("stable")),
        ("argsort(quick)+reduceat", argsort_reduceat("quicksort")), ("lexsort", lexsort),
        ("argsort(z)+assignment", sorted_assignment))}
    results, times = {}, {}
    for name, fn in approaches.items():
        results[name] = fn(x, y, z, intensity, grid)
        times[name] = peerlib.best_time(lambda: fn(x, y, z, intensity, grid), repeat=args.repeat)
        print(f"  numpy {name:24s} {times[name] * 1e3:9.1f} ms")
    first = next(iter(results.values()))
    for name, res in results.items():  # every approach computes the same rasters
        for a, b in zip(first, res):
            assert np.array_equal(a, b, equal_nan=True), name
    best = min(times, key=times.get)

    z_idw = holes_raster(IDW_N)
    peerlib.write_raw(z_idw, "idw_z")
    t_kd1 = peerlib.best_time(lambda: scipy_idw(z_idw, workers=1), repeat=args.repeat)
    t_kdall = peerlib.best_time(lambda: scipy_idw(z_idw, workers=-1), repeat=args.repeat)
    print(f"idw_fill: {IDW_N}^2 cells, {np.isnan(z_idw).mean() * 100:.1f} % holes, k = 8")

    ours = peerlib.run_gbench(exe, "bm_rasterize_scan_order|bm_idw_fill/n:2048/k:8")
    r1 = ours["bm_rasterize_scan_order/threads:1/real_time"]
    rall = ours["bm_rasterize_scan_order/threads:0/real_time"]
    i1 = ours["bm_idw_fill/n:2048/k:8/threads:1/real_time"]
    iall = ours["bm_idw_fill/n:2048/k:8/threads:0/real_time"]
    ok = peerlib.report([
        ("rasterize 1e7 points, 2 m cells, 1 thread", r1, "numpy " + best, times[best], 5.0),
        ("rasterize 1e7 points, 2 m cells, all threads", rall, "numpy " + best, times[best], None),
        ("idw_fill 2048^2, 30 % holes, k=8, 1 thread", i1, "scipy cKDTree (1 worker)", t_kd1, None),
        ("idw_fill 2048^2, 30 % holes, k=8, all threads", iall, "scipy cKDTree (all)", t_kdall, None),
    ])
    rate = POINTS / r1 / 1e6
    print(f"rasterize throughput, 1 thread: {rate:.1f} M points/s (target >= 50){'' if rate >= 50 else ' MISSED'}")
    return 0 if ok and rate >= 50 else 1


if __name__ == "__main__":
    sys.exit(main())
