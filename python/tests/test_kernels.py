# SPDX-License-Identifier: Apache-2.0
"""The kernels against plain NumPy references, on random and adversarial arrays, in every memory layout."""
import math

import numpy as np
import pytest

import lidarfx


def angular_filter_reference(z, cell_m, radius):
    """Steepest angle (degrees) between each cell and the cells of its window, atan(|dz| / distance); NaN
    neighbours are skipped, a NaN centre gives NaN, no valid neighbour gives 0."""
    rows, cols = z.shape
    out = np.full(z.shape, np.nan, dtype=np.float64)
    for r in range(rows):
        for c in range(cols):
            if np.isnan(z[r, c]):
                continue
            best = 0.0
            for dr in range(-radius, radius + 1):
                for dc in range(-radius, radius + 1):
                    rr, cc = r + dr, c + dc
                    if (dr == 0 and dc == 0) or not (0 <= rr < rows and 0 <= cc < cols) or np.isnan(z[rr, cc]):
                        continue
                    d = cell_m * math.hypot(dr, dc)
                    best = max(best, math.degrees(math.atan(abs(float(z[rr, cc]) - float(z[r, c])) / d)))
            out[r, c] = best
    return out


def test_angular_filter_matches_the_definition_on_random_heights_with_holes(rng):
    z = rng.normal(0, 2, (23, 31)).astype(np.float32)
    z[rng.random(z.shape) < 0.1] = np.nan
    for radius in (1, 2):
        got = lidarfx.angular_filter(z, 0.5, radius)
        want = angular_filter_reference(z, 0.5, radius)
        finite = np.isfinite(want)
        assert got.dtype == np.float32 and got.shape == z.shape
        np.testing.assert_allclose(got[finite], want[finite], atol=1e-3)


def test_every_memory_layout_gives_the_contiguous_result(rng):
    big = rng.normal(0, 3, (60, 80)).astype(np.float32)
    z = np.ascontiguousarray(big[5:45, 10:70])
    want = lidarfx.angular_filter(z, 1.0)
    layouts = {
        "window (row stride > cols, read in place)": big[5:45, 10:70],
        "fortran order": np.asfortranarray(z),
        "every other column": np.repeat(z, 2, axis=1)[:, ::2],
        "reversed rows": z[::-1][::-1],
        "float64": z.astype(np.float64),
        "int": None,
    }
    for name, a in layouts.items():
        if a is None:
            continue
        np.testing.assert_array_equal(lidarfx.angular_filter(a, 1.0), want, err_msg=name)
    zi = np.round(z * 10).astype(np.int32)
    np.testing.assert_array_equal(lidarfx.angular_filter(zi, 1.0), lidarfx.angular_filter(zi.astype(np.float32), 1.0))


def test_arrays_are_read_in_place_when_their_layout_allows():
    from lidarfx._lidarfx import _input_is_copied as copied
    z = np.zeros((30, 40), np.float32)
    assert not copied(z, "heights") and not copied(z[3:20, 5:33], "heights") and not copied(z[::2], "heights")
    assert copied(np.asfortranarray(z), "heights") and copied(z[:, ::2], "heights")
    assert copied(z[::-1], "heights") and copied(z.astype(np.float64), "heights")
    assert copied(z.astype(">f4"), "heights")  # big-endian cells are converted
    m = np.zeros((30, 40), bool)
    assert not copied(m, "mask") and not copied(m.view(np.uint8), "mask") and not copied(m[2:9, 1:7], "mask")
    assert copied(m.astype(np.int32), "mask")


def test_results_own_their_cells_without_a_copy_back():
    out = lidarfx.angular_filter(np.zeros((4, 5), np.float32), 1.0)
    assert not out.flags.owndata and type(out.base).__name__ == "PyCapsule"  # the library's raster, moved
    assert out.flags.c_contiguous and out.flags.writeable
    out[0, 0] = 7.0  # writable, and nothing else sees it
    assert lidarfx.angular_filter(np.zeros((4, 5), np.float32), 1.0)[0, 0] == 0.0


