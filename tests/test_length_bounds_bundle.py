"""A length model without the user's length-class bounds (docs/decisions/localization.md L59, L60): the export
records none and warns, the runtime skips the length rule and warns (offline track's line), as ``track`` and
``track --streaming`` do; a bundle exported before L59 with the thesis fallback runs like a new one; a bundle
with the user's bounds is unchanged. L50's case: simulated user 1, scenario A, 20.00 m of labelled strides."""

from __future__ import annotations

import json
import logging
import shutil

import numpy as np
import pytest

from pdrlearn.classify import train_user
from pdrlearn.cli import main
from pdrlearn.export.from_model import export_model
from pdrlearn.io import write_session
from pdrlearn.kernels.stride import NO_BOUNDS_SOURCE, THESIS_FALLBACK_SOURCE
from pdrlearn.runtime import Tracker
from pdrlearn.runtime.bundle import MANIFEST_SHA, sha256_file
from pdrlearn.sim import simulate
from pdrlearn.track.plasys import track_plasys
from tests.runtime_helpers import replay

NO_BOUNDS = "carries no length-class bounds (length_bounds_m)"
FIX = "length_m labels"  # the fix the line names (L59)
#: the thesis step bounds x 2 of an export before L59 (docs/decisions/localization.md L9)
FALLBACK = {"short": [0.0, 0.60], "normal": [0.60, 0.90], "long": [0.92, 20.0]}


def _without_bounds(s):
    """The session without its declared length-class bounds (L50: meta.json's ``length_class_bounds_m``)."""
    s.meta = {k: v for k, v in s.meta.items() if k != "length_class_bounds_m"}
    return s


@pytest.fixture(scope="module")
def case(tmp_path_factory):
    """User 1's length exercise labelled with classes but no ``length_m`` (so no bounds), its heuristic foot
    length model and that model's bundle; scenario A of the same user without its bounds."""
    root = tmp_path_factory.mktemp("nobounds")
    cal = _without_bounds(simulate("length", user_seed=1, speed="normal"))
    user_bounds = list(simulate("length", user_seed=1, speed="normal").meta["length_class_bounds_m"])
    cal.steps = cal.steps.drop(columns=["length_m"])
    model = train_user([cal], tasks=["length"], methods=["heuristic"], units=["foot"], cv=5)
    assert "length_bounds_m" not in model.data_summary
    model.save(root / "model")
    scen = _without_bounds(simulate("A", user_seed=1, speed="normal"))
    write_session(scen, root / "A")
    return {"root": root, "model": model, "A": scen, "user_bounds": user_bounds}


def _xyz(steps) -> np.ndarray:
    return np.array([[st.x, st.y, st.z] for st in steps])


def _rewrite(bundle, edit) -> None:
    m = json.loads((bundle / "manifest.json").read_text())
    edit(m["displacement"])
    (bundle / "manifest.json").write_text(json.dumps(m))
    (bundle / MANIFEST_SHA).write_text(f"{sha256_file(bundle / 'manifest.json')}  manifest.json\n")


def test_export_of_a_model_without_bounds_records_none_and_warns(case, tmp_path, caplog):
    with caplog.at_level(logging.WARNING):
        export_model(case["root"] / "model", tmp_path / "b")
    disp = json.loads((tmp_path / "b" / "manifest.json").read_text())["displacement"]
    assert disp["length_bounds_m"] is None and disp["length_bounds_source"] == NO_BOUNDS_SOURCE == "none"
    lines = [r.getMessage() for r in caplog.records if NO_BOUNDS in r.getMessage()]
    assert len(lines) == 1 and FIX in lines[0] and "--length-bounds" in lines[0] and str(case["root"]) in lines[0]
    # with the user's bounds: recorded as before (source "user"), no warning
    caplog.clear()
    with caplog.at_level(logging.WARNING):
        export_model(case["root"] / "model", tmp_path / "u", length_bounds=case["user_bounds"])
    disp = json.loads((tmp_path / "u" / "manifest.json").read_text())["displacement"]
    assert disp["length_bounds_source"] == "user"
    assert disp["length_bounds_m"]["normal"] == pytest.approx(case["user_bounds"])
    assert not any(NO_BOUNDS in r.getMessage() for r in caplog.records)


