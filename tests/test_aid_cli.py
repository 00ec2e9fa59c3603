"""End to end: ``pdrlearn track --gnss/--fixes`` on a simulated walk (needs pdrlearn.sim and the track CLI)."""

import json

import numpy as np
import pytest

from pdrlearn.aid.fixgen import gnss_fixes, infrastructure_fixes, write_nmea
from pdrlearn.cli import main

sim = pytest.importorskip("pdrlearn.sim")


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    from pdrlearn.io import write_session

    d = tmp_path_factory.mktemp("aidcli")
    ses = sim.simulate("walk", 3, length_m=150)
    write_session(ses, d / "walk")
    truth = ses.trajectory
    origin = (45.4642, 9.19)
    fx = gnss_fixes(truth, accuracy_m=4.0, origin=origin, seed=7)
    fx[["t", "lat", "lon", "accuracy_m"]].to_csv(d / "gnss.csv", index=False)
    write_nmea(fx, d / "gnss.nmea")
    infrastructure_fixes(truth, seed=7).to_csv(d / "cams.csv", index=False)
    return d, truth


def test_track_with_gnss_and_fixes(walk, capsys):
    d, truth = walk
    rc = main(
        [
            "track",
            "--no-plot",
            str(d / "walk"),
            "--pipeline",
            "waist-pll",
            "--gnss",
            str(d / "gnss.nmea"),
            "--gnss-period",
            "30",
            "--out",
            str(d / "out"),
            "--json",
        ]
    )
    assert rc == 0
    summary = json.loads(capsys.readouterr().out.strip().splitlines()[-1])
    aid = summary["info"]["aid"]["gnss"]
    assert aid["mode"] == "saving" and aid["fixes_used"] >= 2 and 0 < aid["gnss_on_fraction"] < 0.5
    assert aid["bad_checksum"] == 0
    traj = (d / "out" / "trajectory.csv").read_text().splitlines()[0].split(",")
    assert {"x_pdr", "y_pdr", "lat", "lon"} <= set(traj)
    rc = main(
        [
            "track",
            "--no-plot",
            str(d / "walk"),
            "--pipeline",
            "waist-pll",
            "--fixes",
            str(d / "cams.csv"),
            "--fix-period",
            "4",
            "--out",
            str(d / "out2"),
            "--json",
        ]
    )
    assert rc == 0
    aid = json.loads(capsys.readouterr().out.strip().splitlines()[-1])["info"]["aid"]
    assert "fix_table" not in aid  # every fix's row (928 on the docs' D walk) is aided.png's, not the summary's
    assert "fix_table" not in json.loads((d / "out2" / "summary.json").read_text())["info"]["aid"]
    info = aid["fixes"]
    assert info["fixes_used"] >= 5 and info["period_s"] == 4.0
    assert np.isfinite(info["queries_per_min"])


def test_track_with_bad_fix_file_is_one_line_error(walk, capsys, tmp_path):
    d, _ = walk
    bad = tmp_path / "bad.csv"
    bad.write_text("t,lat,lon\n0,45,9\n")
    rc = main(
        [
            "track",
            "--no-plot",
            str(d / "walk"),
            "--pipeline",
            "waist-pll",
            "--gnss",
            str(bad),
            "--out",
            str(tmp_path / "o"),
        ]
    )
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 2 and err[-1].startswith("error: ") and "accuracy_m" in err[-1]


def test_track_warns_when_no_fix_lies_within_the_track(walk, capsys, tmp_path):
    """A fix CSV written with millisecond times (the session files' unit) has every fix after the walk:
    nothing is used, and the user is told so instead of getting the PDR path back silently."""
    import pandas as pd

    d, _ = walk
    cams = pd.read_csv(d / "cams.csv")
    cams = cams[cams["t"] >= 1.0]  # the 150 m walk lasts ~2 min: every fix lands after it in ms
    cams["t"] = cams["t"] * 1000.0
    cams.to_csv(tmp_path / "cams_ms.csv", index=False)
    args = ["track", "--no-plot", str(d / "walk"), "--pipeline", "waist-pll", "--fixes"]
    rc = main(args + [str(tmp_path / "cams_ms.csv"), "--fix-period", "4", "--out", str(tmp_path / "o")])
    assert rc == 0
    err = capsys.readouterr().err
    assert "none of the" in err and "is in seconds on the session clock" in err
    rc = main(args + [str(d / "cams.csv"), "--fix-period", "4", "--out", str(tmp_path / "o2"), "--json"])
    assert rc == 0
    summary = json.loads(capsys.readouterr().out.strip().splitlines()[-1])
    assert not any("none of the" in w for w in summary["info"].get("warnings", []))


def test_track_uses_sporadic_fixes_by_default(walk, capsys, tmp_path):
    """D14: three map-matching fixes at irregular times were silently unused (queries at multiples of their
    median interval); now each is used, and with --fix-period the unused ones are named in one line (D18)."""
    import pandas as pd

    d, truth = walk
    t = truth["t"].to_numpy(float)
    times = np.array([30.0, 60.0, 85.0])
    pd.DataFrame({"t": times, "x": np.interp(times, t, truth["x"]), "y": np.interp(times, t, truth["y"]),
                  "accuracy_m": 1.0}).to_csv(tmp_path / "fix.csv", index=False)
    args = ["track", "--no-plot", str(d / "walk"), "--pipeline", "waist-pll", "--fixes", str(tmp_path / "fix.csv"),
            "--json"]
    assert main(args + ["--out", str(tmp_path / "o")]) == 0
    summary = json.loads(capsys.readouterr().out.strip().splitlines()[-1])
    info = summary["info"]["aid"]["fixes"]
    assert info["fixes_used"] == 3 and info["fixes_unused"] == 0 and info["fixes_read"] == 3
    # D18's line only (W83's waist line says that a recorded wMagneticField.csv is "not used" too)
    assert not any(w.startswith("aid:") and "not used" in w for w in summary["info"].get("warnings", []))
    tr = pd.read_csv(tmp_path / "o" / "trajectory.csv")
    assert np.hypot(tr["x"] - tr["x_pdr"], tr["y"] - tr["y_pdr"]).max() > 0.5
    assert main(args + ["--fix-period", "27.5", "--out", str(tmp_path / "o2")]) == 0
    out = capsys.readouterr()
    warned = json.loads(out.out.strip().splitlines()[-1])["info"]["warnings"]
    line = [w for w in warned if w.startswith("aid:") and "not used" in w]
    assert len(line) == 1 and "--fix-period" in line[0] and "not used" in out.err
