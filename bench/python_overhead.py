#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""The cost of the Python binding: angular_filter on a 4096 x 4096 float32 DSM called from Python against the
same call timed inside C++ (same module, same input, same run), interleaved, median of N each.
Usage: PYTHONPATH=build/python /usr/bin/python3 bench/python_overhead.py [size] [repeats] [threads]"""
import statistics
import sys
import time

import numpy as np

import lidarfx
import lidarfx._lidarfx


def cpu_flags():
    try:
        flags = next(line for line in open("/proc/cpuinfo") if line.startswith("flags")).split()
    except (OSError, StopIteration):
        return "unknown"
    return " ".join(f for f in ("sse4_2", "avx", "avx2", "fma", "avx512f", "avx512bw") if f in flags)


def main():
    size = int(sys.argv[1]) if len(sys.argv) > 1 else 4096
    repeats = int(sys.argv[2]) if len(sys.argv) > 2 else 7
    threads = int(sys.argv[3]) if len(sys.argv) > 3 else 1
    rng = np.random.default_rng(1)
    dsm = (np.cumsum(rng.normal(0, 0.2, (size, size)), axis=1) + 100).astype(np.float32)
    lidarfx.angular_filter(dsm, 1.0, threads=threads)  # warm up: pages, caches
    python_s, cpp_s = [], []
    for _ in range(repeats):
        t0 = time.perf_counter()
        lidarfx.angular_filter(dsm, 1.0, threads=threads)
        python_s.append(time.perf_counter() - t0)
        cpp_s.extend(lidarfx._lidarfx._angular_filter_cpp_seconds(dsm, 1.0, 2, threads, 1))
    py_med, cpp_med = statistics.median(python_s), statistics.median(cpp_s)
    print(f"CPU vector extensions: {cpu_flags()}")
    print(f"angular_filter {size}x{size} float32, radius 2, {threads} thread(s), median of {repeats}:")
    print(f"  from Python  {py_med * 1e3:8.1f} ms")
    print(f"  in C++       {cpp_med * 1e3:8.1f} ms")
    print(f"  binding overhead {100 * (py_med / cpp_med - 1):+.1f} %")


if __name__ == "__main__":
    main()
