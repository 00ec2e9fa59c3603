"""Decision W297: `pdrlearn steps` keeps counting a lower-back detector's raw contacts; its W281 note names the
contacts `track`'s default sit veto drops at the chair transfers (a five-times sit-to-stand without walking)."""

from __future__ import annotations

import json

from pdrlearn.cli import main
from pdrlearn.waist.posture import sit_veto_keywords


def test_sit_veto_keywords_map_the_option_values():
    assert sit_veto_keywords("opposite") == {"keep_rhythm": True, "keep_between": "opposite"}  # W184 / W185
    assert sit_veto_keywords("alternation") == {"keep_rhythm": True, "keep_between": True}  # W180
    assert sit_veto_keywords("rhythm") == {"keep_rhythm": True, "keep_between": False}  # W109
    assert sit_veto_keywords(True) == {"keep_rhythm": False, "keep_between": False}  # W104


def test_steps_names_the_transfer_contacts_of_a_sit_to_stand_without_walking(tmp_path, capsys):
    d = tmp_path / "sts"
    assert main(["simulate", "--route", "sit:1, sit:1, sit:1, sit:1", "--sit-start", "3", "--sit-end", "5",
                 "--user-seed", "6650", "--out", str(d)]) == 0
    for f in d.glob("f*.csv"):  # a lower-back recording: `steps` auto picks waist-ic
        f.unlink()
    capsys.readouterr()
    assert main(["steps", str(d)]) == 0
    out = capsys.readouterr().out
    assert out.startswith("route_u6650_normal_s0: 10 steps (waist-ic)")  # the raw count stays (W297)
    assert "10 of them (at 3.6, 12.4, " in out and "(5 sit-to-stand, 5 stand-to-sit found" in out
    assert "(W281, W297)" in out
    assert main(["track", "--no-plot", str(d), "--out", str(tmp_path / "t"), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["n_steps"] == 0  # track drops all ten (W277)
    assert main(["steps", str(d), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["count"] == 10  # one JSON object, no note
