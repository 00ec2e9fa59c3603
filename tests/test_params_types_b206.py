"""Decisions B206-B211 (trial fuzz, session 26): the foot --params types and ranges, model manifests with wrong
types, oracle labels that are no classes, clearer lines (--initial-heading, plot's window, waist params, score_steps,
the CV grouping used) and a model from another version. Each bad input is one ``error:`` line, no traceback."""

from __future__ import annotations

import json
import logging
import math
import re

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError, ModelError
from tests._shared_i2 import cli_sessions


@pytest.fixture(scope="module")
def base(tmp_path_factory):
    """The terrain exercise of user 3 and a heuristic model trained on it, made once per test run
    (:func:`tests._shared_i2.cli_sessions`, the set-up of :func:`tests.cli_helpers.simulated_session_and_model`):
    read-only, every test that edits one copies it."""
    shared = cli_sessions(tmp_path_factory)
    return {"root": shared["root"], "good": shared["terrain"], "model": shared["model"]}


def error_line(argv: list[str], capsys) -> str:
    """Run the CLI: exit 2, one ``error:`` line (warnings before it allowed), no traceback; the message."""
    rc = main(argv)
    err = capsys.readouterr().err
    errors = [ln for ln in err.splitlines() if ln.startswith("error: ")]
    assert rc == 2 and len(errors) == 1 and "Traceback" not in err, (rc, err)
    return errors[0][len("error: "):]


FOOT_PARAMS = [
    ({"timestamps": "no"}, "timestamps='no' is not true or false"),
    ({"timestamps": "yes"}, "timestamps='yes' is not true or false"),
    ({"timestamps": 1}, "timestamps=1 is not true or false"),
    ({"gap_yaw": None}, "gap_yaw=None is not true or false"),
    ({"rest_s": -1}, "rest_s=-1 is not a positive number"),
    ({"max_stride_s": 0}, "max_stride_s=0 is not a positive number"),
    ({"rest_s": "abc"}, "rest_s='abc' is not a positive number"),
    ({"upsample": "no"}, "upsample='no' is not a whole number >= 1 or null"),
    ({"upsample": 2.5}, "upsample=2.5 is not a whole number >= 1 or null"),
    ({"zupt_erode": "no"}, "zupt_erode='no' is not a number from 0 to 0.5"),
    ({"zupt_erode": 0.7, "sw": float("nan")}, "sw=nan is not a positive number; zupt_erode=0.7 is not a number "
                                              "from 0 to 0.5"),  # in the signature's order
    ([1, 2], "parameters must be a JSON object ({\"key\": value, ...}), not a JSON list"),
    ("hello", "parameters must be a JSON object ({\"key\": value, ...}), not a JSON string"),
]


@pytest.mark.parametrize(("params", "said"), FOOT_PARAMS, ids=[json.dumps(p) for p, _ in FOOT_PARAMS])
def test_foot_params_of_the_wrong_type_or_range_are_one_line_naming_the_file(base, tmp_path, capsys, params, said):
    """B206 / B207: text flags had been read as true, -1 s accepted, a list or "abc" a TypeError traceback, a
    string "unknown parameter(s) e, h, l, o"."""
    p = tmp_path / "p.json"
    p.write_text(json.dumps(params))
    msg = error_line(["track", str(base["good"]), "--params", str(p), "--out", str(tmp_path / "o")], capsys)
    assert msg.startswith(f"{p}: ") and said in msg, msg
    assert not (tmp_path / "o").exists()


def test_foot_params_python_api_and_the_good_values_still_track(base):
    from pdrlearn.displace import FootDisplacement
    from pdrlearn.io import read_session
    from pdrlearn.track.base import get_pipeline

    s = read_session(base["good"])
    with pytest.raises(DataError, match=r"plasys params: parameters must be a JSON object .* not list \[1, 2\]"):
        get_pipeline("plasys")(s, params=[1, 2])
    with pytest.raises(DataError, match="plasys params: timestamps='no' is not true or false"):
        get_pipeline("plasys")(s, params={"timestamps": "no"})
    with pytest.raises(DataError, match="FootDisplacement: rest_s=-1 is not a positive number"):
        FootDisplacement(rest_s=-1)
    with pytest.raises(TypeError, match="plasys: model=42 is not a model: pass a trained model directory"):
        get_pipeline("plasys")(s, model=42)  # B208
    a = get_pipeline("plasys")(s, params={"timestamps": True, "upsample": None, "zupt_erode": 0})
    b = get_pipeline("plasys")(s, params={"timestamps": False, "upsample": 5, "rest_s": 0.05})
    assert len(a.steps) and len(b.steps)


