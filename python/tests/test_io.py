# SPDX-License-Identifier: Apache-2.0
"""Reading surveys (LAS/LAZ) and weather years with the program's readers."""
import os

import numpy as np
import pytest

import lidarfx

pytestmark = pytest.mark.skipif(not lidarfx.has_io, reason="built without the readers")


def test_read_survey_reads_every_point_of_a_laz_file(data_dir):
    s = lidarfx.read_survey(os.path.join(data_dir, "simple.laz"))
    assert len(s.x) == 1065 and s.x.dtype == np.float64 and s.intensity.dtype == np.uint16
    # PDAL's simple.las: bounds 635619.85 .. 638982.55, 848899.70 .. 853535.43, 406.59 .. 586.38.
    assert s.x.min() == pytest.approx(635619.85) and s.x.max() == pytest.approx(638982.55)
    assert s.y.min() == pytest.approx(848899.70) and s.y.max() == pytest.approx(853535.43)
    assert s.z.min() == pytest.approx(406.59) and s.z.max() == pytest.approx(586.38)
    assert ((s.return_number >= 1) & (s.return_number <= s.number_of_returns)).all()
    pr = lidarfx.rasterize(s.x, s.y, s.z, s.intensity, s.return_number, s.number_of_returns, 50.0)
    assert pr.points_used == 1065 and int(pr.count.sum()) == 1065


def test_read_survey_keeps_the_crs_and_names_missing_files(data_dir):
    assert lidarfx.read_survey(os.path.join(data_dir, "test_utm17.las")).epsg == 32617
    with pytest.raises(FileNotFoundError, match="no_such.las"):
        lidarfx.read_survey(os.path.join(data_dir, "no_such.las"))
    with pytest.raises((ValueError, RuntimeError), match="README.md"):
        lidarfx.read_survey(os.path.join(data_dir, "README.md"))


def write_tmy3(path, ghi_of_hour):
    """A TMY3 year with only the columns the reader needs; hour h of the year (0..8759) gets GHI ghi_of_hour(h),
    DNI 0 and DHI = GHI (an overcast year), stamped at the end of the hour in local standard time (UTC - 5)."""
    import datetime as dt
    lines = ['723170,"TEST STATION",NC,-5.0,36.1,-79.9,270',
             "Date (MM/DD/YYYY),Time (HH:MM),GHI (W/m^2),DNI (W/m^2),DHI (W/m^2)"]
    start = dt.datetime(2001, 1, 1)
    for h in range(8760):
        end = start + dt.timedelta(hours=h + 1)
        day, hour = (end - dt.timedelta(days=1), 24) if end.hour == 0 else (end, end.hour)
        g = ghi_of_hour(h)
        lines.append(f"{day:%m/%d/%Y},{hour:02d}:00,{g},0,{g}")
    path.write_text("\n".join(lines) + "\n")


def test_read_tmy3_gives_utc_records_and_the_station(tmp_path):
    f = tmp_path / "year.csv"
    write_tmy3(f, lambda h: 100 if 10 <= h % 24 < 16 else 0)
    w = lidarfx.read_tmy3(str(f))
    assert len(w.start_utc) == 8760 and w.interval_s == 3600
    assert w.latitude_deg == pytest.approx(36.1) and w.longitude_deg == pytest.approx(-79.9)
    assert w.utc_offset_h == -5.0
    # The row stamped 01:00 local describes 00:00-01:00 local, which starts at 05:00 UTC.
    assert w.start_utc[0] == np.datetime64("2001-01-01T05:00:00")
    assert w.ghi_w_m2.sum() == pytest.approx(100 * 6 * 365)
    flat = np.zeros((4, 4), np.float32)
    maps = lidarfx.irradiance_maps(flat, 1.0, w)  # the weather carries the site
    assert maps.ghi_kwh_m2 == pytest.approx(0.1 * 6 * 365)
    with pytest.raises(FileNotFoundError):
        lidarfx.read_tmy3(str(tmp_path / "none.csv"))
    bad = tmp_path / "bad.csv"
    bad.write_text("not a tmy3 file\n")
    with pytest.raises((ValueError, RuntimeError), match="bad.csv"):
        lidarfx.read_tmy3(str(bad))
