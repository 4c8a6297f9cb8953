# SPDX-License-Identifier: Apache-2.0
"""The lidarfx program against the library through the module: what `lidarfx solar` writes equals the library
call it stands for. Needs LIDARFX_PROGRAM (ctest sets it); skipped without it."""
import os
import subprocess

import numpy as np
import pytest

import lidarfx

PROGRAM = os.environ.get("LIDARFX_PROGRAM")
pytestmark = pytest.mark.skipif(not PROGRAM or not os.path.exists(PROGRAM), reason="LIDARFX_PROGRAM is not set")


def write_asc(path, z, cell):
    rows, cols = z.shape
    with open(path, "w") as f:
        f.write(f"ncols {cols}\nnrows {rows}\nxllcorner 0\nyllcorner 0\ncellsize {cell}\nNODATA_value -9999\n")
        np.savetxt(f, z, fmt="%.4f")


def read_asc(path):
    return np.loadtxt(path, skiprows=6)


def hill_with_house():
    """A 60 x 50 DSM at 1 m: a hill sloping to the south-east and a gabled house, heights rounded as written."""
    yy, xx = np.mgrid[0:60, 0:50] + 0.5
    z = 100 + 0.15 * (60 - yy) + 0.05 * (50 - xx)
    house = (np.abs(xx - 25) < 8) & (np.abs(yy - 30) < 6)
    z = np.where(house, z.max() + 3 + 0.6 * (6 - np.abs(yy - 30)), z)
    return np.round(z, 4).astype(np.float32)


@pytest.mark.parametrize("svf, method", [("cosine", "cosine_weighted"), ("share", "source_share")])
def test_solar_on_terrain_surfaces_is_irradiance_maps_with_slope_and_aspect(tmp_path, svf, method):
    z = hill_with_house()
    write_asc(tmp_path / "dsm.asc", z, 1.0)
    out = tmp_path / "out"
    subprocess.run([PROGRAM, "solar", str(tmp_path / "dsm.asc"), "--xy-unit", "m", "--z-unit", "m", "--lat", "47",
                    "--lon", "8", "--svf", svf, "--surface", "terrain", "--formats", "asc", "--out", str(out)],
                   check=True, capture_output=True)
    orientation = lidarfx.slope_aspect(z, 1.0)
    want = lidarfx.irradiance_maps(z, 1.0, lidarfx.clear_sky_year(2021, 47.0, 8.0), svf_method=method,
                                   surface_tilt_deg=orientation.slope_deg, surface_azimuth_deg=orientation.aspect_deg)
    got = read_asc(out / "annual_kwh_m2.asc")
    np.testing.assert_allclose(got, want.annual_kwh_m2, atol=0.06)  # the file's decimals
    np.testing.assert_allclose(read_asc(out / "svf.asc"), want.sky_view_factor, atol=6e-4)
    flat = lidarfx.irradiance_maps(z, 1.0, lidarfx.clear_sky_year(2021, 47.0, 8.0), svf_method=method)
    assert np.abs(flat.annual_kwh_m2 - want.annual_kwh_m2).max() > 50  # tilting the cells does change the map


def test_slope_aspect_of_a_plane_is_exact():
    yy, xx = np.mgrid[0:20, 0:30].astype(np.float64)
    z = (0.5 * yy).astype(np.float32)  # rising southwards by 0.5 m per 2 m cell: faces north, 14.04°
    sa = lidarfx.slope_aspect(z, 2.0)
    np.testing.assert_allclose(sa.slope_deg, np.degrees(np.arctan(0.25)), atol=1e-4)
    np.testing.assert_allclose(np.where(sa.aspect_deg > 180, sa.aspect_deg - 360, sa.aspect_deg), 0.0, atol=1e-4)
    assert not sa.flat.any() and lidarfx.slope_aspect(np.zeros((5, 5), np.float32), 1.0).flat.all()
