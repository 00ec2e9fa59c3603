"""Decision E339 (session 52, I3): the lean runtime's foot ``Tracker(altitude="fused")`` and ``pdrlearn run --altitude
fused`` fuse the pushed waist barometer into the strides' heights with L154's filter, shared with offline ``track
--altitude fused`` (:class:`pdrlearn.kernels.barometer.AltitudeFusion`). One short simulated hill walk."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.errors import DataError
from pdrlearn.kernels.barometer import FUSED_WITHOUT_BAROMETER, fuse_altitude, relative_altitude
from pdrlearn.runtime import Tracker, load_bundle
from tests.runtime_helpers import written_route

SHIPPED = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"


@pytest.fixture(scope="module")
def hill(tmp_path_factory):
    from pdrlearn.io import read_session

    folder = written_route(tmp_path_factory.mktemp("e339") / "hill", "stand:2, straight:4, slope:24:12, stand:2", 5339)
    return read_session(folder, streamed=True), folder, load_bundle(SHIPPED)  # what `run` reads


def _live(s, bundle, chunk_s: float, **kw):
    tr = Tracker(bundle, clock_check=False, stream_checks=False, **kw)
    data = {n: (st.t, st.values) for n, st in s.streams.items() if n in tr.used_sensors}
    k = {n: np.floor(t / chunk_s).astype(int) for n, (t, _) in data.items()}
    rows = []
    for c in range(int(max(v.max() for v in k.values())) + 1):
        rows += tr.push({n: (t[k[n] == c], v[k[n] == c]) for n, (t, v) in data.items() if (k[n] == c).any()})
    return tr, rows + tr.flush()


@pytest.fixture(scope="module")
def tracks(hill):
    s, _, bundle = hill
    return {"foot": _live(s, bundle, 1.0)[1], "fused": _live(s, bundle, 1.0, altitude="fused"),
            "fused_0.1": _live(s, bundle, 0.1, altitude="fused")[1]}


def test_the_live_fused_altitude_is_l154s_filter_on_the_live_strides_e339(hill, tracks):
    s, _, _ = hill
    foot, (tr, fused) = tracks["foot"], tracks["fused"]
    assert len(foot) == len(fused) > 12
    b = s["wBarometer"]
    t0, t1 = np.array([r.start_s for r in foot]), np.array([r.end_s for r in foot])
    dz = np.array([r.dz_m for r in foot])
    want = fuse_altitude(dz, t0, t1, b.t, b.values[:, 0])  # the offline kernel (track --altitude fused, L154)
    got = np.array([r.dz_m for r in fused])
    np.testing.assert_allclose(got, want, rtol=0, atol=1e-9)
    # each row's z is the start's plus the fused heights; x, y are the foot track's
    np.testing.assert_allclose([r.z for r in fused], fused[0].z - got[0] + np.cumsum(got), rtol=0, atol=1e-12)
    np.testing.assert_allclose([r.x for r in fused], [r.x for r in foot], rtol=0, atol=1e-9)
    # the climb the barometer reads (the foot's own height misses part of a 12 % slope)
    baro = float(relative_altitude(b.t, b.values[:, 0], [t0[0], t1[-1]])[1])
    assert abs(got.sum() - baro) < 0.5 and abs(got.sum() - baro) < abs(dz.sum() - baro), (got.sum(), dz.sum(), baro)
    assert tr.foot_altitude_change_m == pytest.approx(float(dz.sum()), abs=1e-9)


def test_the_fused_rows_do_not_depend_on_the_chunks_e339(tracks):
    a, b = tracks["fused"][1], tracks["fused_0.1"]
    assert len(a) == len(b)
    for k in ("dz_m", "z", "end_s"):  # E28's chunk tolerance (tests/test_runtime_long_stream.py)
        np.testing.assert_allclose([getattr(r, k) for r in b], [getattr(r, k) for r in a], rtol=0, atol=1e-9)


def test_fused_needs_the_waist_barometer_e339(hill):
    s, _, bundle = hill
    with pytest.raises(DataError, match="altitude='bogus' is not one of foot, fused"):
        Tracker(bundle, altitude="bogus")
    with pytest.raises(DataError, match=r"waist barometer \(wBarometer\).*units \(foot\)"):
        Tracker(bundle, units=("foot",), altitude="fused")
    tr = Tracker(bundle, altitude="fused", sensors=["fAccelerometer", "fGyroscope", "wAccelerometer", "wGyroscope"])
    assert tr._fused is None and tr.foot_altitude_change_m is None
    assert [w for w in tr.warnings if "wBarometer.csv), which the declared streams (sensors=" in w]  # E363


def test_run_altitude_fused_writes_the_fused_track_e339(hill, tracks, tmp_path, capsys):
    from pdrlearn.cli import main

    _, folder, _ = hill
    assert main(["run", str(SHIPPED), str(folder), "--altitude", "fused", "--no-plot", "--out",
                 str(tmp_path / "f")]) == 0, capsys.readouterr().err
    steps = pd.read_csv(tmp_path / "f" / "steps.csv")
    live = tracks["fused"][1]
    np.testing.assert_allclose(steps["dz_m"], [r.dz_m for r in live], rtol=0, atol=1e-9)
    summary = json.loads((tmp_path / "f" / "summary.json").read_text())
    assert summary["info"]["altitude_source"] == "fused" and summary["barometer_unused"] is False
    assert summary["altitude_change_m"] == pytest.approx(sum(r.dz_m for r in live), abs=1e-6)
    assert summary["final_position"]["z"] == pytest.approx(live[-1].z, abs=1e-6)
    assert main(["run", str(SHIPPED), "--protocol", "-", "--altitude", "fused"]) != 0
    assert "carries the foot unit only: drop --altitude" in capsys.readouterr().err



def test_a_row_waits_for_the_barometer_past_its_end_e339():
    from types import SimpleNamespace

    from pdrlearn.runtime.baro_fusion import FusedRows

    f = FusedRows("wBarometer")
    t = np.arange(0.0, 10.25, 0.1)
    f.push(t, np.full((len(t), 1), 1000.0))
    row = SimpleNamespace(start_s=8.8, end_s=10.0, dz_m=0.05, z=0.05)
    assert f.rows([row], latest=10.2) == []  # W89's window past 10.0 s not pushed yet
    t = np.arange(10.3, 10.75, 0.1)
    f.push(t, np.full((len(t), 1), 1000.0))
    out = f.rows([], latest=10.7)
    assert out == [row] and row.dz_m != 0.05 and abs(row.dz_m) < 0.05  # fused: the barometer says level
    late = SimpleNamespace(start_s=10.0, end_s=11.2, dz_m=0.0, z=row.z)
    assert f.rows([late], latest=11.0) == [] and f.rows([], latest=14.3) == [late]  # a stopped barometer: 2 s on
    last = SimpleNamespace(start_s=11.2, end_s=12.4, dz_m=0.0, z=row.z)
    assert f.rows([last], latest=12.5, final=True) == [last]


def test_run_units_foot_refuses_fused_before_the_replay_e339(hill, tmp_path, capsys):
    from pdrlearn.cli import main

    _, folder, _ = hill
    assert main(["run", str(SHIPPED), str(folder), "--units", "foot", "--altitude", "fused", "--out",
                 str(tmp_path / "u")]) != 0
    assert "--units foot leaves out: add waist to --units" in capsys.readouterr().err
    assert not (tmp_path / "u" / "steps.csv").exists()


def test_run_fused_on_a_foot_only_recording_keeps_the_foots_altitude_e339(hill, tracks, tmp_path, capsys):
    """As `track --altitude fused` (L154): a recording without the waist unit is tracked with the foot's altitude and
    L154's one line (before the amendment `run` refused it: the two-unit bundle falls back to the foot, E26)."""
    import shutil

    from pdrlearn.cli import main

    _, folder, _ = hill
    foot_only = tmp_path / "foot_only"
    shutil.copytree(folder, foot_only)
    for f in foot_only.glob("w*.csv"):
        f.unlink()
    assert main(["run", str(SHIPPED), str(foot_only), "--altitude", "fused", "--no-plot", "--out",
                 str(tmp_path / "o")]) == 0
    assert FUSED_WITHOUT_BAROMETER in capsys.readouterr().err
    summary = json.loads((tmp_path / "o" / "summary.json").read_text())
    assert summary["info"].get("altitude_source") != "fused"
