"""Decision C227 (trial s49t2 finding F7b): the out-of-training-range line of a per-user model does not tell its user
to train a per-user model (it is one): it says to add such strides to the calibration; a pooled model keeps C16's."""

from __future__ import annotations

from types import SimpleNamespace

REPORT = {"out_of_domain_fraction": 5 / 7, "warn": False, "warn_at": None,
          "tasks": {"direction": {"unit": "nn/combined", "n_steps": 7, "n_out": 5, "fraction": 5 / 7,
                                  "feature": None}}}


def test_a_per_user_models_line_sends_the_strides_to_the_calibration():
    from pdrlearn.classify.domain import FIX, session_warning_line, warning_line

    pooled = session_warning_line(REPORT)
    assert pooled.startswith("5 of 7 strides (71 %) lie outside") and pooled.endswith(FIX)
    own = session_warning_line(REPORT, user="user.seed:16400")
    assert "train a per-user model" not in own
    assert own.endswith("this is user.seed:16400's own per-user model, so add strides like these to the calibration: "
                        "record them in a labelled session and retrain with it: pdrlearn train CALIBRATION_DIR... "
                        "NEW_SESSION_DIR --out MODEL_DIR (docs/decisions/classifiers.md C227)")
    detail = warning_line({**REPORT, "warn": True, "warn_at": 0.25}, user="P001")
    assert "P001's own per-user model" in detail and FIX not in detail


def test_track_and_run_name_the_models_user():
    from pdrlearn.runtime.tracker import Tracker
    from pdrlearn.track.plasys import domain_check

    class Model:
        tasks, has_domain = ["direction"], True

        def __init__(self, users):
            self.data_summary = {"users": users}

        def domain_report(self, classes, warn_at=None):
            return REPORT

    lines: list[str] = []
    domain_check(Model(["user.seed:16400"]), None, lines)
    domain_check(Model(["user.seed:1", "user.seed:2"]), None, lines)  # pooled: C16's advice
    assert "user.seed:16400's own per-user model" in lines[0] and "train a per-user model" in lines[1]
    said: list[str] = []
    for users in (["user.seed:16400"], []):
        fake = SimpleNamespace(_domain=object(), _domain_said=False, domain_report=lambda: REPORT, _warn=said.append,
                               bundle=SimpleNamespace(manifest={"training": {"data": {"users": users}}}))
        Tracker._warn_out_of_domain(fake)
    assert "user.seed:16400's own per-user model" in said[0] and "train a per-user model" in said[1]
