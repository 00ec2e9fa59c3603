"""Decision B472 (review R1 F1): a waist track option given at the top level of the waist parameters (W571's
documented `--params '{"mount_drift": true}'`) is refused with one line giving the corrected JSON."""

from __future__ import annotations

import json

import pytest

from pdrlearn.errors import DataError
from pdrlearn.waist.params import WaistParams, load_params


def _refusal(d: dict) -> str:
    with pytest.raises(DataError) as e:
        WaistParams.from_dict(d, where="--params x")
    return str(e.value)


def test_a_top_level_option_is_said_with_the_corrected_json():
    msg = _refusal({"mount_drift": True})
    assert msg == ('--params x: mount_drift is a track option, set under "options": give {"options": {"mount_drift": '
                   'true}} (docs/decisions/bad-input.md B472)')
    fixed = json.loads(msg.split("give ", 1)[1].rsplit(" (", 1)[0])
    assert WaistParams.from_dict(fixed).options == {"mount_drift": True}  # the JSON given is read
    with pytest.raises(DataError, match=r'^--params \{"mount_drift": true\}: mount_drift is a track option'):
        load_params('{"mount_drift": true}')  # `pdrlearn track --params` (inline JSON, B466)
    assert load_params('{"options": {"mount_drift": true}}').options == {"mount_drift": True}


def test_the_other_keys_and_options_are_kept_and_a_non_option_keeps_the_old_line():
    msg = _refusal({"k": 1.1, "options": {"sit_veto": "off"}, "mount_drift": True, "gait_check": True})
    assert msg.startswith("--params x: gait_check, mount_drift are track options")
    fixed = json.loads(msg.split("give ", 1)[1].rsplit(" (", 1)[0])
    got = WaistParams.from_dict(fixed)
    assert got.k == 1.1 and got.options == {"sit_veto": "off", "mount_drift": True, "gait_check": True}
    msg = _refusal({"mount_drift": True, "foo": 1})  # not all options: not a waist parameter file
    assert "not a waist parameter file (unknown key(s) foo, mount_drift)" in msg and "B472" not in msg
