"""Trial T3 (session 39) finding 4, decision W415: the waist frame check (D10), the compass mount check (D25) and the
foot placement check (B134) judge forward walking only; a side-shuffle drill gets none of their lines (users 10035,
10036: the fresh-test range of fixer FB)."""

from __future__ import annotations

import json

import numpy as np

from pdrlearn.cli import main
from pdrlearn.track.stride_kinds import MIN_CLASSED_STRIDES, not_judged, stride_kinds

FALSE_LINES = ("contradicts its data", "does not match its frame", "no foot-flat rests found")


def _track(tmp_path, route: str, user: int, name: str, *extra: str) -> dict:
    sim, out = tmp_path / name, tmp_path / f"{name}_tr"
    assert main(["simulate", "--route", route, "--user-seed", str(user), "--out", str(sim)]) == 0
    assert main(["track", "--no-plot", str(sim), "--out", str(out), *extra]) == 0
    return json.loads((out / "summary.json").read_text())


def test_side_shuffle_drill_gets_no_frame_mount_or_placement_line_w415(tmp_path):
    summary = _track(tmp_path, "stand:2, side:3, side:-3, stand:2", 10035, "sh")
    lines = summary["info"].get("warnings", [])
    assert not [ln for ln in lines if any(w in ln for w in FALSE_LINES)], lines
    assert summary["frame_waist"] == "declared"
    # the result the trial called right is kept: the D25 fallback's heading, without its line
    assert summary["info"]["compass_mount"]["fallback"] is True
    assert summary["info"]["compass_mount"]["not_judged"].startswith("not judged: ")
    assert abs(summary["distance_m"] - 6.0) < 0.2 and summary["final_position_error_m"] < 0.3, summary


def test_forward_walk_with_a_turned_waist_unit_is_still_caught_w415(tmp_path):
    """The waist unit worn turned 180 deg (its declared frame kept) on forward walking: D10's and D25's lines stay."""
    sim = tmp_path / "w"
    route = "stand:2, straight:12, stand:2"
    assert main(["simulate", "--route", route, "--user-seed", "10036", "--out", str(sim)]) == 0
    meta = json.loads((sim / "meta.json").read_text())
    meta["frames"]["waist"] = {"x": "right", "y": "up", "z": "backward"}
    (sim / "meta.json").write_text(json.dumps(meta))
    assert main(["track", "--no-plot", str(sim), "--out", str(tmp_path / "w_tr")]) == 0
    lines = json.loads((tmp_path / "w_tr" / "summary.json").read_text())["info"]["warnings"]
    assert any("contradicts its data" in ln for ln in lines) and any("does not match its frame" in ln for ln in lines)


def test_stride_kinds_and_not_judged_w415():
    ang = np.radians([0.0, 5.0, 90.0, -85.0, 175.0, 90.0, 90.0])
    length = np.array([0.8, 0.8, 0.5, 0.5, 0.4, 0.1, 0.5])  # the 0.1 m stride is not classed (L219)
    turn = np.radians([0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 50.0])  # a turn's stride is not classed (L400)
    kinds = stride_kinds(ang, length, turn)
    assert kinds == {"forward": 2, "side": 2, "backward": 1}
    assert not_judged(kinds) == ("not judged: 3 of 5 foot strides travel sideways or backward (2 sideways, 1 "
                                 "backward; the check assumes forward walking, decision W415)")
    assert not_judged({"forward": 3, "side": 2, "backward": 1}) is None  # half forward: judged
    assert not_judged({"forward": 0, "side": 2, "backward": 0}, MIN_CLASSED_STRIDES) is None  # too few to silence B134
    assert not_judged(None) is None