def _manifest_edit(src, dst, fn):
    import shutil

    shutil.copytree(src, dst)
    m = json.loads((dst / "manifest.json").read_text())
    fn(m)
    (dst / "manifest.json").write_text(json.dumps(m))
    return dst


def test_a_model_manifest_with_wrong_types_is_one_line(base, tmp_path, capsys):
    """B208: "tasks": "oops" had been an AttributeError in track / evaluate / export, a chosen unit "nosuch" a
    KeyError."""
    from pdrlearn.classify import load_model

    oops = _manifest_edit(base["model"], tmp_path / "oops", lambda m: m.update(tasks="oops"))
    for argv in (["track", str(base["good"]), "--model", str(oops), "--out", str(tmp_path / "o")],
                 ["evaluate", str(oops), str(base["good"])],
                 ["export", str(oops), "--out", str(tmp_path / "b")]):
        msg = error_line(argv, capsys)
        assert msg.startswith(f"{oops / 'manifest.json'}: 'tasks' is 'oops', not an object"), msg

    def unit(m):
        m["tasks"]["terrain"]["chosen"]["unit"] = "nosuch"

    nosuch = _manifest_edit(base["model"], tmp_path / "nosuch", unit)
    with pytest.raises(ModelError, match=r"task 'terrain': chosen .*'nosuch'.* is not one of its models \(heuristic/"):
        load_model(nosuch)


def test_a_model_from_other_versions_loads_with_one_warning(base, tmp_path, caplog):
    """B211: package_version 9.9.9 and scikit-learn 0.1 had loaded without a word."""
    import sklearn

    import pdrlearn
    from pdrlearn.classify import load_model

    def other(m):
        m["package_version"] = "9.9.9"
        m["versions"]["scikit-learn"] = "0.1"

    old = _manifest_edit(base["model"], tmp_path / "old", other)
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        load_model(old)
    lines = [r.getMessage() for r in caplog.records if "trained with" in r.getMessage()]
    assert lines == [f"model {old}: trained with pdrlearn 9.9.9 (this is {pdrlearn.__version__}), scikit-learn 0.1 "
                     f"(this is {sklearn.__version__}); it loads (same schema version 1), but retrain it with these "
                     "versions if its classes look wrong"]
    caplog.clear()
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        load_model(base["model"])
    assert not [r for r in caplog.records if "trained with" in r.getMessage()]


def test_oracle_with_labels_that_are_no_classes_warns_as_evaluate(base, tmp_path):
    """B209: every terrain label 'lava' had tracked with --model oracle without a word."""
    import shutil

    from pdrlearn.io import read_session
    from pdrlearn.track.base import get_pipeline

    d = shutil.copytree(base["good"], tmp_path / "lava")
    st = pd.read_csv(d / "steps.csv")
    st["terrain"] = "lava"
    st.to_csv(d / "steps.csv", index=False)
    res = get_pipeline("plasys")(read_session(d), model="oracle")
    lines = [w for w in res.info["warnings"] if "'lava'" in w]
    assert len(lines) == 1 and lines[0].startswith(f"steps.csv: {len(st)} of {len(st)} step(s) have a 'terrain' "
                                                   "label that is not a terrain class"), lines
    assert "model='oracle' takes the labels as the strides' classes" in lines[0]
    clean = get_pipeline("plasys")(read_session(base["good"]), model="oracle")
    assert not [w for w in clean.info["warnings"] if "label that is not" in w]


def test_initial_heading_out_of_range_is_said_in_degrees_by_track_and_run(base, tmp_path, capsys):
    """B210: -720 had given Python advice with the converted radians; `run` accepted 1e9."""
    for argv in (["track", str(base["good"]), "--initial-heading", "-720", "--out", str(tmp_path / "o")],
                 ["run", str(tmp_path / "no-bundle"), str(base["good"]), "--initial-heading", "1e9"]):
        msg = error_line(argv, capsys)
        assert msg.startswith("--initial-heading ") and "degrees from -360 to 360" in msg and "radians" not in msg
    from pdrlearn.cli.common import initial_heading_option

    assert initial_heading_option(-360) == pytest.approx(-2 * math.pi)


def test_plot_window_reversed_is_said_so(base, tmp_path, capsys):
    """B210: start 100 > end 50 had said "outside the session"."""
    msg = error_line(["plot", str(base["good"]), "--start", "100", "--end", "50", "--out", str(tmp_path / "p.png")],
                     capsys)
    assert "--end 50 s is not after --start 100 s" in msg


