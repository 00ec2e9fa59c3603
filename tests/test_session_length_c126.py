"""Decisions C126 / C127: ``track --length-reference session``, the length class against the whole session's median
stride, offline, with C126's guard (``pdrlearn.kernels.relative_length.session_length_classes(causal=False,
guard=True)``, ``pdrlearn.track.session_length``). Simulated users of session 37, implementer I5: 9230-9259."""

from __future__ import annotations

import json
from pathlib import Path

import pandas as pd
import pytest

from pdrlearn.cli import main


def _rows(lengths_classes) -> list[dict]:
    return [{"length_m": a, "terrain": "flat", "direction": "forward", "length_class": c, "turn_angle_rad": 0.0}
            for a, c in lengths_classes]


def test_guard_keeps_the_models_classes_on_a_walk_the_model_sees_as_mostly_long():
    from pdrlearn.kernels.relative_length import median_is_normal, session_length_classes

    # 24 long strides (1.85 m) and 6 normal ones (1.40 m), classed right by the model: the median is the long stride
    walk = _rows([(1.85, "long")] * 12 + [(1.40, "normal")] * 6 + [(1.85, "long")] * 12)
    assert not median_is_normal(walk)
    assert session_length_classes(walk, causal=False, guard=True) == [r["length_class"] for r in walk]
    # unguarded (C118's information-only variant), the long strides become normal and the normal ones short
    assert session_length_classes(walk, causal=False) == ["normal"] * 12 + ["short"] * 6 + ["normal"] * 12
    # a balanced exercise all called normal by the model: the median is the normal stride, the guard lets it run
    even = _rows([(0.80, "normal")] * 10 + [(1.40, "normal")] * 10 + [(1.85, "normal")] * 10)
    assert median_is_normal(even)
    assert session_length_classes(even, causal=False, guard=True) == ["short"] * 10 + ["normal"] * 10 + ["long"] * 10
    # exactly half called long is "half or more": kept
    half = _rows([(1.85, "long")] * 10 + [(1.40, "normal")] * 10)
    assert not median_is_normal(half)


def test_whole_session_length_on_a_hand_made_track_table():
    from pdrlearn.track.session_length import whole_session_length

    n = 30
    steps = pd.DataFrame({
        "start_s": range(n), "length_m": [0.8] * 10 + [1.4] * 10 + [1.85] * 10,
        "terrain": ["flat"] * 29 + ["up"], "direction": ["forward"] * n, "length_class": ["normal"] * n,
        "p_length_short": [0.1] * n, "p_length_normal": [0.8] * n, "p_length_long": [0.1] * n,
        "turn_angle_rad": [0.0] * 15 + [1.0] + [0.0] * 14})
    out = whole_session_length(steps)
    want = ["short"] * 10 + ["normal"] * 10 + ["long"] * 9 + ["normal"]  # the stair stride keeps its class
    want[15] = "normal"  # a turning stride (57 deg, L79) keeps its class
    assert out["length_class"].tolist() == want
    changed = out["length_class"] != steps["length_class"]
    assert out.loc[changed, "p_length_short"].tolist() == [1.0] * 10 + [0.0] * 9  # one-hot, as C88
    assert out.loc[changed, "p_length_long"].tolist() == [0.0] * 10 + [1.0] * 9
    assert out.loc[~changed, "p_length_normal"].tolist() == [0.8] * int((~changed).sum())  # untouched
    assert out.drop(columns=[c for c in out if "length_class" in c or c.startswith("p_length")]).equals(
        steps.drop(columns=[c for c in steps if "length_class" in c or c.startswith("p_length")]))
    assert steps["length_class"].tolist() == ["normal"] * n  # the input is not changed
    no_model = steps.drop(columns=["length_class"])
    assert whole_session_length(no_model) is no_model


