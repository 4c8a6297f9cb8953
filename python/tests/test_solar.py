# SPDX-License-Identifier: Apache-2.0
"""Sun, shadows, horizons, sky view and irradiation against published values and plain references."""
import datetime as dt
import math

import numpy as np
import pytest

import lidarfx


def test_sun_position_reproduces_nrel_spa_published_example():
    # Reda & Andreas (2008), table A5.1: 17 October 2003 12:30:30 local time (UTC - 7) at Golden, Colorado.
    when = dt.datetime(2003, 10, 17, 12, 30, 30, tzinfo=dt.timezone(dt.timedelta(hours=-7)))
    s = lidarfx.sun_position(when, 39.742476, -105.1786, elevation_m=1830.14, pressure_mbar=820,
                             temperature_c=11, delta_t_s=67)
    assert s.zenith_deg == pytest.approx(50.11162, abs=1e-4)
    assert s.azimuth_deg == pytest.approx(194.34024, abs=1e-4)
    assert s.elevation_deg == pytest.approx(90 - s.zenith_deg)
    # The same instant as a naive UTC datetime, an ISO string and POSIX seconds.
    utc = dt.datetime(2003, 10, 17, 19, 30, 30)
    for t in (utc, "2003-10-17T19:30:30Z", "2003-10-17T12:30:30-07:00", utc.replace(tzinfo=dt.timezone.utc).timestamp()):
        other = lidarfx.sun_position(t, 39.742476, -105.1786, elevation_m=1830.14, pressure_mbar=820,
                                     temperature_c=11, delta_t_s=67)
        assert other.azimuth_deg == pytest.approx(s.azimuth_deg, abs=1e-9)
    with pytest.raises(ValueError, match="ISO 8601"):
        lidarfx.sun_position("noon", 0, 0)
    with pytest.raises(ValueError, match="latitude"):
        lidarfx.sun_position(utc, 95, 0)


def shadow_reference_south(z, cell_m, elevation_deg):
    """Sun due south (azimuth 180): cell (r, c) is shaded by a cell further south on its column."""
    t = math.tan(math.radians(elevation_deg))
    lit = np.ones(z.shape, np.uint8)
    rows = z.shape[0]
    for r in range(rows):
        for rr in range(r + 1, rows):
            lit[r] &= ~(z[rr] - (rr - r) * cell_m * t > z[r])
    return lit


def horizon_reference_south(z, cell_m):
    rows = z.shape[0]
    out = np.zeros(z.shape)
    for r in range(rows):
        for rr in range(r + 1, rows):
            out[r] = np.maximum(out[r], np.degrees(np.arctan((z[rr] - z[r]) / ((rr - r) * cell_m))))
    return out


def test_horizon_with_line_families_tells_which_cells_a_sun_lights(rng):
    # With the same line_phases, horizon_map and raylines_shadow read each cell along the same line, so a cell is
    # lit by a sun of that azimuth exactly when its horizon is at or below the sun's elevation.
    z = rng.uniform(0, 8, (45, 52)).astype(np.float32)
    for azimuth in (70.0, 200.0, 313.0):
        h = lidarfx.horizon_map(z, 1.0, azimuth, line_phases=4)
        for e in (8.0, 25.0):
            lit = lidarfx.raylines_shadow(z, 1.0, azimuth, e, line_phases=4)
            clear = np.abs(h - e) > 1e-3
            assert clear.sum() > 0.9 * z.size
            np.testing.assert_array_equal((lit == 1)[clear], (h <= e)[clear])
    with pytest.raises(ValueError):
        lidarfx.horizon_map(z, 1.0, 10.0, line_phases=0)


def test_shadows_and_horizons_along_a_grid_axis_equal_a_ray_march(rng):
    z = rng.uniform(0, 10, (40, 30)).astype(np.float32)
    for e in (5.0, 30.0, 60.0):
        np.testing.assert_array_equal(lidarfx.raylines_shadow(z, 1.5, 180.0, e), shadow_reference_south(z, 1.5, e))
    np.testing.assert_allclose(lidarfx.horizon_map(z, 1.5, 180.0), horizon_reference_south(z, 1.5), atol=1e-4)
    # Sun due east: the shading cells lie further east on the row, the same walk on the transposed raster.
    np.testing.assert_array_equal(lidarfx.raylines_shadow(z, 1.5, 90.0, 20.0),
                                  shadow_reference_south(np.ascontiguousarray(z.T), 1.5, 20.0).T)
    nan = z.copy()
    nan[3, 4] = np.nan
    assert lidarfx.raylines_shadow(nan, 1.0, 180.0, 30.0)[3, 4] == 255
    assert lidarfx.raylines_shadow(nan, 1.0, 180.0, 30.0, nan_cell=0)[3, 4] == 0
    assert (lidarfx.raylines_shadow(z, 1.0, 180.0, -1.0) == 0).all()


def test_sky_view_factor_is_the_mean_over_its_horizon_maps(rng):
    z = rng.uniform(0, 4, (24, 26)).astype(np.float32)
    n = 16
    h = np.stack([lidarfx.horizon_map(z, 1.0, 360.0 * i / n).astype(np.float64) for i in range(n)])
    cosine = np.mean(np.cos(np.radians(h)) ** 2, axis=0)
    np.testing.assert_allclose(lidarfx.sky_view_factor(z, 1.0, method="cosine_weighted", directions=n), cosine,
                               atol=2e-4)
    elevations = np.arange(15, 90, 5)
    visible = (elevations[None, None, None, :] >= h[..., None] + 1e-3).sum(axis=(0, 3))
    share = lidarfx.sky_view_factor(z, 1.0, directions=n)
    np.testing.assert_allclose(share, (1 + visible) / (15 * n + 1), atol=1.5 / (15 * n + 1))
    flat = np.zeros((10, 10), np.float32)
    np.testing.assert_array_equal(lidarfx.sky_view_factor(flat, 1.0), 1.0)
    with pytest.raises(ValueError, match="method must be"):
        lidarfx.sky_view_factor(flat, 1.0, method="grass")


def test_open_flat_ground_receives_the_weather_s_global_irradiation():
    weather = lidarfx.clear_sky_year(2023, 45.0, 7.0)
    assert len(weather.start_utc) == 8760 and weather.interval_s == 3600
    flat = np.full((12, 14), 300.0, np.float32)
    maps = lidarfx.irradiance_maps(flat, 2.0, weather)
    assert maps.annual_kwh_m2.shape == flat.shape
    assert maps.annual_kwh_m2.mean() == pytest.approx(maps.ghi_kwh_m2, rel=2e-3)
    np.testing.assert_allclose(maps.month_kwh_m2.sum(axis=0), maps.annual_kwh_m2, rtol=1e-4)
    assert maps.month_kwh_m2[5].mean() > 3 * maps.month_kwh_m2[11].mean()  # June against December in the north
    # A wall south of a cell shades it: less than open ground.
    walled = flat.copy()
    walled[8:, :] = 330.0
    shaded = lidarfx.irradiance_maps(walled, 2.0, weather, threads=2)
    assert shaded.annual_kwh_m2[6, 7] < 0.7 * maps.annual_kwh_m2[6, 7]
    with pytest.raises(ValueError, match="latitude_deg is needed"):
        lidarfx.irradiance_maps(flat, 2.0, lidarfx.Weather(weather.start_utc, weather.dni_w_m2, weather.dhi_w_m2,
                                                           weather.ghi_w_m2, latitude_deg=None))