def test_waist_params_negative_threshold_and_unknown_gait_key_are_refused(tmp_path):
    """B210: walk_threshold_mps2 -1 had been used (more steps), gait {"cadence_spm": "fast"} ignored."""
    from pdrlearn.waist.params import WaistParams, load_params

    base = WaistParams().to_dict()
    for extra, said in [({"walk_threshold_mps2": -1}, "parameter walk_threshold_mps2=-1 is not a positive number"),
                        ({"gait": {"cadence_spm": "fast"}}, "gait has no key(s) cadence_spm"),
                        ({"gait": {"median_cadence_spm": "fast"}},
                         "gait median_cadence_spm='fast' is not a positive number")]:
        (tmp_path / "w.json").write_text(json.dumps({**base, **extra}))
        with pytest.raises(DataError, match=re.escape(f"w.json: {said}")):
            load_params(tmp_path / "w.json")
    (tmp_path / "w.json").write_text(json.dumps({**base, "walk_threshold_mps2": 0.4}))
    assert load_params(tmp_path / "w.json").walk_threshold_mps2 == 0.4


def test_score_steps_refuses_an_event_without_a_time(base):
    """B210: a NaN event_s had been counted (count 2) but never scored, silently."""
    from pdrlearn.io import read_session
    from pdrlearn.steps.evaluate import score_steps

    s = read_session(base["good"])
    with pytest.raises(DataError, match=r"score_steps: 1 of 2 step event\(s\) have no finite event_s \(first: row 0"):
        score_steps(pd.DataFrame({"event_s": [np.nan, 6.0], "unit": "foot"}), s)


def test_train_records_the_cv_grouping_the_folds_used(base, tmp_path, capsys):
    """B210: --cv-groups session on one session fell back to stratified folds, and the JSON and manifest said
    "session"."""
    out = tmp_path / "m"
    assert main(["train", str(base["good"]), "--out", str(out), "--methods", "heuristic", "--tasks", "terrain",
                 "--cv", "3", "--cv-groups", "session", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert (d["cv_groups"], d["cv_groups_asked"], d["cv_groups_by_task"], d["cv_sessions"]) == (
        "steps", "session", {"terrain": "steps"}, 0)
    settings = json.loads((out / "manifest.json").read_text())["settings"]
    assert (settings["cv_groups"], settings["cv_groups_asked"]) == ("steps", "session")


def test_a_waist_bundle_from_another_version_loads_with_b137s_warning(tmp_path, caplog):
    """B211: the waist bundle had loaded another version without a word (the foot bundle says B137's line)."""
    import shutil

    from pdrlearn import __version__
    from pdrlearn.export.waist import export_waist
    from pdrlearn.runtime import load_waist_bundle
    from pdrlearn.runtime.bundle import MANIFEST_SHA, sha256_file
    from pdrlearn.sim import simulate
    from pdrlearn.waist.calibration import calibrate

    s = simulate("A", 2801, rate_hz=100.0)
    calibrate([s], "waist-pendulum", distances=[20.0]).save(tmp_path / "cal.json")
    frame = ",".join(f"{k}={v}" for k, v in s.require_frame("waist").to_dict().items())
    export_waist(tmp_path / "cal.json", tmp_path / "wb", frame=frame)
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        load_waist_bundle(tmp_path / "wb")
    assert "exported by pdrlearn" not in caplog.text
    b = shutil.copytree(tmp_path / "wb", tmp_path / "old")
    m = json.loads((b / "manifest.json").read_text())
    m["package_version"] = "9.9.0"
    (b / "manifest.json").write_text(json.dumps(m))
    (b / MANIFEST_SHA).write_text(f"{sha256_file(b / 'manifest.json')}  manifest.json\n")
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        load_waist_bundle(b)
    lines = [r.getMessage() for r in caplog.records if "exported by pdrlearn" in r.getMessage()]
    assert len(lines) == 1 and lines[0].startswith(f"bundle {b}: exported by pdrlearn 9.9.0, this runtime is "
                                                   f"pdrlearn {__version__}; it loads"), lines


@pytest.mark.parametrize(("kw", "what"), [
    ({"low": 0, "open_low": True}, "a positive number"), ({"low": 0, "high": 0.5}, "a number from 0 to 0.5"),
    ({"low": 1}, "a number >= 1"), ({"high": 2}, "a number <= 2"), ({}, "a number")])
def test_a_rule_says_its_bounds(kw, what):
    """Decision B206's shared Rule names every bound it checks (an upper bound alone had been "a number")."""
    from pdrlearn.settings import Rule

    r = Rule("number", **kw)
    assert r.what() == what
    assert r.fits(3) == ("high" not in kw)  # the line is given exactly when the value breaks the rule