def test_wrong_types_and_shapes_are_refused_with_the_argument_named():
    with pytest.raises(TypeError, match="angular_filter: z must be a NumPy array"):
        lidarfx.angular_filter([[1.0, 2.0]], 1.0)
    with pytest.raises(ValueError, match="angular_filter: z must be 2-D"):
        lidarfx.angular_filter(np.zeros(5, np.float32), 1.0)
    with pytest.raises(TypeError, match="dtype"):
        lidarfx.angular_filter(np.zeros((3, 3), dtype=complex), 1.0)
    with pytest.raises(ValueError, match=r"cell_m must be finite and > 0 \(got -1\)"):
        lidarfx.angular_filter(np.zeros((3, 3), np.float32), -1.0)
    with pytest.raises(ValueError, match="radius_cells"):
        lidarfx.angular_filter(np.zeros((3, 3), np.float32), 1.0, 0)
    with pytest.raises(ValueError, match="threads must be >= 0"):
        lidarfx.angular_filter(np.zeros((3, 3), np.float32), 1.0, threads=-1)
    with pytest.raises(TypeError, match="mask"):
        lidarfx.morph_open(np.zeros((3, 3), np.float32), 3)


def window_reference(mask, size, combine):
    rows, cols = mask.shape
    h = size // 2
    out = np.zeros_like(mask, dtype=bool)
    for r in range(rows):
        for c in range(cols):
            out[r, c] = combine(mask[max(0, r - h):r + h + 1, max(0, c - h):c + h + 1])
    return out


def test_morphology_matches_window_references_for_bool_and_uint8_masks(rng):
    for density in (0.1, 0.5, 0.9):
        m = rng.random((37, 29)) < density
        for size in (1, 3, 5):
            dil = window_reference(m, size, np.any)
            ero = window_reference(m, size, np.all)
            np.testing.assert_array_equal(lidarfx.morph_dilate(m, size), dil)
            np.testing.assert_array_equal(lidarfx.morph_erode(m.astype(np.uint8), size), ero)
            np.testing.assert_array_equal(lidarfx.morph_open(m, size), window_reference(ero, size, np.any))
            np.testing.assert_array_equal(lidarfx.morph_close(m, size), window_reference(dil, size, np.all))
    assert lidarfx.morph_open(m, 3).dtype == np.bool_
    # An integer mask: any nonzero value is set.
    np.testing.assert_array_equal(lidarfx.morph_dilate(m.astype(np.int64) * 7, 3), lidarfx.morph_dilate(m, 3))


def components_reference(mask, eight):
    labels = np.zeros(mask.shape, np.int32)
    sizes = [int((~mask).sum())]
    steps = [(-1, 0), (1, 0), (0, -1), (0, 1)] + ([(-1, -1), (-1, 1), (1, -1), (1, 1)] if eight else [])
    for r in range(mask.shape[0]):
        for c in range(mask.shape[1]):
            if mask[r, c] and labels[r, c] == 0:
                sizes.append(0)
                stack = [(r, c)]
                labels[r, c] = len(sizes) - 1
                while stack:
                    y, x = stack.pop()
                    sizes[-1] += 1
                    for dy, dx in steps:
                        yy, xx = y + dy, x + dx
                        if 0 <= yy < mask.shape[0] and 0 <= xx < mask.shape[1] and mask[yy, xx] and labels[yy, xx] == 0:
                            labels[yy, xx] = len(sizes) - 1
                            stack.append((yy, xx))
    return labels, np.array(sizes)


def test_connected_components_number_in_raster_order_as_a_flood_fill_does(rng):
    for conn in (4, 8):
        m = rng.random((41, 53)) < 0.45
        got = lidarfx.connected_components(m, conn)
        labels, sizes = components_reference(m, conn == 8)
        np.testing.assert_array_equal(got.labels, labels)
        np.testing.assert_array_equal(got.sizes, sizes)
        assert got.count == len(sizes) - 1
    with pytest.raises(ValueError, match="connectivity must be 4 or 8"):
        lidarfx.connected_components(m, 6)


