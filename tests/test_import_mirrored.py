"""Decision L71 (new-user trial s15, finding 8): `pdrlearn import` wrote a mirrored export (acc_y and gyr_y
negated) without a word; `track` refused it later with "negate the mirrored axis back" without naming the
axis. The import now runs the same check (D11, :func:`pdrlearn.io.handedness.check_handedness`) and refuses,
naming the axis and the --acc/--gyro options that negate it back; track's message names the axis too."""

from __future__ import annotations

import shlex
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.io.handedness import PITCH_AXIS_MAX_DEG, Handedness, mirror_fix_text, pitch_axis

FOOT = Path(__file__).resolve().parents[1] / "datasets" / "real" / "gaitmap_level_right"  # y = medio-lateral


def _export(path: Path, mirror: str | None) -> Path:
    """The foot unit of gaitmap_level_right as one lab CSV, one axis negated in both sensors (``mirror``)."""
    s = read_session(FOOT)
    a, w = s["fAccelerometer"], s["fGyroscope"]
    df = pd.DataFrame({"time_s": a.t - a.t[0], **{f"acc_{c}": a.values[:, i] for i, c in enumerate("xyz")},
                       **{f"gyr_{c}": np.interp(a.t, w.t, w.values[:, i]) for i, c in enumerate("xyz")}})
    if mirror:
        df[f"acc_{mirror}"] *= -1
        df[f"gyr_{mirror}"] *= -1
    df.to_csv(path, index=False, float_format="%.9g")
    return path


@pytest.mark.parametrize("mirror", ["y", "z"])
def test_mirrored_export_is_refused_naming_the_axis_and_the_options_fix_it(tmp_path, capsys, mirror):
    csv = _export(tmp_path / "lab.csv", mirror)
    out = tmp_path / "s"
    assert main(["import", str(csv), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "mirrored" in err and "nothing written" in err
    assert not out.exists()
    # the lateral axis (y) is named whichever axis was negated: any one makes the pair right-handed
    assert "negate the y axis back" in err and "if the export negated another one" in err
    fix = err[err.index("import again with ") + len("import again with "):].split(": the foot")[0]
    opts = shlex.split(fix)
    assert opts == ["--acc=acc_x,-acc_y,acc_z", "--gyro=gyr_x,-gyr_y,gyr_z"]
    assert main(["import", str(csv), "--out", str(out), *opts]) == 0  # the printed fix imports
    s = read_session(out)
    h = s.handedness("foot")
    assert not h.mirrored and h.verdict == "right-handed", h.describe()
    if mirror == "y":  # the original data back, bit for bit up to the CSV's 9 digits
        ref = read_session(FOOT)["fAccelerometer"].values
        assert np.allclose(s["fAccelerometer"].values, ref, rtol=1e-6, atol=1e-6)


def test_truthful_export_imports_without_a_warning(tmp_path, capsys):
    csv = _export(tmp_path / "lab.csv", None)
    assert main(["import", str(csv), "--out", str(tmp_path / "s")]) == 0
    assert "mirrored" not in capsys.readouterr().err


def test_pitch_axis_and_the_unnamed_case():
    rng = np.random.default_rng(0)
    g = rng.normal(0, 0.3, (2000, 3))
    g[:, 2] += 5 * np.sin(np.linspace(0, 60, 2000))  # the foot pitches about z
    k, deg = pitch_axis(g)
    assert k == 2 and deg < 10
    assert pitch_axis(np.zeros((10, 3)))[0] == -1
    h = Handedness("foot", -2.0, 10, pitch_axis=2, pitch_deg=deg)
    assert h.mirror_axis == "z" and "negate the z axis back" in mirror_fix_text(h, "fAccelerometer", "fGyroscope")
    h = Handedness("foot", -2.0, 10, pitch_axis=2, pitch_deg=PITCH_AXIS_MAX_DEG + 1)
    text = mirror_fix_text(h, "fAccelerometer", "fGyroscope")
    assert h.mirror_axis is None and "the data do not show which axis" in text
