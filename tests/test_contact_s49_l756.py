"""Decision L756 (session 49, trial s49t4 F1): each stride's contact type from its sole angle at the contact
(steps.csv ``contact``) and the session's toe-contact share over the steady strides (summary.json / sessions.csv
``toe_contact_share_pct``, clinical.md's line). Decision C238: a gait-all output's rows carry their visit, so C221
orders them too."""
from __future__ import annotations

import json
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

from pdrlearn.kernels.contact_type import FLAT_CONTACT_DEG, contact_types, toe_contact_share
from pdrlearn.track.contact_summary import contact_summary


def test_the_sole_angle_at_contact_gives_the_contact_type_l756():
    got = contact_types([-12.0, -3.5, -2.0, 0.0, 2.9, 3.1, 24.8, np.nan])
    assert list(got) == ["forefoot", "forefoot", "flat", "flat", "flat", "heel", "heel", None]
    assert FLAT_CONTACT_DEG == 3.0


def test_the_share_is_over_the_steady_strides_only_l756():
    contact = ["forefoot"] * 6 + ["heel"] * 2 + ["heel"] * 3 + [None]
    steady = [True] * 8 + [False] * 3 + [True]
    assert toe_contact_share(contact, steady) == (pytest.approx(75.0), 8)
    assert toe_contact_share(contact[:4], [True] * 4) == (None, 4)  # under 5 strides: no share


def test_the_summary_keys_and_a_track_without_the_column_l756():
    steps = pd.DataFrame({"contact": ["heel"] * 5 + ["forefoot"] * 2, "steady": [True] * 6 + [False]})
    assert contact_summary(steps) == {"toe_contact_share_pct": pytest.approx(100 / 6), "n_contact_strides": 6}
    assert contact_summary(pd.DataFrame({"start_s": [0.0]})) == {"toe_contact_share_pct": None,
                                                                 "n_contact_strides": 0}


def test_the_foot_track_writes_the_contact_column_after_the_sole_angles_l756():
    from pdrlearn.track.plasys import swing_columns

    table = pd.DataFrame({"event_s": [1.0, 2.0, 3.0], "stride_time_s": [np.nan, 1.0, 1.0]})
    angles = {1.0: -12.0, 2.0: 22.0, 3.0: 0.5}
    fd = SimpleNamespace(lift_m_=np.array([0.1, 0.1, 0.1]), min_toe_clearance=lambda tc, ic: np.full(len(ic), 0.02),
                         sole_angle=lambda t: np.array([angles.get(float(x), np.nan) for x in np.atleast_1d(t)]))
    swing_columns(table, fd, np.array([True, True, True]))
    cols = list(table.columns)
    assert cols.index("contact") == cols.index("tc_angle_deg") + 1
    assert table["contact"].tolist() == ["forefoot", "heel", "flat"]


def test_clinical_md_names_the_toe_contact_share_l756():
    from pdrlearn.report.clinical import contact_line

    line = contact_line({"toe_contact_share_pct": 96.4, "n_contact_strides": 28}, "foot unit")
    assert line == ("- Toe contact: 96 % of 28 steady strides land on the forefoot (sole angle at contact below -3 "
                    "deg; steps.csv contact; foot unit; L756)")
    assert contact_line({"toe_contact_share_pct": None}, "foot unit") is None


def test_gait_outputs_are_listed_in_visit_order_c238(tmp_path):
    from pdrlearn.report.clinical import clinical_markdown

    for visit in ("post", "pre"):  # text order: post first
        sessions = {}
        for side in ("left", "right"):
            s = tmp_path / "sessions" / f"P01_{visit}_{side}"
            s.mkdir(parents=True)
            (s / "meta.json").write_text(json.dumps({"subject": "P01", "visit": visit}))
            sessions[side] = {"session": str(s)}
        g = tmp_path / "gait" / f"P01_{visit}"
        g.mkdir(parents=True)
        (g / "gait_summary.json").write_text(json.dumps({"walk": {}, "sessions": sessions}))
    text = clinical_markdown(tmp_path / "gait")
    assert text.index("Walk P01_pre") < text.index("Walk P01_post")