def test_ks_one_sided_statistic_and_decision_follow_the_formula(rng):
    prev = rng.normal(0, 1, 200)
    cur = rng.normal(0.4, 1, 150)
    r = lidarfx.ks_one_sided(prev, cur, 0.05)
    xs = np.sort(np.concatenate([prev, cur]))
    d = max(0.0, np.max(np.searchsorted(np.sort(prev), xs, "right") / 200 - np.searchsorted(np.sort(cur), xs, "right") / 150))
    assert r.d == pytest.approx(d)
    assert r.critical == pytest.approx(1.36 * math.sqrt((200 + 150) / (200 * 150)))
    assert r.reject == (r.d > r.critical)
    assert r.p_value == pytest.approx(math.exp(-2 * d * d * 200 * 150 / 350))
    assert not lidarfx.ks_one_sided(cur, prev).reject  # the other way round is not "larger"
    assert lidarfx.ks_one_sided(prev, cur, critical="one_sided").critical == pytest.approx(
        math.sqrt(-math.log(0.05) / 2) * math.sqrt(350 / 30000))
    with pytest.raises(ValueError, match="alpha"):
        lidarfx.ks_one_sided(prev, cur, 1.5)


def test_rasterize_bins_points_as_numpy_does(rng):
    n = 5000
    x = rng.uniform(100, 130, n)
    y = rng.uniform(200, 220, n)
    z = rng.normal(10, 1, n)
    intensity = rng.integers(0, 5000, n).astype(np.uint16)
    nret = rng.integers(1, 3, n).astype(np.uint8)
    rn = np.minimum(rng.integers(1, 3, n), nret).astype(np.uint8)
    pr = lidarfx.rasterize(x, y, z, intensity, rn, nret, 2.0)
    g = pr.grid
    assert g.cell_m == 2.0 and g.x0 <= 100 and g.y0 >= 220 and g.x0 % 2 == 0 and g.y0 % 2 == 0
    col = np.floor((x - g.x0) / 2.0).astype(int)
    row = np.floor((g.y0 - y) / 2.0).astype(int)
    count = np.zeros((g.rows, g.cols), np.int64)
    np.add.at(count, (row, col), 1)
    zmin = np.full((g.rows, g.cols), np.inf)
    np.minimum.at(zmin, (row, col), z)
    isum = np.zeros((g.rows, g.cols))
    np.add.at(isum, (row, col), intensity)
    multi = np.zeros((g.rows, g.cols), bool)
    np.logical_or.at(multi, (row, col), nret > 1)
    np.testing.assert_array_equal(pr.count, count)
    has = count > 0
    np.testing.assert_allclose(pr.min_z[has], zmin[has].astype(np.float32))
    assert np.isnan(pr.min_z[~has]).all()
    np.testing.assert_allclose(pr.mean_intensity[has], isum[has] / count[has], rtol=1e-5)
    np.testing.assert_array_equal(pr.dropout, ~has)
    np.testing.assert_array_equal(pr.multiple_returns, multi)
    split = np.zeros((g.rows, g.cols), np.int64)
    np.add.at(split, (row, col), (nret > 1).astype(np.int64))
    np.testing.assert_array_equal(pr.multiple_return_count, split)
    assert pr.points_used == n
    first = lidarfx.rasterize(x, y, z, intensity, rn, nret, 2.0, return_selection="first", grid=g)
    assert first.points_used == int((rn == 1).sum()) and first.points_unselected == int((rn != 1).sum())
    with pytest.raises(ValueError, match="same length"):
        lidarfx.rasterize(x, y[:-1], z)
    with pytest.raises(ValueError, match="return_selection must be"):
        lidarfx.rasterize(x, y, z, return_selection="second")


def test_remove_surface_outliers_replaces_a_bird_and_a_gap_by_their_neighbours_median(rng):
    z = (100 + rng.normal(0, 0.5, (40, 40))).astype(np.float32)
    z[10, 10] += 150  # a bird
    z[30, 25] -= 20   # a return through a canopy gap
    r = lidarfx.remove_surface_outliers(z)
    assert (r.spikes, r.pits) == (1, 1) and r.outlier[10, 10] == 1 and r.outlier[30, 25] == 2
    window = np.delete(z[8:13, 8:13].ravel(), 12)
    assert r.surface[10, 10] == np.sort(window)[(len(window) - 1) // 2]
    changed = r.outlier > 0
    np.testing.assert_array_equal(r.surface[~changed], z[~changed])
    with pytest.raises(ValueError, match="spike_height_m"):
        lidarfx.remove_surface_outliers(z, spike_height_m=0)
