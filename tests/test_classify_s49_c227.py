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


def test_track_and_run_name_the_models_user_on_that_users_session():
    from pdrlearn.classify.training import bundle_own_user
    from pdrlearn.runtime.tracker import Tracker
    from pdrlearn.track.plasys import domain_check

    class Model:
        tasks, has_domain = ["direction"], True

        def __init__(self, users):
            self.data_summary = {"users": users}

        def domain_report(self, classes, warn_at=None):
            return REPORT

    own = SimpleNamespace(meta={"user": {"seed": 16400}}, folder=None)
    other = SimpleNamespace(meta={"user": {"seed": 7}}, folder=None)
    lines: list[str] = []
    domain_check(Model(["user.seed:16400"]), None, lines, session=own)
    domain_check(Model(["user.seed:16400"]), None, lines, session=other)  # another user: train that user's model
    domain_check(Model(["user.seed:1", "user.seed:2"]), None, lines, session=own)  # pooled: C16's advice
    assert "user.seed:16400's own per-user model" in lines[0]
    assert all("train a per-user model" in line for line in lines[1:]) and len(lines) == 3
    bundle = SimpleNamespace(manifest={"training": {"data": {"users": ["user.seed:16400"]}}})
    assert bundle_own_user(bundle, own) == "user.seed:16400" and bundle_own_user(bundle, other) is None
    said: list[str] = []
    for user in ("user.seed:16400", None):
        fake = SimpleNamespace(_domain=object(), _domain_said=False, domain_report=lambda: REPORT, _warn=said.append,
                               domain_user=user)
        Tracker._warn_out_of_domain(fake)
    assert "user.seed:16400's own per-user model" in said[0] and "train a per-user model" in said[1]
