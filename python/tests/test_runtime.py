# SPDX-License-Identifier: Apache-2.0
"""Threads, progress, cancellation and the GIL: what a long call promises a Python caller."""
import os
import signal
import threading
import time

import numpy as np
import pytest

import lidarfx


@pytest.fixture
def terrain(rng):
    return rng.uniform(0, 20, (900, 900)).astype(np.float32)


def test_results_do_not_depend_on_threads(terrain):
    one = lidarfx.sky_view_factor(terrain[:300, :300], 1.0, directions=16)
    two = lidarfx.sky_view_factor(terrain[:300, :300], 1.0, directions=16, threads=2)
    every = lidarfx.sky_view_factor(terrain[:300, :300], 1.0, directions=16, threads=0)
    np.testing.assert_array_equal(one, two)
    np.testing.assert_array_equal(one, every)


def test_progress_is_monotone_and_ends_at_one(terrain):
    seen = []
    lidarfx.angular_filter(terrain, 1.0, progress=seen.append)
    assert len(seen) >= 2 and seen[-1] == 1.0
    assert all(a <= b for a, b in zip(seen, seen[1:]))


def test_a_progress_callable_returning_false_cancels(terrain):
    calls = []

    def stop_half_way(f):
        calls.append(f)
        return f < 0.3

    with pytest.raises(lidarfx.Cancelled, match="sky_view_factor: cancelled"):
        lidarfx.sky_view_factor(terrain, 1.0, progress=stop_half_way)
    assert calls and calls[-1] >= 0.3 and max(calls) < 1.0
    assert issubclass(lidarfx.Cancelled, RuntimeError)


def test_an_exception_in_the_progress_callable_stops_the_call_and_propagates(terrain):
    def broken(f):
        raise ZeroDivisionError("from the callable")

    with pytest.raises(ZeroDivisionError, match="from the callable"):
        lidarfx.angular_filter(terrain, 1.0, progress=broken)
    with pytest.raises(TypeError, match="progress must be a callable"):
        lidarfx.angular_filter(terrain, 1.0, progress=3)


def test_ctrl_c_cancels_a_long_call_with_keyboard_interrupt(terrain):
    timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
    start = time.perf_counter()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            for _ in range(50):  # far longer than 0.3 s in all
                lidarfx.sky_view_factor(terrain, 1.0)
    finally:
        timer.cancel()
    assert time.perf_counter() - start < 20


def test_two_calls_in_two_python_threads_run_at_once(terrain):
    if (os.cpu_count() or 1) < 2:
        pytest.skip("one core: calls cannot overlap")

    def work():
        lidarfx.sky_view_factor(terrain[:600, :600], 1.0, directions=24)

    work()  # warm up
    start = time.perf_counter()
    work()
    single = time.perf_counter() - start
    spans = []

    def timed():
        t0 = time.perf_counter()
        work()
        spans.append((t0, time.perf_counter()))

    threads = [threading.Thread(target=timed) for _ in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    (a0, a1), (b0, b1) = spans
    overlap = min(a1, b1) - max(a0, b0)
    # With the GIL held the second call could only start when the first ended: no overlap at all. The
    # overlap, unlike the wall time, does not depend on free cores (ctest runs other tests beside this one).
    assert overlap > 0.5 * single, (single, spans)