def test_export_cli_prints_the_warning_once(case, tmp_path, capsys):
    assert main(["export", str(case["root"] / "model"), "--out", str(tmp_path / "b")]) == 0
    err = capsys.readouterr().err
    assert sum(NO_BOUNDS in ln for ln in err.splitlines()) == 1 and err.startswith("warning: ")


@pytest.mark.parametrize("rules", ["bayes", "thesis"])
def test_runtime_without_bounds_equals_streaming_track_and_skips_the_clamp(case, tmp_path, rules):
    """L50: with the thesis fallback the runtime clamped A's 1.3 m strides to 0.60 / 0.90 m (-27 %)."""
    export_model(case["root"] / "model", tmp_path / "b")
    s = case["A"]
    res = track_plasys(s, method="M3", model=case["model"], streaming=True, rules=rules, heading="foot")
    assert res.info["length_bounds_m"] is None
    assert sum(NO_BOUNDS in w and FIX in w for w in res.info["warnings"]) == 1
    tr = Tracker(tmp_path / "b", rules=rules, heading_source="foot")  # the sim parity tests' heading
    assert tr.bounds is None
    steps = replay(tr, s)
    ours = [w for w in tr.warnings if NO_BOUNDS in w]
    theirs = [w for w in res.info["warnings"] if NO_BOUNDS in w]
    assert len(ours) == 1 and ours[0].split(NO_BOUNDS)[1] == theirs[0].split(NO_BOUNDS)[1]  # offline's wording
    assert len(steps) == len(res.steps) >= 14
    assert np.abs(_xyz(steps) - res.trajectory[["x", "y", "z"]].to_numpy()[1:]).max() < 1e-3  # issue 7: 1 mm
    dist = sum(abs(st.length_m) for st in steps)
    assert dist == pytest.approx(float(np.abs(res.steps["length_m"]).sum()), abs=1e-3)
    ref = float(s.steps["length_m"].sum())
    assert abs(dist / ref - 1) < 0.03  # no stride clamped into the fallback's 0.60-0.90 m
    # the length rule is skipped: each stride keeps its measured length, whatever its class
    raw = res.steps["raw_length_m"].to_numpy()
    np.testing.assert_allclose([st.length_m for st in steps], raw * res.info["distance_gain"], atol=1e-6)


def test_offline_track_skips_the_clamp_with_the_same_line(case):
    res = track_plasys(case["A"], method="M3", model=case["model"], rules="thesis")
    assert sum(NO_BOUNDS in w and FIX in w for w in res.info["warnings"]) == 1
    assert res.info["length_bounds_m"] is None


