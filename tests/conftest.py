"""Shared fixtures: paths to the bundled real recordings and a temporary session factory."""

from __future__ import annotations

from pathlib import Path

import matplotlib
import pytest

matplotlib.use("Agg")

ROOT = Path(__file__).resolve().parents[1]
REAL = ROOT / "datasets" / "real"


@pytest.fixture(scope="session")
def real_dir() -> Path:
    return REAL


@pytest.fixture(scope="session")
def gaitmap_level_left() -> Path:
    return REAL / "gaitmap_level_left"


@pytest.fixture(scope="session")
def mobgap_test5() -> Path:
    return REAL / "mobgap_HA001_Test5_Trial1"
