"""Decision B48: `pdrlearn import --acc=-ax,-ay,-az` negates columns (iOS Core Motion reports gravity as -1 g);
the mirrored-data test (D11) cannot see an un-negated iOS accelerometer (d(g)/dt = -omega x g is unchanged by
g -> -g), so the docs tell the user instead."""

from __future__ import annotations

import json
import logging
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session

ROOT = Path(__file__).resolve().parents[1]
T11 = ROOT / "datasets" / "real" / "mobgap_HA001_Test11_Trial1"
T5 = ROOT / "datasets" / "real" / "mobgap_HA001_Test5_Trial1"
G = 9.80665


def _ios_export(path: Path) -> tuple[Path, object]:
    """HA001 Test11 as an iPhone export: acceleration in g with gravity -1 g (the specific force negated)."""
    s = read_session(T11)
    a, w = s["wAccelerometer"], s["wGyroscope"]
    df = pd.DataFrame({"t_s": a.t - a.t[0],
                       **{f"acc{c}(G)": -a.values[:, i] / G for i, c in enumerate("XYZ")},
                       **{f"rot{c}(rad/s)": w.values[:, i] for i, c in enumerate("XYZ")}})
    df.to_csv(path, index=False, float_format="%.9g")
    return path, s


def test_minus_name_negates_the_column(tmp_path, capsys):
    csv, s = _ios_export(tmp_path / "ios.csv")
    out = tmp_path / "ip"
    assert main(["import", str(csv), "--out", str(out), "--unit", "waist", "--time", "t_s",
                 "--acc=-accX(G),-accY(G),-accZ(G)", "--gyro", "rotX(rad/s),rotY(rad/s),rotZ(rad/s)"]) == 0
    err = capsys.readouterr().err  # the summary shows the negation it applied
    assert "wAccelerometer: -accX(G),-accY(G),-accZ(G) (given)" in err
    assert "wGyroscope: rotX(rad/s),rotY(rad/s),rotZ(rad/s) (given)" in err
    got = read_session(out)
    np.testing.assert_allclose(got["wAccelerometer"].values, s["wAccelerometer"].values, rtol=1e-6, atol=1e-6)
    np.testing.assert_allclose(got["wGyroscope"].values, s["wGyroscope"].values, rtol=1e-6, atol=1e-9)
    rec = json.loads((out / "meta.json").read_text())["imported"]["streams"]
    assert rec["wAccelerometer"]["negated"] == ["accX(G)", "accY(G)", "accZ(G)"]
    assert "negated" not in rec["wGyroscope"]
    # a file whose column really is called "-x" keeps it as it is
    df = pd.DataFrame({"t": [0.01 * i for i in range(300)], "-x": [9.8] * 300, "y": [0.0] * 300, "z": [0.0] * 300})
    df.to_csv(tmp_path / "m.csv", index=False)
    from pdrlearn.io.importer import signed_columns

    assert signed_columns(["-x", "-y", "z"], list(df.columns)) == (["-x", "y", "z"], pytest.approx([1, -1, 1]))


def test_d11_cannot_see_an_un_negated_ios_accelerometer():
    """The waist D11 log ratio of the recording and of its accelerometer negated are the same (measured on the
    trial's iPhone export: +1.94 both ways; it is not the test that can catch the iOS sign)."""
    from pdrlearn.io.handedness import check_handedness
    from pdrlearn.io.session import Stream

    logging.disable(logging.WARNING)
    try:
        s = read_session(T5)
        h0, _ = check_handedness(s, "waist", ratio=True)
        neg = read_session(T5)
        a = neg["wAccelerometer"]
        neg.streams["wAccelerometer"] = Stream(a.name, a.t, -a.values)
        h1, _ = check_handedness(neg, "waist", ratio=True)
    finally:
        logging.disable(logging.NOTSET)
    assert h0.log_ratio > 0.1 and h0.segments >= 4 and h1.log_ratio == pytest.approx(h0.log_ratio, abs=0.05)


def test_declared_frame_against_an_ios_accelerometer_names_the_sign(caplog):
    """The true frame declared over an un-negated iOS accelerometer: the D10 warning used to say only "write the
    data's frame" (a 180-degree turn that mirrors every turn); it now names the -1 g convention (B48)."""
    from pdrlearn.io.session import Stream
    from pdrlearn.track.frame_inference import check_declared_frame

    s = read_session(T5)
    a = s["wAccelerometer"]
    s.streams["wAccelerometer"] = Stream(a.name, a.t, -a.values)
    msg = check_declared_frame(s, "waist", s.frames["waist"]).message
    assert msg is not None and "gravity as -1 g" in msg and "--acc=-X,-Y,-Z" in msg
    assert check_declared_frame(read_session(T5), "waist", s.frames["waist"]).message is None