def test_old_bundle_with_the_thesis_fallback_runs_like_a_new_one(case, tmp_path, monkeypatch):
    export_model(case["root"] / "model", tmp_path / "new")
    old = tmp_path / "old"
    shutil.copytree(tmp_path / "new", old)
    _rewrite(old, lambda d: d.update(length_bounds_m=FALLBACK, length_bounds_source=THESIS_FALLBACK_SOURCE))
    older = tmp_path / "older"  # exported before the source field (8e1520d): the fallback in every bundle, no source
    shutil.copytree(old, older)
    _rewrite(older, lambda d: d.pop("length_bounds_source"))
    s = case["A"]
    for rules in ("thesis", "bayes"):
        new_xyz = _xyz(replay(Tracker(tmp_path / "new", rules=rules), s))
        for b in (old, older):
            old_tr = Tracker(b, rules=rules)
            assert old_tr.bounds is None
            lines = [w for w in old_tr.warnings if NO_BOUNDS in w]
            assert len(lines) == 1 and "exported before decision L59" in lines[0] and FIX in lines[0]
            np.testing.assert_array_equal(_xyz(replay(old_tr, s)), new_xyz)
    # the same fallback bounds given as the user's (source "user"), or other bounds without a source, still clamp
    user = tmp_path / "user_fallback"
    shutil.copytree(old, user)
    _rewrite(user, lambda d: d.update(length_bounds_source="user"))
    tr = Tracker(user, rules="thesis")
    assert tr.bounds is not None and not any(NO_BOUNDS in w for w in tr.warnings)
    # decision C191 gives a stride the class of a measured length the class contradicts (here every 1.3 m stride
    # classed normal reads long and is not clamped): off, so that the clamp itself is what this checks
    monkeypatch.setattr("pdrlearn.kernels.turn_length.CONTRADICTION_MARGIN", float("inf"))
    assert sum(abs(st.length_m) for st in replay(tr, s)) < 0.85 * float(s.steps["length_m"].sum())  # L50: -27 %
    hand = tmp_path / "hand_written"
    shutil.copytree(older, hand)
    _rewrite(hand, lambda d: d.update(length_bounds_m={**FALLBACK, "normal": [0.60, 0.95]}))
    assert Tracker(hand, rules="thesis").bounds["normal"] == (0.60, 0.95)


def test_bundle_with_the_users_bounds_is_unchanged(case, tmp_path):
    """Measured bounds: the runtime reads them as before L59 (no warning) and equals track --streaming with them."""
    export_model(case["root"] / "model", tmp_path / "b", length_bounds=case["user_bounds"])
    s = case["A"]
    for rules in ("thesis", "bayes"):
        res = track_plasys(s, method="M3", model=case["model"], streaming=True, rules=rules, heading="foot",
                           bounds=case["user_bounds"])
        assert not any(NO_BOUNDS in w for w in res.info["warnings"])
        tr = Tracker(tmp_path / "b", rules=rules, heading_source="foot")
        lo, hi = case["user_bounds"]
        assert tr.bounds == {"short": (0.0, lo), "normal": (lo, hi), "long": (hi, 10.0)}
        assert not any(NO_BOUNDS in w for w in tr.warnings)
        steps = replay(tr, s)
        assert np.abs(_xyz(steps) - res.trajectory[["x", "y", "z"]].to_numpy()[1:]).max() < 1e-3
        if rules == "thesis":  # the clamp acts: every stride of a class lies in that class's bounds
            for st in steps:
                c = st.classes.get("length")
                assert tr.bounds[c][0] - 1e-9 <= abs(st.length_m) <= tr.bounds[c][1] + 1e-9


def test_streaming_oracle_without_session_bounds_warns_as_offline(case):
    """L60: oracle labels without bounds keep L9's fallback, offline and streamed, with offline's line."""
    line = "no length-class bounds in the session: thesis step bounds x 2 used"
    for streaming in (False, True):
        res = track_plasys(case["A"], method="M3", model="oracle", streaming=streaming)
        assert line in res.info["warnings"]
        assert res.info["length_bounds_m"]["normal"] == pytest.approx((0.60, 0.90))


def test_run_cli_with_thesis_rules_on_a_no_bounds_bundle(case, tmp_path, capsys):
    export_model(case["root"] / "model", tmp_path / "b")
    assert main(["run", "--no-plot", str(tmp_path / "b"), str(case["root"] / "A"), "--rules", "thesis", "--out",
                 str(tmp_path / "run"), "--json"]) == 0
    cap = capsys.readouterr()
    out = json.loads(cap.out)
    assert sum(NO_BOUNDS in ln for ln in cap.err.splitlines()) == 1
    assert abs(out["distance_error_pct"]) < 3.0  # L50: -27.3 % with the fallback clamp
