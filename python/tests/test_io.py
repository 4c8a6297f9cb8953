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