@pytest.fixture(scope="module")
def length_walk(tmp_path_factory) -> dict[str, Path]:
    """User 9232's length exercise and a heuristic model of the three tasks trained on its three exercises."""
    root = tmp_path_factory.mktemp("c126")
    for s in ("length", "terrain", "direction"):
        assert main(["simulate", "--scenario", s, "--user-seed", "9232", "--out", str(root / s), "--json"]) == 0
    model = root / "model"
    assert main(["train", *(str(root / s) for s in ("length", "terrain", "direction")), "--out", str(model),
                 "--methods", "heuristic", "--cv", "3", "--json"]) == 0
    return {"session": root / "length", "model": model}


def test_track_length_reference_session_writes_the_whole_session_classes(length_walk, tmp_path, capsys, monkeypatch):
    from pdrlearn.kernels import turn_length
    from pdrlearn.track.session_length import whole_session_length

    # decision C191 gives this walk's straight strides their measured class already (the option then changes no
    # class): the option is judged against the classifier's own straight classes
    monkeypatch.setattr(turn_length, "CONTRADICTION_MARGIN", float("inf"))
    s, m = length_walk["session"], length_walk["model"]
    assert main(["track", "--no-plot", str(s), "--model", str(m), "--out", str(tmp_path / "a"), "--json"]) == 0
    assert main(["track", "--no-plot", str(s), "--model", str(m), "--length-reference", "session", "--out",
                 str(tmp_path / "b"),
                 "--json"]) == 0
    capsys.readouterr()
    a, b = (pd.read_csv(tmp_path / k / "steps.csv") for k in ("a", "b"))
    want = whole_session_length(a)
    assert b["length_class"].fillna("").tolist() == want["length_class"].fillna("").tolist()
    assert (a["length_class"] != b["length_class"]).sum() > 0  # the default is not the whole-session rule
    pcols = [c for c in a if c.startswith("p_length_")]
    assert pcols and b[pcols].equals(want[pcols])
    rest = [c for c in a if c != "length_class" and c not in pcols]
    pd.testing.assert_frame_equal(a[rest], b[rest])  # lengths, positions, terrain, direction: the default track's
    assert json.loads((tmp_path / "b" / "run.json").read_text())["options"]["length_reference"] == "session"


def test_track_length_reference_default_is_the_model():
    from pdrlearn.cli.track import track_settings

    assert track_settings()["length_reference"] == "model"  # decision C127: not adopted as the default


@pytest.mark.parametrize("extra, line", [
    (["--model", "MODEL", "--length-reference", "median"], "length_reference='median' is not one of model, session"),
    (["--length-reference", "session"], "track: --length-reference session replaces a trained model's length "
                                        "classes (no --model given)"),
    (["--model", "oracle", "--length-reference", "session"], "oracle classes are the labels"),
])
def test_track_length_reference_bad_input_is_one_line(length_walk, tmp_path, capsys, extra, line):
    out = tmp_path / "out"
    argv = ["track", "--no-plot", str(length_walk["session"]),
            *(str(length_walk["model"]) if a == "MODEL" else a for a in extra),
            "--out", str(out)]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error: ") and line in err[0] and "Traceback" not in err[0], err
    assert not out.exists()


def test_a_nan_length_or_turn_is_no_traceback_closing_reread():
    """Closing re-read (session 37): a NaN ``length_m`` or ``turn_angle_rad`` became None and a TypeError in the
    kernel; NaN is now not eligible (length) or straight (turn, L79), and an absent class stays None."""
    import numpy as np
    import pandas as pd

    from pdrlearn.track.session_length import whole_session_length

    n = 30
    st = pd.DataFrame({"terrain": ["flat"] * n, "direction": ["forward"] * n,
                       "length_m": np.linspace(1.3, 1.5, n), "turn_angle_rad": np.zeros(n),
                       "length_class": ["normal"] * n, "p_length_short": 0.0, "p_length_normal": 1.0,
                       "p_length_long": 0.0})
    st.loc[3, "length_m"] = np.nan
    st.loc[5, "turn_angle_rad"] = np.nan
    st.loc[7, "terrain"] = np.nan
    out = whole_session_length(st)
    assert out["length_class"].tolist() == ["normal"] * n
