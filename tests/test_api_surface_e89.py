"""Decisions E89 (docs/decisions/export.md) and B179-B181 (bad-input.md): the Python API surface a notebook
user meets (session 24 trial, notebook API): path figures discoverable, ``py.typed``, lazy subpackages, one-line
errors for a non-path folder and a misspelled detector setting, a short ``Session`` repr, and
``TrackResult.summary`` refusing a session other than the one tracked.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

import pdrlearn
from pdrlearn.errors import DataError, NotASessionError
from pdrlearn.io import read_session, write_session
from pdrlearn.steps import AccelStepDetector, PLLStepDetector
from pdrlearn.track import get_pipeline

ROOT = Path(__file__).resolve().parents[1]


def test_subpackages_are_lazy_attributes_and_import_pdrlearn_imports_none():
    code = ("import sys, pdrlearn; before = [m for m in sys.modules if m.startswith('pdrlearn.')]; "
            "print(sorted(before)); print(pdrlearn.io.read_session.__module__, pdrlearn.track.plot_paths.__name__)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT,
                         env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin"}, check=True).stdout.splitlines()
    assert out == ["['pdrlearn.errors']", "pdrlearn.io.plasys plot_paths"]
    assert "NotASessionError" in pdrlearn.__all__ and "track" in dir(pdrlearn)
    with pytest.raises(AttributeError, match="has no attribute 'nope'"):
        pdrlearn.nope  # noqa: B018


def test_py_typed_ships_as_package_data():
    assert (ROOT / "pdrlearn" / "py.typed").is_file()
    assert '"py.typed"' in (ROOT / "pyproject.toml").read_text()


def test_path_figures_are_exported_and_a_track_plots_itself(gaitmap_level_left, tmp_path):
    from matplotlib.figure import Figure

    import pdrlearn.track as track

    assert {"path_figure", "plot_paths"} <= set(track.__all__)
    s = read_session(gaitmap_level_left)
    r = get_pipeline("plasys")(s)
    fig = r.plot(s, out=tmp_path / "path.png")
    assert isinstance(fig, Figure) and (tmp_path / "path.png").stat().st_size > 0
    assert [t.get_text() for t in fig.axes[0].get_legend().get_texts()][1].startswith("ground truth")


@pytest.mark.parametrize("fn", [read_session, lambda x: write_session(None, x)])
def test_a_folder_that_is_not_a_path_is_one_line(fn):
    with pytest.raises(NotASessionError, match=r"_session\(42\): expected a session folder, a str or pathlib.Path "
                                               r"\(got int\)"):
        fn(42)


def test_a_misspelled_detector_setting_names_the_closest():
    with pytest.raises(TypeError, match="AccelStepDetector: unexpected keyword argument 'thresh' "
                                        "\\(did you mean 'threshold'\\?\\)"):
        AccelStepDetector(thresh=1)
    assert AccelStepDetector(threshold=2.0).get_params()["threshold"] == 2.0  # valid settings unchanged
    assert "gate_var" in PLLStepDetector().get_params()


def test_session_repr_is_short(gaitmap_level_left):
    s = read_session(gaitmap_level_left)
    text = repr(s)
    assert len(text) < 300 and "array" not in text and "meta" not in text
    assert "fAccelerometer 204.8 Hz m/s^2" in text and "38.71 s" in text and "steps: 28 rows" in text
    assert repr(s.streams["fGyroscope"]) == "Stream('fGyroscope', 7928 samples, 204.8 Hz, 38.71 s, rad/s)"


def test_summary_refuses_another_session(gaitmap_level_left):
    from pdrlearn.sim import simulate

    s = read_session(gaitmap_level_left)
    r = get_pipeline("plasys")(s)
    assert r.summary(s)["session"] == "gaitmap_level_left"
    assert r.summary(read_session(gaitmap_level_left))["distance_m"] == r.distance_m  # read again: the same one
    with pytest.raises(DataError, match="this track is of session 'gaitmap_level_left' .* pass the session you"):
        r.summary(simulate("A", user_seed=1832))
