# SPDX-License-Identifier: Apache-2.0
"""Shared fixtures of the lidarfx Python tests: the module under test and small deterministic inputs."""
import os

import numpy as np
import pytest

import lidarfx  # noqa: F401  (the module built in the build tree: PYTHONPATH points at it)


@pytest.fixture
def rng():
    return np.random.default_rng(20261205)


@pytest.fixture
def data_dir():
    """tests/data of the repository (small real LAS/LAZ files and DSMs)."""
    here = os.path.dirname(os.path.abspath(__file__))
    return os.environ.get("LIDARFX_TEST_DATA", os.path.join(here, "..", "..", "tests", "data"))
